// SPDX-License-Identifier: BSD-3-Clause
// Large-deformation Coulomb friction against rigid obstacles (that may
// translate) and between two bodies: the tangential rows of the
// large-deformation contact (model/finite_strain_problem.hpp), in the
// same semismooth Newton.
//
// Per multiplier K (S^{p-2}, the normal one's space) dim-1 tangential
// multipliers lambda_t,K, and the weighted tangential slip increment over
// the load step: the displacement increment of the slave point X relative
// to the obstacle's (or the master's material point X' it faced at the
// start of the step), projected on the tangent plane there at the start of
// the step, weighted by B_K on the reference face,
//   s_K,j = int B_K ((u - u_prev)(X) - (u - u_prev)(X') - (c(t) - c(t_prev))) . t_j dGamma_0,
// u_prev, t_prev the last converged step, c an obstacle's translation, t_j
// the obstacle's (the master's) tangents at the projection of X + u_prev(X)
// (contact/weighted_gap.hpp, tangent_basis), X' that projection.  Two
// material points that coincide at the start of the step and move
// together (a rigid motion of both, a stuck pair) slip nothing, whatever
// the rotation; the tangent plane is the one the step starts from, so the
// rows are linear in u within a step, s = T (u - u_prev) + t0(t) - t0(t_prev)
// with T, t0 the small-deformation kernels (assemble_weighted_gaps,
// assemble_mortar_gaps) at the configuration u_prev, rebuilt at each step:
// their derivative is exact with no second-order term.  Against a plane
// the tangent plane does not turn and T is the same at every step.
//
// The Coulomb cone as in small deformation (contact/small_strain_friction.hpp),
// with c the normal complementarity scale, c_t,K the tangential one
// (finite_strain_tangential_scales), xi = lambda_t + c_t,K s_K / K_K and
// b = -f (lambda_n + c gamma_K / K_K): K is open where its normal row is
// inactive, stick where |xi| <= b, slip otherwise; against an obstacle a
// closed K whose normal multiplier is exactly 0 (it carries no force yet:
// the step's predictor extrapolates the zeros of a multiplier that was
// open) slips where xi != 0.  No converged state has such a K (an active
// row holds gamma = 0, so lambda_n < 0): the rule changes the path, never
// the solution.  The residual rows
// (forces, as the normal ones):
//   open:  K_K lambda_t = 0,   stick:  c s_K = 0,
//   slip:  K_K (lambda_t - b xi / |xi|) = 0,
// and R_u gains sum_K lambda_t,K . ds_K/du = T^T lambda_t.  The Jacobian is
// their exact derivative (linearise_slip: across the slip direction in 3D,
// along b through lambda_n and gamma), so Newton converges quadratically
// once the states settle; checked against central differences.
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "contact/mortar_gap.hpp"
#include "contact/small_strain_friction.hpp"
#include "contact/weighted_gap.hpp"
#include "engine/load_curve.hpp"

namespace igac {

// One frictional contact as the friction rows see it.
struct FrictionContact {
  const ContactFace* face = nullptr;
  const Obstacle* obstacle = nullptr;  // at its reference position; or
  const MasterSurface* master = nullptr;  // a master face (at its reference position: copied)
  MortarIntegration integration = MortarIntegration::element;
  Eigen::VectorXd motion;              // an obstacle's translation at curve(t) = 1 (empty: none)
  const LoadCurve* curve = nullptr;    // (no points: the factor is t)
  ContactLaw law;                      // (contact/interface_law.hpp)
  int offset = 0;                      // its first multiplier
};

// The tangential scale c_t,K of large deformation: in 3D tangential_scales
// (E / h_K: the slip directions on the disc settle with the tangential
// stiffness), in 2D E / (10 h_K), h_K = K_K, E = c_n h (d = +-1: c_t only
// weighs the stick/slip decision, and a smaller one keeps a stuck
// multiplier's decision on lambda_t rather than on the slip a line-search
// step leaves; docs/benchmarks.md, "Friction in large deformation").
Eigen::VectorXd finite_strain_tangential_scales(double cn, double mesh_size, const Eigen::VectorXd& weights, int dim);
inline constexpr double kTangentialScale2D = 0.1;

class FiniteStrainFriction {
 public:
  using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  // `dofs` numbers the free unknowns; `weights` K_K of every multiplier
  // (m); c the normal rows' complementarity scale (stress per length), c_t
  // the tangential one per multiplier (finite_strain_tangential_scales).
  FiniteStrainFriction(const Body& body, const DofMap& dofs, const std::vector<FrictionContact>& contacts,
                       const Eigen::VectorXd& weights, double complementarity_scale,
                       const Eigen::VectorXd& tangential_scale);
  int rows() const { return int(T_free_.rows()); }  // m (dim-1)
  int per_multiplier() const { return nt_; }
  // T: d s / du on the free equations (rows() x n), for the step's start.
  const RowSparse& slip_rows() const { return T_free_; }

  // The weighted tangential position T u + t0(t) of the body relative to the
  // obstacles, u per control point (n_cp x dim, prescribed values included).
  Eigen::VectorXd position(double t, const Eigen::MatrixXd& u) const;
  // The converged state the next step starts from: the slip counts from it,
  // T and t0 are taken there; a new time adds the last step's slip to the
  // accumulated one.
  void begin_step(double t, const Eigen::MatrixXd& u);
  // The history after a converged step (the slip accumulated up to the
  // start of the step and that start's time), and back to it: `u_from` the
  // converged state at h.from, from which T and t0 are taken again.
  FrictionHistory history() const;
  void restore(const FrictionHistory& h, const Eigen::MatrixXd& u_from);

  // The state of each multiplier (FrictionState, friction_state.hpp)
  // for the normal multipliers, their weighted gaps gamma, the normal
  // rows' activity and the tangential multipliers, at (t, u).
  std::vector<char> states(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n,
                           const Eigen::VectorXd& gamma, const std::vector<char>& normal_active,
                           const Eigen::VectorXd& lambda_t) const;
  // Adds T^T lambda_t to r_u (n) and writes the tangential rows r_t.
  void residual(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n, const Eigen::VectorXd& gamma,
                const std::vector<char>& normal_active, const Eigen::VectorXd& lambda_t,
                Eigen::Ref<Eigen::VectorXd> r_u, Eigen::Ref<Eigen::VectorXd> r_t) const;
  // Their derivatives as the Newton matrix's constraint rows
  // (engine/block_jacobian.hpp), numbered after the m normal ones: the
  // tangential rows T of B (slip_rows(); their columns T^T in the u rows),
  // and per row stick: s = c (c T_K du), open: d = K_K, slip: through M_B
  // (its T rows and the gap row G_K) and M_l (its lambda_t and lambda_n).
  // Indices of mixed_B and mixed_lambda are among all m + rows() constraints.
  struct TangentialRows {
    Eigen::VectorXd s, d;  // rows() each
    std::vector<Eigen::Triplet<double>> mixed_B, mixed_lambda;
  };
  void constraint_rows(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n,
                       const Eigen::VectorXd& gamma, const std::vector<char>& normal_active,
                       const Eigen::VectorXd& lambda_t, TangentialRows& out) const;
  // sum_K lambda_t,K . ds_K/du on every dof (num_dofs): T_all^T lambda_t.
  Eigen::VectorXd forces_on_every_dof(const Eigen::VectorXd& lambda_t) const { return T_all_.transpose() * lambda_t; }
  // The tangential force on the (slave) face of contact k, -sum_K lambda_t,K . int B_K t_j.
  Eigen::VectorXd tangential_resultant(int k, const Eigen::VectorXd& lambda_t) const;
  // The slip accumulated from t = 0 to (t, u), u a state of the step after
  // the last begin_step (/ K_K), per row.
  Eigen::VectorXd accumulated_slip(double t, const Eigen::MatrixXd& u) const;

 private:
  int m_ = 0, nt_ = 0, n_ = 0, dim_ = 0;
  double c_ = 1;
  Eigen::VectorXd ct_;  // c_t per multiplier
  std::vector<FrictionContact> contacts_;
  std::vector<std::unique_ptr<MasterSurface>> masters_;  // per contact: moved to each step's start (null: an obstacle)
  const Body* body_;
  const DofMap* dofs_;
  DofMap every_;                           // the body's dofs, none prescribed: T_all's columns
  RowSparse T_all_, T_free_;
  Eigen::MatrixXd row_tangent_;            // per row: int B_K t_j on the slave face (m nt x dim)
  std::vector<Eigen::VectorXd> t0_;        // per contact: the rows of its motion at curve = 1 (m nt)
  Eigen::VectorXd weights_, friction_, row_weights_;  // row_weights_: K_K per tangential row
  std::vector<const InterfaceLaw*> laws_;  // per multiplier (contact/interface_law.hpp)
  std::vector<char> on_obstacle_;          // per multiplier: its contact is against an obstacle (not a master)
  // history
  bool started_ = false;
  double t_prev_ = 0;
  Eigen::VectorXd tau_prev_, slip_total_;

  Eigen::VectorXd slip(double t, const Eigen::MatrixXd& u) const { return position(t, u) - tau_prev_; }
  // T, t0 and row_tangent_ at the configuration u, the obstacles where they stand at t.
  void assemble_rows(double t, const Eigen::MatrixXd& u);
};

}  // namespace igac
