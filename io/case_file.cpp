// SPDX-License-Identifier: BSD-3-Clause
#include "io/case_file.hpp"

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

#include "contact/obstacle.hpp"
#include "engine/geometry/shapes.hpp"
#include "io/gismo_xml.hpp"
#include "io/toml_guard.hpp"
#include "model/references.hpp"
#include "materials/hyperelastic.hpp"
#include <unistd.h>

namespace igac {
namespace {

// The keys of the tables whose keys are fixed; read_case refuses any other,
// and declared_case_keys() lists them for docs/case_file.md's test.  The
// keys of a shape, a law or an obstacle come from their registries.
const std::set<std::string> kTopKeys{"name", "description", "geometry", "mesh", "material", "dirichlet",
                                     "pressure", "body_force", "contact", "reference", "output", "loading",
                                     "faces", "solver", "units"};
const std::set<std::string> kGeometryKeys{"shape", "file"};  // and the shape's own
const std::set<std::string> kGeometryFileKeys{"radius", "inner_radius", "outer_radius"};  // with file =
const std::set<std::string> kMeshKeys{"degree", "elements", "refine", "grading"};
const std::set<std::string> kGradingKeys{"direction", "toward", "span_fraction", "range_fraction", "coarse"};
const std::set<std::string> kDirichletKeys{"faces", "component", "value"};
const std::set<std::string> kPressureKeys{"faces", "value"};
const std::set<std::string> kBodyForceKeys{"value"};
const std::set<std::string> kContactKeys{"face", "obstacle", "master"};
const std::set<std::string> kObstacleKeys{"type", "motion"};  // and the obstacle type's own
const std::set<std::string> kReferenceKeys{"solution"};
const std::set<std::string> kLoadingKeys{"steps", "first_increment", "min_increment", "max_increment",
                                         "max_newton_iterations", "line_search", "predictor", "pressure"};
const std::set<std::string> kOutputKeys{"vtk"};
const std::set<std::string> kSolverKeys{"type", "options", "preconditioner"};
const std::set<std::string> kUnitsKeys{"system", "length", "force", "stress"};

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

namespace {

// A view of one TOML table that knows its name for messages and refuses
// keys it does not expect.
class Section {
 public:
  Section(const std::string& file, std::string name, const toml::table& t, std::set<std::string> allowed)
      : file_(file), name_(std::move(name)), t_(t) {
    for (const auto& [k, v] : t)
      if (!allowed.count(std::string(k.str()))) {
        const auto near = nearest_name(std::string(k.str()), {allowed.begin(), allowed.end()});
        fail(std::string(k.str()),
             fmt::format("unknown key{} (expected one of: {})", near ? fmt::format("; did you mean '{}'?", *near) : "",
                         fmt::join(allowed, ", ")),
             v.source().begin.line);
      }
  }
  [[noreturn]] void fail(const std::string& key, const std::string& why, int line = 0) const {
    if (!line)
      if (const auto* n = t_.get(key)) line = int(n->source().begin.line);
    const std::string where = line ? fmt::format("{}:{}", file_, line) : file_;
    throw InputError(fmt::format("{}: [{}] {}: {}", where, name_, key, why));
  }
  bool has(const std::string& key) const { return t_.contains(key); }
  const toml::node* node(const std::string& key) const { return t_.get(key); }

  // A length or modulus: positive and within the range where det J, strains
  // and stresses neither underflow nor overflow in double precision.
  double scale(const std::string& key, const char* what) const {
    const double v = number(key);
    if (!(v > 0)) fail(key, fmt::format("{} = {} must be positive ({})", key, v, what));
    if (v < 1e-100 || v > 1e100)
      fail(key, fmt::format("{} = {:g} is outside [1e-100, 1e100], where the computation under- or overflows; "
                            "choose units that bring it near 1", key, v));
    return v;
  }

  // A load (a pressure, a prescribed displacement, a body force, an
  // obstacle's motion): finite and at most 1e100 in size, as the moduli and
  // lengths are, so that what it produces neither overflows nor turns into
  // inf or NaN in the results.
  double load(const std::string& key, std::optional<double> def = {}) const {
    const double v = number(key, def);
    if (std::abs(v) > kLargestLoad)
      fail(key, fmt::format("{} = {:g} is larger than 1e100 in size, where the computation overflows; choose units "
                            "that bring it near 1", key, v));
    return v;
  }
  std::vector<double> loads(const std::string& key, size_t len) const {
    std::vector<double> v = numbers(key, len);
    for (double x : v)
      if (std::abs(x) > kLargestLoad)
        fail(key, fmt::format("{:g} is larger than 1e100 in size, where the computation overflows; choose units that "
                              "bring it near 1", x));
    return v;
  }
  static constexpr double kLargestLoad = 1e100;

  double number(const std::string& key, std::optional<double> def = {}) const {
    const auto* n = t_.get(key);
    if (!n) {
      if (def) return *def;
      fail(key, "missing (a number is required)");
    }
    if (auto v = n->value<double>()) {
      if (!std::isfinite(*v)) fail(key, "must be a finite number");
      return *v;
    }
    fail(key, "must be a number");
  }
  int integer(const std::string& key, std::optional<int> def = {}) const {
    const auto* n = t_.get(key);
    if (!n) {
      if (def) return *def;
      fail(key, "missing (an integer is required)");
    }
    if (n->is_integer()) {
      const auto v = n->value<int64_t>().value();
      if (v < -1000000000 || v > 1000000000) fail(key, "integer out of range");
      return int(v);
    }
    fail(key, "must be an integer");
  }
  std::string string(const std::string& key, std::optional<std::string> def = {}) const {
    const auto* n = t_.get(key);
    if (!n) {
      if (def) return *def;
      fail(key, "missing (a string is required)");
    }
    if (auto v = n->value<std::string>()) return *v;
    fail(key, "must be a string");
  }
  bool boolean(const std::string& key, bool def) const {
    const auto* n = t_.get(key);
    if (!n) return def;
    if (auto v = n->value<bool>()) return *v;
    fail(key, "must be true or false");
  }
  std::vector<double> numbers(const std::string& key, std::optional<size_t> len = {}) const {
    const auto* n = t_.get(key);
    if (!n) fail(key, "missing (an array of numbers is required)");
    const auto* arr = n->as_array();
    if (!arr) fail(key, "must be an array of numbers");
    std::vector<double> out;
    for (const auto& e : *arr) {
      auto v = e.value<double>();
      if (!v || !std::isfinite(*v)) fail(key, "must be an array of finite numbers");
      out.push_back(*v);
    }
    if (len && out.size() != *len) fail(key, fmt::format("must have {} entries, has {}", *len, out.size()));
    return out;
  }
  std::vector<std::string> strings(const std::string& key) const {
    const auto* n = t_.get(key);
    if (!n) fail(key, "missing (an array of face names is required)");
    if (auto s = n->value<std::string>()) return {*s};
    const auto* arr = n->as_array();
    if (!arr || arr->empty()) fail(key, "must be a non-empty array of strings");
    std::vector<std::string> out;
    for (const auto& e : *arr) {
      auto v = e.value<std::string>();
      if (!v) fail(key, "must be an array of strings");
      out.push_back(*v);
    }
    return out;
  }
  const toml::table& sub(const std::string& key) const {
    const auto* n = t_.get(key);
    if (!n || !n->is_table()) fail(key, "missing or not a table");
    return *n->as_table();
  }
  const std::string& name() const { return name_; }

 private:
  const std::string& file_;
  std::string name_;
  const toml::table& t_;
};

int component_index(const Section& s, const std::string& key, int dim) {
  const std::string c = s.string(key);
  static const std::string names = "xyz";
  if (c.size() == 1 && names.find(c[0]) != std::string::npos && int(names.find(c[0])) < dim)
    return int(names.find(c[0]));
  s.fail(key, fmt::format("'{}' is not a displacement component (x, y{})", c, dim == 3 ? ", z" : ""));
}

// Tables may come as [x] or [[x]]: give every entry of an array of tables.
std::vector<const toml::table*> tables(const std::string& file, const toml::table& root, const std::string& key) {
  std::vector<const toml::table*> out;
  const auto* n = root.get(key);
  if (!n) return out;
  if (const auto* t = n->as_table()) return {t};
  if (const auto* a = n->as_array()) {
    for (const auto& e : *a) {
      if (!e.is_table()) break;
      out.push_back(e.as_table());
    }
    if (out.size() == a->size()) return out;
  }
  throw InputError(fmt::format("{}:{}: {}: must be a table ([{}] or [[{}]])", file, n->source().begin.line, key, key, key));
}

}  // namespace

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

CaseSpec read_case(const std::string& path) {
  std::error_code ec;  // (a symlink loop, a folder without search permission: not a library's words, exit 1)
  const auto st = std::filesystem::status(path, ec);
  if (st.type() == std::filesystem::file_type::not_found) throw InputError(fmt::format("{}: no such case file", path));
  if (!std::filesystem::exists(st))
    throw InputError(fmt::format("{}: cannot read the case file ({})", path, ec.message()));
  if (!std::filesystem::is_regular_file(st))
    throw InputError(fmt::format("{}: not a regular file (a folder, FIFO or device): a case file must be a regular file", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the case file ({})", path, std::strerror(errno)));
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (const auto line = overlong_toml_key(text))  // (toml++ would overflow its stack)
    throw InputError(fmt::format("{}:{}: a key of more than {} dotted parts", path, *line, kMaxTomlKeyParts));
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}: malformed TOML: {}", path, e.source().begin.line, e.description()));
  }
  CaseSpec c;
  c.path = path;
  const Section top(path, "top level", root, kTopKeys);
  c.name = top.string("name", std::filesystem::path(path).stem().string());
  // The name becomes a folder under out/: a plain file name, nothing that
  // climbs out of it or that a shell or a file system would read otherwise.
  const bool plain = !c.name.empty() && c.name != "." && c.name != ".." && c.name.size() <= 200 &&
                     std::none_of(c.name.begin(), c.name.end(), [](unsigned char ch) { return ch == '/' || ch == '\\' || ch < 32 || ch == 127; });
  if (!plain)
    top.fail("name", fmt::format("{:?} is not a plain file name (it names the output folder out/<name>: "
                                 "no '/', not empty, not '.' or '..')", c.name));
  c.description = top.string("description", "");

  // The shape names a registered built-in shape (engine/geometry/shapes.hpp),
  // which declares its keys: those, and only those, go with it.
  const toml::table& gt = top.sub("geometry");
  const ShapeType* kind = find_shape_type(gt["shape"].value_or(std::string()));
  std::set<std::string> geo_keys = kGeometryKeys;
  if (kind)
    for (const ShapeKey& k : kind->keys) geo_keys.insert(std::string(k.key));
  if (gt.contains("file")) geo_keys.insert(kGeometryFileKeys.begin(), kGeometryFileKeys.end());
  if (!kind && !gt.contains("file"))
    for (const ShapeType* t : shape_types())
      for (const ShapeKey& k : t->keys) geo_keys.insert(std::string(k.key));
  const Section geo(path, "geometry", gt, geo_keys);
  if (geo.has("file")) {
    if (geo.has("shape")) geo.fail("file", "give either a shape or a file, not both");
    const std::filesystem::path f = geo.string("file");
    c.geometry_file = (f.is_absolute() ? f : std::filesystem::path(path).parent_path() / f).lexically_normal().string();
    if (std::error_code ec; !std::filesystem::exists(c.geometry_file, ec))
      geo.fail("file", fmt::format("no such file: {} (a relative file is read from the case file's folder)",
                                   std::filesystem::absolute(c.geometry_file).lexically_normal().string()));
    auto read = std::make_shared<const MultiPatch>(read_gismo_xml(c.geometry_file));  // one-line errors naming the file's line
    const MultiPatch& body = *read;
    c.file_body = read;
    c.dimension = body.patches.front().space_dim();
    if (body.patches.front().param_dim() != c.dimension)
      geo.fail("file", fmt::format("{}: a {}D patch in {}D space is not a solid body", c.geometry_file,
                                   body.patches.front().param_dim(), c.dimension));
    c.shape = "file";
    c.radius = geo.has("radius") ? geo.scale("radius", "the radius a Hertz reference uses") : 0.0;
    c.inner_radius = geo.has("inner_radius") ? geo.scale("inner_radius", "the inner radius a Lame reference uses") : 0.0;
    c.outer_radius = geo.has("outer_radius") ? geo.scale("outer_radius", "the outer radius a Lame reference uses") : 0.0;
    if (c.inner_radius > 0 && c.outer_radius > 0 && !(c.outer_radius > c.inner_radius))
      geo.fail("outer_radius", "must be larger than inner_radius");
  } else {
    c.shape = geo.string("shape");
    if (kind) c.dimension = kind->dim;
    if (!kind) {
      std::vector<std::string> names;
      for (const ShapeType* t : shape_types()) names.emplace_back(t->name);
      geo.fail("shape", fmt::format("unknown shape '{}' ({}; or file = \"body.xml\")", c.shape, fmt::join(names, ", ")));
    }
    for (const ShapeKey& k : kind->keys) {
      const std::string key(k.key);
      std::vector<double> v;
      if (k.length == 1) {
        v = {geo.scale(key, std::string(k.meaning).c_str())};
      } else {
        v = geo.numbers(key, size_t(k.length));
        for (double x : v)
          if (!(x >= 1e-100 && x <= 1e100))
            geo.fail(key, fmt::format("every length must be positive and within [1e-100, 1e100] (got {:g})", x));
      }
      c.shape_values[key] = v;
    }
    try {
      static_cast<void>(kind->make(c.shape_values));  // the shape's own cross-checks (outer > inner radius, ...)
    } catch (const SplineError& e) {
      geo.fail(std::string(kind->keys.back().key), e.what());
    }
    // The reference solutions read these (Hertz: radius; Lame: the radii).
    if (c.shape_values.count("radius")) c.radius = c.shape_values["radius"][0];
    if (c.shape_values.count("inner_radius")) c.inner_radius = c.shape_values["inner_radius"][0];
    if (c.shape_values.count("outer_radius")) c.outer_radius = c.shape_values["outer_radius"][0];
    if (c.shape_values.count("size")) c.size = c.shape_values["size"];
  }
  const int dim = c.dim();

  const Section mesh(path, "mesh", top.sub("mesh"), kMeshKeys);
  c.degree = mesh.integer("degree");
  if (c.degree < 1) mesh.fail("degree", fmt::format("degree {} must be at least 1", c.degree));
  if (c.degree > 10) mesh.fail("degree", fmt::format("degree {} is above the supported 10", c.degree));
  if (c.degree < 2 && kind && kind->curved)
    mesh.fail("degree", fmt::format("degree {}: a {} has exact circular arcs, quadratic NURBS; the degree must be at "
                                    "least 2", c.degree, c.shape));
  for (double e : mesh.numbers("elements", dim)) {
    if (e != std::floor(e) || e < 1 || e > 1e6) mesh.fail("elements", "entries must be whole numbers from 1 to 1e6");
    c.elements.push_back(int(e));
  }
  c.refine = mesh.integer("refine", 0);
  if (c.refine < 0) mesh.fail("refine", "must be >= 0");
  if (mesh.has("grading")) {
    // one table, or an array of tables (one per graded direction)
    std::vector<const toml::table*> gts;
    const toml::node* gn = mesh.node("grading");
    if (gn->is_table()) gts.push_back(gn->as_table());
    else if (gn->is_array_of_tables())
      for (const auto& e : *gn->as_array()) gts.push_back(e.as_table());
    else mesh.fail("grading", "must be a table [mesh.grading] or tables [[mesh.grading]]");
    for (const auto* gt : gts) {
      const Section g(path, "mesh.grading", *gt, kGradingKeys);
      GradingSpec gs;
      const std::string d = g.string("direction");
      if (d != "u" && d != "v" && !(d == "w" && dim == 3))
        g.fail("direction", fmt::format("'{}' is not a parametric direction (u, v{})", d, dim == 3 ? ", w" : ""));
      gs.direction = d == "u" ? 0 : d == "v" ? 1 : 2;
      for (const auto& other : c.gradings)
        if (other.direction == gs.direction) g.fail("direction", fmt::format("direction '{}' is graded twice", d));
      const std::string t = g.string("toward", "start");
      if (t != "start" && t != "end") g.fail("toward", "must be \"start\" or \"end\"");
      gs.at_start = t == "start";
      gs.span_fraction = g.number("span_fraction");
      gs.range_fraction = g.number("range_fraction");
      const std::string coarse = g.string("coarse", "uniform");
      if (coarse != "uniform" && coarse != "geometric") g.fail("coarse", "must be \"uniform\" or \"geometric\"");
      gs.geometric_coarse = coarse == "geometric";
      if (!(gs.span_fraction > 0 && gs.span_fraction < 1)) g.fail("span_fraction", "must lie in (0, 1)");
      if (!(gs.range_fraction > 0 && gs.range_fraction < 1)) g.fail("range_fraction", "must lie in (0, 1)");
      if (c.elements[gs.direction] < 2) g.fail("direction", "a graded direction needs at least 2 elements");
      c.gradings.push_back(gs);
    }
  }

  {
    // The model names a registered law; the law declares its parameters
    // (materials/hyperelastic.hpp): those, and only those, are the table's
    // other keys.  linear_elastic runs the small-deformation path.
    const toml::table& mt = top.sub("material");
    const auto laws = law_names();
    const std::string model = mt["model"].value_or(std::string("linear_elastic"));
    std::set<std::string> keys{"model"};
    const bool known = std::find(laws.begin(), laws.end(), model) != laws.end();
    if (known)
      for (const LawParameter& p : law_parameters(model)) keys.insert(std::string(p.key));
    const Section mat(path, "material", mt, known ? keys : std::set<std::string>{"model", "E", "nu"});
    c.model = mat.string("model", "linear_elastic");
    if (!known)
      mat.fail("model", fmt::format("unknown material model '{}' (available: {}; linear_elastic is small deformation)",
                                    c.model, fmt::join(laws, ", ")));
    MaterialParameters given;
    for (const LawParameter& p : law_parameters(model)) {
      const bool modulus = p.lower == 0 && std::isinf(p.upper);  // a stiffness: within the computable range
      const double v = modulus ? mat.scale(std::string(p.key), std::string(p.meaning).c_str()) : mat.number(std::string(p.key));
      if (!modulus && std::abs(v) > 1e100)  // a law's own constant (C10): the same range as a modulus
        mat.fail(std::string(p.key), fmt::format("{} = {:g} is outside [-1e100, 1e100], where the computation "
                                                 "overflows; choose units that bring it near 1", p.key, v));
      if (p.key == "E") given.E = v;
      else if (p.key == "nu") given.nu = v;
      else given.values[std::string(p.key)] = v;
    }
    try {
      const MaterialParameters linear = small_strain_equivalent(model, given);
      const auto law = make_law(model, given);  // the law's own cross-checks (e.g. C10 + C01 > 0)
      try {  // its stiffness at F = I, as both paths use it: blamed on the keys the user gave
        static_cast<void>(small_strain_material(*law, dim));
      } catch (const MaterialParameterError&) {
        throw;
      } catch (const MaterialError& e) {
        std::vector<std::string> keys;
        for (const LawParameter& p : law_parameters(model)) keys.push_back(fmt::format("{} = {:g}", p.key, given.value(p.key)));
        mat.fail(std::string(law_parameters(model).front().key),
                 fmt::format("{} give a small-strain stiffness that is not usable ({})", fmt::join(keys, ", "), e.what()));
      }
      c.E = linear.E;
      c.nu = linear.nu;
      c.material_parameters = given;
    } catch (const MaterialParameterError& e) {
      mat.fail(e.key(), e.what());
    }
  }

  if (root.contains("faces")) {  // names of one's own for sets of faces
    const toml::table& ft = top.sub("faces");
    std::set<std::string> keys;
    for (const auto& [k, v] : ft) keys.insert(std::string(k.str()));
    const Section faces(path, "faces", ft, keys);
    for (const auto& k : keys) c.face_sets[k] = faces.strings(k);
  }

  for (const auto* t : tables(path, root, "dirichlet")) {
    const Section s(path, "dirichlet", *t, kDirichletKeys);
    c.dirichlet.push_back({s.strings("faces"), component_index(s, "component", dim), s.load("value", 0.0)});
  }
  for (const auto* t : tables(path, root, "pressure")) {
    const Section s(path, "pressure", *t, kPressureKeys);
    c.pressure.push_back({s.strings("faces"), s.load("value")});
  }
  if (root.contains("body_force")) {
    const Section s(path, "body_force", top.sub("body_force"), kBodyForceKeys);
    c.body_force = s.loads("value", dim);
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
      if (c.finite_strain())
        s.fail("master", fmt::format("contact between two deformable bodies runs in small deformation only (material "
                                     "model \"linear_elastic\"), not with model \"{}\"", c.model));
    } else {
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
    const Section s(path, "loading", top.sub("loading"), kLoadingKeys);
    if (!c.finite_strain())
      s.fail("steps", "[loading] drives the large-deformation models; linear_elastic is solved in one linear step");
    LoadingSpec& l = c.loading;
    l.steps = s.integer("steps", 10);
    if (l.steps < 1 || l.steps > 100000) s.fail("steps", "must lie in 1..100000");
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
    l.line_search = s.boolean("line_search", true);
    const std::string predictor = s.string("predictor", "tangent");
    if (predictor != "tangent" && predictor != "none")
      s.fail("predictor", "must be \"tangent\" (the first step starts from x - J^-1 dR/dt dt) or \"none\"");
    l.tangent_predictor = predictor == "tangent";
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
    c.solver.type = s.string("type", "direct");
    if (c.solver.type != "direct" && c.solver.type != "petsc")
      s.fail("type", fmt::format("unknown solver '{}' (direct: CHOLMOD on one process; petsc: PETSc, also under mpirun)",
                                 c.solver.type));
    c.solver.options = s.string("options", "");
    if (!c.solver.options.empty() && c.solver.type != "petsc")
      s.fail("options", "PETSc options need type = \"petsc\"");
    if (const std::string why = check_case_petsc_options(c.solver.options); !why.empty()) s.fail("options", why);
    c.solver.preconditioner = s.string("preconditioner", "options");
    if (const std::string why = check_preconditioner(c.solver); !why.empty()) s.fail("preconditioner", why);
    if (c.solver.type == "petsc" && c.finite_strain())
      s.fail("type", "the PETSc solver runs the small-deformation (linear_elastic) contact solve only");
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
  }
  apply_overrides(c, {}, {});
  return c;
}

std::vector<std::string> declared_case_keys() {
  std::set<std::string> out;
  const auto add = [&](const std::string& table, const auto& keys) {
    for (const auto& k : keys) out.insert(table.empty() ? std::string(k) : table + "." + std::string(k));
  };
  add("", kTopKeys);
  add("geometry", kGeometryKeys);
  add("geometry", kGeometryFileKeys);
  for (const ShapeType* t : shape_types())
    for (const ShapeKey& k : t->keys) out.insert("geometry." + std::string(k.key));
  add("mesh", kMeshKeys);
  add("mesh.grading", kGradingKeys);
  out.insert("material.model");
  for (const std::string& law : law_names())
    for (const LawParameter& p : law_parameters(law)) out.insert("material." + std::string(p.key));
  out.insert("faces.*");  // names of one's own
  add("dirichlet", kDirichletKeys);
  add("pressure", kPressureKeys);
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
  return {out.begin(), out.end()};
}

std::string check_preconditioner(const SolverSpec& s) {
  if (s.preconditioner != "options" && s.preconditioner != "spline_multigrid")
    return fmt::format("unknown preconditioner '{}' (options: as [solver] options say, default MUMPS; "
                       "spline_multigrid: geometric multigrid over the nested meshes)", s.preconditioner);
  if (s.preconditioner == "spline_multigrid" && s.type != "petsc")
    return "spline_multigrid runs in the PETSc solver: needs type = \"petsc\"";
  return {};
}

}  // namespace igac
