// SPDX-License-Identifier: BSD-3-Clause
// Small-deformation Coulomb friction against rigid obstacles and between
// two bodies: the frictionless active-set solve
// (contact/small_strain_contact.hpp) with, per multiplier K, dim-1
// tangential multipliers lambda_t,K in the same space S^{p-2} and the
// weighted tangential slip increment over the load step
//     s_K = (T (u - u_prev))_K + t0_K - t0_prev,K
// (T: contact/weighted_gap.hpp for an obstacle, contact/mortar_gap.hpp for
// a master body; the body's tangential displacement relative to the
// obstacle's or the master's, weighted by B_K).  Coulomb per multiplier, lambda_n <= 0 the normal one:
//     |lambda_t| <= -f lambda_n,  s = 0 where |lambda_t| < -f lambda_n,
//     s = a lambda_t (a >= 0) where |lambda_t| = -f lambda_n.
// Primal-dual active set (Hueber, Stadler & Wohlmuth 2008): with
// xi = lambda_t + c_t s/K_K and the bound b = -f (lambda_n + c_n g_K),
// K is open when lambda_n + c_n g_K >= 0 (the frictionless rule), stick
// when |xi| <= b, slip with direction d = xi / |xi| otherwise.
//
// One linear system per iteration on the factor of K computed once for all
// load steps: the constraint rows are the active normal rows and the stick
// tangential rows (equalities, like the frictionless active rows); a slip
// multiplier's tangential part is not an unknown but tied to its normal one,
// lambda_t = -f d lambda_n, so its normal column becomes G_K - f d . T_K.
// The dense system (Schur complement of the stacked rows [G; T], columns
// computed once, contact/active_schur.hpp) is then not symmetric: solved by
// LU, bordered by the rigid motions the contact holds.  In 2D d = +-1 and
// each iteration solves the piecewise-linear problem exactly (nothing to
// linearise: the iteration ends when the states repeat); in 3D the cone is a
// disc, d = xi / |xi| of the last iterate, and the slip law is linearised
// across d (linearise_slip below: a semismooth Newton step), until d moves
// less than 1e-10.
#pragma once

#include <memory>

#include "contact/friction_state.hpp"
#include "contact/small_strain_contact.hpp"
#include "engine/linear_backend.hpp"

namespace igac {

// The slip law of one multiplier, Phi = lambda_t - b xi / |xi| = 0 with
// xi = lambda_t + c_t s, and its derivatives at a slipping state
// (|xi| > b): with v = xi / |xi|, alpha = b / |xi|, P = I - v v^T,
//   dPhi/dlambda_t = I - alpha P,  dPhi/ds = -alpha c_t P,  dPhi/db = -v.
// Along v this says v . lambda_t = b; across it (3D), for w orthogonal to v,
// (1 - alpha) w . lambda_t = alpha c_t w . s: the slip across the direction
// is the traction across it times slip_compliance(alpha, c_t)
// = (1 - alpha) / (alpha c_t), the row the solve adds per slip multiplier
// (alpha clamped to [kMinAlpha, 1]).  Checked against finite differences.
struct SlipLinearisation {
  Eigen::VectorXd v;
  Eigen::MatrixXd d_lambda_t, d_s;
  Eigen::VectorXd d_b;
};
SlipLinearisation linearise_slip(const Eigen::VectorXd& lambda_t, const Eigen::VectorXd& s, double b, double ct);
inline constexpr double kMinAlpha = 1e-12;
double slip_compliance(double alpha, double ct);

// The tangential scale c_t,K of each multiplier, in 3D: E / h_K, with
// E = c_n h (c_n = E / h the normal rows' scale, h the mesh size: the
// largest element) and h_K = K_K^(1/2) the size of the multiplier's support
// on the face.  c_t weighs slip against traction in xi = lambda_t + c_t s / K_K:
// a tangential stiffness, the traction a slip of one element's size costs;
// where the mesh is graded toward the contact (hertz3d_neohookean: h_K down
// to h / 20) E / h underrates it, and the slip directions (the disc) took
// more iterations to settle (docs/benchmarks.md, "Friction in large
// deformation").  In 2D, and for h <= 0: c_n for every multiplier (small
// deformation; large deformation's 2D scale is finite_strain_tangential_scales,
// contact/finite_strain_friction.hpp).
Eigen::VectorXd tangential_scales(double cn, double mesh_size, const Eigen::VectorXd& weights, int dim);
// factor * E / h_K, h_K = K_K^(1/(dim-1)), for every multiplier of positive
// weight in any dimension (c_n where h <= 0 or K_K = 0): the one formula of
// both tangential scales.
Eigen::VectorXd per_multiplier_scales(double cn, double mesh_size, const Eigen::VectorXd& weights, int dim,
                                      double factor);

class SmallStrainFriction {
 public:
  // Factorises K (pinned rigid motions as the frictionless solve) for the
  // operator's sparsity; `op` must have its tangential rows.  With a
  // `backend` (engine/linear_backend.hpp; it must outlive this) nothing is
  // factorised here and chol is not used: each iteration's saddle-point
  // system is solved whole and sparse by the backend (PETSc's), the same
  // states, rules and stopping test.
  SmallStrainFriction(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f, const WeightedGapOperator& op,
                      const RigidModes& modes, SparseCholesky& chol, const ContactSolverOptions& options,
                      LinearBackend* backend = nullptr);
  ~SmallStrainFriction();
  // One load step with the same K, f, G, T and the step's g0, t0 (the
  // obstacle where the step leaves it).  Updates the slip history; the
  // solution carries lambda_t, the state and the accumulated slip.
  ContactSolution step(const WeightedGapOperator& op);
  // Along load curves (model/load_history.cpp): the load f of the next
  // steps (K and its factor unchanged), and where the tangential positions
  // count from, T u + t0 with u = 0 and op0's t0 (the obstacle at time 0).
  void set_load(const Eigen::VectorXd& f);
  void start_from(const WeightedGapOperator& op0);
  // The history after the last step, and back to it (a restart: the solver
  // built as the run built it, then the history of the step it continues after).
  FrictionHistory history() const;
  void restore(const FrictionHistory& h);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace igac
