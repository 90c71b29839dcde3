// SPDX-License-Identifier: BSD-3-Clause
// Degrees of freedom and the linear-elastic system of a body (one or more
// patches, engine/body.hpp).
//
// Unknowns are control-point displacements, dof = cp * dim + component, cp
// the body's control point number.
// Dirichlet conditions fix one component on whole faces (with a value,
// usually 0 for symmetry); fixed dofs are eliminated, so the matrix is the
// SPD block K_ff and the prescribed values move to the right-hand side.
// Coincident control points of a collapsed face share their unknowns.
//
// a(u, v) = int sigma(u) : eps(v) dX, assembled element by element with
// (p+1)^dim Gauss points, threaded over the elements of one colour at a time
// (OpenMP; engine/sparsity.hpp's colouring: no per-thread copy of K).  Loads: a
// pressure P on faces (traction -P n, n the outward normal of the body) and a
// body force b (per unit volume).
#pragma once

#include <Eigen/Sparse>
#include <functional>
#include <vector>

#include "engine/body.hpp"
#include "engine/discretisation.hpp"
#include "engine/pressure_space.hpp"
#include "engine/volumetric_projection.hpp"
#include "materials/linear_elastic.hpp"

namespace igac {

struct DirichletCondition {
  std::vector<PatchSide> faces;
  int component = 0;
  double value = 0.0;
};

class DofMap {
 public:
  DofMap(const Body& body, const std::vector<DirichletCondition>& conditions);
  int dim() const { return dim_; }
  int num_dofs() const { return int(equation_.size()); }
  int num_free() const { return n_free_; }
  // Free equation number of a dof, or -1 when it is prescribed.
  int equation(int dof) const { return equation_[dof]; }
  double prescribed_value(int dof) const { return value_[dof]; }
  // The element's dof indices: eq[a * dim + i] = equation(cps[a] * dim + i),
  // the free equation of component i of its local control point a (or -1).
  // What scatter_element_vector and scatter_element_matrix (sparsity.hpp) take.
  void element_equations(const std::vector<int>& cps, std::vector<int>& eq) const {
    eq.resize(cps.size() * dim_);
    for (size_t a = 0; a < cps.size(); ++a)
      for (int i = 0; i < dim_; ++i) eq[a * dim_ + i] = equation_[cps[a] * dim_ + i];
  }
  // Full coefficient matrix (n_cp x dim) from the free unknowns.
  Eigen::MatrixXd expand(const Eigen::VectorXd& free) const;

 private:
  int dim_;
  int n_free_ = 0;
  std::vector<int> equation_;
  std::vector<double> value_;
};

// Face quadrature: the side as its own patch, numbered by the body's cps.
PatchQuadrature face_quadrature(const Body& body, const PatchSide& side, int points);

struct LinearSystem {
  Eigen::SparseMatrix<double> K;  // free x free, SPD when the body is held
  Eigen::VectorXd f;              // loads minus the lift of prescribed values
  double min_det_J = 0;           // smallest Jacobian met at a Gauss point
};

// A contiguous block [begin, end) of the body's elements (end < 0: to the
// last one).  A distributed solve gives each process its own block; the
// matrices and loads of all blocks sum to those of the whole body, wherever
// the cuts lie.
struct ElementRange {
  int begin = 0, end = -1;
};

// A process's share of sums over processes (engine/ knows no MPI: the caller
// gives the sums): its block of elements, the sum in place of an array over
// every process, and whether a condition holds on every process.  Empty (no
// `sum`): one process, the whole.
struct ProcessShare {
  ElementRange elements;
  std::function<void(double* values, int count)> sum;
  std::function<bool(bool)> everywhere;
  bool distributed() const { return bool(sum); }
};

// Throws std::runtime_error when the geometry map folds (det J <= 0 at a
// Gauss point).  With `elements`, only those elements are assembled (K keeps
// its full size, the other entries are structurally absent), with the
// pressure functions the range owns (engine/sparsity.hpp: those whose first
// support element it holds; their support elements outside it are evaluated
// again, for the functions' terms only).  `mixed`: the B-bar stiffness of
// engine/volumetric_projection.hpp over the pressure space
// (mixed_pressure_space, pressure_space.hpp), the energy
//   int mu |dev eps|^2 dX + mu/2 int (div u - Pi_e div u)^2 dX
//     + K/2 sum_A (int N_A div u dX)^2 / m_A,   m_A = int N_A dX
// (a mixed method with the row-sum pressure mass, so no pressure unknowns):
// per element the deviatoric part (lambda - K = -2 mu / 3 for lambda) and the
// stabilisation mu (B^T W B - V_e mB_e^T mB_e), per function
// K / m_A g_A g_A^T, g_A = int N_A div N dX (B = div N, mB_e its element
// mean); the pattern widened to the supports (coupling_pattern with the
// space).  Constants per element (mixed_element) give Pi_e: each element's
// own K V_e mB_e^T mB_e.
LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const LinearElastic& material,
                                        const Eigen::VectorXd& body_force, ElementRange elements = {},
                                        Formulation formulation = Formulation::displacement);
// Patch k of the body of material patch_materials[k] and formulation
// patch_formulations[k] (bodies of several materials); one entry: every
// patch's; no formulations: displacement everywhere.
LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const std::vector<LinearElastic>& patch_materials,
                                        const Eigen::VectorXd& body_force, ElementRange elements = {},
                                        const std::vector<Formulation>& patch_formulations = {});
// The same with the pressure space given (mixed_pressure_space above;
// PressureSpace(quad, {{0, 0, 0}}, {1}) gives constants per element on every
// patch).  Its functions on the mixed patches count; the others are unused.
LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const std::vector<LinearElastic>& patch_materials,
                                        const Eigen::VectorXd& body_force, ElementRange elements,
                                        const std::vector<Formulation>& patch_formulations,
                                        const PressureSpace& space);
// Adds the work of a pressure P on the faces to f (free numbering): the dead
// pressure of follower_pressure.hpp (one face loop for both).
void add_pressure_load(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces,
                       double pressure, Eigen::VectorXd& f);
// The number of Gauss points per direction used everywhere for degree p.
inline int gauss_points_for(int degree) { return degree + 1; }

// int N_A b dX of a body force b per unit reference volume (free numbering
// of `dofs`): the load alone, without the stiffness the linear assembly
// computes with it.  Dead in large deformation too (total Lagrangian: the
// force per unit reference volume does not follow the body), so constant in
// u: no load stiffness.
Eigen::VectorXd body_force_load(const Body& body, const DofMap& dofs, const Eigen::VectorXd& b);

}  // namespace igac
