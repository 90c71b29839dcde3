#include "app/case_run.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <optional>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/spline/refinement.hpp"
#include "app/case_body.hpp"
#include "app/petsc_run.hpp"
#include "contact/coarse_start.hpp"
#include "engine/prolongation.hpp"
#include "engine/geometry/side_names.hpp"
#include "engine/spline/split.hpp"

namespace igac {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::vector<PatchSide> resolve_faces(const Model& m, const std::vector<std::string>& names, const char* section) {
  std::vector<PatchSide> out;
  for (const auto& n : names) {
    auto f = find_faces(m, n);
    if (!f)
      throw InputError(fmt::format("{}: [{}] faces: unknown face '{}' on a {} (known: {})", m.spec.path, section, n,
                                   m.spec.shape, fmt::join(face_names(m), ", ")));
    for (const PatchSide& side : *f)
      for (const PatchInterface& itf : m.body.interfaces())
        if (side == itf.first || side == itf.second)
          throw InputError(fmt::format("{}: [{}] faces: '{}' is the interface {} - {} inside the body, not a face on "
                                       "its boundary",
                                       m.spec.path, section, n, m.body.describe(itf.first),
                                       m.body.describe(itf.second)));
    out.insert(out.end(), f->begin(), f->end());
  }
  return out;
}

// `target` with every breakpoint of `have` (at least its multiplicity there)
// added: a geometry file's own interior knots stay, so refining it is exact.
KnotVector with_knots_of(const KnotVector& target, const KnotVector& have) {
  std::map<double, int> mult;
  const auto add = [&](const KnotVector& kv) {
    const auto b = kv.breakpoints();
    const auto m = kv.multiplicities();
    for (size_t i = 0; i < b.size(); ++i) {
      auto it = mult.lower_bound(b[i] - 1e-12);
      if (it != mult.end() && std::abs(it->first - b[i]) <= 1e-12) it->second = std::max(it->second, m[i]);
      else mult[b[i]] = m[i];
    }
  };
  add(target);
  const size_t before = mult.size();
  add(have);
  if (mult.size() == before) return target;  // nothing new: the usual case
  std::vector<double> knots;
  for (const auto& [x, m] : mult) knots.insert(knots.end(), m, x);
  return KnotVector(target.degree(), knots);
}

double largest_element_diameter(const NurbsPatch& p) {
  const int pd = p.param_dim();
  std::array<std::vector<double>, 3> b;
  std::array<int, 3> ne{1, 1, 1};
  for (int d = 0; d < pd; ++d) {
    b[d] = p.knots(d).breakpoints();
    ne[d] = int(b[d].size()) - 1;
  }
  double h = 0;
  for (int k = 0; k < ne[2]; ++k)
    for (int j = 0; j < ne[1]; ++j)
      for (int i = 0; i < ne[0]; ++i) {
        std::vector<Eigen::VectorXd> corners;
        for (int c = 0; c < (1 << pd); ++c) {
          Eigen::VectorXd xi(pd);
          const std::array<int, 3> e{i, j, k};
          for (int d = 0; d < pd; ++d) xi[d] = b[d][e[d] + ((c >> d) & 1)];
          corners.push_back(p.point(xi));
        }
        for (size_t a = 0; a < corners.size(); ++a)
          for (size_t c = a + 1; c < corners.size(); ++c) h = std::max(h, (corners[a] - corners[c]).norm());
      }
  return h;
}

// Refines one coarse patch as the case asks: degree elevation to
// [mesh] degree, then per direction the uniform or graded knots (with the
// patch's own interior knots kept), subdivided `refine` times.
NurbsPatch refine_patch(const CaseSpec& spec, const NurbsPatch& coarse, const std::string& which) {
  for (int d = 0; d < coarse.param_dim(); ++d)
    if (coarse.degree(d) > spec.degree)
      throw InputError(fmt::format("{}: [mesh] degree = {} is below the geometry's degree {} in direction {}{}: igac "
                                   "raises the degree, never lowers it, so that the geometry stays exact",
                                   spec.path, spec.degree, coarse.degree(d), "uvw"[d], which));
  NurbsPatch patch = elevate_to(coarse, spec.degree);
  for (int d = 0; d < patch.param_dim(); ++d) {
    const GradingSpec* g = nullptr;
    for (const auto& gs : spec.gradings)
      if (gs.direction == d) g = &gs;
    KnotVector target;
    try {
      target = g ? KnotVector::graded(spec.degree, spec.elements[d], g->span_fraction, g->range_fraction, g->at_start,
                                      g->geometric_coarse ? KnotVector::CoarseSpans::geometric
                                                          : KnotVector::CoarseSpans::uniform)
                 : KnotVector::uniform(spec.degree, spec.elements[d]);
      if (spec.refine > 0) target = target.subdivided(1 << spec.refine);
    } catch (const SplineError& e) {
      if (!g) throw;
      throw InputError(fmt::format("{}: [mesh.grading] range_fraction = {:g}: the graded spans are too short to be "
                                   "told apart ({}); use a larger range_fraction or fewer elements",
                                   spec.path, g->range_fraction, e.what()));
    }
    patch = refine_to(patch, d, with_knots_of(target, patch.knots(d)));
  }
  return patch;
}

// A geometry file's patch must map its parameter cube onto the body without
// folding: det J > 0 at every Gauss point.  Names the patch and the place.
void check_patch_map(const CaseSpec& spec, const NurbsPatch& patch, int k) {
  const PatchQuadrature quad(patch, gauss_points_for(spec.degree));
  ElementData ed;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, false);
    if (ed.min_det_J > 0) continue;
    for (int q = 0; q < ed.JxW.size(); ++q)
      if (!(ed.JxW[q] > 0))
        throw InputError(fmt::format("{}: [geometry] file {}: patch {} folds: its Jacobian determinant is not positive "
                                     "at parameter ({:.4g}), point ({:.4g})",
                                     spec.path, spec.geometry_file, k, fmt::join(ed.xi.row(q), ", "),
                                     fmt::join(ed.X.row(q), ", ")));
  }
}

}  // namespace

std::optional<std::vector<PatchSide>> find_faces(const Model& m, const std::string& name) {
  if (auto it = m.faces.find(name); it != m.faces.end()) return it->second;
  if (auto side = parametric_side(name, m.body.num_patches(), m.body.param_dim())) return std::vector<PatchSide>{*side};
  return std::nullopt;
}

std::vector<std::string> face_names(const Model& m) {
  std::vector<std::string> out;
  for (const auto& [k, v] : m.faces) out.push_back(k);
  for (auto& n : parametric_side_names(m.body.num_patches(), m.body.param_dim())) out.push_back(std::move(n));
  return out;
}

Model build_model(const CaseSpec& spec) {
  Model m;
  m.spec = spec;
  // The coarse body: a built-in shape (one patch, with its face names) or
  // the patches of a geometry file.
  MultiPatch coarse;
  if (spec.geometry_file.empty()) {
    const Geometry g = case_geometry(spec);
    coarse = MultiPatch{{g.patch}, {}, {}};
    m.faces = g.faces;
  } else {
    coarse = case_body(spec);
    for (auto& p : coarse.patches) p = normalised(p);  // knots on [0, 1], geometry unchanged
  }
  const bool several = coarse.patches.size() > 1;
  std::vector<NurbsPatch> patches;
  for (size_t k = 0; k < coarse.patches.size(); ++k) {
    patches.push_back(refine_patch(spec, coarse.patches[k], several ? fmt::format(" of patch {}", k) : ""));
    if (!spec.geometry_file.empty()) check_patch_map(spec, patches.back(), int(k));
  }
  try {
    m.body = several ? Body(std::move(patches), coarse.interfaces) : Body(std::move(patches.front()));
  } catch (const BodyError& e) {
    throw InputError(fmt::format("{}: [geometry] file {}: {}", spec.path, spec.geometry_file, e.what()));
  }
  double h = 0;
  for (const auto& p : m.body.patches()) h = std::max(h, largest_element_diameter(p));
  m.mesh_size = h;

  for (const auto& [name, members] : spec.face_sets) {  // [faces]: names of the user's own
    if (find_faces(m, name))
      throw InputError(fmt::format("{}: [faces] {}: the name is taken by a face of the body", spec.path, name));
    m.faces[name] = resolve_faces(m, members, "faces");
  }

  std::vector<DirichletCondition> dc;
  for (const auto& d : spec.dirichlet)
    dc.push_back({resolve_faces(m, d.faces, "dirichlet"), d.component, d.value});
  for (const auto& p : spec.pressure) resolve_faces(m, p.faces, "pressure");
  // The same face and component held at two values: the conditions are
  // applied in order, so the last one wins; say so.
  for (size_t a = 0; a < spec.dirichlet.size(); ++a)
    for (size_t b = a + 1; b < spec.dirichlet.size(); ++b) {
      const auto &da = spec.dirichlet[a], &db = spec.dirichlet[b];
      if (da.component != db.component || da.value == db.value) continue;
      for (const auto& fa : da.faces)
        if (std::find(db.faces.begin(), db.faces.end(), fa) != db.faces.end())
          m.warnings.push_back(fmt::format("{}: [[dirichlet]] face '{}' component {} is given two values ({} and {}); "
                                           "the last one applies", spec.path, fa, "xyz"[da.component], da.value,
                                           db.value));
    }
  m.dofs = std::make_unique<DofMap>(m.body, dc);
  // The case's law: the Newton path's material, and the stress of the
  // ParaView output in both paths (small strain: the linear law's P is sigma).
  // (A CaseSpec made in code may give only E and nu.)
  const MaterialParameters& given = spec.material_parameters;
  m.law = make_law(spec.model, std::isnan(given.E) && given.values.empty() ? MaterialParameters{spec.E, spec.nu, {}} : given);
  // The small-deformation path assembles with the law's own elasticity at
  // F = I (materials/hyperelastic.hpp): a law is written once.
  try {
    m.material = small_strain_material(*m.law, m.body.space_dim());
  } catch (const MaterialError& e) {
    throw InputError(fmt::format("{}: [material] {}", spec.path, e.what()));
  }

  for (const ContactSpec& cs : spec.contacts) {
    const auto faces = find_faces(m, cs.face);
    if (!faces)
      throw InputError(fmt::format("{}: [contact] face: unknown face '{}' on a {} (known: {})", spec.path, cs.face,
                                   spec.shape, fmt::join(face_names(m), ", ")));
    Model::Contact c;
    c.face_name = cs.face;
    const auto& o = cs.obstacle;
    try {
      c.obstacle = find_obstacle_type(o.type)->make(o.values);
    } catch (const std::exception& e) {
      throw InputError(fmt::format("{}: [contact.obstacle] {}", spec.path, e.what()));
    }
    if (!o.motion.empty()) {
      c.motion = Eigen::Map<const Eigen::VectorXd>(o.motion.data(), Eigen::Index(o.motion.size()));
      // Small deformation: the obstacle stands where its motion puts it.
      if (!spec.finite_strain()) c.obstacle = std::make_unique<TranslatedObstacle>(std::move(c.obstacle), c.motion);
    }
    try {
      c.face = std::make_unique<ContactFace>(m.body, *faces);
    } catch (const SplineError& e) {
      throw InputError(fmt::format("{}: [contact] face '{}': {}", spec.path, cs.face, e.what()));
    }
    // A Dirichlet condition on the contact face along the obstacle's normal
    // leaves the contact nothing to do there.
    const Eigen::VectorXd n = initial_contact_point(*c.face, *c.obstacle).second;
    for (const auto& d : spec.dirichlet)
      if (std::find(d.faces.begin(), d.faces.end(), cs.face) != d.faces.end() && n.size() > d.component &&
          std::abs(n[d.component]) > 0.5)
        m.warnings.push_back(fmt::format("{}: [[dirichlet]] holds component {} of the contact face '{}', along the "
                                         "obstacle's normal: the contact cannot act where it holds",
                                         spec.path, "xyz"[d.component], cs.face));
    if (auto why = contact_cannot_happen(*c.face, *c.obstacle))
      throw InputError(fmt::format("{}: [contact] face '{}' and its obstacle: {}", spec.path, cs.face, *why));
    m.contacts.push_back(std::move(c));
  }
  return m;
}

std::optional<ExactDisplacement> exact_displacement(const CaseSpec& spec) {
  if (spec.reference != "lame") return std::nullopt;
  // Plane strain thick cylinder, internal pressure pi on r = a, free at r = b:
  // sigma_rr = A - B/r^2, A = pi a^2/(b^2-a^2), B = pi a^2 b^2/(b^2-a^2),
  // u_r = (1+nu)/E ((1-2nu) A r + B/r).
  double pi = 0;
  for (const auto& p : spec.pressure)
    for (const auto& f : p.faces)
      if (f == "inner") pi += p.value;
  const double a = spec.inner_radius, b = spec.outer_radius, E = spec.E, nu = spec.nu;
  const double A = pi * a * a / (b * b - a * a), B = pi * a * a * b * b / (b * b - a * a);
  const double c = (1 + nu) / E;
  return [=](const Eigen::VectorXd& X, Eigen::VectorXd& u, Eigen::MatrixXd& g) {
    const double r = std::hypot(X[0], X[1]);
    const double ur = c * ((1 - 2 * nu) * A * r + B / r);
    const double dur = c * ((1 - 2 * nu) * A - B / (r * r));
    const double ct = X[0] / r, st = X[1] / r;
    u.resize(2);
    u << ur * ct, ur * st;
    // grad u = dur e_r e_r^T + (ur / r) e_t e_t^T
    g.resize(2, 2);
    g << dur * ct * ct + ur / r * st * st, (dur - ur / r) * ct * st, (dur - ur / r) * ct * st,
        dur * st * st + ur / r * ct * ct;
  };
}

double pressure_resultant(const Model& m) {
  const int dim = m.body.space_dim();
  double total = 0;
  for (const auto& p : m.spec.pressure)  // |int P n dGamma| per pressure load, on the reference faces
    for (const auto& n : p.faces) {
      const std::vector<PatchSide> faces = *find_faces(m, n);
      Eigen::VectorXd res = Eigen::VectorXd::Zero(dim);  // a face made of several sides sums them
      for (const PatchSide& f : faces) {
        const PatchQuadrature q = face_quadrature(m.body, f, gauss_points_for(m.body.degree()));
        ElementData ed;
        for (int e = 0; e < q.num_elements(); ++e) {
          q.evaluate(e, ed, false);
          for (int k = 0; k < ed.JxW.size(); ++k) res += p.value * ed.normal.row(k).transpose() * ed.JxW[k];
        }
      }
      total += res.norm();
    }
  return total;
}

std::vector<ObstacleReaction> obstacle_reactions(const Model& m, const Eigen::VectorXd& lambda,
                                                const Eigen::VectorXd& weights, const std::vector<char>& active) {
  std::vector<ObstacleReaction> out;
  int offset = 0;
  for (const auto& c : m.contacts) {
    ObstacleReaction rr{c.face_name, c.obstacle->describe(), 0.0, 0};
    for (int K = offset; K < offset + c.face->num_multipliers(); ++K) {
      rr.normal_force -= lambda[K] * weights[K];
      rr.active += active[K] ? 1 : 0;
    }
    rr.normal_force += 0.0;  // no -0
    offset += c.face->num_multipliers();
    out.push_back(rr);
  }
  return out;
}

WeightedGapOperator assemble_contact_operator(const Model& m) {
  std::vector<WeightedGapOperator> ops;
  for (const auto& c : m.contacts) ops.push_back(assemble_weighted_gaps(*m.dofs, *c.face, *c.obstacle));
  return stack(ops);
}

void check_body_is_held(const Model& m, const RigidModes& modes, const Eigen::VectorXd& f) {
  const int k = int(modes.modes.cols());
  if (k == 0) return;
  if (m.contacts.empty())
    throw InputError(fmt::format(
        "{}: the body is not held: {} rigid motion(s) are free of Dirichlet conditions and there is no [contact]",
        m.spec.path, k));
  // A frictionless contact holds a rigid motion only if the motion changes
  // the weighted gaps: H = G * modes must have full column rank.
  const WeightedGapOperator op = assemble_contact_operator(m);
  const Eigen::MatrixXd H = op.G * modes.modes;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(H);
  const double s_max = svd.singularValues().size() ? svd.singularValues()[0] : 0.0;
  int held = 0;
  for (int i = 0; i < svd.singularValues().size(); ++i)
    if (svd.singularValues()[i] > 1e-8 * s_max && s_max > 0) ++held;
  if (held < k)
    throw InputError(fmt::format(
        "{}: the body is not held: {} rigid motion(s) are free of Dirichlet conditions and the frictionless contact "
        "cannot stop them (it pushes only along the obstacle's normal); add a [[dirichlet]] condition",
        m.spec.path, k - held));
  // One free motion (the usual symmetric case): the load must move the body
  // toward the obstacle, closing some gap, or nothing balances it.
  if (k == 1) {
    const double push = modes.modes.col(0).dot(f);
    const double scale = H.col(0).cwiseAbs().maxCoeff();
    const Eigen::VectorXd opening = (push > 0 ? 1.0 : -1.0) * H.col(0);  // gap change along the load's motion
    if (std::abs(push) > 1e-12 * f.norm() && opening.minCoeff() >= -1e-12 * scale && opening.maxCoeff() > 1e-12 * scale)
      throw InputError(fmt::format(
          "{}: the load pulls the body away from the obstacle: only the contact holds it along its free rigid "
          "motion, and the load opens every gap (is the load's sign reversed?)",
          m.spec.path));
  }
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
    built->quiet = true;
    solved.emplace(solve_model(*built));
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
}  // namespace

RunResult solve_model(const Model& m, const StepObserver& on_step, CoarserRun coarser) {
  if (m.spec.finite_strain()) return solve_finite_strain(m, on_step);
  RunResult r;
  const auto t_start = Clock::now();
  const Body& body = m.body;
  const int dim = body.space_dim();
  auto t0 = Clock::now();
  Eigen::VectorXd bf = m.spec.body_force.empty()
                           ? Eigen::VectorXd::Zero(dim)
                           : Eigen::Map<const Eigen::VectorXd>(m.spec.body_force.data(), dim).eval();
  // One process: every element.  PETSc on several: this process's block
  // (the element loads summed over the processes, so f is whole everywhere).
  const bool petsc = uses_petsc(m);
  LinearSystem sys = assemble_linear_elasticity(body, *m.dofs, m.material, bf, process_elements(m));
  sum_over_processes(sys.f);
  for (const auto& p : m.spec.pressure) add_pressure_load(body, *m.dofs, resolve_faces(m, p.faces, "pressure"), p.value, sys.f);
  r.timing.assembly = since(t0);
  const RigidModes modes = free_rigid_modes(body, *m.dofs);
  r.applied_force = pressure_resultant(m);
  SparseCholesky chol;
  check_body_is_held(m, modes, sys.f);
  if (m.contacts.empty() && petsc) {
    WeightedGapOperator none;
    none.G.resize(0, m.dofs->num_free());
    const ContactSolution s = solve_with_petsc(m, sys, none, modes, ContactSolverOptions{}, r.linear_solver);
    r.timing.factorization = s.factorize_s;
    r.timing.linear_solve = s.iterations_s;
    r.status = s.status;
    r.u = m.dofs->expand(s.u);
  } else if (m.contacts.empty()) {
    t0 = Clock::now();
    chol.factorize(sys.K);
    r.timing.factorization = since(t0);
    t0 = Clock::now();
    r.u = m.dofs->expand(chol.solve(sys.f));
    r.timing.linear_solve = since(t0);
  } else {
    t0 = Clock::now();
    auto c = std::make_unique<ContactResult>();
    c->op = assemble_contact_operator(m);
    r.timing.assembly += since(t0);
    ContactSolverOptions opt;
    opt.complementarity_scale = m.spec.E / std::max(m.mesh_size, 1e-300);
    t0 = Clock::now();
    // Nested iteration from the solution one refinement below: the PETSc
    // path solves it first (a Krylov or MUMPS solve per active-set
    // iteration: 17 -> 2 of them on hertz3d's 225k reference); the direct
    // path takes it when it is at hand (a study's previous level) but does
    // not solve it for itself, which costs more than the Schur columns it
    // saves (hertz2d --refine 2: 0.39 -> 0.47 s, hertz3d_study --refine 2:
    // 3.9 -> 4.2 s; only at 225k unknowns did it gain, 116 -> 98 s).
    if (m.spec.refine > 0 && (petsc || coarser.result))
      start_from_coarser_mesh(m, coarser, c->op, int(modes.modes.cols()), opt);
    c->solution = petsc ? solve_with_petsc(m, sys, c->op, modes, opt, r.linear_solver)
                        : solve_small_strain_contact(sys.K, sys.f, c->op, modes, chol, opt);
    r.timing.factorization = c->solution.factorize_s;
    r.timing.contact = since(t0) - c->solution.factorize_s;
    r.status = c->solution.status;
    if (c->solution.u.size() != m.dofs->num_free())
      throw std::runtime_error(fmt::format("contact solve failed: {}", c->solution.status));
    r.u = m.dofs->expand(c->solution.u);
    t0 = Clock::now();
    r.reactions = obstacle_reactions(m, c->solution.lambda, c->op.weights, c->solution.active);
    const Model::Contact& first = m.contacts.front();
    const int m0 = first.face->num_multipliers();
    std::tie(c->X0, c->normal) = initial_contact_point(*first.face, *first.obstacle);
    c->pressure = std::make_unique<ContactPressure>(
        *first.face, c->solution.lambda.head(m0), c->op.weights.head(m0),
        std::vector<char>(c->solution.active.begin(), c->solution.active.begin() + m0), c->X0, c->normal);
    c->report = c->pressure->report();
    // A rigid obstacle can only push: a net pull on the body (tensile
    // multipliers) is a wrong result, never a converged one.
    for (const auto& rr : r.reactions)
      if (r.status == "converged" && rr.normal_force < -1e-9 * std::max(r.applied_force, 1e-300))
        r.status = fmt::format("failed: the obstacle of face '{}' pulls on the body (contact force {:.3g} < 0)",
                               rr.face, rr.normal_force);
    if (m.spec.reference == "hertz") {
      double P = 0;
      for (const auto& p : m.spec.pressure) P += p.value;
      r.hertz = dim == 2 ? hertz_cylinder(m.spec.radius, P, m.spec.E, m.spec.nu)
                         : hertz_sphere(m.spec.radius, P, m.spec.E, m.spec.nu);
      const HertzSolution h = *r.hertz;
      const ContactPressure& cp = *c->pressure;
      r.pressure_error = cp.l2_error(*first.face,
                                     [&](int, const Eigen::VectorXd&, const Eigen::VectorXd& X) { return h.pressure(cp.r_of(X)); },
                                     std::max(10, body.degree() + 1));
    }
    r.timing.postprocess += since(t0);
    r.contact = std::move(c);
  }
  if (auto exact = exact_displacement(m.spec)) {
    t0 = Clock::now();
    r.displacement_errors = errors_against_exact(body, r.u, *exact, body.degree() + 2);
    r.timing.postprocess += since(t0);
  }
  r.timing.total = since(t_start);
  return r;
}

}  // namespace igac
