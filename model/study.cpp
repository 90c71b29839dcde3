// SPDX-License-Identifier: BSD-3-Clause
#include "model/study.hpp"

#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "model/memory_estimate.hpp"
#include "model/references.hpp"
#include "model/solve.hpp"

namespace igac {

StudyResult solve_study(CaseSpec spec, int levels, bool quiet, const LevelObserver& on_level) {
  if (levels < 2) throw InputError(fmt::format("--levels {}: a study needs at least 2 levels", levels));
  const int r0 = spec.refine;
  try {  // Every level's size is checked before the first level is computed.
    CaseSpec finest = spec;
    apply_overrides(finest, {}, r0 + levels - 1);
  } catch (const InputError& e) {
    throw InputError(fmt::format("--levels {}: the finest level is too large: {}", levels, e.what()));
  }
  StudyResult out;
  const bool exact = out.exact = exact_displacement(spec).has_value();
  const int n_ref = levels - 1;
  std::vector<int>& reported = out.reported;
  for (int l = 0; l < levels; ++l)
    if (exact || l <= n_ref - 2) reported.push_back(l);  // nested bisection: h_ref = h / 2^(n_ref - l) <= h/4
  if (reported.size() < 2)
    throw InputError(fmt::format("--levels {}: too few levels with h >= 4 h_ref to form a rate (use at least 4)", levels));
  std::vector<Model>& models = out.models;
  std::vector<RunResult>& results = out.results;
  models.reserve(levels);  // level l - 1 is referred to while level l is solved
  results.reserve(levels);
  for (int l = 0; l < levels; ++l) {
    apply_overrides(spec, {}, r0 + l);
    models.push_back(build_model(spec));
    // Level l starts its contact iteration from level l - 1 (its mesh one refinement below).
    const CoarserRun previous = l > 0 ? CoarserRun{&models[l - 1], &results[l - 1]} : CoarserRun{};
    RunControl control;
    control.quiet = quiet;
    control.coarser = previous;
    results.push_back(solve_model(models.back(), control));
    if (on_level) on_level(l, models.back(), results.back());
    if (!results.back().status.is_converged())
      throw std::runtime_error(fmt::format("level {} did not converge: {}", l, results.back().status));
  }
  auto& errors = out.errors;
  errors.resize(levels);
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
    if (!r.contacts.empty() && !exact) {
      // On the union of the contact faces: every contact's error and norm summed in squares.
      double e2 = 0, n2 = 0;
      std::pair<double, double> pe;
      for (size_t i = 0; i < r.contacts.size(); ++i) {
        const ContactPressure& pref = *rref.contacts[i].pressure;
        pe = r.contacts[i].pressure->l2_error(
            *ref.contacts[i].face,
            [&](int side, const Eigen::VectorXd& xi, const Eigen::VectorXd&) { return pref.pressure_at(side, xi); },
            ref.body.degree() + 2);
        e2 += pe.first * pe.first;
        n2 += pe.second * pe.second;
      }
      if (r.contacts.size() > 1) pe = {std::sqrt(e2), std::sqrt(n2)};
      e["pressure_l2_vs_reference"] = pe.first;
      e["pressure_l2_vs_reference_rel"] = pe.first / pe.second;
    }
  }
  for (const auto& [name, v0] : errors[reported.front()]) {
    std::vector<double>& rate = out.rates[name];
    for (size_t i = 0; i + 1 < reported.size(); ++i) {
      const int a = reported[i], b = reported[i + 1];
      rate.push_back(std::log(errors[a].at(name) / errors[b].at(name)) / std::log(models[a].mesh_size / models[b].mesh_size));
    }
  }
  return out;
}

}  // namespace igac
