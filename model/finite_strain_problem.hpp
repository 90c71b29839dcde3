// SPDX-License-Identifier: BSD-3-Clause
// The large-deformation problem (model/: it composes the body's stored
// energy, its loads and its contact interfaces), as a NonlinearProblem for the
// load-stepping driver (engine/load_stepping.hpp): total-Lagrangian
// elasticity with a hyperelastic law, follower (or dead) pressure, dead
// tractions and body force, ramped prescribed displacements, and the weighted-gap contact of the paper
// (Appendix 1) at the CURRENT position, solved by a semismooth Newton method.
//
// Unknowns x = [u_free (n); lambda (m)], and with friction on some contact
// the tangential multipliers [lambda_t (m (dim-1))] after them
// (contact/finite_strain_friction.hpp; the Newton matrix is then handed over
// whole, BlockJacobian::general).  With a mixed patch, last, every pressure
// function's dilatation z_A = theta_A - 1 (the u-p Newton of the mixed
// formulation, docs/design.md "Nearly incompressible solids"; one per
// function of TotalLagrangianAssembler::pressure_space(), continuous on a
// mixed patch, one per element elsewhere): the pressure is U'(theta_A),
// updated by Newton from the linearised constraint (dtheta_A = mB_A du +
// Pi_A J - theta_A, Pi_A J = (1/m_A) int N_A J dX), not recomputed from u
// as K (Pi_A J - 1), whose error after a rotation-like step is K times the
// step squared.  Its rows
//   R_z_A = mu_s m_A^{(d-1)/d} (Pi_A J - 1 - z_A)
// (zero at the condensed formulation's solution, so the converged state is
// the same) are condensed function by function in the linear solve
// (BlockJacobian::local): the matrix the solvers see keeps its pattern and
// symmetry.  Scaled with the shear modulus mu_s in the residual (the line
// search's |R|_2), with the bulk modulus in the convergence test
// (residual_weights): there U''(1) m_A^{(d-1)/d} |Pi_A J - theta_A|, about
// the force the pressure error K (Pi_A J - theta_A) puts on the support's
// nodes, must fall below the force tolerance as the displacement rows do.  With gamma_K(u) = int B_K g_n(X + u) dGamma_0
// (weighted gaps integrated on the reference face, K_K = int B_K dGamma_0):
//   R_u       = f_int(u) - t f_ext(u) + sum_K lambda_K dgamma_K/du,
//   R_lambda_K = c gamma_K            where K_K lambda_K + c gamma_K < 0 (active),
//              = K_K lambda_K          otherwise (inactive: lambda_K = 0),
// c = E / h so both rows are forces.  dgamma_K/du_(A,i) = int B_K N_A n_i(x)
// (exact for any obstacle: d g_n / dx = n), and its derivative, the
// curvature term int B_K N_A N_B dn/dx, enters the tangent for a curved
// obstacle.  The Jacobian is the exact derivative of this piecewise smooth
// residual, so Newton converges quadratically once the active set settles.
#pragma once

#include <memory>
#include <vector>

#include "contact/finite_strain_friction.hpp"
#include "contact/finite_strain_mortar.hpp"
#include "contact/pressure_penetration.hpp"
#include "contact/weighted_gap.hpp"
#include "engine/linear_static.hpp"
#include "engine/load_curve.hpp"
#include "engine/load_stepping.hpp"
#include "engine/total_lagrangian.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {

struct PressureLoad {
  std::vector<PatchSide> faces;
  double value = 0;
  LoadCurve curve;  // the pressure at t is curve(t) * value (engine/load_curve.hpp; no points: t)
  // A fluid's pressure (contact/pressure_penetration.hpp): it acts on the
  // elements of `faces` the fluid reaches from its entry without crossing
  // a pressed one, the contacts' state at the start of the load step, and
  // the step is solved again while that set changes (augment).  Null: on
  // every element.
  std::shared_ptr<const FluidFront> fluid;
};

// A dead traction t (force per unit reference area, any direction) on
// reference faces: in total Lagrangian a constant external force
// int N_A t dA (add_dead_traction), no load stiffness.
struct TractionLoad {
  std::vector<PatchSide> faces;
  Eigen::VectorXd value;
  LoadCurve curve;  // the traction at t is curve(t) * value (no points: t)
};

struct FiniteStrainSetup {
  const Body* body = nullptr;
  const DofMap* dofs = nullptr;               // prescribed values at full load (ramped with t)
  // With load curves, per dof: the curve of the condition that prescribes
  // it (its value at t is curve(t) * value); empty: t * value.
  std::vector<const LoadCurve*> prescribed_curves;
  const HyperelasticLaw* law = nullptr;
  Formulation formulation = Formulation::displacement;  // engine/volumetric_projection.hpp
  // Several bodies (or materials): the law and formulation of each patch of
  // `body`; empty: `law` and `formulation` for every patch.
  std::vector<const HyperelasticLaw*> patch_laws;
  std::vector<Formulation> patch_formulations;
  std::vector<PressureLoad> pressures;
  bool follower_pressure = true;
  std::vector<TractionLoad> tractions;
  // A dead body force per unit reference volume (empty: none), at t
  // body_force_curve(t) * body_force (engine/assembly.hpp body_force_load).
  Eigen::VectorXd body_force;
  LoadCurve body_force_curve;
  // One face pressed on one rigid obstacle; several are stacked, each with its
  // own multipliers (S^{p-2} on its face), in order.  Empty: no multipliers.
  // Or a face pressed on a face of a second deformable body (`master` not
  // null, at its reference position; contact/finite_strain_mortar.hpp):
  // both move, the master is projected on where it stands.
  struct Contact {
    const ContactFace* face = nullptr;
    const Obstacle* obstacle = nullptr;  // at its reference position
    Eigen::VectorXd motion;              // empty, or its translation at full load (ramped with t)
    const MasterSurface* master = nullptr;
    MortarIntegration integration = MortarIntegration::element;
    LoadCurve curve;                     // the translation at t is curve(t) * motion (no points: t)
    // Its interface law and coefficient (contact/interface_law.hpp): a law
    // with tangential rows brings contact/finite_strain_friction.hpp in.
    ContactLaw law;
    // The faces start overlapping on purpose: the overlap of the reference
    // configuration is removed with the load (Model::Contact::interference).
    bool interference = false;
  };
  std::vector<Contact> contacts;
  // A distributed run's share (engine/assembly.hpp; empty: the whole
  // problem here): each process evaluates the elasticity of its elements
  // and the sums make every process's residual and tangent the whole ones;
  // loads and contact are evaluated whole on every process.  Ignored with
  // a mixed patch (evaluated whole on every process).
  ProcessShare share;
  double complementarity_scale = 1;           // c, stress per length
  double mesh_size = 0;                       // h of c = E / h: friction's c_t,K (finite_strain_tangential_scales; 0: c)
  // > 0: the mixed patches are incompressible (K = infinity), their
  // pressures updated by augment() until max |theta_A - 1| <= this
  // (TotalLagrangianAssembler::make_incompressible).
  double incompressibility_tolerance = 0;
};

class FiniteStrainProblem final : public NonlinearProblem {
 public:
  explicit FiniteStrainProblem(FiniteStrainSetup setup);
  int size() const override { return n_ + m_ + mt_ + nz_; }
  int num_displacements() const { return n_; }
  int num_multipliers() const { return m_; }
  // Tangential multipliers (0 without friction), after the normal ones.
  int num_tangential() const { return mt_; }
  // Dilatations (the u-p Newton of a mixed patch), after them: one per
  // pressure function of the body, 0 without a mixed patch.
  int num_local() const { return nz_; }
  Eigen::VectorXd residual_weights() const override { return weights_of_rows_; }
  void begin_step(double t, const Eigen::VectorXd& x) override;
  bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) override;
  bool jacobian(double t, const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& J) override;
  // K = K_T + load stiffness + the obstacle's curvature term (the TL
  // pattern), B = dgamma/du (m x n), s = c on active rows, d = K_K on
  // inactive ones, and the body's rigid motions (held by contact).
  bool block_jacobian(double t, const Eigen::VectorXd& x, BlockJacobian& J) override;
  // The normal rows' set decided again on gamma + B du and lambda + dlambda,
  // the last block_jacobian's gaps and multipliers moved by dx; the rows of
  // J and rhs rewritten for it at x.  False when nothing changes, or the
  // set was already tried since block_jacobian (a cycle).  Not with
  // friction: its whole matrix is factorised by LU, and an LU per change of
  // set cost more than the Newton iterations it saved (docs/design.md,
  // "Large deformation").
  bool relinearise_active_set(const Eigen::VectorXd& dx, BlockJacobian& J, Eigen::VectorXd& rhs) override;
  // The active set of (t, x), K_K lambda_K + c gamma_K(t, x) < 0: the one
  // residual and Jacobian at (t, x) use (each decides it from its own x).
  int active_set_size(double t, const Eigen::VectorXd& x) const override;
  std::vector<char> active_set(double t, const Eigen::VectorXd& x) const override;
  double force_scale(double t, const Eigen::VectorXd& x) override;
  // The incompressible limit's Uzawa update (TotalLagrangianAssembler::augment),
  // and the fluid pressures' wet elements from the converged contact (true:
  // either changed, the step is solved again).
  bool augment(double t, const Eigen::VectorXd& x) override;
  void keep_augmentation(bool accepted) override { tl_->keep_multipliers(accepted); }
  std::string unsettled_augmentation() const override { return unsettled_; }
  // The elements each pressure acts on (PressureLoad::fluid; empty for a
  // pressure on whole faces), as the last step left them.
  const std::vector<FaceElementFlags>& wet_elements() const { return wet_; }
  // The body's assembler (its pressures in the incompressible limit).
  const TotalLagrangianAssembler& assembler() const { return *tl_; }
  // Friction: per multiplier open, stick or slip (FrictionState) at (t, x),
  // and the slip accumulated from t = 0 (per tangential multiplier, / K_K).
  std::vector<char> friction_states(double t, const Eigen::VectorXd& x) const;
  Eigen::VectorXd accumulated_slip(double t, const Eigen::VectorXd& x) const;

  // What the steps carry beyond x, after a converged step: the friction
  // history (empty without friction) and the incompressible limit's
  // pressure multipliers (empty otherwise).  A restart restores them before its
  // first step, x_from the converged state at the friction history's `from`
  // (the driver's x_old).
  struct History {
    FrictionHistory friction;
    Eigen::VectorXd pressure_multipliers;
  };
  History history() const;
  void restore(const History& h, const Eigen::VectorXd& x_from);

  // Displacement per control point at load factor t.
  Eigen::MatrixXd displacement(double t, const Eigen::VectorXd& x) const;
  // Weighted gaps gamma_K / K_K at the current position.
  Eigen::VectorXd weighted_gaps(double t, const Eigen::VectorXd& x) const;
  // The force each contact exerts on its face, -int lambda_h n dGamma_0
  // with n the obstacle's (the master's) current normal: a vector per
  // contact.  On a plane it is the total force along the normal; on a
  // surface that curves or deforms the resultant, what balances the loads.
  std::vector<Eigen::VectorXd> contact_resultants(double t, const Eigen::VectorXd& x) const;
  // sum_K lambda_K dgamma_K/du on every dof (num_dofs, prescribed ones
  // too): what the contact adds to the residual, and what a support holding
  // a dof the contact pushes must also carry (model/reactions.hpp).
  Eigen::VectorXd contact_forces_on_every_dof(double t, const Eigen::VectorXd& x) const;
  const Eigen::VectorXd& multiplier_weights() const { return weights_; }
  // First multiplier of contact k (k = number of contacts: the total).
  int multiplier_offset(int k) const { return offsets_[k]; }
  // A starting guess for a body held only by contact: the multipliers
  // nearest to the obstacle are made active by a small negative lambda.
  void activate_nearest(Eigen::VectorXd& x, int count) const;

 private:
  // What evaluate_contact computes besides the gaps.
  enum class ContactTerms {
    gaps,        // gamma alone
    forces,      // and the force G^T lambda on the free equations, the resultants
    linearised,  // and G itself, the resultants (and the curvature terms where K is given)
  };
  struct ContactEval {
    Eigen::VectorXd gamma;                                // m
    std::vector<Eigen::Triplet<double>> G;                // (K, free eq, value): linearised
    Eigen::VectorXd force;                                // G^T lambda: forces
    std::vector<Eigen::VectorXd> resultants;              // per contact (forces, linearised): the force on its face
  };
  // gamma and what `terms` asks for at displacement u (ContactQuadrature,
  // the one face loop; a master face: the mortar points); when K is not
  // null, adds the curvature term (the obstacle's int lambda B N_A N_B dn/dx,
  // a master's lambda int B Delta delta g) to it, and a master's
  // slave-master blocks to K_coupling.  `numbering`: the equations G's
  // columns and the force count (null: the problem's own).
  void evaluate_contact(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda,
                        Eigen::SparseMatrix<double>* K, ContactEval& out, ContactTerms terms,
                        std::vector<Eigen::Triplet<double>>* K_coupling = nullptr,
                        const DofMap* numbering = nullptr) const;
  // Adds the dead loads at t to f_ext, the tractions and the body force (no
  // load stiffness: constant in u).
  void add_dead_loads(double t, Eigen::VectorXd& f_ext) const;
  Eigen::VectorXd body_force_load_;  // int N_A b dX at body_force_curve = 1 (empty: none)
  std::vector<char> decide_active(const Eigen::VectorXd& gamma, const Eigen::VectorXd& lambda) const;

  FiniteStrainSetup s_;
  int n_ = 0, m_ = 0, mt_ = 0, nz_ = 0;
  Eigen::VectorXd tangential(const Eigen::VectorXd& x) const { return x.segment(n_ + m_, mt_); }
  // The u-p Newton (num_local): the dilatation rows' scale mu_s m_A^{(d-1)/d}
  // (1 for a displacement patch's z_A, which stays 0), and the weights
  // of the convergence test (1 on the other rows, U''(1) / mu_s on these).
  Eigen::VectorXd local_scale_, weights_of_rows_;
  // r_z = h (Pi_A J - 1 - z) from the assembler's per-function values
  Eigen::VectorXd local_residual(const TotalLagrangianAssembler::LocalDilatation& local, const Eigen::VectorXd& z) const;
  std::vector<const InterfaceLaw*> laws_;  // per multiplier
  Eigen::VectorXd gamma_start_;             // a tie's g_0 per multiplier (empty: no tie)
  Eigen::VectorXd overlap_;                 // an interference fit's max(0, -g_0) per multiplier (empty: none)
  std::unique_ptr<FiniteStrainFriction> friction_;  // null: frictionless
  Eigen::VectorXd normal_multipliers(const Eigen::VectorXd& x) const { return x.segment(n_, m_); }
  std::unique_ptr<TotalLagrangianAssembler> tl_;
  Eigen::VectorXd weights_;          // K_K
  // f_int and K of the elasticity (TotalLagrangianAssembler::assemble), summed
  // over the processes of a distributed run (FiniteStrainSetup::share); false
  // on every process when the state is inadmissible on one.
  bool elasticity(const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K,
                  const Eigen::VectorXd* z = nullptr, TotalLagrangianAssembler::LocalDilatation* local = nullptr) const;
  RigidModes modes_;                 // of the free displacements
  BlockJacobian blocks_;             // jacobian()'s, reused across calls
  // block_jacobian()'s contact terms and slave-master blocks: their triplet
  // buffers keep their memory from one Jacobian to the next
  ContactEval jacobian_contact_;
  std::vector<Eigen::Triplet<double>> jacobian_coupling_;
  FiniteStrainFriction::TangentialRows jacobian_tangential_;
  std::vector<int> contact_equations_;  // every equation a contact row may touch (BlockJacobian::constraint_equations)  // (the friction rows: their memory kept)
  // The follower pressures' load stiffness, of the loaded faces' pattern
  // (follower_pressure_pattern; empty: no follower load): handed over as
  // BlockJacobian::K_coupling, so that K stays the symmetric tangent a
  // factorisation uses, without a copy of it.
  Eigen::SparseMatrix<double> load_stiffness_;
  // per pressure: the elements it acts on (empty: every element), and their
  // update from the contact state x (true when they change)
  std::vector<FaceElementFlags> wet_;
  bool update_wet_elements(const Eigen::VectorXd& x);
  std::string unsettled_;  // what the last augment() that asked for another solve left unsettled
  const FaceElementFlags* wet(size_t pressure) const { return wet_[pressure].empty() ? nullptr : &wet_[pressure]; }
  std::vector<ContactQuadrature> contact_quadratures_;  // per contact: tabulated once
  mutable std::vector<MortarPointCache> mortar_points_;  // per contact: its last state's mortar points
  std::vector<int> offsets_;         // first multiplier of each contact
  // per contact: its master surface, moved to every state asked about (null: an obstacle)
  std::vector<std::unique_ptr<MasterSurface>> masters_;
  // The gaps of the last residual's (t, x): the driver asks the active set
  // of the state whose residual it has just evaluated (a mortar evaluation saved).
  mutable double last_t_ = 0;
  mutable Eigen::VectorXd last_x_, last_gamma_;
  // The last block_jacobian's state and the set its J holds (changed by
  // relinearise_active_set).
  struct JacobianPoint {
    Eigen::VectorXd gamma, lambda;
    std::vector<char> active;
    std::vector<std::vector<char>> visited;  // the sets tried from this point
  } at_jacobian_;
  Eigen::VectorXd gaps_at(double t, const Eigen::VectorXd& x) const;
};

}  // namespace igac
