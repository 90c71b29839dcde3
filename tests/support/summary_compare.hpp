// SPDX-License-Identifier: BSD-3-Clause
// Two runs' summary.json (and CSV files) compared number by number under the
// rule of tests/support/solve_tolerance.hpp: the golden records
// (tests/cli/test_golden_cases.cpp, which says the rule per kind of key)
// and the two solver backends on every shipped case
// (tests/cli/test_petsc_cases.cpp).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "tests/support/igac_process.hpp"
#include "tests/support/solve_tolerance.hpp"

namespace igac_test::summary_compare {

namespace fs = std::filesystem;
using nlohmann::json;
using igac_test::SolveAccuracy;

constexpr double kCsvPrinted = 1.5e-9;  // 10 printed digits

// Numbers compared, and the largest |a - b| / tolerance per kind: results
// and the CSV files: how much of the rule's margin a run used (the
// portability script's measure).
struct Tally {
  int numbers = 0, exact = 0;
  struct Worst {
    double ratio = 0;
    std::string at = "-";
  } result, csv;
  int newton_paths = 0;  // load steps whose Newton path was not compared
};

// What one comparison holds: the rule, the scale of every key's kind.
struct Rule {
  SolveAccuracy accuracy;
  std::map<std::string, double> kind_scale;  // key -> largest |value| under it in the record
};

// The kind of a key or CSV column: every force (reactions per face and
// component, contact, normal, tangential, applied and total forces) is one
// kind, each in the same units and balancing the others; any other key is
// its own kind.
inline std::string kind_of(const std::string& key) {
  return key.find("force") != std::string::npos || key.starts_with("reaction") ? "force" : key;
}

inline void collect_scales(const json& j, const std::string& key, std::map<std::string, double>& out) {
  if (j.is_object()) {
    for (const auto& [k, v] : j.items()) collect_scales(v, k, out);
  } else if (j.is_array()) {
    for (const auto& v : j) collect_scales(v, key, out);
  } else if (j.is_number()) {
    double& s = out[kind_of(key)];
    s = std::max(s, std::abs(j.get<double>()));
  }
}

// |golden - actual| <= printed relative + the rule's relative times scale.
inline bool close(double golden, double actual, double scale, const std::string& where, const Rule& rule, Tally& t,
           double printed = 0) {
  const double diff = std::abs(golden - actual);
  const double tol = printed * std::max(std::abs(golden), std::abs(actual)) +
                     rule.accuracy.relative() * std::max({scale, std::abs(golden), std::abs(actual)});
  ++t.numbers;
  Tally::Worst& w = where.find(".csv") != std::string::npos ? t.csv : t.result;
  if (diff > 0 && tol > 0 && diff / tol > w.ratio) w = {diff / tol, where};
  if (diff <= tol) return true;
  ADD_FAILURE() << where << ": recorded " << std::setprecision(17) << golden << ", now " << actual << " (|diff| "
                << diff << " > tolerance " << tol << " = " << rule.accuracy.relative() << " x scale " << scale
                << ", condition estimate " << rule.accuracy.condition << ")";
  return false;
}

// The scale of the error norm `key` in an "errors" object: the norm it is
// relative to (key / key_rel), or 1 for a relative error itself.
inline double error_scale(const json& errors, const std::string& key) {
  if (key.size() > 4 && key.ends_with("_rel")) return 1.0;
  const auto rel = errors.find(key + "_rel");
  if (rel == errors.end() || !rel->is_number() || rel->get<double>() == 0) return 0;
  return std::abs(errors.at(key).get<double>() / rel->get<double>());
}

inline void compare(const json& g, const json& a, const std::string& where, double scale, const Rule& rule, Tally& t);

// study.json's "rates": rates[key][k] is the rate between the k-th and the
// k+1-th of the levels that report errors[key].
inline void compare_rates(const json& g_rates, const json& a_rates, const json& g_levels, const std::string& where,
                   const Rule& rule, Tally& t) {
  ASSERT_TRUE(a_rates.is_object()) << where;
  for (const auto& [key, g_list] : g_rates.items()) {
    ASSERT_TRUE(a_rates.contains(key)) << where << "/" << key << " is missing";
    const json& a_list = a_rates.at(key);
    std::vector<const json*> levels;
    for (const json& l : g_levels)
      if (l.contains("errors") && l["errors"].contains(key)) levels.push_back(&l);
    ASSERT_EQ(g_list.size() + 1, levels.size()) << where << "/" << key << ": rates between consecutive levels";
    ASSERT_EQ(a_list.size(), g_list.size()) << where << "/" << key;
    for (size_t k = 0; k < g_list.size(); ++k) {
      const json &ea = (*levels[k])["errors"], &eb = (*levels[k + 1])["errors"];
      const double a = ea[key], b = eb[key];
      const double rel = rule.accuracy.relative();
      const double tol_a = rel * std::max(std::abs(a), error_scale(ea, key)),
                   tol_b = rel * std::max(std::abs(b), error_scale(eb, key));
      const double log_h = std::abs(std::log((*levels[k])["h"].get<double>() / (*levels[k + 1])["h"].get<double>()));
      // the rate's tolerance in absolute terms, as a scale for the rule
      const double rate_tol = (tol_a / std::abs(a) + tol_b / std::abs(b)) / log_h;
      close(g_list[k], a_list[k], rate_tol / rel, where + "/" + key + "[" + std::to_string(k) + "]", rule, t);
    }
  }
}

inline void compare(const json& g, const json& a, const std::string& where, double scale, const Rule& rule, Tally& t) {
  switch (g.type()) {
    case json::value_t::object:
      ASSERT_TRUE(a.is_object()) << where << ": not an object";
      for (const auto& [key, gv] : g.items()) {
        const std::string at = where + "/" + key;
        if (!a.contains(key)) {
          ADD_FAILURE() << at << " is missing";
          continue;
        }
        if (key == "rates" && g.contains("levels")) {
          compare_rates(gv, a.at(key), g.at("levels"), at, rule, t);
        } else if (g.contains("residual_norms") &&
                   (key == "residual_norms" || key == "newton_iterations" || key == "active_set_sizes")) {
          // A Newton step's path (above): that the run took one is all.
          ASSERT_TRUE(a.at(key).is_array() || a.at(key).is_number_integer()) << at;
          if (key == "residual_norms") ++t.newton_paths;
        } else if (where.ends_with("/errors") && gv.is_number_float()) {
          compare(gv, a.at(key), at, error_scale(g, key), rule, t);
        } else {
          const auto s = rule.kind_scale.find(kind_of(key));
          compare(gv, a.at(key), at, s == rule.kind_scale.end() ? 0.0 : s->second, rule, t);
        }
      }
      return;
    case json::value_t::array:
      ASSERT_TRUE(a.is_array()) << where << ": not an array";
      ASSERT_EQ(a.size(), g.size()) << where << ": length";
      for (size_t i = 0; i < g.size(); ++i) compare(g[i], a[i], where + "[" + std::to_string(i) + "]", scale, rule, t);
      return;
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      ++t.numbers;
      ++t.exact;
      EXPECT_TRUE(a.is_number_integer()) << where << ": recorded the integer " << g << ", now " << a;
      EXPECT_EQ(g, a) << where;
      return;
    case json::value_t::number_float:
      ASSERT_TRUE(a.is_number()) << where << ": recorded " << g << ", now " << a;
      close(g.get<double>(), a.get<double>(), scale, where, rule, t);
      return;
    default:  // strings, booleans, null
      EXPECT_EQ(g, a) << where;
  }
}

// A CSV file igac wrote (pressure.csv, load_curve.csv) against its record:
// the header and the kind column exactly, empty cells empty, numbers to the
// 10 printed digits.
inline void compare_csv(const json& g, const fs::path& file, const Rule& rule, Tally& t) {
  const std::string name = file.filename().string();
  ASSERT_TRUE(fs::exists(file)) << file;
  const auto rows = igac_test::csv_rows(file);
  ASSERT_FALSE(rows.empty()) << file;
  EXPECT_EQ(json(rows[0]), g["header"]) << file;
  const json& g_rows = g["rows"];
  ASSERT_EQ(rows.size(), g_rows.size() + 1) << file << ": rows";
  const size_t columns = g["header"].size();
  std::map<std::string, double> kind_scale;  // the file's own: a CSV's columns are not the summary's keys
  for (const json& r : g_rows)
    for (size_t c = 0; c < columns; ++c)
      if (r[c].is_number()) {
        double& k = kind_scale[kind_of(g["header"][c].get<std::string>())];
        k = std::max(k, std::abs(r[c].get<double>()));
      }
  std::vector<double> scale(columns, 0.0);
  for (size_t c = 0; c < columns; ++c) scale[c] = kind_scale[kind_of(g["header"][c].get<std::string>())];
  for (size_t i = 0; i < g_rows.size(); ++i) {
    const auto& row = rows[i + 1];
    const json& gr = g_rows[i];
    ASSERT_EQ(row.size(), columns) << name << " row " << i + 1;
    for (size_t c = 0; c < columns; ++c) {
      const std::string where = name + " row " + std::to_string(i + 1) + " " + g["header"][c].get<std::string>();
      if (gr[c].is_null()) {
        EXPECT_EQ(row[c], "") << where;
      } else if (gr[c].is_string()) {
        EXPECT_EQ(row[c], gr[c].get<std::string>()) << where;
      } else {
        ASSERT_FALSE(row[c].empty()) << where;
        close(gr[c].get<double>(), std::strtod(row[c].c_str(), nullptr), scale[c], where, rule, t, kCsvPrinted);  // (strtod: a denormal is a number)
      }
    }
  }
}

// A run's summary.json as a record holds it (tests/data/golden/record.py):
// without the keys that measure the machine (times, memory, paths, the
// condition estimate) and without those named in `also`.
inline json without_machine_keys(const json& j, const std::set<std::string>& also = {}) {
  static const std::regex excluded("(time|timing|seconds|_s$|memory|resident|path|folder|^out$|condition_estimate)");
  if (j.is_object()) {
    json out = json::object();
    for (const auto& [k, v] : j.items())
      if (!std::regex_search(k, excluded) && !also.count(k)) out[k] = without_machine_keys(v, also);
    return out;
  }
  if (j.is_array()) {
    json out = json::array();
    for (const auto& v : j) out.push_back(without_machine_keys(v, also));
    return out;
  }
  return j;
}

// A CSV file igac wrote as a record holds it: {"header": [...], "rows":
// [[number | string | null, ...], ...]}.
inline json csv_record(const fs::path& file) {
  const auto rows = igac_test::csv_rows(file);
  json r{{"header", rows.empty() ? json::array() : json(rows[0])}, {"rows", json::array()}};
  for (size_t i = 1; i < rows.size(); ++i) {
    json row = json::array();
    for (const std::string& cell : rows[i]) {
      if (cell.empty()) {
        row.push_back(nullptr);
        continue;
      }
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (end && *end == 0) row.push_back(v);
      else row.push_back(cell);
    }
    r["rows"].push_back(row);
  }
  return r;
}

}  // namespace igac_test::summary_compare
