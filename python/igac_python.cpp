// SPDX-License-Identifier: BSD-3-Clause
// The Python module `igac` (pybind11): runs a case from a file or a dict,
// with keys overridden, and returns what a script sweeps over: the summary
// (as summary.json holds it) and NumPy arrays of the control points, the
// displacements, the multipliers, the pressure along each contact face and
// the reaction on each [[dirichlet]] face set.  The same read_case / build_model / solve_model / run_summary as
// `igac run`, so a result equals the command line's to round-off
// (tests/python/test_module.py).  No files are written.
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>
#include <string>
#include <toml++/toml.h>

#include "io/case_table.hpp"
#include "io/input_file.hpp"
#include "io/toml_guard.hpp"
#include "io/json_out.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace py = pybind11;

namespace igac {
namespace {

// How deep a value may nest: a case file's values nest a few levels (a
// load curve: an array of pairs), and the conversion below and toml++'s
// own walks are recursive (a list nested 1e5 deep overflowed the stack).
constexpr int kMaxDepth = 64;

// A Python value as a TOML node: bool, int, float, str, list/tuple (or any
// sequence, a NumPy array), dict (any mapping), and the NumPy scalars (an
// np.int64 from np.arange, an np.float32, an np.bool_) as the numbers they
// are: numbers.Integral through __index__, numbers.Real through __float__.
// Anything else, a container that holds itself, a value nested deeper than
// kMaxDepth and an integer beyond 64 bits are InputErrors naming `where`.
class ToToml {
 public:
  explicit ToToml(std::string where) : where_(std::move(where)) {
    const py::module_ numbers = py::module_::import("numbers"), abc = py::module_::import("collections.abc");
    integral_ = numbers.attr("Integral");
    real_ = numbers.attr("Real");
    mapping_ = abc.attr("Mapping");
    sequence_ = abc.attr("Sequence");
    // np.bool_ is neither Integral nor Real; NumPy is not imported for it
    const py::dict modules = py::module_::import("sys").attr("modules");
    if (modules.contains("numpy")) numpy_bool_ = modules["numpy"].attr("bool_");
  }
  std::unique_ptr<toml::node> operator()(const py::handle& v) { return convert(v, "", 0); }

 private:
  [[noreturn]] void fail(const std::string& at, const std::string& why) const {
    // (at most 60 characters of where in the value: one nested 64 deep has [0] 64 times)
    throw InputError(fmt::format("{}{}{}: {}", where_, at.substr(0, 60), at.size() > 60 ? "..." : "", why));
  }
  static std::string type_name(const py::handle& v) { return py::str(v.get_type().attr("__name__")); }
  static bool is(const py::handle& v, const py::object& type) {
    return type && PyObject_IsInstance(v.ptr(), type.ptr()) == 1;
  }

  std::unique_ptr<toml::node> convert(const py::handle& v, const std::string& at, int depth) {
    if (depth > kMaxDepth) fail(at, fmt::format("nested more than {} levels deep (a case file's values nest a few)", kMaxDepth));
    if (py::isinstance<py::bool_>(v) || is(v, numpy_bool_)) return std::make_unique<toml::value<bool>>(PyObject_IsTrue(v.ptr()) == 1);
    if (py::isinstance<py::str>(v)) return std::make_unique<toml::value<std::string>>(v.cast<std::string>());
    if (is(v, integral_)) return integer(v, at);
    if (is(v, real_)) return real(v, at);
    if (is(v, mapping_)) return table(v, at, depth);
    if (py::isinstance<py::bytes>(v) || py::isinstance<py::bytearray>(v)) fail(at, not_a_value(v));
    // A NumPy array (of any shape, a 0-d one too) as the Python values it
    // holds (an array has __index__ too: before the protocols below).
    if (py::hasattr(v, "__array__") && py::hasattr(v, "tolist")) return convert(v.attr("tolist")(), at, depth);
    if (is(v, sequence_)) return array(v, at, depth);
    if (PyIndex_Check(v.ptr())) return integer(v, at);
    if (py::hasattr(v, "__float__")) return real(v, at);
    fail(at, not_a_value(v));
  }
  static std::string not_a_value(const py::handle& v) {
    return fmt::format("a value of type {} is not a case-file value (bool, int, float, str, list, dict)", type_name(v));
  }
  std::unique_ptr<toml::node> integer(const py::handle& v, const std::string& at) {
    const py::object i = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
    if (!i) throw py::error_already_set();
    int overflow = 0;
    const long long x = PyLong_AsLongLongAndOverflow(i.ptr(), &overflow);
    if (overflow) fail(at, fmt::format("the integer {} is beyond 64 bits", std::string(py::str(i))));
    if (x == -1 && PyErr_Occurred()) throw py::error_already_set();
    return std::make_unique<toml::value<int64_t>>(int64_t(x));
  }
  std::unique_ptr<toml::node> real(const py::handle& v, const std::string& at) {
    const double x = PyFloat_AsDouble(v.ptr());
    if (x == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      fail(at, fmt::format("a value of type {} that is not a number", type_name(v)));
    }
    return std::make_unique<toml::value<double>>(x);
  }
  // A container: refused when it is one of those it is inside (a list that
  // holds itself had no end).
  struct Inside {
    std::vector<PyObject*>& path;
    Inside(std::vector<PyObject*>& p, PyObject* o) : path(p) { path.push_back(o); }
    ~Inside() { path.pop_back(); }
  };
  void enter(const py::handle& v, const std::string& at) const {
    if (std::find(path_.begin(), path_.end(), v.ptr()) != path_.end())
      fail(at, fmt::format("a {} that holds itself (a case-file value is a tree)", type_name(v)));
  }
  std::unique_ptr<toml::node> table(const py::handle& v, const std::string& at, int depth) {
    enter(v, at);
    const Inside inside(path_, v.ptr());
    auto t = std::make_unique<toml::table>();
    for (const py::handle item : v.attr("items")()) {
      const py::tuple kv = py::reinterpret_borrow<py::tuple>(item);
      if (!py::isinstance<py::str>(kv[0]))
        fail(at, fmt::format("a key of type {} (the keys of a table are strings)", type_name(kv[0])));
      const std::string name = kv[0].cast<std::string>();
      t->insert_or_assign(name, std::move(*convert(kv[1], at + "." + name, depth + 1)));
    }
    return t;
  }
  std::unique_ptr<toml::node> array(const py::handle& v, const std::string& at, int depth) {
    enter(v, at);
    const Inside inside(path_, v.ptr());
    auto a = std::make_unique<toml::array>();
    size_t k = 0;
    for (const py::handle x : v) a->push_back(std::move(*convert(x, fmt::format("{}[{}]", at, k++), depth + 1)));
    return a;
  }

  std::string where_;
  py::object integral_, real_, mapping_, sequence_, numpy_bool_;
  std::vector<PyObject*> path_;
};

// Every table and array of `n` written inline, so that a value prints as
// one TOML value ("{ a = 1, b = [2] }"), not as [table] sections.
void make_inline(toml::node& n) {
  if (auto* t = n.as_table()) {
    t->is_inline(true);
    for (auto&& [k, v] : *t) make_inline(v);
  } else if (auto* a = n.as_array()) {
    for (auto& v : *a) make_inline(v);
  }
}

// A Python value of an override as a TOML node whose source is named
// "override 'KEY'": a message about it names the override, not a line of
// the case file (io/case_section.hpp, node_place).  The node is printed and
// parsed back (toml++ prints a double in its shortest exact form).
toml::table override_node(const std::string& key, const py::handle& value) {
  const std::string name = fmt::format("override '{}'", key);
  toml::table wrapper;
  wrapper.insert("v", std::move(*ToToml(name)(value)));
  make_inline(*wrapper.get("v"));
  std::ostringstream text;
  text << wrapper;
  try {
    return toml::parse(text.str(), name);
  } catch (const toml::parse_error& e) {  // (a value TOML cannot hold)
    throw InputError(fmt::format("{}: not a TOML value: {}", name, e.description()));
  }
}

// root[dotted] = value: "material.E", "contact.0.obstacle.motion" (a number
// indexes an array of tables, [[contact]]).  Missing tables are made.
void set_key(toml::table& root, const std::string& dotted, const py::handle& value) {
  std::vector<std::string> parts;
  std::stringstream in(dotted);
  for (std::string p; std::getline(in, p, '.');) parts.push_back(p);
  if (parts.empty() || dotted.back() == '.' || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    throw InputError(fmt::format("override '{}': not a dotted key (\"material.E\")", dotted));
  if (parts.size() > size_t(kMaxTomlKeyParts))  // (each part a table deeper)
    throw InputError(fmt::format("override '{:.40}...': a key of more than {} dotted parts", dotted, kMaxTomlKeyParts));
  toml::node* at = &root;
  std::string walked;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    if (auto* t = at->as_table()) {
      if (!t->contains(parts[i])) t->insert(parts[i], toml::table{});
      at = t->get(parts[i]);
    } else if (auto* a = at->as_array(); a && std::all_of(parts[i].begin(), parts[i].end(), ::isdigit)) {
      size_t k = 0;
      const auto [end, err] = std::from_chars(parts[i].data(), parts[i].data() + parts[i].size(), k);
      if (err != std::errc() || k >= a->size())
        throw InputError(fmt::format("override '{}': '{}' has {} entries", dotted, walked, a->size()));
      at = a->get(k);
    } else {
      throw InputError(fmt::format("override '{}': '{}' is not a table", dotted, walked));
    }
  }
  auto* t = at->as_table();
  if (!t) throw InputError(fmt::format("override '{}': '{}' is not a table", dotted, walked));
  toml::table parsed = override_node(dotted, value);
  t->insert_or_assign(parts.back(), std::move(*parsed.get("v")));  // (a move keeps the node's source)
}

// A path given from Python: a str, bytes or os.PathLike (os.fsdecode).
std::string path_argument(const py::handle& p, const char* argument) {
  try {
    return py::module_::import("os").attr("fsdecode")(p).cast<std::string>();
  } catch (const py::error_already_set& e) {
    if (!e.matches(PyExc_TypeError)) throw;
    throw InputError(fmt::format("{}: a value of type {} is not a path", argument,
                                 std::string(py::str(p.get_type().attr("__name__")))));
  }
}

// refine and degree: None, or an integer (a NumPy one too).
std::optional<int> int_argument(const py::handle& v, const char* argument) {
  if (v.is_none()) return std::nullopt;
  const auto node = ToToml(argument)(v);
  const auto x = node->value<int64_t>();
  if (!node->is_integer() || !x || *x < -1000000 || *x > 1000000)
    throw InputError(fmt::format("{}: must be None or an integer of at most 6 digits", argument));
  return int(*x);
}

// The case file with the overrides set in its parsed table.
toml::table with_overrides(const std::string& path, const py::handle& overrides) {
  toml::table root = parse_case_text(read_input_file(path, kCaseFile), path);
  if (overrides.is_none()) return root;
  if (!py::isinstance<py::dict>(overrides))
    throw InputError(fmt::format("overrides: a value of type {} is not a dict of dotted keys",
                                 std::string(py::str(overrides.get_type().attr("__name__")))));
  for (const auto& [k, v] : py::reinterpret_borrow<py::dict>(overrides)) {
    if (!py::isinstance<py::str>(k))
      throw InputError(fmt::format("overrides: a key of type {} (a dotted key is a str: \"material.E\")",
                                   std::string(py::str(k.get_type().attr("__name__")))));
    set_key(root, k.cast<std::string>(), v);
  }
  return root;
}

py::dict run_table(const toml::table& root, const std::string& path, std::optional<int> refine,
                   std::optional<int> degree) {
  CaseSpec spec = read_case_table(root, path);
  apply_overrides(spec, degree, refine);
  Model model = build_model(spec);
  RunResult r;
  {
    py::gil_scoped_release free;  // the solve needs no Python
    r = solve_model(model, quiet_run());
  }
  py::dict out;
  out["summary"] = py::module_::import("json").attr("loads")(run_summary(model, r).dump());
  out["status"] = r.status.text();
  out["control_points"] = Eigen::MatrixXd(model.body.points().leftCols(model.body.space_dim()));
  out["displacement"] = r.u;
  out["multipliers"] = r.contact ? Eigen::VectorXd(r.contact->solution.lambda) : Eigen::VectorXd();
  py::list pressure;
  for (const ContactResult& c : r.contacts) {
    Eigen::VectorXd s(Eigen::Index(c.report.multipliers.size())), p(s.size());
    for (size_t k = 0; k < c.report.multipliers.size(); ++k) {
      s[Eigen::Index(k)] = c.report.multipliers[k].r;
      p[Eigen::Index(k)] = c.report.multipliers[k].pressure;
    }
    py::dict d;
    d["face"] = c.face;
    d["r"] = s;  // each multiplier's anchor: distance from the initial contact point
    d["pressure"] = p;
    pressure.append(d);
  }
  out["pressure"] = pressure;
  // Per [[dirichlet]] face set its reaction at the end and, for a run in
  // steps, at each row of load_curve.csv (its load factor or time in `t`).
  py::list reactions;
  for (size_t i = 0; i < r.dirichlet_reactions.size(); ++i) {
    const FaceReaction& f = r.dirichlet_reactions[i];
    Eigen::MatrixXd history(0, f.force.size());
    std::vector<double> t;
    for (const LoadCurvePoint& p : r.load_curve)
      if (i < p.dirichlet_reactions.size() && p.dirichlet_reactions[i].force.size() == f.force.size()) {
        history.conservativeResize(history.rows() + 1, Eigen::NoChange);
        history.row(history.rows() - 1) = p.dirichlet_reactions[i].force.transpose();
        t.push_back(p.load_factor);
      }
    py::dict d;
    d["face"] = f.face;
    d["force"] = Eigen::VectorXd(f.force);
    d["steps"] = history;
    d["t"] = Eigen::Map<const Eigen::VectorXd>(t.data(), Eigen::Index(t.size())).eval();
    reactions.append(d);
  }
  out["reactions"] = reactions;
  return out;
}

}  // namespace
}  // namespace igac

PYBIND11_MODULE(igac, m) {
  using namespace igac;
  m.doc() = "igac: isogeometric contact mechanics. run(case_file, overrides) and run_dict(case) return the summary "
            "and NumPy arrays of a run (docs/python.md).";
  m.attr("__version__") = IGAC_VERSION;
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(e.what());
    }
  });
  m.def(
      "run",
      [](const py::object& case_file, const py::object& overrides, const py::object& refine, const py::object& degree) {
        const std::string path = path_argument(case_file, "case_file");
        return run_table(with_overrides(path, overrides), path, int_argument(refine, "refine"),
                         int_argument(degree, "degree"));
      },
      py::arg("case_file"), py::arg("overrides") = py::none(), py::arg("refine") = py::none(),
      py::arg("degree") = py::none(),
      "Runs a case file, its keys overridden by `overrides` ({'material.E': 2.0, 'contact.0.obstacle.motion': [0, "
      "-0.5]}); returns a dict: summary, status, control_points, displacement, multipliers, pressure, reactions.");
  m.def(
      "run_dict",
      [](const py::object& case_table, const py::object& folder, const py::object& refine, const py::object& degree) {
        if (!py::isinstance<py::dict>(case_table))
          throw InputError(fmt::format("case: a value of type {} is not a dict of the case file's tables",
                                       std::string(py::str(case_table.get_type().attr("__name__")))));
        const auto root = ToToml("case")(case_table);
        const auto name = root->as_table()->get_as<std::string>("name");
        const std::string dir = path_argument(folder, "folder");
        if (dir.find('\0') != std::string::npos) throw InputError("folder: a path with a NUL character in it");
        return run_table(*root->as_table(), (std::filesystem::path(dir) / ((name ? name->get() : "case") + ".toml")).string(),
                         int_argument(refine, "refine"), int_argument(degree, "degree"));
      },
      py::arg("case"), py::arg("folder") = ".", py::arg("refine") = py::none(), py::arg("degree") = py::none(),
      "Runs a case given as a dict of the case file's tables (geometry files relative to `folder`).");
}
