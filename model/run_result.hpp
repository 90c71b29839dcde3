// SPDX-License-Identifier: BSD-3-Clause
// What a run of a model produces: displacements, contact multipliers and
// reports, errors against a reference, timings, load steps.  Plain data:
// model/solve fills it, io's writers (json_out, vtk_output) put it in files.
#pragma once

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact/pressure.hpp"
#include "contact/small_strain_contact.hpp"
#include "contact/friction_state.hpp"
#include "engine/error_norms.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/load_stepping.hpp"

namespace igac {

// The contact solve of every contact at once: the multipliers of all the
// contacts stacked in case order (Model::contacts), and their operator.
struct ContactSolve {
  ContactSolution solution;
  WeightedGapOperator op;
};

// One contact's pressure and report (RunResult::contacts, in case order):
// its block [first_multiplier, first_multiplier + num_multipliers) of the
// stacked multipliers.
struct ContactResult {
  std::string face;  // the case's face name
  int first_multiplier = 0, num_multipliers = 0;
  Eigen::VectorXd X0, normal;  // the initial contact point and the obstacle normal there
  PressureReport report;
  std::unique_ptr<ContactPressure> pressure;
  // The face starts touching at a point (a round contact: report.half_width
  // is the extent of the zone), or over an extent (a flat face on a plane:
  // no half width; contact_area says how much is pressed).
  bool has_half_width = true;
  double contact_area = 0;  // sum of K_K over the active multipliers (a length per unit thickness in 2D)
  // Large deformation: the extent in the deformed configuration and the
  // Cauchy pressure at the most pressed multiplier.
  double half_width_deformed = 0, max_pressure_cauchy = 0;
  // The normal force the contact exerts on the face, -int lambda_h n
  // dGamma_0, n the partner's normal (large deformation: the current one):
  // on a plane total_force along the normal; against a curved obstacle or a
  // second body the resultant, what balances the loads.
  Eigen::VectorXd resultant;
  // The resultant's component along the contact normal, signed as
  // report.total_force (a tie that pulls has both negative); none without
  // a resultant.  The console and summary.json report it.
  std::optional<double> resultant_along_normal() const {
    if (resultant.size() == 0 || resultant.size() != normal.size()) return std::nullopt;
    return std::copysign(std::abs(resultant.dot(normal)), report.total_force);
  }
};

// The force each obstacle exerts on the body: -sum_K lambda_K K_K over its
// multipliers (the normal force, per unit thickness in 2D, on the modelled part).
struct ObstacleReaction {
  std::string face, obstacle;
  double normal_force = 0;
  int active = 0;
  // Friction: -sum_K lambda_t,K K_K along the obstacle's tangents (one in
  // 2D, two in 3D: docs/design.md, "Friction"); empty without.
  Eigen::VectorXd tangential_force;
  // Against an edge (contact/obstacles/edge.hpp): how far the deformed face
  // reaches past it, over its second face (the extrusion into a gap
  // there); 0 when no point is past it, none against other obstacles.
  std::optional<double> extrusion;
};

// The force the supports of a [[dirichlet]] face set exert on the body
// (model/reactions.hpp), a vector of the body's dimension (per unit
// thickness in 2D, on the modelled part).
struct FaceReaction {
  std::string face;
  Eigen::VectorXd force;
};

struct Timing {
  double setup = 0, assembly = 0, factorization = 0, linear_solve = 0, contact = 0, postprocess = 0, total = 0;
};

// One point of the load curve of a large-deformation run.
struct LoadCurvePoint {
  double load_factor = 0;
  std::vector<double> contact_forces;  // sum_K -lambda_K K_K (modelled part) of every contact, in case order
  double contact_force() const { return contact_forces.empty() ? 0.0 : contact_forces.front(); }  // the first's
  double face_displacement = 0;  // mean displacement of the loaded face along the last axis
  double obstacle_displacement = 0;  // how far a moving obstacle has moved (t |motion|; along a curve curve(t) |motion|)
  // Friction: each contact's tangential force (ObstacleReaction), in case order; empty without.
  std::vector<Eigen::VectorXd> tangential_forces;
  std::vector<FaceReaction> dirichlet_reactions;  // every [[dirichlet]] face set's, at this step
};

// One converged step of a run in steps, as a restart needs it
// (io/state_file.hpp writes one per step next to its .vtu): the driver's
// state after it (large deformation; along load curves in small
// deformation t and x = [u_free; lambda]), what the path-dependent parts
// carry to the next step, and what the step added to the summary and the
// load curve.
struct StepState {
  int step = 0;  // from 1
  LoadSteppingState driver;
  // Friction's slip history (FrictionHistory: small deformation from
  // SmallStrainFriction, large from FiniteStrainFriction), and the
  // incompressible limit's multipliers (lambda_A per pressure function, at the
  // step's end); empty without.
  FrictionHistory friction;
  Eigen::VectorXd pressure_multipliers;
  LoadStepRecord record;
  LoadCurvePoint point;
};

// Who solved the linear systems, and how (summary.json "solver").
struct LinearSolverRecord {
  std::string type = "direct";        // direct | petsc
  std::string method;                 // e.g. "preonly + cholesky (mumps)", "fgmres + fieldsplit"
  std::vector<int> iterations;        // Krylov iterations per active-set iteration
  int ranks = 1;
  double peak_resident_all_ranks_gib = 0;
  // The direct solver: kappa_1 of the last matrix it factorised (the
  // stiffness with the rigid motions pinned; in large deformation the last
  // Newton matrix), estimated (engine/condition_estimate.hpp).  A result
  // holds about -log10(eps kappa) correct digits.  0: not estimated (PETSc).
  double condition_estimate = 0;
};

// A fluid's pressure (PressureSpec::fluid_entry, contact/pressure_penetration.hpp)
// at the end of the run: how many of its faces' elements it wets, the force
// it puts on the body (on the deformed faces), and the highest contact
// pressure (Cauchy) of the contacts on those faces, the seal's criterion:
// the fluid is held where the contact presses harder than it.
struct FluidReport {
  std::vector<std::string> faces;  // the [[pressure]] faces, as the case names them
  double pressure = 0;             // at the end of the run
  int wet_elements = 0, elements = 0;
  Eigen::VectorXd force;
  double peak_contact_pressure = 0;
};

struct RunResult {
  // Moved, never copied (the contacts own their pressures); said so that a
  // std::vector<RunResult> moves its elements.
  RunResult() = default;
  RunResult(RunResult&&) = default;
  RunResult& operator=(RunResult&&) = default;
  RunResult(const RunResult&) = delete;
  RunResult& operator=(const RunResult&) = delete;

  RunStatus status;  // how the run ended (engine/run_status.hpp); not_run until a solve says
  Eigen::MatrixXd u;  // n_cp x dim
  // The incompressible limit ([material] incompressible): the pressure U' =
  // lambda_A + kappa (theta_A - 1) of each pressure function, one value per
  // function of mixed_pressure_space (engine/pressure_space.hpp; the name is
  // older than the space) (TotalLagrangianAssembler::element_pressures);
  // empty otherwise.
  Eigen::VectorXd element_pressures;
  std::optional<ContactSolve> contact;      // the contact solve (every contact's multipliers)
  std::vector<ContactResult> contacts;      // one per contact, in case order (pressure files, reports, VTK)
  std::vector<ObstacleReaction> reactions;  // every contact, in case order
  std::optional<HertzSolution> hertz;
  std::optional<ErrorNorms> displacement_errors;           // against a closed form
  std::optional<std::pair<double, double>> pressure_error;  // against Hertz: (error, norm)
  double applied_force = 0;  // resultant of the pressure loads, or the driven reaction (model/reactions.hpp)
  std::vector<FaceReaction> dirichlet_reactions;            // every [[dirichlet]] face set's
  std::vector<FluidReport> fluids;                          // every fluid pressure's, in case order
  std::optional<LoadSteppingSummary> load_steps;            // large deformation only
  std::vector<LoadCurvePoint> load_curve;
  std::optional<StepState> step_state;  // a step handed to the StepObserver: what a restart needs of it
  Timing timing;
  LinearSolverRecord linear_solver;
  std::vector<std::string> warnings;  // what the solve found doubtful (printed unless quiet; summary.json)
};

// pressure.csv and pressure.svg scale r by Hertz's a and p by its p0 when
// the case has Hertz and both are positive (a zero load has no Hertz scale).
inline bool has_hertz_scale(const RunResult& r) { return r.hertz && r.hertz->a > 0 && r.hertz->p0 > 0; }

}  // namespace igac
