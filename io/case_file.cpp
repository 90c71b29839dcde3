// SPDX-License-Identifier: BSD-3-Clause
#include "io/case_file.hpp"

#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <set>
#include <sstream>
#include <toml++/toml.h>
#include <algorithm>

#include "contact/interface_law.hpp"
#include "contact/obstacle.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/load_curve.hpp"
#include "io/gismo_xml.hpp"
#include "io/input_file.hpp"
#include "io/case_section.hpp"
#include "io/case_table.hpp"
#include "io/toml_guard.hpp"
#include "model/references.hpp"
#include "materials/hyperelastic.hpp"
#include <unistd.h>

namespace igac {
using namespace case_reading;
namespace {

// The keys of the tables whose keys are fixed; read_case refuses any other,
// and declared_case_keys() lists them for docs/case_file.md's test.  The
// keys of a shape, a law or an obstacle come from their registries.
const std::set<std::string> kTopKeys{"name", "description", "geometry", "mesh", "material", "dirichlet",
                                     "pressure", "traction", "body_force", "contact", "reference", "output", "loading",
                                     "faces", "solver", "body", "units", "model"};
const std::set<std::string> kBodyKeys{"name", "geometry", "mesh", "material"};
const std::set<std::string> kDirichletKeys{"faces", "component", "value", "curve"};
const std::set<std::string> kPressureKeys{"faces", "value", "curve", "fluid_entry"};
const std::set<std::string> kTractionKeys{"faces", "value", "curve"};
const std::set<std::string> kBodyForceKeys{"value", "curve"};
const std::set<std::string> kContactKeys{"face",         "obstacle", "master",     "master_motion",
                                          "master_curve", "friction", "integration", "law",
                                          "interference"};
const std::set<std::string> kObstacleKeys{"type", "motion", "curve"};  // and the obstacle type's own
const std::set<std::string> kReferenceKeys{"solution"};
const std::set<std::string> kLoadingKeys{"steps", "first_increment", "min_increment", "max_increment",
                                         "max_newton_iterations", "line_search", "predictor", "pressure", "active_set"};
const std::set<std::string> kOutputKeys{"vtk"};
const std::set<std::string> kSolverKeys{"type", "options", "preconditioner"};
const std::set<std::string> kUnitsKeys{"system", "length", "force", "stress"};
const std::set<std::string> kModelKeys{"kind"};

// Why the case cannot be the plane stress model it declares ("" when it can).
std::string plane_stress_refusal(const CaseSpec& c) {
  if (c.dim() != 2) return "plane_stress is a 2D model (this case is 3D: leave [model] out)";
  for (const BodySpec& b : c.body_list())
    if (is_mixed(b.formulation))
      return fmt::format("plane stress needs no mixed formulation (the thickness takes the volume change, nothing "
                         "locks): give{} [material] formulation = \"displacement\"",
                         b.body_name.empty() ? "" : " body '" + b.body_name + "'");
  if (c.finite_strain() && c.loading.follower_pressure && !c.pressure.empty())
    return "a follower pressure in large-deformation plane stress would act on a face whose thickness changes, "
           "which igac does not model: give [loading] pressure = \"dead\" (on the reference face)";
  return {};
}

}  // namespace

std::optional<std::string> nearest_name(const std::string& word, const std::vector<std::string>& candidates) {
  // Levenshtein distance, one row at a time.
  auto distance = [](const std::string& a, const std::string& b) {
    std::vector<size_t> row(b.size() + 1);
    for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
      size_t diagonal = row[0];
      row[0] = i;
      for (size_t j = 1; j <= b.size(); ++j) {
        const size_t up = row[j];
        row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
        diagonal = up;
      }
    }
    return row[b.size()];
  };
  std::optional<std::string> best;
  size_t best_d = std::max<size_t>(1, word.size() / 3) + 1;
  for (const std::string& c : candidates)
    if (const size_t d = distance(word, c); d < best_d) best_d = d, best = c;
  return best;
}


// A case file is data: of PETSc's options it may give only these, each
// with a value checked here (no option that names a file, so that a case
// file can neither read nor write one).  Any other option is given on the
// command line (--petsc-options), where the user types it.
std::string check_case_petsc_options(const std::string& options) {
  enum class Value { word, positive_number, positive_integer };
  struct Allowed {
    const char* option;
    Value value;
    std::vector<const char*> words;
  };
  static const std::vector<Allowed> allowed{
      {"-ksp_type", Value::word, {"cg", "gmres", "fgmres", "minres", "bcgs", "gcr", "preonly"}},
      {"-pc_type", Value::word, {"lu", "cholesky", "fieldsplit", "gamg", "hypre", "ml", "jacobi", "bjacobi", "asm", "ilu", "icc", "none"}},
      {"-pc_factor_mat_solver_type", Value::word, {"mumps", "superlu_dist", "petsc"}},
      {"-pc_fieldsplit_type", Value::word, {"additive", "multiplicative", "symmetric_multiplicative", "schur"}},
      {"-pc_fieldsplit_schur_fact_type", Value::word, {"diag", "lower", "upper", "full"}},
      {"-ksp_rtol", Value::positive_number, {}},
      {"-ksp_atol", Value::positive_number, {}},
      {"-ksp_divtol", Value::positive_number, {}},
      {"-ksp_max_it", Value::positive_integer, {}},
      {"-ksp_gmres_restart", Value::positive_integer, {}},
  };
  std::istringstream in(options);
  std::vector<std::string> tokens;
  for (std::string t; in >> t;) tokens.push_back(t);
  std::vector<std::string> names;
  for (const Allowed& a : allowed) names.emplace_back(a.option);
  for (size_t i = 0; i < tokens.size(); ++i) {
    const auto a = std::find_if(allowed.begin(), allowed.end(), [&](const Allowed& x) { return tokens[i] == x.option; });
    if (a == allowed.end())
      return fmt::format("'{}' is not among the PETSc options a case file may give ({}); give it on the command "
                         "line with --petsc-options", tokens[i], fmt::join(names, " "));
    if (i + 1 >= tokens.size()) return fmt::format("{} needs a value", a->option);
    const std::string& v = tokens[++i];
    bool ok = false;
    if (a->value == Value::word) {
      ok = std::any_of(a->words.begin(), a->words.end(), [&](const char* w) { return v == w; });
      if (!ok) return fmt::format("{} {}: the value must be one of {}", a->option, v, fmt::join(a->words, " "));
    } else {
      char* end = nullptr;
      const double x = std::strtod(v.c_str(), &end);
      ok = end && *end == '\0' && std::isfinite(x) && x > 0 &&
           (a->value == Value::positive_number || (x == std::floor(x) && x <= 1e9));
      if (!ok)
        return fmt::format("{} {}: the value must be a positive {}", a->option, v,
                           a->value == Value::positive_number ? "number" : "whole number");
    }
  }
  return {};
}

namespace {

// [[body]] tables: each body's own geometry, mesh and material, and what the
// case's BodySpec part holds for all of them (model/case_spec.hpp).
void read_bodies(const std::string& path, const toml::table& root, CaseSpec& c) {
  std::vector<const toml::table*> tabs = tables(path, root, "body");
  for (const toml::table* t : tabs) {
    const Section s(path, "body", *t, kBodyKeys);
    BodySpec b;
    b.body_name = s.string("name");
    // A face of a body is "NAME:FACE": the name starts with a letter (patch
    // numbers start with a digit) and holds no ':'.
    const bool word = !b.body_name.empty() && std::isalpha((unsigned char)b.body_name[0]) &&
                      b.body_name.size() <= 64 &&
                      std::all_of(b.body_name.begin(), b.body_name.end(), [](unsigned char ch) {
                        return std::isalnum(ch) || ch == '_' || ch == '-';
                      });
    if (!word)
      s.fail("name", fmt::format("{:?} is not a body name (a letter, then letters, digits, '_' or '-': faces are "
                                 "named NAME:FACE)", b.body_name));
    for (const BodySpec& other : c.bodies)
      if (other.body_name == b.body_name) s.fail("name", fmt::format("two bodies are named '{}'", b.body_name));
    read_body_tables(path, s, fmt::format("body '{}' ", b.body_name), b);
    if (!c.bodies.empty() && b.dim() != c.bodies.front().dim())
      s.fail("geometry", fmt::format("body '{}' is {}D, body '{}' {}D: the bodies of a case share one dimension",
                                     b.body_name, b.dim(), c.bodies.front().body_name, c.bodies.front().dim()));
    // One kinematics per case: a linear body (small strain, not objective)
    // beside a hyperelastic one would turn its rotations into strain.
    if (!c.bodies.empty() && b.finite_strain() != c.bodies.front().finite_strain())
      s.fail("material", fmt::format("body '{}' has model \"{}\" and body '{}' model \"{}\": the bodies of a case are "
                                     "all small-deformation (\"linear_elastic\") or all hyperelastic (large "
                                     "deformation; \"saint_venant_kirchhoff\" for a stiff part)",
                                     b.body_name, b.model, c.bodies.front().body_name, c.bodies.front().model));
    c.bodies.push_back(std::move(b));
  }
  // What the bodies share (model/case_spec.hpp): the stiffest body's E and
  // nu set the contact's scales; the smallest degree is the one a contact
  // check needs; refine is what --refine adds to every body.
  const BodySpec* stiffest = &c.bodies.front();
  for (const BodySpec& b : c.bodies)
    if (b.E > stiffest->E) stiffest = &b;
  static_cast<BodySpec&>(c) = *stiffest;
  c.body_name.clear();
  c.shape = fmt::format("case of {} bodies", c.bodies.size());
  c.geometry_file.clear();
  c.file_body.reset();
  c.shape_values.clear();
  c.elements.clear();
  c.gradings.clear();
  c.refine = 0;
  for (const BodySpec& b : c.bodies) c.degree = std::min(c.degree, b.degree);
}

bool has_control_character(std::string_view text) {
  return std::any_of(text.begin(), text.end(), [](unsigned char ch) { return ch < 32 || ch == 127; });
}

// [faces.NAME] side = "...", range = [from, to] (2D) or [[from, to], [from,
// to]] (3D: the side's two directions in the patch's order): fractions of
// the side's parameter range, 0 <= from < to <= 1.
PartialFaceSpec read_partial_face(const std::string& path, const std::string& name, const toml::table& t, int dim) {
  const Section s(path, "faces." + name, t, {"side", "range"});
  PartialFaceSpec out{name, s.string("side"), {}};
  const char* form = dim == 2 ? "must be [from, to], fractions of the side's parameter range, e.g. [0.25, 0.75]"
                              : "must be [[from, to], [from, to]], fractions of the side's two parameter ranges "
                                "in the patch's order, e.g. [[0, 0.5], [0, 1]]";
  const auto* range = s.node("range");
  if (!range) s.fail("range", form);
  const auto pair_of = [&](const toml::node& n) {
    const auto* a = n.as_array();
    if (!a || a->size() != 2) s.fail("range", form);
    std::array<double, 2> r{};
    for (size_t i = 0; i < 2; ++i) {
      const auto v = (*a)[i].value<double>();
      if (!v) s.fail("range", form);
      r[i] = *v;
    }
    if (!(r[0] >= 0 && r[0] < r[1] && r[1] <= 1))
      s.fail("range", fmt::format("[{:g}, {:g}] must satisfy 0 <= from < to <= 1 (fractions of the side's parameter "
                                  "range)", r[0], r[1]));
    return r;
  };
  if (dim == 2) {
    out.range.push_back(pair_of(*range));
  } else {
    const auto* a = range->as_array();
    if (!a || a->size() != 2) s.fail("range", form);
    for (const auto& n : *a) out.range.push_back(pair_of(n));
  }
  return out;
}

// A case with load curves: what they do not run with, one line; then every
// load without a curve of its own ramps to its value over [0, 1] and keeps it.
void check_load_curves(CaseSpec& c) {
  if (!c.has_load_curves()) return;
  if (c.reference != "none")
    throw InputError(fmt::format("{}: [reference] solution: a reference solution is compared with the loads at their "
                                 "values, not along load curves; give solution = \"none\"",
                                 c.where({.table = "reference", .key = "solution"})));
  auto hold = [](LoadCurve& curve) {
    if (!curve.has_points()) curve = LoadCurve::ramp_and_hold();
  };
  for (DirichletSpec& d : c.dirichlet) hold(d.curve);
  for (PressureSpec& p : c.pressure) hold(p.curve);
  for (TractionSpec& p : c.traction) hold(p.curve);
  hold(c.body_force_curve);
  for (ContactSpec& cs : c.contacts) hold(cs.obstacle.curve);
}

// Every key of `t` (a table called `name`, the index-th of that name, in
// the body-th [[body]]) into `out`, its tables' keys after it; `count`
// numbers the tables per name.
void index_keys(const toml::table& t, const std::string& name, int index, int body,
                std::map<std::string, int>& count, std::vector<CaseSource::Key>& out) {
  out.push_back({name, index, body, "", int(t.source().begin.line), {}});
  std::vector<std::pair<std::string, const toml::table*>> tables;
  for (const auto& [k, v] : t) {
    const std::string key(k.str()), sub = name.empty() ? key : name + "." + key;
    if (const auto* table = v.as_table()) {
      tables.emplace_back(sub, table);
      continue;
    }
    const auto* array = v.as_array();
    if (array && !array->empty() && array->front().is_table()) {
      for (const auto& e : *array)
        if (const auto* table = e.as_table()) tables.emplace_back(sub, table);
      continue;
    }
    CaseSource::Key entry{name, index, body, key, int(v.source().begin.line), {}};
    if (const auto word = v.value<std::string>()) entry.words.push_back(*word);
    if (array)
      for (const auto& e : *array)
        if (const auto word = e.value<std::string>()) entry.words.push_back(*word);
    out.push_back(std::move(entry));
  }
  for (const auto& [sub, table] : tables) {
    const int i = count[sub]++;
    index_keys(*table, sub, i, sub == "body" ? i : body, count, out);
  }
}

// The curve of `root` (any table, key curve or master_curve) whose last
// time is the latest: its table's name, key and line (line 0: none).
struct CurveKey {
  double end = -1;
  std::string table, key;
  int line = 0;
};
void find_latest_curve(const toml::table& t, const std::string& name, CurveKey& best) {
  for (const auto& [k, v] : t) {
    const std::string key(k.str()), sub = name.empty() ? key : name + "." + key;
    if (const auto* table = v.as_table()) {
      find_latest_curve(*table, sub, best);
    } else if (const auto* array = v.as_array()) {
      if (key == "curve" || key == "master_curve") {
        const auto* last = array->empty() ? nullptr : array->back().as_array();
        const auto end = last && !last->empty() ? (*last)[0].value<double>() : std::nullopt;
        if (end && *end > best.end) best = {*end, name, key, int(v.source().begin.line)};
      } else {
        for (const auto& e : *array)
          if (const auto* table = e.as_table()) find_latest_curve(*table, sub, best);
      }
    }
  }
}

// A run in steps takes at most kMaxLoadSteps (engine/load_curve.hpp): small
// deformation along load curves takes [loading] steps per unit time to the
// curves' end, large deformation at least one step per max_increment of
// time.  A long curve times many steps (2e9 step times: 16 GB) or a tiny
// max_increment is refused on the key that sets the count: the [loading]
// key when the case gives it, else the curve that ends last.
void check_load_step_count(const CaseSpec& c, const toml::table& root, const std::string& path) {
  const bool curves = c.has_load_curves();
  if (!c.finite_strain() && !curves) return;  // (friction without curves: [loading] steps <= kMaxLoadSteps)
  const std::vector<double> corners = curves ? curve_corners(c.load_curves()) : std::vector<double>{1.0};
  const double per_unit = c.finite_strain() ? 1.0 / c.loading.max_increment : double(c.loading.steps);
  const double n = count_step_times(corners, per_unit);
  if (n <= kMaxLoadSteps) return;
  const char* key = c.finite_strain() ? "max_increment" : "steps";
  const std::string along = curves ? fmt::format(" along load curves that end at t = {:g}", corners.back()) : "";
  const std::string why =
      c.finite_strain()
          ? fmt::format("max_increment = {:g}{} makes at least {:.3g} load steps, more than {:g} (each writes a "
                        "ParaView step and a state file); give a larger max_increment{}",
                        c.loading.max_increment, along, n, kMaxLoadSteps, curves ? " or shorter curves" : "")
          : fmt::format("steps = {} per unit time{} make {:.3g} load steps, more than {:g} (each writes a ParaView "
                        "step and a state file); give fewer steps per unit time or shorter curves",
                        c.loading.steps, along, n, kMaxLoadSteps);
  const toml::table* loading = root["loading"].as_table();
  if (loading && loading->contains(key)) Section(path, "loading", *loading, kLoadingKeys).fail(key, why);
  CurveKey latest;
  find_latest_curve(root, "", latest);
  if (latest.line > 0)
    throw InputError(fmt::format("{}:{}: [{}] {}: {}", path, latest.line, latest.table, latest.key, why));
  throw InputError(fmt::format("{}: [loading] {}: {}", path, key, why));
}

}  // namespace

CaseSpec read_case(const std::string& path) { return read_case_text(read_input_file(path, kCaseFile), path); }

toml::table parse_case_text(const std::string& text, const std::string& path) {
  if (const auto line = overlong_toml_key(text))  // (toml++ would overflow its stack)
    throw InputError(fmt::format("{}:{}: a key of more than {} dotted parts", path, *line, kMaxTomlKeyParts));
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}: malformed TOML: {}", path, e.source().begin.line, e.description()));
  }
}

CaseSpec read_case_text(const std::string& text, const std::string& path) {
  return read_case_table(parse_case_text(text, path), path);
}

CaseSpec read_case_table(const toml::table& root, const std::string& path) {
  CaseSpec c;
  c.path = path;
  {
    std::map<std::string, int> count;
    index_keys(root, "", 0, -1, count, c.source.keys);
  }
  const Section top(path, "top level", root, kTopKeys);
  c.name = top.string("name", std::filesystem::path(path).stem().string());
  // The name becomes a folder under out/: a plain file name, nothing that
  // climbs out of it or that a shell or a file system would read otherwise.
  const bool plain = !c.name.empty() && c.name != "." && c.name != ".." && c.name.size() <= 200 &&
                     !has_control_character(c.name) &&
                     std::none_of(c.name.begin(), c.name.end(), [](unsigned char ch) { return ch == '/' || ch == '\\'; });
  if (!plain)
    top.fail("name", fmt::format("{:?} is not a plain file name (it names the output folder out/<name>: "
                                 "no '/', not empty, not '.' or '..')", c.name));
  c.description = top.string("description", "");

  // One body: [geometry], [mesh] and [material] at the top level; several:
  // [[body]] tables, each with its own.
  if (root.contains("body")) {
    for (const char* k : {"geometry", "mesh", "material"})
      if (root.contains(k))
        top.fail(k, fmt::format("a case of [[body]] tables gives each body its own [body.{}], not one [{}] at the "
                                "top level", k, k));
    read_bodies(path, root, c);
  } else {
    read_body_tables(path, top, "", c);
  }
  const int dim = c.dim();

  if (root.contains("faces")) {  // names of one's own for sets of faces
    const toml::table& ft = top.sub("faces");
    std::set<std::string> keys;
    for (const auto& [k, v] : ft) {
      keys.insert(std::string(k.str()));
      if (has_control_character(k.str()))  // (a face's name is printed, and titles the SVG plots)
        top.fail("faces", fmt::format("the name {:?} holds a control character", std::string(k.str())), &v);
    }
    const Section faces(path, "faces", ft, keys);
    for (const auto& k : keys) {
      if (const auto* part = ft.get(k)->as_table())
        c.partial_faces.push_back(read_partial_face(path, k, *part, dim));
      else
        c.face_sets[k] = faces.strings(k);
    }
  }

  for (const auto* t : tables(path, root, "dirichlet")) {
    const Section s(path, "dirichlet", *t, kDirichletKeys);
    c.dirichlet.push_back({s.strings("faces"), component_index(s, "component", dim), s.load("value", 0.0), {}});
    if (s.has("curve")) {
      if (c.dirichlet.back().value == 0)
        s.fail("curve", "the condition holds the faces at 0: there is no prescribed value for the curve to scale");
      c.dirichlet.back().curve = s.curve("curve");
    }
  }
  for (const auto* t : tables(path, root, "pressure")) {
    const Section s(path, "pressure", *t, kPressureKeys);
    c.pressure.push_back({s.strings("faces"), s.load("value"), {}, {}});
    if (s.has("curve")) c.pressure.back().curve = s.curve("curve");
    if (s.has("fluid_entry")) {
      c.pressure.back().fluid_entry = s.loads("fluid_entry", size_t(dim));
      if (!c.finite_strain())
        s.fail("fluid_entry", "a fluid pressure that follows the contact front is posed in large deformation (a "
                              "hyperelastic [material] model): the linear solve has no front to follow");
    }
  }
  for (const auto* t : tables(path, root, "traction")) {
    const Section s(path, "traction", *t, kTractionKeys);
    c.traction.push_back({s.strings("faces"), s.loads("value", size_t(dim)), {}});
    if (s.has("curve")) c.traction.back().curve = s.curve("curve");
  }
  if (root.contains("body_force")) {
    const Section s(path, "body_force", top.sub("body_force"), kBodyForceKeys);
    c.body_force = s.loads("value", dim);
    if (s.has("curve")) c.body_force_curve = s.curve("curve");
  }
  for (const auto* contact_table : tables(path, root, "contact")) {  // [contact] or [[contact]]
    const Section s(path, "contact", *contact_table, kContactKeys);
    ContactSpec cs;
    cs.face = s.string("face");
    // Against a rigid obstacle, or (two deformable bodies) against a master
    // face of the body: the patches of one geometry file that no interface
    // joins are separate bodies.
    if (s.has("master") && s.has("obstacle"))
      s.fail("master", "give an obstacle (a rigid body) or a master face (a second deformable body), not both");
    if (!s.has("master") && !s.has("obstacle"))
      s.fail("obstacle", "missing: give an obstacle (a rigid body) or a master face (a second deformable body)");
    if (s.has("master")) {
      cs.master = s.string("master");
      if (cs.master.empty()) s.fail("master", "empty: name the face of the second body");  // ("" means no master)
      if (cs.master == cs.face) s.fail("master", "the master face is the contact face itself");
      if (s.has("master_motion")) {
        if (c.finite_strain())
          s.fail("master_motion", fmt::format("moves the master body in small deformation only (material model "
                                              "\"linear_elastic\"), not with model \"{}\": move its supports "
                                              "instead, a [[dirichlet]] value with a curve on their faces "
                                              "(cases/ironing.toml)",
                                              c.model));
        cs.master_motion = s.loads("master_motion", dim);
      }
      if (s.has("master_curve")) {  // (kept as the obstacle's curve: every load's curve is in CaseSpec::load_curves)
        if (!s.has("master_motion")) s.fail("master_curve", "there is no master_motion for the curve to scale");
        cs.obstacle.curve = s.curve("master_curve");
      }
    } else {
      if (s.has("master_curve"))
        s.fail("master_curve", "is the curve of a master body's master_motion; an obstacle's motion has its curve in "
                               "[contact.obstacle] curve");
      if (s.has("master_motion"))
        s.fail("master_motion", "moves the master body of a contact between two bodies; an obstacle moves by "
                                "[contact.obstacle] motion");
      const toml::table& ot = s.sub("obstacle");
      const std::string type = ot["type"].value_or(std::string());
      const ObstacleType* kind = find_obstacle_type(type);
      std::set<std::string> keys = kObstacleKeys;
      // An unknown type, or one for another dimension: the type is the
      // error, not the keys written for the type meant.
      const bool fits = kind && dim >= kind->min_dim && dim <= kind->max_dim;
      for (const ObstacleType* t : obstacle_types())
        if (t == kind || !fits)
          for (const ObstacleKey& k : t->keys) keys.insert(std::string(k.key));
      const Section o(path, "contact.obstacle", ot, keys);
      cs.obstacle.type = o.string("type");
      if (!kind) {
        std::vector<std::string> names;
        for (const ObstacleType* t : obstacle_types()) names.emplace_back(t->name);
        o.fail("type", fmt::format("unknown obstacle '{}' ({})", cs.obstacle.type, fmt::join(names, ", ")));
      }
      if (dim < kind->min_dim || dim > kind->max_dim)
        o.fail("type", fmt::format("a {} obstacle needs a {}D body", kind->name, kind->min_dim));
      for (const ObstacleKey& k : kind->keys) {
        const std::string key(k.key);
        if (k.vector) {
          const auto v = o.loads(key, dim);  // finite, at most 1e100 in size
          double n2 = 0;
          for (double x : v) n2 += x * x;
          if (k.nonzero && !(n2 > 0)) o.fail(key, "must not be zero");
          cs.obstacle.values[key] = v;
        } else {
          const double v = o.load(key);
          if (k.positive && !(v > 0)) o.fail(key, "must be positive");
          cs.obstacle.values[key] = {v};
        }
      }
      if (o.has("motion")) cs.obstacle.motion = o.loads("motion", dim);
      if (o.has("curve")) {
        if (!o.has("motion")) o.fail("curve", "the obstacle has no motion for the curve to scale");
        cs.obstacle.curve = o.curve("curve");
      }
    }
    if (s.has("friction")) {  // Coulomb (contact/small_strain_friction.hpp)
      cs.friction = s.number("friction");  // finite
      if (!(cs.friction >= 0 && cs.friction <= 10)) s.fail("friction", "must lie in [0, 10] (a Coulomb coefficient)");
    }
    if (s.has("law")) {  // the interface law (contact/interface_law.hpp)
      cs.law = s.string("law");
      const InterfaceLaw* law = nullptr;
      try {
        law = &interface_law(cs.law);
      } catch (const std::invalid_argument& e) {
        s.fail("law", e.what());
      }
      if (law->has_coefficient() && !(cs.friction > 0))
        s.fail("law", fmt::format("\"{}\" needs a friction coefficient: friction = f > 0 in the same table", cs.law));
      if (!law->has_coefficient() && cs.friction > 0)
        s.fail("friction", fmt::format("a coefficient of the law \"{}\", which takes none (friction is law = "
                                       "\"coulomb\", the default where friction > 0)", cs.law));
    }
    if (s.has("integration")) {  // the mortar integral between two bodies (contact/mortar_gap.hpp)
      if (!s.has("master"))
        s.fail("integration", "is the mortar integration of a contact between two bodies (with master); against an "
                              "obstacle the face's own Gauss points integrate");
      const std::string integration = s.string("integration");
      if (const auto i = mortar_integration_named(integration)) cs.integration = *i;
      else s.fail("integration", fmt::format("\"{}\" is not one of \"segmented\", \"element\"", integration));
    }
    if (s.has("interference")) {  // an intended starting overlap, removed with the load (model/model.hpp)
      cs.interference = s.boolean("interference", false);
      if (cs.interference && !cs.law.empty() && interface_law(cs.law).bilateral())
        s.fail("interference", fmt::format("a \"{}\" contact holds the gap it starts with; an interference fit needs "
                                           "a contact that can push the faces apart", cs.law));
    }
    if (c.degree < 2) s.fail("face", "contact needs mesh.degree >= 2 (multipliers have degree p-2)");
    for (const ContactSpec& o : c.contacts)  // its multipliers twice over: a singular system
      if (o.face == cs.face && o.master == cs.master && o.obstacle.type == cs.obstacle.type &&
          o.obstacle.values == cs.obstacle.values && o.obstacle.motion == cs.obstacle.motion)
        s.fail("face", fmt::format("the contact of face '{}' is given twice", cs.face));
    c.contacts.push_back(cs);
  }
  if (root.contains("reference")) {
    const Section s(path, "reference", top.sub("reference"), kReferenceKeys);
    c.reference = s.string("solution");
    const ReferenceSolution* ref = find_reference(c.reference);
    if (!ref && c.reference != "none")
      s.fail("solution", fmt::format("unknown reference solution '{}' ({})", c.reference, fmt::join(reference_names(), ", ")));
    if (ref)
      if (const std::string why = ref->unusable(c); !why.empty()) s.fail("solution", why);
  }
  if (root.contains("loading")) {
    // Read whatever the model: a linear case without friction or a curve is
    // solved in one step and reads none of it, but a sweep of a case over
    // friction 0, 0.1, ... keeps one table (it was refused at 0).
    const Section s(path, "loading", top.sub("loading"), kLoadingKeys);
    LoadingSpec& l = c.loading;
    l.steps = s.integer("steps", 10);
    if (l.steps < 1 || l.steps > kMaxLoadSteps) s.fail("steps", fmt::format("must lie in 1..{:g}", kMaxLoadSteps));
    l.first_increment = s.number("first_increment", 0.0);
    if (s.has("first_increment") && !(l.first_increment > 0 && l.first_increment <= 1))
      s.fail("first_increment", "must lie in (0, 1]");
    l.min_increment = s.number("min_increment", 1e-4);
    if (!(l.min_increment > 0 && l.min_increment < 1)) s.fail("min_increment", "must lie in (0, 1)");
    l.max_increment = s.number("max_increment", 1.0);
    if (!(l.max_increment >= l.min_increment && l.max_increment <= 1))
      s.fail("max_increment", "must lie in [min_increment, 1]");
    l.max_newton_iterations = s.integer("max_newton_iterations", 30);
    if (l.max_newton_iterations < 1 || l.max_newton_iterations > 1000) s.fail("max_newton_iterations", "must lie in 1..1000");
    const auto* search = s.node("line_search");
    if (search && search->is_string()) {
      if (s.string("line_search") != "halving")
        s.fail("line_search", "must be true (KINSOL's), false (none) or \"halving\" (the driver's own)");
      l.halving_line_search = true;
    } else {
      l.line_search = s.boolean("line_search", true);
    }
    const std::string predictor = s.string("predictor", "tangent");
    if (predictor != "tangent" && predictor != "tangent_every_step" && predictor != "none")
      s.fail("predictor", "must be \"tangent\" (the first step starts from x - J^-1 dR/dt dt), "
                          "\"tangent_every_step\" or \"none\"");
    l.tangent_predictor = predictor != "none";
    l.tangent_every_step = predictor == "tangent_every_step";
    const std::string active_set = s.string("active_set", "linearised");
    if (active_set != "linearised" && active_set != "semismooth")
      s.fail("active_set", "must be \"linearised\" (each Newton step solves its linearised contact problem to "
                           "its own active set) or \"semismooth\" (one active set per Newton step)");
    l.linearised_active_set = active_set == "linearised";
    const std::string pk = s.string("pressure", "follower");
    if (pk != "follower" && pk != "dead") s.fail("pressure", "must be \"follower\" or \"dead\"");
    l.follower_pressure = pk == "follower";
  }
  if (root.contains("output")) {
    const Section s(path, "output", top.sub("output"), kOutputKeys);
    c.write_vtk = s.boolean("vtk", true);
  }
  if (root.contains("solver")) {
    const Section s(path, "solver", top.sub("solver"), kSolverKeys);
    const std::string type = s.string("type", "direct");
    if (const auto t = solver_type_named(type)) c.solver.type = *t;
    else
      s.fail("type", fmt::format("unknown solver '{}' (direct: CHOLMOD on one process; petsc: PETSc, also under mpirun)",
                                 type));
    c.solver.options = s.string("options", "");
    if (!c.solver.options.empty() && !c.solver.petsc())
      s.fail("options", "PETSc options need type = \"petsc\"");
    if (const std::string why = check_case_petsc_options(c.solver.options); !why.empty()) s.fail("options", why);
    const std::string preconditioner = s.string("preconditioner", "options");
    if (!set_preconditioner(c.solver, preconditioner)) s.fail("preconditioner", unknown_preconditioner(preconditioner));
    if (const std::string why = check_preconditioner(c.solver); !why.empty()) s.fail("preconditioner", why);
    if (c.solver.petsc())
      if (const std::string why = check_petsc_case(c); !why.empty()) s.fail("type", why);
  }
  if (root.contains("units")) {  // labels only
    const Section s(path, "units", top.sub("units"), kUnitsKeys);
    UnitsSpec& u = c.units;
    u.system = s.string("system", "");
    if (u.system == "mm-N-MPa") u = {u.system, "mm", "N", "MPa"};
    else if (u.system == "SI") u = {u.system, "m", "N", "Pa"};
    else if (!u.system.empty())
      s.fail("system", fmt::format("unknown system '{}' (\"mm-N-MPa\" or \"SI\"; or give length, force and stress)",
                                   u.system));
    u.length = s.string("length", u.length);
    u.force = s.string("force", u.force);
    u.stress = s.string("stress", u.stress);
    // Labels printed on the console and in the SVG plots, which XML forbids
    // control characters in (and a terminal reads as commands).
    for (const auto& [key, label] : {std::pair{"length", &u.length}, {"force", &u.force}, {"stress", &u.stress}})
      if (has_control_character(*label))
        s.fail(key, fmt::format("{:?} holds a control character: a unit's name is a label (\"mm\", \"N\", \"MPa\")",
                                *label));
  }
  if (root.contains("model")) {
    const Section s(path, "model", top.sub("model"), kModelKeys);
    const std::string kind = s.string("kind", "plane_strain");
    if (const auto k = model_kind_named(kind)) c.kind = *k;
    else
      s.fail("kind", fmt::format("unknown kind '{}' (plane_strain: a long body, eps_zz = 0; plane_stress: a thin "
                                 "plate, sigma_zz = 0; axisymmetric: x the radius, y the axis)", kind));
    if (c.kind == ModelKind::plane_stress)
      if (const std::string why = plane_stress_refusal(c); !why.empty()) s.fail("kind", why);
    if (c.kind != ModelKind::plane_stress && c.dim() != 2)
      s.fail("kind", fmt::format("{} is a 2D model (this case is 3D: leave [model] out)", name_of(c.kind)));
  }
  check_load_curves(c);
  check_load_step_count(c, root, path);
  apply_overrides(c, {}, {});
  return c;
}

std::vector<std::string> declared_case_keys() {
  std::set<std::string> out;
  const auto add = [&](const std::string& table, const auto& keys) {
    for (const auto& k : keys) out.insert(table.empty() ? std::string(k) : table + "." + std::string(k));
  };
  add("", kTopKeys);
  add("body", kBodyKeys);
  add("geometry", kGeometryKeys);
  add("geometry", kGeometryFileKeys);
  for (const ShapeType* t : shape_types())
    for (const ShapeKey& k : t->keys) out.insert("geometry." + std::string(k.key));
  add("mesh", kMeshKeys);
  add("mesh.grading", kGradingKeys);
  out.insert("material.model");
  out.insert("material.formulation");
  out.insert("material.incompressible");
  for (const std::string& law : law_names())
    for (const LawParameter& p : law_parameters(law)) out.insert("material." + std::string(p.key));
  out.insert("faces.*");  // names of one's own
  out.insert("faces.*.side");
  out.insert("faces.*.range");
  add("dirichlet", kDirichletKeys);
  add("pressure", kPressureKeys);
  add("traction", kTractionKeys);
  add("body_force", kBodyForceKeys);
  add("contact", kContactKeys);
  add("contact.obstacle", kObstacleKeys);
  for (const ObstacleType* t : obstacle_types())
    for (const ObstacleKey& k : t->keys) out.insert("contact.obstacle." + std::string(k.key));
  add("reference", kReferenceKeys);
  add("loading", kLoadingKeys);
  add("output", kOutputKeys);
  add("solver", kSolverKeys);
  add("units", kUnitsKeys);
  add("model", kModelKeys);
  return {out.begin(), out.end()};
}

}  // namespace igac
