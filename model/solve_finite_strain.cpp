// SPDX-License-Identifier: BSD-3-Clause
// The large-deformation path of solve_model: a FiniteStrainProblem driven by
// the load-stepping Newton driver, with the contact report in the reference
// and the deformed configuration and a load curve per step.
#include <chrono>
#include <cmath>
#include <mutex>
#include <optional>
#include <fmt/format.h>

#include "model/finite_strain_problem.hpp"
#include "engine/stopwatch.hpp"
#include "engine/face_quadrature.hpp"
#include "engine/follower_pressure.hpp"
#include "engine/linear_static.hpp"
#include "model/load_history.hpp"
#include "model/petsc_run.hpp"
#include "model/progress.hpp"
#include "model/reactions.hpp"
#include "model/references.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

// Each fluid pressure's report (RunResult::fluids) at the end of the run:
// its wet elements, its resultant on the deformed faces (every dof free, so
// that the held ones count too), the highest Cauchy pressure of the
// contacts whose face shares a side with it.
std::vector<FluidReport> fluid_reports(const Model& m, const FiniteStrainSetup& setup,
                                       const std::vector<FaceElementFlags>& wet, double t, const RunResult& r) {
  std::vector<FluidReport> out;
  const int dim = m.body.space_dim();
  for (size_t i = 0; i < setup.pressures.size(); ++i) {
    const PressureLoad& p = setup.pressures[i];
    if (!p.fluid) continue;
    FluidReport f;
    f.faces = m.spec.pressure[i].faces;
    f.pressure = p.curve(t) * p.value;
    for (const std::vector<char>& side : wet[i]) {
      f.elements += int(side.size());
      f.wet_elements += int(std::count(side.begin(), side.end(), char(1)));
    }
    const DofMap every(m.body, {});
    Eigen::VectorXd force = Eigen::VectorXd::Zero(every.num_free());
    if (setup.follower_pressure) add_follower_pressure(m.body, every, p.faces, f.pressure, r.u, force, nullptr, &wet[i]);
    else add_dead_pressure(m.body, every, p.faces, f.pressure, force, &wet[i]);
    f.force = Eigen::VectorXd::Zero(dim);
    for (int dof = 0; dof < every.num_dofs(); ++dof)  // each equation once (a collapsed point's dofs share one)
      if (const int eq = every.equation(dof); eq >= 0 && force[eq] != 0) {
        f.force[dof % dim] += force[eq];
        force[eq] = 0;
      }
    for (size_t k = 0; k < setup.contacts.size() && k < r.contacts.size(); ++k)
      for (const ContactSide& side : setup.contacts[k].face->sides)
        if (std::find(p.faces.begin(), p.faces.end(), side.side) != p.faces.end())
          f.peak_contact_pressure = std::max(f.peak_contact_pressure, r.contacts[k].max_pressure_cauchy);
    out.push_back(std::move(f));
  }
  return out;
}

// The deformed extent and the Cauchy peak of contact `c` (face `cf`) for
// the displacement u (n_cp x dim).
void deformed_report(const Model& m, const ContactFace& cf, const Eigen::VectorXd& lambda, const Eigen::MatrixXd& u,
                     ContactResult& c) {
  if (c.report.active == 0) return;  // released (or never touched): no zone, no peak
  // Deformed extent: the face point at the reference half width, displaced.
  double best = std::numeric_limits<double>::infinity();
  int K_max = 0;  // the most pressed multiplier, numbered on the face
  for (int K = 0; K < c.num_multipliers; ++K)
    if (-lambda[c.first_multiplier + K] > -lambda[c.first_multiplier + K_max]) K_max = K;
  std::vector<PatchSide> sides;
  std::vector<PatchQuadrature> quads;
  for (const ContactSide& side : cf.sides) {
    sides.push_back(side.side);
    quads.push_back(side.quadrature(10));
  }
  FaceQuadrature(std::move(sides), std::move(quads)).for_each_element([&](int, const auto& v) {
    for (int k = 0; k < v.n_q; ++k) {
      const Eigen::VectorXd X = v.X[k];
      const double d = std::abs(c.pressure->r_of(X) - c.report.half_width);
      if (d < best) {
        best = d;
        Eigen::VectorXd xk = X;
        for (int a = 0; a < v.n_loc; ++a) xk += v.N(k, a) * u.row(v.cps[a]).transpose();
        c.half_width_deformed = c.pressure->r_of(xk);
      }
    }
  });
  // Cauchy pressure at the most pressed multiplier: nominal / surface stretch.
  const ContactSide* side = &cf.sides.front();
  for (const ContactSide& s : cf.sides)
    if (K_max >= s.first_multiplier) side = &s;
  const Eigen::VectorXd xi = side->space.anchor(K_max - side->first_multiplier);
  Eigen::MatrixXd uf(side->face_cps.size(), m.body.space_dim());
  for (size_t a = 0; a < side->face_cps.size(); ++a) uf.row(a) = u.row(side->face_cps[a]);
  Eigen::MatrixXd dudxi;
  side->face_patch.field(uf, xi, &dudxi);
  const Eigen::MatrixXd T0 = side->face_patch.jacobian(xi), T = T0 + dudxi;
  const double stretch = face_area_vector(side->face(), T).norm() / face_area_vector(side->face(), T0).norm();
  c.max_pressure_cauchy = c.report.max_pressure / stretch;
}

// Contact report of state x at load factor t: every contact's, in r.contacts.
void fill_contact(const Model& m, FiniteStrainProblem& problem, double t, const Eigen::VectorXd& x, RunResult& r) {
  ContactSolve& c = r.contact.emplace();
  const int n = problem.num_displacements(), mm = problem.num_multipliers();
  c.solution.u = x.head(n);
  c.solution.lambda = x.segment(n, mm);
  if (problem.num_tangential() > 0) {  // friction
    c.solution.lambda_t = x.segment(n + mm, problem.num_tangential());
    c.solution.friction_state = problem.friction_states(t, x);
    c.solution.slip = problem.accumulated_slip(t, x);
  }
  c.solution.active = problem.active_set(t, x);
  c.solution.weighted_gap = problem.weighted_gaps(t, x);
  c.solution.converged = true;
  c.op.weights = problem.multiplier_weights();
  r.reactions = obstacle_reactions(m, c.solution.lambda, c.op.weights, c.solution.active, c.solution.lambda_t);
  add_extrusions(m, r.u, t, r.reactions);
  r.contacts = report_contacts(m, c);
  const std::vector<Eigen::VectorXd> resultants = problem.contact_resultants(t, x);
  for (size_t i = 0; i < r.contacts.size(); ++i) {
    deformed_report(m, *m.contacts[i].face, c.solution.lambda, r.u, r.contacts[i]);
    r.contacts[i].resultant = resultants[i];
  }
}

// What loads a large-deformation body: something, nothing (u = 0 solves
// it), or nothing but an obstacle that moves away from it (along the
// obstacle's normal where the face is nearest).  A face that starts inside
// its obstacle is pushed out: a load.
enum class Loading { some, none, obstacle_leaves };
Loading loading_of(const Model& m) {
  for (const auto& p : m.spec.pressure)
    if (p.value != 0) return Loading::some;
  for (const auto& l : m.spec.traction)
    for (double v : l.value)
      if (v != 0) return Loading::some;
  for (const auto& d : m.spec.dirichlet)
    if (d.value != 0) return Loading::some;
  for (double b : m.spec.body_force)
    if (b != 0) return Loading::some;
  bool leaves = false;
  for (const auto& c : m.contacts) {
    const auto [X0, n0] = initial_contact_point(*c.face, *c.obstacle);
    if (c.obstacle->probe(X0).gap < 0) return Loading::some;
    if (c.motion.size() == 0 || !(c.motion.norm() > 0)) continue;
    const double toward = c.motion.dot(n0);  // the normal points from the obstacle into the body
    if (toward > 1e-12 * c.motion.norm()) return Loading::some;
    if (toward < -1e-12 * c.motion.norm()) leaves = true;
  }
  return leaves ? Loading::obstacle_leaves : Loading::none;
}

}  // namespace

FiniteStrainSetup finite_strain_setup(const Model& m) {
  const Body& body = m.body;
  FiniteStrainSetup setup;
  setup.body = &body;
  setup.dofs = m.dofs.get();
  setup.law = m.law.get();
  setup.formulation = m.spec.formulation;
  if (m.parts.size() > 1) {  // several bodies: each patch with its body's law
    setup.patch_formulations = m.patch_formulations();
    setup.patch_laws = m.patch_laws();
  }
  for (const auto& p : m.spec.pressure) {
    setup.pressures.push_back({resolve_faces(m, p.faces, "pressure"), p.value, p.curve, nullptr});
    if (!p.fluid_entry.empty())
      setup.pressures.back().fluid = std::make_shared<const FluidFront>(
          body, setup.pressures.back().faces, Eigen::Map<const Eigen::VectorXd>(p.fluid_entry.data(), Eigen::Index(p.fluid_entry.size())));
  }
  for (const auto& l : m.spec.traction)
    setup.tractions.push_back({resolve_faces(m, l.faces, "traction"),
                               Eigen::Map<const Eigen::VectorXd>(l.value.data(), Eigen::Index(l.value.size())), l.curve});
  if (!m.spec.body_force.empty()) {
    setup.body_force = Eigen::Map<const Eigen::VectorXd>(m.spec.body_force.data(), Eigen::Index(m.spec.body_force.size()));
    setup.body_force_curve = m.spec.body_force_curve;
  }
  setup.prescribed_curves = prescribed_curves(m);
  setup.follower_pressure = m.spec.loading.follower_pressure;
  for (const auto& c : m.contacts)
    setup.contacts.push_back({c.face.get(), c.obstacle.get(), c.motion, c.master.get(),
                              c.integration, c.curve, c.contact_law(), c.interference});
  setup.complementarity_scale = m.spec.E / std::max(m.mesh_size, 1e-300);
  setup.mesh_size = m.mesh_size;
  setup.share = elasticity_share(m);  // (several processes: each its elements)
  if (m.spec.incompressible) setup.incompressibility_tolerance = TotalLagrangianAssembler::kIncompressibilityTolerance;
  return setup;
}

namespace {
// A body held only by contact along one free rigid motion, whose load steps
// failed after t_final: the end of the segment they failed in (the first
// corner of the load curves after t_final; 1 without curves) when there the
// load, dead on the reference faces, pulls the body off the contact of the
// reference configuration (load_pulls_off); loads are linear in t between
// corners, so it pulls from some time in between.  Nothing when it does not:
// the steps failed for another reason.  (The follower load and the contact
// normals turn with the body: a diagnosis of a failure, not a decision
// about a solution.)
std::optional<double> pulled_off_after(const Model& m, const RigidModes& modes, double t_final,
                                       const std::vector<double>& corners) {
  double t = 1.0;
  for (const double c : corners)
    if (c > t_final) {
      t = c;
      break;
    }
  if (t <= t_final) return std::nullopt;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(m.dofs->num_free());
  for (const auto& p : m.spec.pressure)
    add_pressure_load(m.body, *m.dofs, resolve_faces(m, p.faces, "pressure"), p.curve(t) * p.value, f);
  add_traction_loads(m, *m.dofs, t, f);
  const WeightedGapOperator op = assemble_contact_operator_at_time(m, t);
  if (!op.bilateral() && load_pulls_off(op.G * modes.modes.col(0), modes.modes.col(0).dot(f), f.norm())) return t;
  return std::nullopt;
}
}  // namespace

RunResult solve_finite_strain(const Model& m, const RunControl& control) {
  const StepObserver& on_step = control.on_step;
  RunResult r;
  Stopwatch t_start;
  const Body& body = m.body;
  const FiniteStrainSetup setup = finite_strain_setup(m);
  FiniteStrainProblem problem(setup);

  const RigidModes modes = free_rigid_modes(body, *m.dofs);
  if (modes.modes.cols() > 0) {  // the reference (dead) load decides whether the body is held
    Eigen::VectorXd f_ref = Eigen::VectorXd::Zero(m.dofs->num_free());
    for (const auto& p : setup.pressures) add_pressure_load(body, *m.dofs, p.faces, p.value, f_ref);
    add_traction_loads(m, *m.dofs, {}, f_ref);
    check_body_is_held(m, modes, f_ref);
  }
  Eigen::VectorXd x = Eigen::VectorXd::Zero(problem.size());
  problem.activate_nearest(x, int(modes.modes.cols()));
  r.applied_force = pressure_resultant(m);

  const LoadCurveProbe probe(m);  // the face whose displacement the load curve follows, the moving obstacle
  LoadSteppingOptions opt;
  opt.steps = m.spec.loading.steps;
  opt.first_increment = m.spec.loading.first_increment;
  opt.min_increment = m.spec.loading.min_increment;
  opt.max_increment = m.spec.loading.max_increment;
  opt.max_newton_iterations = m.spec.loading.max_newton_iterations;
  opt.line_search = m.spec.loading.line_search;
  opt.halving_line_search = m.spec.loading.halving_line_search;
  opt.tangent_predictor = m.spec.loading.tangent_predictor;
  opt.tangent_every_step = m.spec.loading.tangent_every_step;
  opt.linearised_active_set = m.spec.loading.linearised_active_set;
  opt.quiet = control.quiet;
  // PETSc's linear solver when the case asks for it (else the driver's direct
  // one); the console's header once its first solve has read the options
  // (or the run has gone a while without a line), so that a wrong one stays
  // a one-line input error.
  std::optional<Progress> progress;  // the heartbeat of a long load step (the step lines are load_stepping's)
  std::once_flag header_once;
  const auto header = [&] {
    std::call_once(header_once, [&] {
      if (control.on_solve_start) control.on_solve_start();
    });
  };
  const std::unique_ptr<LinearBackend> petsc_solver = petsc_linear_backend(m, [&] {
    header();
    if (progress) progress->hold(false);
  });
  opt.linear_backend = petsc_solver.get();
  const bool curves = m.spec.has_load_curves();
  if (curves) opt.corners = curve_corners(m.spec.load_curves());
  ReactionEvaluator reactions(m);
  auto snapshot = [&](double t, const Eigen::VectorXd& xs, RunResult& out) {
    out.u = problem.displacement(t, xs);
    if (problem.assembler().incompressible()) problem.assembler().element_pressures(out.u, out.element_pressures);
    if (!m.contacts.empty()) fill_contact(m, problem, t, xs, out);
    LoadCurvePoint p;
    p.load_factor = t;
    for (const ContactResult& c : out.contacts) p.contact_forces.push_back(c.report.total_force);
    if (problem.num_tangential() > 0)  // friction: the tangential force of each contact
      for (const ObstacleReaction& rr : out.reactions) p.tangential_forces.push_back(rr.tangential_force);
    p.face_displacement = probe.face_displacement(body, out.u);
    p.obstacle_displacement = probe.obstacle_displacement(t);
    reactions.take_element_pressures(problem.assembler());
    p.dirichlet_reactions = reactions(out.u, t, problem.contact_forces_on_every_dof(t, xs), problem.wet_elements());
    out.dirichlet_reactions = p.dirichlet_reactions;
    return p;
  };
  // A restart: the earlier steps' records and load-curve points, and the
  // driver continues from the state after the last of them.
  std::vector<LoadStepRecord> earlier;
  for (const StepState& st : control.resume) {
    earlier.push_back(st.record);
    r.load_curve.push_back(st.point);
  }
  if (!control.resume.empty()) {
    const StepState& from = control.resume.back();
    // a state whose unknowns are not this problem's is refused, not read past its end
    if (from.driver.x.size() != problem.size())
      throw InputError(fmt::format("{}: the state file holds {} unknowns, this run has {}; "
                                   "run the case again from the start",
                                   m.spec.path, from.driver.x.size(), problem.size()));
    opt.start = from.driver;
    opt.steps_done = int(control.resume.size());
    problem.restore({from.friction, from.pressure_multipliers}, from.driver.x_old);
  }
  opt.max_steps = control.stop_after_step;
  LoadSteppingState latest;  // the driver's state after the step record_step sees
  opt.on_state = [&latest](const LoadSteppingState& s) { latest = s; };
  const auto record_step = [&](const LoadStepRecord& rec, const Eigen::VectorXd& xs) {
    if (progress) {
      progress->now(fmt::format("in the load step after load factor {:.4f}", rec.load_factor));
      progress->fraction(rec.load_factor / (opt.corners.empty() ? 1.0 : opt.corners.back()));
    }
    RunResult step;
    r.load_curve.push_back(snapshot(rec.load_factor, xs, step));
    const FiniteStrainProblem::History history = problem.history();
    step.step_state = StepState{int(r.load_curve.size()), latest, history.friction, history.pressure_multipliers, rec,
                                r.load_curve.back()};
    if (on_step) on_step(step, rec.load_factor);
  };
  // Nothing loads the body: u = 0 is the solution (Newton, measuring its
  // residual against a zero load, would stop in the line search); unless
  // only the contact holds it and its obstacle moves away.
  LoadSteppingSummary summary;
  const Loading loading = loading_of(m);
  if (loading == Loading::obstacle_leaves && modes.modes.cols() > 0)
    throw InputError(fmt::format("{}: the body is not held: {} rigid motion(s) are free of Dirichlet conditions and "
                                 "only the contact holds them, but nothing presses the body on the obstacle and the "
                                 "obstacle moves away from it; add a [[dirichlet]] condition or a load toward the "
                                 "obstacle",
                                 m.spec.where({.table = "contact.obstacle", .key = "motion"}), modes.modes.cols()));
  progress.emplace(control.quiet);
  if (petsc_solver) progress->hold_until_late(header);
  else header();
  progress->now("in the first load step");
  if (loading != Loading::some) {
    r.warnings.push_back(fmt::format("{}: nothing loads the body (no pressure, prescribed displacement or body force, "
                                     "and no obstacle moves toward it or starts inside it): the solution is u = 0",
                                     m.spec.path));
    x.setZero();  // no multiplier either (activate_nearest primed some for Newton)
    summary.steps.push_back({1.0, 0, {0.0}, {0}, 0});
    latest = {1.0, 1.0, 0.0, x, x};  // (its state file names the step's time, as a driver's step does)
    record_step(summary.steps.back(), x);
    summary.status = RunStatus::converged();  // (u = 0 solves it)
  } else {
    summary = run_load_steps(problem, x, opt, record_step);
    summary.steps.insert(summary.steps.begin(), earlier.begin(), earlier.end());
  }
  header();  // (a run that solved nothing)
  r.load_steps = summary;
  r.linear_solver.condition_estimate = summary.condition_estimate;
  if (petsc_solver && summary.linear.setups > 0) take_report(*petsc_solver, r.linear_solver);
  r.status = summary.status;
  r.timing.contact = summary.newton_seconds;
  const double t_final = summary.steps.empty() ? 0.0 : summary.steps.back().load_factor;
  if (summary.status.outcome() == RunStatus::Outcome::failed && modes.modes.cols() == 1)
    if (const std::optional<double> t = pulled_off_after(m, modes, t_final, opt.corners)) {
      const char* at = curves ? "time" : "load factor";
      const std::string& text = summary.status.text();
      const std::string why = text.substr(std::min(text.size(), text.find(": ") + 2));
      r.status = RunStatus::failed(fmt::format("stopped at {} {:.6g}: {}", at, t_final,
                                               pulled_off_status(0, fmt::format("so at {} {:.6g}, where the failed "
                                                                                "steps were going; their last: {}",
                                                                                at, *t, why))));
    }
  // No step converged: the state is the reference one, u = 0 and no contact
  // force (not the multipliers primed for the first Newton iteration), and
  // there is no contact zone to report.
  if (summary.steps.empty()) x.setZero();
  snapshot(t_final, x, r);
  if (summary.steps.empty()) r.contacts.clear();
  if (curves) r.applied_force = pressure_resultant(m, t_final);  // (the follower's, below, when it applies)
  if (!r.contacts.empty() && setup.follower_pressure && !setup.pressures.empty()) {
    // the follower load's resultant along the obstacle normal, on the deformed faces
    Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(problem.num_displacements());
    for (size_t i = 0; i < setup.pressures.size(); ++i) {
      const PressureLoad& p = setup.pressures[i];
      const FaceElementFlags& wet = problem.wet_elements()[i];
      add_follower_pressure(body, *m.dofs, p.faces, p.curve(t_final) * p.value, r.u, f_ext, nullptr, wet.empty() ? nullptr : &wet);
    }
    const int dim = body.space_dim();
    std::vector<int> component(problem.num_displacements(), 0);
    for (int i = 0; i < m.dofs->num_dofs(); ++i)
      if (m.dofs->equation(i) >= 0) component[m.dofs->equation(i)] = i % dim;
    Eigen::VectorXd resultant = Eigen::VectorXd::Zero(dim);
    for (int e = 0; e < f_ext.size(); ++e) resultant[component[e]] += f_ext[e];
    r.applied_force = std::abs(resultant.dot(r.contacts.front().normal));
  }
  if (r.applied_force == 0) r.applied_force = driven_reaction(m, r.dirichlet_reactions);
  r.fluids = fluid_reports(m, setup, problem.wet_elements(), t_final, r);
  compare_with_reference(m, r);
  r.timing.total = t_start.seconds();
  return r;
}

}  // namespace igac
