#include "app/study.hpp"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <map>
#include <optional>

#include "app/case_run.hpp"
#include "io/json_out.hpp"
#include "app/output_folder.hpp"
#include "io/plots.hpp"

namespace igac {

int run_study(CaseSpec spec, const StudyOptions& opt) {
  if (opt.levels < 2) throw InputError(fmt::format("--levels {}: a study needs at least 2 levels", opt.levels));
  const int r0 = spec.refine;
  try {  // Every level's size is checked before the first level is computed.
    CaseSpec finest = spec;
    apply_overrides(finest, {}, r0 + opt.levels - 1);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--levels {}: the finest level is too large: {}", opt.levels, e.what()));
  }
  std::optional<OutputFolder> folder;  // --out checked now, written at the end
  if (!opt.out.empty()) folder.emplace(opt.out);
  const bool exact = exact_displacement(spec).has_value();
  const int n_ref = opt.levels - 1;
  std::vector<int> reported;
  for (int l = 0; l < opt.levels; ++l)
    if (exact || l <= n_ref - 2) reported.push_back(l);  // nested bisection: h_ref = h / 2^(n_ref - l) <= h/4
  if (reported.size() < 2)
    throw InputError(fmt::format("--levels {}: too few levels with h >= 4 h_ref to form a rate (use at least 4)", opt.levels));
  std::vector<Model> models;
  std::vector<RunResult> results;
  models.reserve(opt.levels);  // level l - 1 is referred to while level l is solved
  results.reserve(opt.levels);
  for (int l = 0; l < opt.levels; ++l) {
    apply_overrides(spec, {}, r0 + l);
    models.push_back(build_model(spec));
    models.back().quiet = opt.quiet;
    // Level l starts its contact iteration from level l - 1 (its mesh one refinement below).
    const CoarserRun previous = l > 0 ? CoarserRun{&models[l - 1], &results[l - 1]} : CoarserRun{};
    results.push_back(solve_model(models.back(), {}, previous));
    if (!opt.quiet)
      fmt::print(stderr, "level {}: h = {:.4g}, {} dofs, {:.2f} s, {}\n", l, models.back().mesh_size,
                 models.back().dofs->num_free(), results.back().timing.total, results.back().status);
    if (results.back().status != "converged")
      throw std::runtime_error(fmt::format("level {} did not converge: {}", l, results.back().status));
  }
  std::vector<std::map<std::string, double>> errors(opt.levels);
  const Model& ref = models[n_ref];
  const RunResult& rref = results[n_ref];
  for (int l : reported) {
    auto& e = errors[l];
    const RunResult& r = results[l];
    ErrorNorms d = exact ? *r.displacement_errors
                         : errors_against_reference(models[l].body, r.u, ref.body, rref.u, ref.body.degree() + 1);
    e["displacement_l2"] = d.l2;
    e["displacement_h1"] = d.h1;
    e["displacement_l2_rel"] = d.l2 / d.ref_l2;
    e["displacement_h1_rel"] = d.h1 / d.ref_h1;
    if (r.pressure_error) {
      e["pressure_l2"] = r.pressure_error->first;
      e["pressure_l2_rel"] = r.pressure_error->first / r.pressure_error->second;
    }
    if (r.contact && !exact) {
      const ContactPressure& pref = *rref.contact->pressure;
      const auto pe = r.contact->pressure->l2_error(
          *ref.contacts.front().face, [&](int side, const Eigen::VectorXd& xi, const Eigen::VectorXd&) { return pref.pressure_at(side, xi); },
          ref.body.degree() + 2);
      e["pressure_l2_vs_reference"] = pe.first;
      e["pressure_l2_vs_reference_rel"] = pe.first / pe.second;
    }
  }
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
    Json ej;
    for (const auto& [k, v] : errors[l]) ej[k] = finite_or_null(v);
    lv["errors"] = ej;
    levels.push_back(lv);
  }
  j["levels"] = levels;
  Json rates;
  for (const auto& [name, v0] : errors[reported.front()]) {
    Json arr = Json::array();
    for (size_t i = 0; i + 1 < reported.size(); ++i) {
      const int a = reported[i], b = reported[i + 1];
      arr.push_back(finite_or_null(std::log(errors[a][name] / errors[b][name]) /
                                   std::log(models[a].mesh_size / models[b].mesh_size)));
    }
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
    std::string row = fmt::format("{},{:.8g},{}", l, models[l].mesh_size, models[l].dofs->num_free());
    for (const auto& n : names) {
      const double rate = i == 0 ? NAN : j["rates"][n][i - 1].is_null() ? NAN : j["rates"][n][i - 1].get<double>();
      line += fmt::format(" {:>24.4e} {:>5}", errors[l][n], i == 0 ? "" : fmt::format("{:.2f}", rate));
      row += fmt::format(",{:.8g},{}", errors[l][n], i == 0 ? "" : fmt::format("{:.4f}", rate));
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
      for (auto& e : plotted) e.values.push_back(errors[l][e.name]);
    }
    write_file_atomically(dir + "/study.svg", svg::render(study_figure(h, plotted, spec.name)));
    folder->commit();
  }
  return 0;
}

}  // namespace igac
