// SPDX-License-Identifier: BSD-3-Clause
#include "app/study.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <optional>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/study.hpp"
#include "io/json_out.hpp"
#include "app/output_folder.hpp"
#include "io/plots.hpp"

namespace igac {

int run_study(CaseSpec spec, const StudyOptions& opt) {
  std::optional<OutputFolder> folder;  // --out checked now, written at the end
  if (!opt.out.empty()) folder.emplace(opt.out);
  const StudyResult study = solve_study(spec, opt.levels, opt.quiet, [&](int l, const Model& m, const RunResult& r) {
    if (!opt.quiet)
      fmt::print(stderr, "level {}: h = {:.4g}, {} dofs, {:.2f} s, {}\n", l, m.mesh_size, m.dofs->num_free(),
                 r.timing.total, r.status);
  });
  const std::vector<Model>& models = study.models;
  const std::vector<RunResult>& results = study.results;
  const std::vector<int>& reported = study.reported;
  const auto& errors = study.errors;
  const bool exact = study.exact;
  const int n_ref = opt.levels - 1;
  const Model& ref = models[n_ref];
  Json j;
  j["case"] = spec.name;
  j["degree"] = spec.degree;
  j["reference"] = exact ? Json("closed form") : Json(fmt::format("level {} (h = {:.6g}, {} dofs)", n_ref, ref.mesh_size, ref.dofs->num_free()));
  Json levels = Json::array();
  for (int l : reported) {
    Json lv;
    lv["level"] = l;
    lv["h"] = models[l].mesh_size;
    lv["dofs"] = models[l].dofs->num_free();
    lv["multipliers"] = models[l].num_multipliers();
    lv["time_s"] = results[l].timing.total;
    if (results[l].linear_solver.condition_estimate > 0)
      lv["condition_estimate"] = finite_or_null(results[l].linear_solver.condition_estimate);
    Json ej;
    for (const auto& [k, v] : errors[l]) ej[k] = finite_or_null(v);
    lv["errors"] = ej;
    levels.push_back(lv);
  }
  j["levels"] = levels;
  // The errors are differences with the finest level too: the largest of
  // every level's conditioning says how many of their digits are round-off.
  double condition = 0;
  for (const RunResult& r : results) condition = std::max(condition, r.linear_solver.condition_estimate);
  if (condition > 0) j["condition_estimate"] = finite_or_null(condition);
  Json rates;
  for (const auto& [name, values] : study.rates) {
    Json arr = Json::array();
    for (double v : values) arr.push_back(finite_or_null(v));
    rates[name] = arr;
  }
  j["rates"] = rates;

  // table on stdout
  std::vector<std::string> names;
  for (const auto& [k, v] : errors[reported.front()])
    if (k.find("_rel") == std::string::npos) names.push_back(k);
  std::string head = fmt::format("{:>5} {:>10} {:>8}", "level", "h", "dofs");
  for (const auto& n : names) head += fmt::format(" {:>24} {:>5}", n, "rate");
  fmt::print("{}\n", head);
  std::string csv = "level,h,dofs";
  for (const auto& n : names) csv += fmt::format(",{},{}_rate", n, n);
  csv += "\n";
  for (size_t i = 0; i < reported.size(); ++i) {
    const int l = reported[i];
    std::string line = fmt::format("{:>5} {:>10.4g} {:>8}", l, models[l].mesh_size, models[l].dofs->num_free());
    std::string row = fmt::format("{},{},{}", l, csv_number(models[l].mesh_size, 8), models[l].dofs->num_free());
    for (const auto& n : names) {
      const double rate = i == 0 ? NAN : std::isfinite(study.rates.at(n)[i - 1]) ? study.rates.at(n)[i - 1] : NAN;
      line += fmt::format(" {:>24.4e} {:>5}", errors[l].at(n), i == 0 ? "" : fmt::format("{:.2f}", rate));
      row += fmt::format(",{},{}", csv_number(errors[l].at(n), 8), std::isfinite(rate) ? fmt::format("{:.4f}", rate) : "");
    }
    fmt::print("{}\n", line);
    csv += row + "\n";
  }
  if (folder) {
    folder->create_staging();
    const std::string dir = folder->staging();
    write_file_atomically(dir + "/study.csv", csv);
    write_file_atomically(dir + "/study.json", j.dump(2) + "\n");
    std::vector<double> h;
    std::vector<StudyError> plotted;
    for (const auto& n : names) plotted.push_back({n, {}});
    for (int l : reported) {
      h.push_back(models[l].mesh_size);
      for (auto& e : plotted) e.values.push_back(errors[l].at(e.name));
    }
    write_file_atomically(dir + "/study.svg", svg::render(study_figure(h, plotted, spec.name)));
    if (const std::string note = folder->commit(); !note.empty()) fmt::print(stderr, "igac: warning: {}\n", note);
  }
  return 0;
}

}  // namespace igac
