// SPDX-License-Identifier: BSD-3-Clause
// Solving a model: one Cholesky solve for a linear case, the active-set
// contact solve when the case has an obstacle, the load-stepping Newton
// driver for a hyperelastic law.  No Newton loop, no multipliers and no
// stress recovery unless the case needs them.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "model/finite_strain_problem.hpp"
#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

// `on_step` (large deformation, load curves) sees the state after each converged load step.
using StepObserver = std::function<void(const RunResult&, double load_factor)>;
// The same case one refinement below, already solved (a study's previous
// level): where a contact run at --refine r >= 1 starts from (nested
// iteration, contact/coarse_start).  Without it, the PETSc path solves that
// case first itself; the direct path starts from the closed gaps.
struct CoarserRun {
  const Model* model = nullptr;
  const RunResult* result = nullptr;
};
// How a solve is driven, apart from what it models (the Model): what it
// prints, where it continues from, where it stops and whom it tells.
struct RunControl {
  bool quiet = false;  // no progress lines
  // A restart (app: igac run --restart): the steps an earlier run of the
  // same case completed, in order; the solve continues after the last.
  std::vector<StepState> resume;
  int stop_after_step = 0;  // > 0: stop once this many steps are done (igac run --stop-after-step)
  // Called once the solve has checked what only a solve can (the body is
  // held, something loads it), before the long work: the console's header,
  // so that bad input stays one line.
  std::function<void()> on_solve_start;
  StepObserver on_step;  // large deformation, load curves: after each converged step
  CoarserRun coarser;    // a study's previous level (contact at --refine >= 1)
};
// A run that prints nothing (tests, the Python module, nested solves), with its step observer.
inline RunControl quiet_run(StepObserver on_step = {}) {
  RunControl control;
  control.quiet = true;
  control.on_step = std::move(on_step);
  return control;
}
RunResult solve_model(const Model& model, const RunControl& control = {});
// The large-deformation path (model/solve_finite_strain.cpp).
RunResult solve_finite_strain(const Model& model, const RunControl& control);
// What the large-deformation problem of a model is made of: its body, dofs,
// laws (one per body), pressures, contacts (obstacles and master faces) and
// the complementarity scale.  Borrows from `model`.
FiniteStrainSetup finite_strain_setup(const Model& model);

// Throws InputError (naming the case) when free rigid motions (`modes`, not
// held by Dirichlet conditions) are not held: no contact, a contact that
// cannot stop them, or a load `f` that pulls the body off the obstacle.
// `op`: the contact operator when the caller has it (else assembled here,
// and only when some rigid motion is free).
void check_body_is_held(const Model& model, const RigidModes& modes, const Eigen::VectorXd& f,
                        const WeightedGapOperator* op = nullptr);
// The stacked weighted-gap operator of every contact (small deformation),
// with the tangential rows of the frictional ones; `motion_factor` t puts
// each moving obstacle at t * motion (1: where the case has it) and leaves
// (1 - t) of each interference fit's overlap in the gaps.
WeightedGapOperator assemble_contact_operator(const Model& model, double motion_factor = 1.0);
// The same at time t of the load curves: each moving obstacle at curve(t) *
// motion, (1 - min(t, 1)) of each interference fit's overlap left.
WeightedGapOperator assemble_contact_operator_at_time(const Model& model, double time);
// Does contact c's operator change along the load (a moving partner, an
// interference fit being removed)?
bool changes_with_the_load(const Model::Contact& c);
// What the contacts of a small-deformation solve add to the residual
// K u - f on every dof, prescribed ones included: G^T lambda + T^T lambda_t
// of the operator the solve used, with its couplings to the prescribed dofs
// (G_held, T_held), in dof order (control point * dim + component; each dof
// of a collapsed point holds its equation's).  On a prescribed dof the
// support carries it: the reactions take it (ReactionEvaluator), as in large
// deformation (FiniteStrainProblem::contact_forces_on_every_dof).
Eigen::VectorXd contact_forces_on_every_dof(const Model& model, const ContactSolve& contact);
// Per contact: the normal force -sum lambda_K K_K of its multipliers and how many are active.
// With friction (lambda_t not empty) also the tangential force -sum lambda_t,K K_K along the obstacle's tangents.
std::vector<ObstacleReaction> obstacle_reactions(const Model& model, const Eigen::VectorXd& lambda,
                                                const Eigen::VectorXd& weights, const std::vector<char>& active,
                                                const Eigen::VectorXd& lambda_t = {});
// Each reaction's extrusion (ObstacleReaction::extrusion): the largest
// reach of contact i's deformed face (displacement u, load time t) past its
// obstacle's edge, sampled at p + 2 points a direction of each face
// element, its ends included.  Contacts
// against an obstacle without an edge, or a body, keep none.
void add_extrusions(const Model& model, const Eigen::MatrixXd& u, double t, std::vector<ObstacleReaction>& reactions);
// Every contact's pressure and report (RunResult::contacts, case order:
// the pressure files, the reports, ParaView), from the stacked s.solution
// and s.op.weights.
std::vector<ContactResult> report_contacts(const Model& model, const ContactSolve& s);
// |int P n dGamma| summed over the pressure loads (the modelled part), at
// their values or (`time`) at their curves' factors at that time.
double pressure_resultant(const Model& model, std::optional<double> time = {});
// Adds the [[traction]] loads (dead, on the reference faces) to f, numbered
// by `dofs` (the model's, or one of its variants): at their values, or times
// their curves at `time`.
void add_traction_loads(const Model& model, const DofMap& dofs, std::optional<double> time, Eigen::VectorXd& f);
// A master body moved rigidly with its supports ([[contact]] master_motion):
// its motion (at time: curve(time) x motion) added to every control point of
// that body, whose solved displacement is relative to the moved supports.
void add_master_motions(const Model& model, Eigen::MatrixXd& u, std::optional<double> time = {});

}  // namespace igac
