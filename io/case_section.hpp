// SPDX-License-Identifier: BSD-3-Clause
// The case reader's own tools (io/case_file.cpp and io/case_body_tables.cpp),
// not an interface: a TOML table that knows its name for messages and
// refuses keys it does not expect, and the key lists of the tables that
// describe one body.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include "io/case_file.hpp"

namespace igac::case_reading {

// The keys of one body's tables (the keys of a shape and a law come from
// their registries).
inline const std::set<std::string> kGeometryKeys{"shape", "file", "scale", "mirror", "rotate", "translate"};  // and the shape's own
inline const std::set<std::string> kGeometryFileKeys{"radius", "inner_radius", "outer_radius"};  // with file =
inline const std::set<std::string> kMeshKeys{"degree", "elements", "refine", "grading"};
inline const std::set<std::string> kGradingKeys{"direction", "toward", "span_fraction", "range_fraction", "coarse"};

// Where a node of the case stands, for messages: "case.toml:12"; for a
// node set from elsewhere, whose source is named otherwise (a Python
// override, io/case_table.hpp), "case.toml: override 'material.E'"; the
// file alone when nothing says (a table made to hold an override, a case
// given as a Python dict).
inline std::string node_place(const std::string& file, const toml::node* n) {
  if (!n) return file;
  const toml::source_region& s = n->source();
  if (s.path && *s.path != file) return fmt::format("{}: {}", file, *s.path);
  return s.begin.line ? fmt::format("{}:{}", file, s.begin.line) : file;
}

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
             &v);
      }
  }
  // "FILE:LINE: [name] key: why", where the node `at` stands (by default
  // the key's; for a key the table lacks, its header's: the top level has
  // none) (node_place).
  [[noreturn]] void fail(const std::string& key, const std::string& why, const toml::node* at = nullptr) const {
    if (!at) at = t_.get(key);
    if (!at && name_ != "top level") at = &t_;
    throw InputError(fmt::format("{}: [{}] {}: {}", node_place(file_, at), name_, key, why));
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
    // (is_boolean: toml++'s value<bool>() takes an integer too, and vtk = 0 read as false)
    if (n->is_boolean()) return *n->value<bool>();
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
  // A load curve: [[t0, f0], [t1, f1], ...], at least two pairs, t0 = 0,
  // the times increasing, every number finite (engine/load_curve.hpp).
  LoadCurve curve(const std::string& key) const {
    const auto* n = t_.get(key);
    const char* form = "must be a list of [time, factor] pairs, e.g. [[0, 0], [1, 1], [2, 0]]";
    if (!n || !n->as_array()) fail(key, form);
    std::vector<std::array<double, 2>> points;
    for (const auto& e : *n->as_array()) {
      const auto* pair = e.as_array();
      if (!pair || pair->size() != 2) fail(key, form);
      std::array<double, 2> p{};
      for (size_t i = 0; i < 2; ++i) {
        const auto v = (*pair)[i].value<double>();
        if (!v) fail(key, form);
        if (!std::isfinite(*v)) fail(key, fmt::format("point {} holds a non-finite number", points.size() + 1));
        if (std::abs(*v) > kLargestLoad) fail(key, fmt::format("{:g} is larger than 1e100 in size", *v));
        p[i] = *v;
      }
      if (points.empty() && p[0] != 0) fail(key, fmt::format("must start at time 0, where the run starts (not {:g})", p[0]));
      if (!points.empty() && !(p[0] > points.back()[0]))
        fail(key, fmt::format("the times must increase: {:g} follows {:g}", p[0], points.back()[0]));
      points.push_back(p);
    }
    if (points.size() < 2) fail(key, fmt::format("{} (at least two)", form));
    return LoadCurve(std::move(points));
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

inline int component_index(const Section& s, const std::string& key, int dim) {
  const std::string c = s.string(key);
  static const std::string names = "xyz";
  if (c.size() == 1 && names.find(c[0]) != std::string::npos && int(names.find(c[0])) < dim)
    return int(names.find(c[0]));
  s.fail(key, fmt::format("'{}' is not a displacement component (x, y{})", c, dim == 3 ? ", z" : ""));
}

// Tables may come as [x] or [[x]]: give every entry of an array of tables.
inline std::vector<const toml::table*> tables(const std::string& file, const toml::table& root, const std::string& key) {
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
  throw InputError(fmt::format("{}: {}: must be a table ([{}] or [[{}]])", node_place(file, n), key, key, key));
}


// Reads the [geometry], [mesh] and [material] tables of `owner` (the case
// file's top level, or one [[body]] table) into `body`.  `where` prefixes
// the tables' names in messages ("" or "body 'roller' ").  Throws InputError.
void read_body_tables(const std::string& path, const Section& owner, const std::string& where, BodySpec& body);

}  // namespace igac::case_reading
