// SPDX-License-Identifier: BSD-3-Clause
// The small-deformation path of solve_model: one linear solve, or the
// active-set contact solve; the reactions and the contact report.
#include <algorithm>
#include <mutex>
#include <chrono>
#include <cmath>
#include <optional>
#include <set>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contact/coarse_start.hpp"
#include "contact/small_strain_friction.hpp"
#include "engine/stopwatch.hpp"
#include "engine/face_quadrature.hpp"
#include "engine/follower_pressure.hpp"
#include "engine/prolongation.hpp"
#include "model/deformation_check.hpp"
#include "model/held_motions.hpp"
#include "model/load_history.hpp"
#include "model/petsc_run.hpp"
#include "model/progress.hpp"
#include "model/reactions.hpp"
#include "model/references.hpp"
#include "model/solve.hpp"

#include "contact/mortar_gap.hpp"

namespace igac {

double pressure_resultant(const Model& m, std::optional<double> time) {
  const int dim = m.body.space_dim();
  double total = 0;
  for (const auto& p : m.spec.pressure) {  // |int P n dGamma| per pressure load, on the reference faces
    const double value = time ? p.curve(*time) * p.value : p.value;
    for (const auto& n : p.faces) {
      Eigen::VectorXd res = Eigen::VectorXd::Zero(dim);  // a face made of several sides sums them
      FaceQuadrature(m.body, *find_faces(m, n), gauss_points_for(m.body.degree()))
          .for_each_element([&](int, const auto& v) {
            for (int k = 0; k < v.n_q; ++k) res += value * v.normal[k] * v.JxW[k];
          });
      total += res.norm();
    }
  }
  return total;
}

void add_traction_loads(const Model& m, const DofMap& dofs, std::optional<double> time, Eigen::VectorXd& f) {
  for (const auto& t : m.spec.traction) {
    const double factor = time ? t.curve(*time) : 1.0;
    const Eigen::Map<const Eigen::VectorXd> value(t.value.data(), Eigen::Index(t.value.size()));
    add_dead_traction(m.body, dofs, resolve_faces(m, t.faces, "traction"), factor * value, f);
  }
}

namespace {
// The stacked operator with each moving obstacle at factor(contact) *
// motion, and each interference fit's overlap removed by `fit` (1: whole).
template <class Factor>
WeightedGapOperator contact_operator(const Model& m, Factor&& factor, double fit) {
  std::vector<WeightedGapOperator> ops;
  for (const auto& c : m.contacts) {
    const double t = factor(c);
    if (c.master) {  // a master body moved (master_motion) by t * motion
      const Eigen::VectorXd shift = c.motion.size() ? Eigen::VectorXd(t * c.motion) : Eigen::VectorXd();
      ops.push_back(assemble_mortar_gaps(*m.dofs, *c.face, *c.master, c.integration,
                                         c.contact_law(), shift));
    } else {
      const bool moved = t != 1.0 && c.motion.size() > 0;
      const Eigen::VectorXd shift = c.motion.size() ? Eigen::VectorXd(t * c.motion) : Eigen::VectorXd();
      std::optional<TranslatedObstacle> at;  // the obstacle at t * motion (c.obstacle stands at 1 * motion)
      if (moved) at.emplace(*c.obstacle, (t - 1.0) * c.motion);
      ops.push_back(assemble_weighted_gaps(*m.dofs, *c.face, at ? static_cast<const Obstacle&>(*at) : *c.obstacle,
                                           c.contact_law(), shift));
    }
    if (c.interference_overlap.size() > 0 && fit < 1.0) ops.back().g0 += (1.0 - fit) * c.interference_overlap;
  }
  return stack(ops);
}
}  // namespace

bool changes_with_the_load(const Model::Contact& c) { return (c.motion.size() > 0 && c.motion.norm() > 0) || c.interference; }

WeightedGapOperator assemble_contact_operator(const Model& m, double t) {
  return contact_operator(m, [t](const Model::Contact&) { return t; }, t);
}

WeightedGapOperator assemble_contact_operator_at_time(const Model& m, double time) {
  return contact_operator(m, [time](const Model::Contact& c) { return c.curve(time); }, std::clamp(time, 0.0, 1.0));
}

Eigen::VectorXd contact_forces_on_every_dof(const Model& m, const ContactSolve& c) {
  const ContactSolution& s = c.solution;
  const bool friction = s.lambda_t.size() > 0;
  if (c.op.G_held.rows() != s.lambda.size() || c.op.G_held.cols() != m.dofs->num_dofs() ||
      (friction && (c.op.T.rows() != s.lambda_t.size() || c.op.T_held.rows() != s.lambda_t.size())))
    throw std::logic_error("contact_forces_on_every_dof: an operator without the couplings of its solution");
  Eigen::VectorXd free = c.op.G.transpose() * s.lambda, held = c.op.G_held.transpose() * s.lambda;
  if (friction) {
    free += c.op.T.transpose() * s.lambda_t;
    held += c.op.T_held.transpose() * s.lambda_t;
  }
  // Per equation of the dofs with none prescribed (a collapsed point's dofs
  // are one; a held one got a coupling per dof), then each dof its equation's.
  const DofMap every(m.body, {});
  Eigen::VectorXd f = Eigen::VectorXd::Zero(every.num_free());
  for (int dof = 0; dof < every.num_dofs(); ++dof)
    if (const int eq = m.dofs->equation(dof); eq >= 0) f[every.equation(dof)] = free[eq];
    else f[every.equation(dof)] += held[dof];
  Eigen::VectorXd out(every.num_dofs());
  for (int dof = 0; dof < every.num_dofs(); ++dof) out[dof] = f[every.equation(dof)];
  return out;
}

// A rigid translation strains nothing (K r = 0): the reactions are those of u.
void add_master_motions(const Model& m, Eigen::MatrixXd& u, std::optional<double> time) {
  const std::vector<int> part = m.body.parts();
  for (const auto& c : m.contacts) {
    if (!c.master || c.motion.size() == 0) continue;
    const int moved = part[find_faces(m, c.master_name)->front().patch];
    const Eigen::VectorXd motion = time ? Eigen::VectorXd(c.curve(*time) * c.motion) : c.motion;
    for (int k = 0; k < m.body.num_patches(); ++k)
      if (part[k] == moved)
        for (int a : m.body.body_cps(k)) u.row(a) += motion.transpose();
  }
}

namespace {

// Which patches the rigid motions `free` (free numbering, one per column)
// move, said when the body is several bodies (patches no interface joins):
// the patch that came loose is the one to look at.
std::string loose_patches(const Model& m, const Eigen::MatrixXd& free) {
  const std::vector<int> part = m.body.parts();
  const int parts = int(std::set<int>(part.begin(), part.end()).size());
  if (free.cols() == 0 || parts < 2) return "";
  const int dim = m.body.space_dim();
  std::vector<int> moved;
  for (int k = 0; k < m.body.num_patches(); ++k) {
    double amount = 0;
    for (int a : m.body.body_cps(k))
      for (int i = 0; i < dim; ++i)
        if (const int eq = m.dofs->equation(a * dim + i); eq >= 0) amount += free.row(eq).squaredNorm();
    if (amount > 1e-16 * free.squaredNorm()) moved.push_back(k);
  }
  return fmt::format(" (they move patch(es) {}: the body is {} parts that no interface joins, and these are not held)",
                     fmt::join(moved, ", "), parts);
}
}  // namespace

namespace {
// "path:line" of the case's first load: a [[pressure]] or [[traction]]
// value, else the [body_force].
std::string load_key(const Model& m) {
  for (const char* table : {"pressure", "traction", "body_force"})
    if (m.spec.source.find({.table = table, .key = "value"})) return m.spec.where({.table = table, .key = "value"});
  return m.spec.path;
}
}  // namespace

void check_body_is_held(const Model& m, const RigidModes& modes, const Eigen::VectorXd& f,
                        const WeightedGapOperator* given) {
  const int k = int(modes.modes.cols());
  if (k == 0) return;
  // Where the messages point: the conditions that leave the motions free
  // (the first [[dirichlet]], else the file), the contact that cannot stop
  // them, the load that pulls.
  if (m.contacts.empty())
    throw InputError(fmt::format(
        "{}: the body is not held: {} rigid motion(s) are free of Dirichlet conditions and there is no [contact]{}",
        m.spec.where({.table = "dirichlet", .key = "faces"}), k, loose_patches(m, modes.modes)));
  // A frictionless contact holds a rigid motion only if the motion changes
  // the weighted gaps: H = G * modes must have full column rank.
  std::optional<WeightedGapOperator> assembled;
  const WeightedGapOperator& op = given ? *given : assembled.emplace(assemble_contact_operator(m));
  // With friction a motion along the obstacle is held too (by the
  // tangential rows T) as long as the load does not exceed f N.
  Eigen::MatrixXd H = op.G * modes.modes;
  if (op.tangential()) {
    const Eigen::MatrixXd HT = op.T * modes.modes;
    H.conservativeResize(H.rows() + HT.rows(), Eigen::NoChange);
    H.bottomRows(HT.rows()) = HT;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(H, Eigen::ComputeFullV);
  const double s_max = svd.singularValues().size() ? svd.singularValues()[0] : 0.0;
  int held = 0;
  for (int i = 0; i < svd.singularValues().size(); ++i)
    if (svd.singularValues()[i] > 1e-8 * s_max && s_max > 0) ++held;
  if (held < k)
    throw InputError(fmt::format(
        "{}: the body is not held: {} rigid motion(s) are free of Dirichlet conditions and the frictionless contact "
        "cannot stop them (it pushes only along the obstacle's normal); add a [[dirichlet]] condition{}",
        m.spec.where({.table = "contact", .key = "face"}), k - held, loose_patches(m, modes.modes * svd.matrixV().rightCols(k - held))));
  // One free motion (the usual symmetric case): the load must move the body
  // toward the obstacle, closing some gap, or nothing balances it (a tie
  // holds either way).
  if (k == 1 && !op.bilateral() && load_pulls_off(H.col(0).head(op.G.rows()), modes.modes.col(0).dot(f), f.norm()))
    throw InputError(fmt::format(
        "{}: the load pulls the body away from the obstacle: only the contact holds it along its free rigid "
        "motion, and the load opens every gap (is the load's sign reversed?)",
        load_key(m)));
}

namespace {
// Nested iteration (contact/coarse_start): the first active set and first
// guess of `m`'s contact iteration from the solution of the case one
// refinement below (solved here unless `coarser` has it, itself started
// the same way).  Nothing when that solve did not converge.  (The spline
// multigrid builds the same coarse model and prolongation again for its
// hierarchy: 0.1 s of a 74 s run at 225k unknowns, left so.)
void start_from_coarser_mesh(const Model& m, CoarserRun coarser, const WeightedGapOperator& op, int k,
                             ContactSolverOptions& opt) {
  std::optional<Model> built;
  std::optional<RunResult> solved;
  if (!coarser.model || !coarser.result) {
    CaseSpec spec = m.spec;
    --spec.refine;
    built.emplace(build_model(spec));
    solved.emplace(solve_model(*built, quiet_run()));
    coarser = {&*built, &*solved};
  }
  const RunResult& rc = *coarser.result;
  if (!rc.contact || !rc.contact->solution.converged) return;
  auto faces = [](const Model& model) {
    std::vector<const ContactFace*> out;
    for (const auto& c : model.contacts) out.push_back(c.face.get());
    return out;
  };
  const Model& cm = *coarser.model;
  ActiveSetStart start = start_from_coarse(faces(cm), faces(m), prolongation(cm.body, *cm.dofs, m.body, *m.dofs),
                                           rc.contact->solution, op, k, opt.complementarity_scale);
  opt.initial_active = std::move(start.active);
  opt.initial_u = std::move(start.u);
  opt.initial_lambda = std::move(start.lambda);
}

// Friction is path dependent: the loads are applied whole with every
// obstacle where it starts, then a moving obstacle is moved in
// [loading] steps increments (none: one step), each step a frictional
// active-set solve on the same factor of K from the slip history of the last.
ContactSolution solve_with_friction(const Model& m, const LinearSystem& sys, const WeightedGapOperator& op,
                                    const RigidModes& modes, SparseCholesky& chol, const ContactSolverOptions& opt,
                                    LinearSolverRecord& record) {
  const std::unique_ptr<LinearBackend> petsc = petsc_linear_backend(m);  // (null: CHOLMOD)
  bool moving = false;
  for (const auto& c : m.contacts) moving = moving || changes_with_the_load(c);
  const int steps = moving ? m.spec.loading.steps : 0;
  const WeightedGapOperator first = moving ? assemble_contact_operator(m, 0.0) : WeightedGapOperator{};
  Stopwatch clock;
  SmallStrainFriction friction(sys.K, sys.f, moving ? first : op, modes, chol, opt, petsc.get());
  const double factorize_s = clock.seconds();
  ContactSolution s = friction.step(moving ? first : op);
  std::vector<int> sizes = s.active_set_sizes, per_step{int(s.active_set_sizes.size())};
  for (int i = 1; i <= steps && s.converged; ++i) {
    s = friction.step(i == steps ? op : assemble_contact_operator(m, double(i) / steps));
    if (!s.converged) s.status = fmt::format("{} (load step {} of {})", s.status, i, steps);
    sizes.insert(sizes.end(), s.active_set_sizes.begin(), s.active_set_sizes.end());
    per_step.push_back(int(s.active_set_sizes.size()));
  }
  s.active_set_sizes = std::move(sizes);
  s.step_iterations = std::move(per_step);
  s.factorize_s = factorize_s;
  if (petsc) {
    s.factorize_s = petsc->stats().factorize_s;
    take_report(*petsc, record);
  }
  return s;
}
}  // namespace

RunResult solve_model(const Model& m, const RunControl& control) {
  if (m.spec.finite_strain()) return solve_finite_strain(m, control);
  if (m.spec.has_load_curves()) return solve_small_strain_history(m, control);
  const CoarserRun coarser = control.coarser;
  RunResult r;
  Stopwatch t_start;
  const Body& body = m.body;
  const int dim = body.space_dim();
  const bool petsc = uses_petsc(m);
  Progress progress(control.quiet);
  std::once_flag header_once;  // the heartbeat's thread may print it
  const auto header = [&] { std::call_once(header_once, [&] { if (control.on_solve_start) control.on_solve_start(); }); };
  bool started = false;
  const auto start = [&] {
    if (started) return;
    started = true;
    progress.hold(false);
    header();
  };
  progress.hold_until_late(header);
  progress.phase("setting up the contact operator and the rigid modes");
  Stopwatch t0;
  Eigen::VectorXd bf = m.spec.body_force.empty()
                           ? Eigen::VectorXd::Zero(dim)
                           : Eigen::Map<const Eigen::VectorXd>(m.spec.body_force.data(), dim).eval();
  const RigidModes modes = free_rigid_modes(body, *m.dofs);
  // The contact operator once: the held-body check and the solve read it
  // (for two bodies it projects every slave point on the master).
  std::optional<WeightedGapOperator> op;
  if (!m.contacts.empty()) op = assemble_contact_operator(m);
  // Is the body held?  Checked before the stiffness is assembled, with the
  // loads alone: the lift K_fp u_p of prescribed values does no work on a
  // rigid motion free of Dirichlet conditions (K r = 0 and r_p = 0).
  if (modes.modes.cols() > 0) {
    Eigen::VectorXd f = body_force_load(body, *m.dofs, bf);
    for (const auto& p : m.spec.pressure) add_pressure_load(body, *m.dofs, resolve_faces(m, p.faces, "pressure"), p.value, f);
    add_traction_loads(m, *m.dofs, {}, f);
    check_body_is_held(m, modes, f, op ? &*op : nullptr);
  }
  r.timing.assembly = t0.seconds();
  // The header once the case is accepted (the held-body check above), with
  // PETSc after its first solve (where it reads its options: a wrong one is
  // an input error, one line); then the progress lines.  Or once it has run
  // 4 s without a line: a long run is never silent.
  if (!petsc) start();
  progress.phase(fmt::format("assembling {} equations", m.dofs->num_free()));
  t0.restart();
  // One process: every element.  PETSc on several: this process's block
  // (the element loads summed over the processes, so f is whole everywhere);
  // friction's iterations hand PETSc the whole matrix from every process
  // (petsc_run.hpp), which then assembles every element.
  const bool frictional = op && op->tangential();
  const ElementRange elements = frictional ? ElementRange{} : process_elements(m);
  LinearSystem sys =
      assemble_linear_elasticity(body, *m.dofs, m.patch_materials(), bf, elements, m.patch_formulations());
  if (!frictional) sum_over_processes(sys.f);
  for (const auto& p : m.spec.pressure) add_pressure_load(body, *m.dofs, resolve_faces(m, p.faces, "pressure"), p.value, sys.f);
  add_traction_loads(m, *m.dofs, {}, sys.f);
  r.timing.assembly += t0.seconds();
  r.applied_force = pressure_resultant(m);
  SparseCholesky chol;
  // A line per active-set iteration (with the Krylov iterations of its
  // solve on the PETSc path).
  const auto report_iteration = [&progress, &start](int it, int active, int changed, int krylov) {
    start();
    progress.line(fmt::format("active set {:3d}: {} active, {} changing{} ({:.1f} s)", it + 1, active, changed,
                              krylov >= 0 ? fmt::format(", {} Krylov iterations", krylov) : "", progress.seconds()),
                  changed > 0 ? "in the next active-set iteration" : "computing the reactions and reports");
  };
  if (m.contacts.empty() && petsc) {
    progress.phase(fmt::format("solving K u = f ({} equations) with PETSc", m.dofs->num_free()));
    WeightedGapOperator none;
    none.G.resize(0, m.dofs->num_free());
    ContactSolverOptions no_contact;
    if (!control.quiet)
      no_contact.on_iteration = [&progress, &start](int, int, int, int krylov) {
        start();
        progress.line(fmt::format("solved: {} Krylov iterations ({:.1f} s)", krylov, progress.seconds()),
                      "computing the reactions and reports");
      };
    const ContactSolution s = solve_with_petsc(m, sys, none, modes, no_contact, r.linear_solver);
    r.timing.factorization = s.factorize_s;
    r.timing.linear_solve = s.iterations_s;
    r.status = s.converged ? RunStatus::converged() : RunStatus::failed(s.status);
    r.u = m.dofs->expand(s.u);
  } else if (m.contacts.empty()) {
    progress.phase(fmt::format("factorising K ({} equations)", m.dofs->num_free()));
    t0.restart();
    chol.factorize(sys.K);
    r.timing.factorization = t0.seconds();
    t0.restart();
    r.u = m.dofs->expand(chol.solve(sys.f));
    r.timing.linear_solve = t0.seconds();
    r.status = RunStatus::converged();  // (one direct solve: nothing to fail but the factorisation, which throws)
    if (auto w = stiffness_warning(m, sys.K, {}, chol)) r.warnings.push_back(std::move(*w));
  } else {
    ContactSolve* c = &r.contact.emplace();
    c->op = std::move(*op);
    ContactSolverOptions opt;
    opt.complementarity_scale = m.spec.E / std::max(m.mesh_size, 1e-300);
    opt.mesh_size = m.mesh_size;
    if (!control.quiet) opt.on_iteration = report_iteration;
    progress.phase(petsc ? fmt::format("the active-set iterations with PETSc ({} equations, {} multipliers)",
                                       m.dofs->num_free(), m.num_multipliers())
                         : fmt::format("factorising K ({} equations), then the active-set iterations ({} multipliers)",
                                       m.dofs->num_free(), m.num_multipliers()));
    t0.restart();
    // Nested iteration from the solution one refinement below: the PETSc
    // path solves it first (a Krylov or MUMPS solve per active-set
    // iteration, and it saves most of those iterations); the direct
    // path takes it when it is at hand (a study's previous level) but does
    // not solve it for itself, which costs more than the Schur columns it
    // saves except on the largest meshes (measured: docs/petsc.md,
    // "Nested iteration").
    if (m.spec.refine > 0 && (petsc || coarser.result))
      start_from_coarser_mesh(m, coarser, c->op, int(modes.modes.cols()), opt);
    c->solution = c->op.tangential() ? solve_with_friction(m, sys, c->op, modes, chol, opt, r.linear_solver)
                  : petsc              ? solve_with_petsc(m, sys, c->op, modes, opt, r.linear_solver)
                                       : solve_small_strain_contact(sys.K, sys.f, c->op, modes, chol, opt);
    r.timing.factorization = c->solution.factorize_s;
    r.timing.contact = t0.seconds() - c->solution.factorize_s;
    r.status = c->solution.converged ? RunStatus::converged() : RunStatus::failed(c->solution.status);
    if (c->solution.u.size() != m.dofs->num_free())
      throw std::runtime_error(fmt::format("contact solve failed: {}", c->solution.status));
    r.u = m.dofs->expand(c->solution.u);
    add_master_motions(m, r.u);
    t0.restart();
    // A motion the stiffness or the contact barely holds (the factor is K's
    // with the free rigid motions pinned).
    if (!petsc && r.status.is_converged()) {
      if (auto w = stiffness_warning(m, sys.K, modes.pinned, chol)) r.warnings.push_back(std::move(*w));
      if (auto w = contact_hold_warning(m, c->op, c->solution, modes)) r.warnings.push_back(std::move(*w));
    }
    r.reactions = obstacle_reactions(m, c->solution.lambda, c->op.weights, c->solution.active, c->solution.lambda_t);
    add_extrusions(m, r.u, 1.0, r.reactions);
    r.contacts = report_contacts(m, *c);
    // A unilateral partner can only push: a net pull on the body (tensile
    // multipliers) is a wrong result, never a converged one; a tie pulls.
    for (size_t i = 0; i < r.reactions.size(); ++i)
      if (const auto& rr = r.reactions[i]; r.status.is_converged() && !m.contacts[i].contact_law().get().bilateral() &&
                                           rr.normal_force < -1e-9 * std::max(r.applied_force, 1e-300))
        r.status = RunStatus::failed(fmt::format(
            "failed: the obstacle of face '{}' pulls on the body (contact force {:.3g} < 0)", rr.face, rr.normal_force));
    r.timing.postprocess += t0.seconds();
  }
  start();  // (a PETSc solve that ended before its first iteration's report)
  t0.restart();
  if (!petsc && chol.analyzed()) r.linear_solver.condition_estimate = chol.condition_estimate();
  // What the supports carry; a displacement-driven case's applied force.
  r.dirichlet_reactions =
      ReactionEvaluator(m)(r.u, 1.0, r.contact ? contact_forces_on_every_dof(m, *r.contact) : Eigen::VectorXd());
  if (r.applied_force == 0) r.applied_force = driven_reaction(m, r.dirichlet_reactions);
  if (auto w = small_deformation_warning(m, r)) r.warnings.push_back(std::move(*w));
  compare_with_reference(m, r);
  r.timing.postprocess += t0.seconds();
  r.timing.total = t_start.seconds();
  return r;
}

}  // namespace igac
