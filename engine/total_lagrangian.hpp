// SPDX-License-Identifier: BSD-3-Clause
// Total-Lagrangian kinematics of a hyperelastic body of NURBS patches: the
// internal force and its consistent tangent, integrated over the reference
// configuration (Holzapfel, Nonlinear Solid Mechanics, ch. 8; Wriggers,
// Nonlinear Finite Element Methods, ch. 4).
//
//   x = X + u,   F = I + Grad u = I + sum_A u_A (x) dN_A/dX,
//   f_int_(A,i)      = int_Omega0 P_iJ(F) dN_A/dX_J dX,
//   K_(A,i)(B,k)     = d f_int_(A,i) / d u_(B,k)
//                    = int_Omega0 dN_A/dX_J A_iJkL(F) dN_B/dX_L dX,
// with P the first Piola-Kirchhoff stress and A = dP/dF the law's first
// elasticity tensor.  A contains both the material and the geometric
// (initial-stress) stiffness, so the assembler needs nothing but P and A.
// A hyperelastic A has the major symmetry A_iJkL = A_kLiJ, hence K is
// symmetric; the kernel computes one triangle of each element matrix.
//
// Discretisation: (p+1)^dim Gauss points per element (as the linear
// assembler).  The dimension is a compile-time parameter of the kernel and of
// its element values (ElementValues<dim, dim>, filled by the one element
// kernel PatchQuadrature::evaluate: 2D pays nothing for 3D; nothing is
// allocated per element).  Elements are threaded with OpenMP colour by colour: elements of
// one colour share no equation, so threads add straight into K and f_int
// (memory independent of the thread count, no reduction pass); with the
// mixed formulation the pressure functions' rank-one terms follow in a
// second pass, function colour by function colour.  The sparsity pattern
// (free x free: two equations couple when their control points share an
// element, or the support of a pressure function of the mixed formulation)
// is built once in the constructor
// and every tangent has exactly that pattern, so a driver can analyse it
// once and refactorise numerically.
//
// Failure is reported, never carried: assemble returns false when det F <= 0
// (or F is not finite) at a Gauss point or the law refuses F, so a Newton
// driver can cut the load step back.  A geometry map that folds (det J <= 0)
// is an input error: the constructor throws.
//
// Owner: engine/ (kinematics).  The KINSOL driver and the large-deformation
// contact call it; the follower pressure (follower_pressure.hpp) adds its
// load stiffness into the same pattern.
#pragma once

#include <Eigen/Sparse>
#include <array>
#include <optional>
#include <vector>

#include "engine/assembly.hpp"
#include "engine/discretisation.hpp"
#include "engine/pressure_space.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {

class TotalLagrangianAssembler {
 public:
  // Copies what it needs of the patch (its quadrature) and the dof map; keeps
  // a pointer to `law`, which must outlive the assembler (a law keeps no
  // scratch, so it may be shared).  Throws std::invalid_argument unless the
  // patch is a 2D or 3D volume patch matching the dof map, and
  // std::runtime_error when the geometry map folds.
  // `mixed` (engine/volumetric_projection.hpp) needs a law with a volumetric
  // split (std::invalid_argument otherwise); its pattern couples the control
  // points of each pressure function's support.
  // `tangent` false: the internal force only (no sparsity pattern is built;
  // e.g. the reactions of model/reactions.hpp), and assemble throws
  // std::logic_error if given a K.
  TotalLagrangianAssembler(const Body& body, const DofMap& dofs, const HyperelasticLaw& law,
                           Formulation formulation = Formulation::displacement, bool tangent = true);
  // Patch k of the body with law patch_laws[k] and formulation
  // patch_formulations[k] (a list of one entry: every patch's), e.g. two
  // bodies of different rubbers in one model.  The laws must outlive the
  // assembler.
  TotalLagrangianAssembler(const Body& body, const DofMap& dofs, std::vector<const HyperelasticLaw*> patch_laws,
                           std::vector<Formulation> patch_formulations, bool tangent = true);

  // u: displacement per control point (n_cp x dim), prescribed values
  // included (e.g. DofMap::expand of the free values).  Fills f_int (free
  // numbering, resized) and, when K is not null, the tangent K (free x free,
  // the pattern() structure; K is reset to it unless it has it already, so
  // reusing one K across calls allocates nothing).  Rows and columns of
  // prescribed dofs are skipped: the driver works with the full u.
  // Returns false, leaving f_int and K unspecified, when det F <= 0 or F is
  // not finite at a Gauss point, or the law refuses F.  Throws
  // std::invalid_argument when u has the wrong shape.
  bool assemble(const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K) const;

  // The mixed formulation's pressure space (engine/pressure_space.hpp,
  // mixed_pressure_space: on a `mixed` patch the continuous B-splines of
  // degree p - 1 on breakpoints twice coarser, on a `mixed_element` or
  // displacement patch one constant per element): one dilatation theta_A and
  // one pressure p_A = U'(theta_A) per function N_A,
  //   theta_A = (1/m_A) int N_A J dX,   m_A = int N_A dX
  // (the L2 projection with the pressure mass lumped, so local), the point
  // pressure sum_A N_A p_A, and the stabilisation mu_s (J - Pi_e J) per
  // element.  Everything "per pressure" below is numbered as
  // pressure_space() numbers its functions.
  //
  // The u-p Newton of the mixed formulation (docs/design.md, "Nearly
  // incompressible solids"): each mixed function's dilatation theta_A an
  // unknown of the iteration beside u.  `dilatation` (theta_A - 1 per
  // function) sets p_A = U'(theta_A) and U''(theta_A) in place of their
  // values at the projection of J (the stabilisation keeps mu_s (J - Pi_e J));
  // K is then d f_int/du at fixed theta plus the sum over functions of
  // m_A U''(theta_A) mB_A^T mB_A, the matrix with theta condensed
  // (engine/saddle_solver.hpp, BlockJacobian::local), of the pattern and
  // symmetry of the other overload's.  `local`, when not null, receives what
  // the pressure rows of the Newton matrix need; its mean_B only with K.
  struct LocalDilatation {
    Eigen::VectorXd projected;  // (1/m_A) int N_A (J - 1) dX per function (0: a displacement patch's)
    Eigen::VectorXd stiffness;  // m_A U''(theta_A) (0: a displacement patch's)
    Eigen::VectorXd volume;     // m_A (reference; 0: a displacement patch's)
    Eigen::VectorXd shear;      // mu_s of the function's law (0: a displacement patch's)
    // mB_A = (1/m_A) int N_A dJ/du dX on the free equations
    Eigen::SparseMatrix<double, Eigen::RowMajor> mean_B;
  };
  bool assemble(const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K,
                const Eigen::VectorXd* dilatation, LocalDilatation* local) const;
  const PressureSpace& pressure_space() const { return space_; }
  int num_pressures() const { return space_.num_functions(); }
  // Another pressure space than mixed_pressure_space's (e.g. constants per
  // element: the pair before the sub-grid space, for the tests'
  // comparisons); rebuilds the pattern and the colourings.  Throws
  // std::invalid_argument when the space is not of this body's elements or
  // the incompressible limit is on (its multipliers are per function).
  void set_pressure_space(PressureSpace space);
  // The assembly's per-element storage: element e's entries start at
  // function_entry[e] (one per function of e), g_entry[e] (int_e N_A B per
  // function, a mixed element's nd values each) and eq_entry[e] (its nd
  // equations); volume: m_A per function.
  struct PressureLayout {
    std::vector<int> function_entry, g_entry, eq_entry;
    Eigen::VectorXd volume;
  };
  int num_elements() const { return quad_.num_elements(); }
  // Whether any patch is in the mixed formulation.
  bool has_mixed() const;
  // This process's share of a distributed run: assemble() evaluates the
  // elements [begin, end) only, so that f_int and K are this share of sums
  // over processes (the caller sums them).  Not with a mixed patch, whose
  // pressure functions' terms are not sums over elements:
  // std::invalid_argument.
  void set_element_range(ElementRange elements);

  // Zero-valued matrix with the tangent's pattern (compressed, column major,
  // sorted; contains every coupling of control points that share an element,
  // or a pressure function's support, so face loads and contact on the patch's faces fit
  // in it too).
  const Eigen::SparseMatrix<double>& pattern() const { return pattern_; }
  const DofMap& dofs() const { return dofs_; }
  int dim() const { return dofs_.dim(); }
  // Smallest det J of the geometry map met at a Gauss point.
  double min_det_J() const { return min_det_J_; }

  // Tolerance on max_A |theta_A - 1| of the incompressible limit's runs.
  static constexpr double kIncompressibilityTolerance = 1e-8;
  // The fully incompressible limit of the mixed patches (K = infinity,
  // docs/design.md): an augmented Lagrangian, as FEBio's.  Each pressure
  // function's volumetric energy becomes m_A U(theta_A), U(theta) =
  // lambda_A (theta - 1) + kappa/2 (theta - 1)^2, with lambda_A its pressure
  // multiplier (0 at first) and kappa the law's bulk modulus U''(1) as the
  // penalty; the assembly is otherwise the mixed one (same pattern,
  // symmetric).  After a Newton solve, augment(u) updates lambda_A +=
  // kappa (theta_A - 1) (Uzawa) unless max_A |theta_A - 1| <= tolerance
  // already; solving again and again drives int N_A (J - 1) dX to 0 for
  // every function, the constraint of the consistent (unlumped) mixed method,
  // whatever kappa (kappa only sets how fast).  Throws
  // std::invalid_argument without a mixed patch.
  void make_incompressible(double tolerance);
  bool incompressible() const { return incompressibility_.has_value(); }
  // Updates the multipliers from u and returns true when the constraint was
  // not yet met (the state must be solved again); false when it is met, or
  // u is inadmissible, or the body is not incompressible.
  bool augment(const Eigen::MatrixXd& u);
  // A step accepted: its multipliers are the ones to return to; not
  // accepted (cut back): back to those of the last accepted step.
  void keep_multipliers(bool accepted);
  // The multipliers of another assembler of the same body (e.g. the
  // reactions' one, model/reactions.hpp); makes this one incompressible.
  void copy_multipliers(const TotalLagrangianAssembler& from);
  // The multipliers of an accepted step (a restart: the ones the step it
  // continues after ended with, its Incompressibility::accepted).  Throws
  // std::invalid_argument unless incompressible with one per pressure function.
  void restore_multipliers(const Eigen::VectorXd& accepted);
  // theta_A - 1 = (1/m_A) int N_A (J - 1) dX per pressure function (0 for a
  // displacement patch's); false when u is inadmissible.
  bool volume_changes(const Eigen::MatrixXd& u, Eigen::VectorXd& dilatation) const;
  // The incompressible limit: each function's pressure U'(theta_A) =
  // lambda_A + kappa (theta_A - 1) at u (positive in tension); false when u
  // is inadmissible or the body is not incompressible.
  bool element_pressures(const Eigen::MatrixXd& u, Eigen::VectorXd& pressure) const;
  struct Incompressibility {
    double tolerance = 0;
    std::vector<double> penalties;        // kappa per law (one, or one per patch)
    Eigen::VectorXd multipliers, accepted;  // lambda_A per pressure function: current, of the last accepted step
    double last_volume_change = 0;        // max_A |theta_A - 1| at the last augment()
    int augmentations = 0;                // Uzawa updates so far
  };
  const std::optional<Incompressibility>& incompressibility() const { return incompressibility_; }

 private:
  Body body_;
  BodyQuadrature quad_;  // the elements, their tabulated basis and control points
  DofMap dofs_;
  std::vector<const HyperelasticLaw*> laws_;  // one, or one per patch
  std::vector<Formulation> formulations_;     // one, or one per patch
  std::vector<double> stabilisations_;        // mu_s of each law in the mixed formulation (0: none)
  int pressure_degree_;
  PressureSpace space_;                   // the pressure functions (pressure_space.hpp)
  PressureLayout layout_;
  bool tangent_ = true;
  Eigen::SparseMatrix<double> pattern_;   // with the functions' supports (constants per element: the element pattern)
  std::vector<std::vector<int>> colours_, function_colours_;  // by colour: one colour shares no equation
  ElementRange elements_;                 // the elements assemble() evaluates (set_element_range)
  void keep_range_in_colours();
  double min_det_J_ = 0;
  std::optional<Incompressibility> incompressibility_;
};

}  // namespace igac
