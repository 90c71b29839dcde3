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
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <toml++/toml.h>

#include "io/case_file.hpp"
#include "io/json_out.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace py = pybind11;

namespace igac {
namespace {

// A Python value as a TOML node: bool, int, float, str, list/tuple, dict.
std::unique_ptr<toml::node> to_toml(const py::handle& v, const std::string& key) {
  if (py::isinstance<py::bool_>(v)) return std::make_unique<toml::value<bool>>(v.cast<bool>());
  if (py::isinstance<py::int_>(v)) return std::make_unique<toml::value<int64_t>>(v.cast<int64_t>());
  if (py::isinstance<py::float_>(v)) return std::make_unique<toml::value<double>>(v.cast<double>());
  if (py::isinstance<py::str>(v)) return std::make_unique<toml::value<std::string>>(v.cast<std::string>());
  if (py::isinstance<py::dict>(v)) {
    auto t = std::make_unique<toml::table>();
    for (const auto& [k, x] : v.cast<py::dict>()) {
      const std::string name = py::str(k);
      auto node = to_toml(x, key + "." + name);
      t->insert_or_assign(name, std::move(*node));
    }
    return t;
  }
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v) || py::hasattr(v, "tolist")) {
    const py::list items = py::hasattr(v, "tolist") ? py::list(v.attr("tolist")()) : py::list(py::reinterpret_borrow<py::object>(v));
    auto a = std::make_unique<toml::array>();
    for (const auto& x : items) {
      auto node = to_toml(x, key);
      a->push_back(std::move(*node));
    }
    return a;
  }
  throw InputError(fmt::format("override '{}': a {} is not a case-file value (bool, int, float, str, list, dict)", key,
                               std::string(py::str(v.get_type().attr("__name__")))));
}

// root[dotted] = value: "material.E", "contact.0.obstacle.motion" (a number
// indexes an array of tables, [[contact]]).  Missing tables are made.
void set_key(toml::table& root, const std::string& dotted, const py::handle& value) {
  std::vector<std::string> parts;
  std::stringstream in(dotted);
  for (std::string p; std::getline(in, p, '.');) parts.push_back(p);
  if (parts.empty() || std::any_of(parts.begin(), parts.end(), [](const std::string& p) { return p.empty(); }))
    throw InputError(fmt::format("override '{}': not a dotted key (\"material.E\")", dotted));
  toml::node* at = &root;
  std::string walked;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    if (auto* t = at->as_table()) {
      if (!t->contains(parts[i])) t->insert(parts[i], toml::table{});
      at = t->get(parts[i]);
    } else if (auto* a = at->as_array(); a && std::all_of(parts[i].begin(), parts[i].end(), ::isdigit)) {
      const size_t k = std::stoul(parts[i]);
      if (k >= a->size())
        throw InputError(fmt::format("override '{}': '{}' has {} entries", dotted, walked, a->size()));
      at = a->get(k);
    } else {
      throw InputError(fmt::format("override '{}': '{}' is not a table", dotted, walked));
    }
  }
  auto* t = at->as_table();
  if (!t) throw InputError(fmt::format("override '{}': '{}' is not a table", dotted, walked));
  t->insert_or_assign(parts.back(), std::move(*to_toml(value, dotted)));
}

std::string file_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: no such case file", path));
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The case's text with the overrides written in (toml++ prints the table
// back as TOML).
std::string with_overrides(const std::string& text, const std::string& path, const py::dict& overrides) {
  if (overrides.empty()) return text;
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(fmt::format("{}:{}: malformed TOML: {}", path, e.source().begin.line, e.description()));
  }
  for (const auto& [k, v] : overrides) set_key(root, py::str(k), v);
  std::ostringstream out;
  out << root;
  return out.str();
}

py::dict run_text(const std::string& text, const std::string& path, std::optional<int> refine,
                  std::optional<int> degree) {
  CaseSpec spec = read_case_text(text, path);
  apply_overrides(spec, degree, refine);
  Model model = build_model(spec);
  model.quiet = true;
  RunResult r;
  {
    py::gil_scoped_release free;  // the solve needs no Python
    r = solve_model(model);
  }
  py::dict out;
  out["summary"] = py::module_::import("json").attr("loads")(run_summary(model, r).dump());
  out["status"] = r.status;
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
      [](const std::string& case_file, const py::dict& overrides, std::optional<int> refine, std::optional<int> degree) {
        return run_text(with_overrides(file_text(case_file), case_file, overrides), case_file, refine, degree);
      },
      py::arg("case_file"), py::arg("overrides") = py::dict(), py::arg("refine") = py::none(),
      py::arg("degree") = py::none(),
      "Runs a case file, its keys overridden by `overrides` ({'material.E': 2.0, 'contact.0.obstacle.motion': [0, "
      "-0.5]}); returns a dict: summary, status, control_points, displacement, multipliers, pressure, reactions.");
  m.def(
      "run_dict",
      [](const py::dict& case_table, const std::string& folder, std::optional<int> refine, std::optional<int> degree) {
        auto root = to_toml(case_table, "case");
        std::ostringstream text;
        text << *root->as_table();
        const std::string name = case_table.contains("name") ? py::str(case_table["name"]).cast<std::string>() : "case";
        return run_text(text.str(), (std::filesystem::path(folder) / (name + ".toml")).string(), refine, degree);
      },
      py::arg("case"), py::arg("folder") = ".", py::arg("refine") = py::none(), py::arg("degree") = py::none(),
      "Runs a case given as a dict of the case file's tables (geometry files relative to `folder`).");
}
