// SPDX-License-Identifier: BSD-3-Clause
#include "model/load_history.hpp"

#include <cmath>
#include <mutex>
#include <fmt/format.h>

#include "contact/small_strain_friction.hpp"
#include "engine/assembly.hpp"
#include "engine/cholesky.hpp"
#include "engine/face_quadrature.hpp"
#include "engine/stopwatch.hpp"
#include "model/petsc_run.hpp"
#include "model/progress.hpp"
#include "model/reactions.hpp"

namespace igac {
namespace {

// The DofMap of the case's [[dirichlet]] conditions with the values of
// condition j alone (the others held at 0): the same free equations as
// m.dofs, and at a prescribed dof the value condition j gives it when it is
// the one that applies there (the last in case order), else 0.
DofMap values_of_condition(const Model& m, size_t j) {
  std::vector<DirichletCondition> dc;
  for (size_t k = 0; k < m.spec.dirichlet.size(); ++k) {
    const DirichletSpec& d = m.spec.dirichlet[k];
    dc.push_back({resolve_faces(m, d.faces, "dirichlet"), d.component, k == j ? d.value : 0.0});
  }
  return DofMap(m.body, dc);
}

}  // namespace

std::vector<const LoadCurve*> prescribed_curves(const Model& m) {
  if (!m.spec.has_load_curves()) return {};
  static const LoadCurve none = LoadCurve::ramp_and_hold();  // (a dof held at 0: any factor)
  std::vector<const LoadCurve*> out(size_t(m.dofs->num_dofs()), &none);
  for (size_t j = 0; j < m.spec.dirichlet.size(); ++j) {
    if (m.spec.dirichlet[j].value == 0) continue;
    const DofMap alone = values_of_condition(m, j);
    for (int i = 0; i < alone.num_dofs(); ++i)
      if (alone.equation(i) < 0 && alone.prescribed_value(i) != 0) out[size_t(i)] = &m.spec.dirichlet[j].curve;
  }
  return out;
}

LoadCurveProbe::LoadCurveProbe(const Model& m) {
  for (const auto& p : m.spec.pressure) {
    const auto f = resolve_faces(m, p.faces, "pressure");
    faces.insert(faces.end(), f.begin(), f.end());
  }
  // Driven by a moving obstacle: follow the face it pushes, and how far it moved.
  for (const auto& c : m.contacts)
    if (c.motion.size() > 0 && !mover) mover = &c;
  if (faces.empty() && mover)
    for (const ContactSide& side : mover->face->sides) faces.push_back(side.side);
  if (faces.empty())
    for (const auto& d : m.spec.dirichlet)
      if (d.value != 0) {
        const auto f = resolve_faces(m, d.faces, "dirichlet");
        faces.insert(faces.end(), f.begin(), f.end());
      }
}

double LoadCurveProbe::face_displacement(const Body& body, const Eigen::MatrixXd& u) const {
  const int dim = body.space_dim();
  double s = 0, area = 0;
  FaceQuadrature(body, faces, gauss_points_for(body.degree())).for_each_element([&](int, const auto& v) {
    for (int k = 0; k < v.n_q; ++k) {
      double value = 0;
      for (int a = 0; a < v.n_loc; ++a) value += v.N(k, a) * u(v.cps[a], dim - 1);
      s += value * v.JxW[k];
      area += v.JxW[k];
    }
  });
  return area > 0 ? s / area : 0.0;
}

double LoadCurveProbe::obstacle_displacement(double t) const {
  return mover ? mover->curve(t) * mover->motion.norm() : 0.0;  // (signed: a curve below 0 reverses the motion)
}

RunResult solve_small_strain_history(const Model& m, const RunControl& control) {
  const StepObserver& on_step = control.on_step;
  RunResult r;
  const Stopwatch t_start;
  const Body& body = m.body;
  const int dim = body.space_dim();
  const Eigen::VectorXd bf = m.spec.body_force.empty()
                                 ? Eigen::VectorXd::Zero(dim)
                                 : Eigen::Map<const Eigen::VectorXd>(m.spec.body_force.data(), dim).eval();
  const RigidModes modes = free_rigid_modes(body, *m.dofs);
  // The loads one by one, each at its value (factor 1).
  const Eigen::VectorXd f_body = body_force_load(body, *m.dofs, bf);
  std::vector<Eigen::VectorXd> f_pressure;
  for (const auto& p : m.spec.pressure) {
    f_pressure.push_back(Eigen::VectorXd::Zero(m.dofs->num_free()));
    add_pressure_load(body, *m.dofs, resolve_faces(m, p.faces, "pressure"), p.value, f_pressure.back());
  }
  if (modes.modes.cols() > 0) {  // held? (with every load at its value, as without curves)
    Eigen::VectorXd f = f_body;
    for (const auto& fp : f_pressure) f += fp;
    add_traction_loads(m, *m.dofs, {}, f);
    check_body_is_held(m, modes, f);
  }
  // The console's header once the case is accepted; on PETSc once the first
  // step has solved (its first solve reads the options: a wrong one stays a
  // one-line input error) or the run has gone a while without a line.
  std::once_flag header_once;
  const auto header = [&] {
    std::call_once(header_once, [&] {
      if (control.on_solve_start) control.on_solve_start();
    });
  };
  Progress progress(control.quiet);
  if (uses_petsc(m)) progress.hold_until_late(header);
  else header();
  progress.phase(fmt::format("assembling {} equations", m.dofs->num_free()));
  Stopwatch clock;
  const Eigen::VectorXd no_body_force = Eigen::VectorXd::Zero(dim);
  LinearSystem sys = assemble_linear_elasticity(body, *m.dofs, m.patch_materials(), no_body_force, {},
                                                m.patch_formulations());
  std::vector<std::pair<const LoadCurve*, Eigen::VectorXd>> lifts;  // l_j of each nonzero condition
  for (size_t j = 0; j < m.spec.dirichlet.size(); ++j)
    if (m.spec.dirichlet[j].value != 0)
      lifts.emplace_back(&m.spec.dirichlet[j].curve,
                         assemble_linear_elasticity(body, values_of_condition(m, j), m.patch_materials(), no_body_force,
                                                    {}, m.patch_formulations()).f);
  r.timing.assembly = clock.seconds();
  auto load_at = [&](double t) {
    Eigen::VectorXd f = m.spec.body_force_curve(t) * f_body;
    for (size_t i = 0; i < f_pressure.size(); ++i) f += m.spec.pressure[i].curve(t) * f_pressure[i];
    add_traction_loads(m, *m.dofs, t, f);
    for (const auto& [curve, l] : lifts) f += (*curve)(t) * l;
    return f;
  };
  bool moving = false;
  for (const auto& c : m.contacts) moving = moving || changes_with_the_load(c);
  std::optional<WeightedGapOperator> fixed_op;
  if (!m.contacts.empty() && !moving) fixed_op = assemble_contact_operator(m);
  // Friction depends on the path: one frictional solve (K factorised once)
  // goes through the steps, each from the state and slip history where the
  // last one ended (the slip counted from the obstacle at time 0); a
  // restart builds it as the run did (at the first step's time) and takes
  // the history of the step before the first it solves from its state file.
  bool frictional = false;
  for (const auto& c : m.contacts) frictional = frictional || c.contact_law().tangential();
  std::optional<SmallStrainFriction> friction;
  std::vector<int> friction_steps;  // active-set iterations per step
  SparseCholesky chol;
  // PETSc (petsc_run.hpp): K whole on every process; without contact one
  // factorisation for every step, with friction SmallStrainFriction's
  // iterations; frictionless contact solves each step's saddle system.
  const bool petsc = uses_petsc(m);
  const std::unique_ptr<LinearBackend> backend = petsc ? petsc_linear_backend(m) : nullptr;
  BlockJacobian stiffness;  // (K alone, for the backend without contact)
  if (m.contacts.empty()) {
    progress.phase(fmt::format("factorising K ({} equations)", m.dofs->num_free()));
    clock.restart();
    if (backend) {
      stiffness.K = sys.K;
      stiffness.B.resize(0, sys.K.cols());
      if (!backend->setup(stiffness)) throw std::runtime_error(fmt::format("the PETSc factorisation of K failed: {}", backend->why()));
    } else {
      chol.factorize(sys.K);
    }
    r.timing.factorization = clock.seconds();
  }
  ContactSolverOptions opt;
  opt.complementarity_scale = m.spec.E / std::max(m.mesh_size, 1e-300);
  opt.mesh_size = m.mesh_size;
  const ReactionEvaluator reactions(m);
  const LoadCurveProbe probe(m);
  LoadSteppingSummary steps;
  const std::vector<double> times = step_times(curve_corners(m.spec.load_curves()), m.spec.loading.steps);
  // The displacement of the free unknowns at time t, with every prescribed
  // value at its curve's factor (DofMap::expand puts the values whole).
  const std::vector<const LoadCurve*> curve_of = prescribed_curves(m);
  auto expand = [&](const Eigen::VectorXd& free, double t) {
    Eigen::MatrixXd u = m.dofs->expand(free);
    for (int i = 0; i < m.dofs->num_dofs(); ++i)
      if (m.dofs->equation(i) < 0) u(i / dim, i % dim) = (*curve_of[size_t(i)])(t) * m.dofs->prescribed_value(i);
    return u;
  };
  // A restart: the earlier steps are taken as they were recorded (each
  // step is solved afresh, so none depends on the one before); the last of
  // them is solved again for the run's final state when nothing follows it.
  const size_t resumed = std::min(control.resume.size(), times.size());
  for (size_t i = 0; i < resumed; ++i) {
    steps.steps.push_back(control.resume[i].record);
    r.load_curve.push_back(control.resume[i].point);
  }
  RunResult last;
  for (size_t i = resumed > 0 ? resumed - 1 : 0; i < times.size(); ++i) {
    const double t = times[i];
    const bool again = resumed > 0 && i == resumed - 1;  // (its record is in already)
    if (again && i + 1 < times.size()) continue;
    if (!again && control.stop_after_step > 0 && int(i) >= control.stop_after_step) {
      steps.status = RunStatus::stopped_as_asked(int(i));
      break;
    }
    clock.restart();
    RunResult step;
    const Eigen::VectorXd f = load_at(t);
    LoadStepRecord record{t, 0, {}, {}, 0};
    if (m.contacts.empty()) {
      Eigen::VectorXd u_free;
      if (backend && !backend->solve(f, u_free, 0)) {
        steps.status = RunStatus::failed(fmt::format("stopped at time {:.6g}: {}", t, backend->why()));
        break;
      }
      step.u = expand(backend ? u_free : Eigen::VectorXd(chol.solve(f)), t);
      r.timing.linear_solve += clock.seconds();
    } else {
      ContactSolve& c = step.contact.emplace();
      c.op = fixed_op ? *fixed_op : assemble_contact_operator_at_time(m, t);
      if (frictional) {
        if (!friction) {
          const WeightedGapOperator first_op = i == 0 || fixed_op ? c.op : assemble_contact_operator_at_time(m, times[0]);
          friction.emplace(sys.K, i == 0 ? f : load_at(times[0]), first_op, modes, chol, opt, backend.get());
          friction->start_from(fixed_op ? *fixed_op : assemble_contact_operator_at_time(m, 0.0));
          if (i > 0) friction->restore(control.resume[i - 1].friction);  // the history where step i - 1 ended
          for (size_t j = 0; j < i; ++j) friction_steps.push_back(int(control.resume[j].record.active_set_sizes.size()));
          r.timing.factorization += clock.seconds();
          clock.restart();
        }
        friction->set_load(f);
        c.solution = friction->step(c.op);
        friction_steps.push_back(int(c.solution.active_set_sizes.size()));
        c.solution.step_iterations = friction_steps;
      } else if (petsc) {
        c.solution = solve_with_petsc_from_whole(m, sys.K, f, c.op, modes, opt, r.linear_solver);
      } else {
        c.solution = solve_small_strain_contact(sys.K, f, c.op, modes, chol, opt);
      }
      record.active_set_sizes = c.solution.active_set_sizes;
      r.timing.factorization += c.solution.factorize_s;
      r.timing.contact += clock.seconds() - c.solution.factorize_s;
      if (!c.solution.converged || c.solution.u.size() != m.dofs->num_free()) {
        steps.status = RunStatus::failed(fmt::format("stopped at time {:.6g}: {}", t, c.solution.status));
        break;
      }
      step.u = expand(c.solution.u, t);
      add_master_motions(m, step.u, t);
      step.reactions = obstacle_reactions(m, c.solution.lambda, c.op.weights, c.solution.active, c.solution.lambda_t);
      add_extrusions(m, step.u, t, step.reactions);
      step.contacts = report_contacts(m, c);
    }
    clock.restart();
    step.dirichlet_reactions =
        reactions(step.u, t, step.contact ? contact_forces_on_every_dof(m, *step.contact) : Eigen::VectorXd());
    if (again) {
      last = std::move(step);
      continue;
    }
    LoadCurvePoint p;
    p.load_factor = t;
    for (const ContactResult& c : step.contacts) p.contact_forces.push_back(c.report.total_force);
    for (const ObstacleReaction& rr : step.reactions) p.tangential_forces.push_back(rr.tangential_force);
    p.face_displacement = probe.face_displacement(body, step.u);
    p.obstacle_displacement = probe.obstacle_displacement(t);
    p.dirichlet_reactions = step.dirichlet_reactions;
    r.load_curve.push_back(p);
    steps.steps.push_back(record);
    // what a restart needs of the step: its time and solution x = [u_free; lambda]
    Eigen::VectorXd xs = step.contact ? Eigen::VectorXd(step.contact->solution.u.size() + step.contact->solution.lambda.size())
                                      : Eigen::VectorXd(m.dofs->num_free());
    if (step.contact) xs << step.contact->solution.u, step.contact->solution.lambda;
    else for (int d = 0; d < m.dofs->num_dofs(); ++d)
      if (m.dofs->equation(d) >= 0) xs[m.dofs->equation(d)] = step.u(d / dim, d % dim);
    StepState state;
    state.step = int(steps.steps.size());
    state.driver.t = t;
    state.driver.x = std::move(xs);
    state.record = record;
    state.point = std::move(p);
    if (friction) state.friction = friction->history();
    step.step_state = std::move(state);
    r.timing.postprocess += clock.seconds();
    header();
    progress.hold(false);
    if (!control.quiet)
      progress.line(fmt::format("step {:3d}: time {:.4f}{} ({:.1f} s){}", steps.steps.size(), t,
                                step.contact ? fmt::format(", {} active", std::count(step.contact->solution.active.begin(),
                                                                                     step.contact->solution.active.end(), 1))
                                             : "",
                                progress.seconds(), progress_suffix(t / times.back())));
    if (on_step) on_step(step, t);
    last = std::move(step);
  }
  // The state of the last step is the run's.
  const double t_end = steps.steps.empty() ? 0.0 : steps.steps.back().load_factor;
  if (steps.steps.empty()) last.u = Eigen::MatrixXd::Zero(body.num_control_points(), dim);
  r.u = std::move(last.u);
  r.contact = std::move(last.contact);
  r.contacts = std::move(last.contacts);
  r.reactions = std::move(last.reactions);
  r.dirichlet_reactions = std::move(last.dirichlet_reactions);
  if (!steps.status.is_set()) steps.status = RunStatus::converged();  // (every step solved)
  r.status = steps.status;
  r.load_steps = std::move(steps);
  r.applied_force = pressure_resultant(m, t_end);
  if (r.applied_force == 0) r.applied_force = driven_reaction(m, r.dirichlet_reactions);
  if (chol.analyzed()) r.linear_solver.condition_estimate = chol.condition_estimate();
  if (backend && backend->stats().setups > 0) take_report(*backend, r.linear_solver);
  header();  // (a run that solved no step)
  r.timing.total = t_start.seconds();
  return r;
}

}  // namespace igac
