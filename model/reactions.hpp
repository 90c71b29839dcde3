// SPDX-License-Identifier: BSD-3-Clause
// Reaction forces of the Dirichlet conditions: what the supports exert on
// the body, per face set named in [[dirichlet]], as a vector.
//
// The residual of every dof, prescribed ones included, R = f_int(u) - f_ext
// (f_int the law's internal force, total-Lagrangian, which is K u for the
// linear law; f_ext the pressure loads -- follower or dead as the case
// says, times the load factor -- and the body force, dead in both
// kinematics), vanishes at the free
// dofs of a converged solution (but where the contact pushes); at a
// prescribed dof it is the force the support exerts there.  The reaction of
// a face set is the sum of R over the dofs its conditions prescribe, as a
// vector (component i from the conditions on component i).  A dof prescribed
// by conditions of several face sets (a corner) counts for the first in
// case order, so the reactions of all the sets sum to the total support
// force: with the loads and the contact forces it balances to round-off
// (sum_A f_int_A = 0 since the basis sums to one).  A contact force on a
// prescribed dof goes to the support (the contact solve has no unknown
// there), so it is in the reaction: both paths pass what the contacts add
// to the residual on every dof (small deformation:
// contact_forces_on_every_dof, model/solve.hpp; large deformation:
// FiniteStrainProblem::contact_forces_on_every_dof).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "engine/follower_pressure.hpp"  // FaceElementFlags
#include "engine/total_lagrangian.hpp"
#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

class ReactionEvaluator {
 public:
  explicit ReactionEvaluator(const Model& model);
  // The reactions for the displacement u (n_cp x dim) at load factor t
  // (small deformation: 1; with load curves the time, each load at its
  // curve's factor), one per face set, in the order of first mention.
  // contact_forces: what the contacts add to the residual on every dof, in
  // dof order (each dof of a collapsed point holding its equation's force;
  // empty: none), which a support carries where it holds a dof the contact
  // pushes.  wet: per [[pressure]], the elements a fluid's pressure acts on
  // (FiniteStrainProblem::wet_elements; empty, or an empty entry: every element).
  std::vector<FaceReaction> operator()(const Eigen::MatrixXd& u, double t, const Eigen::VectorXd& contact_forces = {},
                                       const std::vector<FaceElementFlags>& wet = {}) const;
  // The incompressible limit: f_int depends on the element pressures of the
  // solve's assembler too; take them (before each call).
  void take_element_pressures(const TotalLagrangianAssembler& solve_assembler) {
    if (assembler_) assembler_->copy_multipliers(solve_assembler);
  }

 private:
  const Model& model_;
  DofMap all_free_;  // every dof an unknown: the residual of the prescribed ones too
  std::unique_ptr<HyperelasticLaw> own_law_;  // a Model made in code without a law
  std::unique_ptr<TotalLagrangianAssembler> assembler_;  // or:
  Eigen::SparseMatrix<double> linear_K_;                   // K over every dof (several materials, mixed)
  std::vector<std::string> faces_;
  std::vector<std::vector<std::pair<int, int>>> equations_;  // per face set: (equation of all_free_, component)
  std::vector<std::vector<PatchSide>> pressure_faces_;
};

// The force a displacement-driven case applies: |sum of the reaction
// components that nonzero prescribed values drive|; 0 when none is (a
// moving obstacle's force is the contact's: against a curved obstacle the
// sum of the normal forces -sum lambda_K K_K exceeds the resultant the
// supports carry, 0.0437 against 0.0410 in indented_block, so it is not
// called the applied force).
double driven_reaction(const Model& model, const std::vector<FaceReaction>& reactions);

}  // namespace igac
