// SPDX-License-Identifier: BSD-3-Clause
#include "io/plots.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace igac {

namespace {

// matplotlib's first colours ("tab10"), so the pictures read as they did.
const std::vector<std::string> kPalette{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                        "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

}  // namespace

svg::Figure pressure_figure(const RunResult& r, const std::string& title, size_t contact, const UnitsSpec& units) {
  const PressureReport& rep = r.contacts.at(contact).report;
  const bool analytic = has_hertz_scale(r);
  const double sx = analytic ? 1 / r.hertz->a : 1.0, sy = analytic ? 1 / r.hertz->p0 : 1.0;
  std::vector<PressureSample> mult = rep.multipliers;
  std::stable_sort(mult.begin(), mult.end(), [](const auto& a, const auto& b) { return a.r < b.r; });
  std::vector<double> mx, my, px, py;
  for (const auto& m : mult) mx.push_back(m.r * sx), my.push_back(m.pressure * sy);
  for (const auto& p : rep.p1) px.push_back(p.r * sx), py.push_back(p.pressure * sy);

  svg::Panel panel;
  panel.title = title;
  panel.legend = svg::Corner::upper_right;
  panel.x.label = analytic ? "r / a" : "r (distance from the initial contact point)" + UnitsSpec::bracket(units.length);
  panel.y.label = analytic ? "p / p0" : "p = -lambda" + UnitsSpec::bracket(units.stress);
  const std::string blue = kPalette[0], orange = kPalette[1];
  // One constant per element (S0): the P1 breakpoints bound each multiplier's element.
  const bool constants = !mx.empty() && px.size() == mx.size() + 1;
  if (constants) {
    svg::Series seg{.label = "multipliers (constant per element)", .color = blue, .segments = true, .line_width = 1.2};
    for (size_t i = 0; i < mx.size(); ++i) {
      seg.x.insert(seg.x.end(), {px[i], px[i + 1]});
      seg.y.insert(seg.y.end(), {my[i], my[i]});
    }
    panel.series.push_back(std::move(seg));
    panel.series.push_back({.color = blue, .x = mx, .y = my, .line = false, .marker = svg::Marker::circle, .marker_size = 2.8});
  } else {
    panel.series.push_back({.label = "multipliers (at their anchors)", .color = blue, .x = mx, .y = my, .line = false,
                            .marker = svg::Marker::circle, .marker_size = 2.5});
  }
  if (!px.empty())
    panel.series.push_back({.label = "P1 re-interpolation", .color = orange, .x = px, .y = py,
                            .marker = svg::Marker::circle, .marker_size = 1.5});
  double xmax = 0;
  if (analytic) {
    svg::Series hertz{.label = "Hertz: p/p0 = √(1 − (r/a)²)", .color = "#000000", .dashed = true, .line_width = 1.2};
    for (int k = 0; k <= 400; ++k) {
      const double x = 1.2 * k / 400;
      hertz.x.push_back(x);
      hertz.y.push_back(x < 1 ? std::sqrt(1 - x * x) : 0.0);
    }
    panel.series.push_back(std::move(hertz));
    xmax = 1.6;
  } else if (!mx.empty()) {
    // 1.5 times the end of the pressed zone: the far end of the last pressed
    // element (or the next anchor), so the edge of contact shows.
    double all = *std::max_element(mx.begin(), mx.end());
    if (!px.empty()) all = std::max(all, *std::max_element(px.begin(), px.end()));
    xmax = all;
    for (size_t j = mx.size(); j-- > 0;)
      if (my[j] > 0) {
        const double edge = constants ? px[j + 1] : mx[std::min(j + 1, mx.size() - 1)];
        xmax = std::min(1.5 * edge, all);
        break;
      }
  }
  if (!mx.empty()) {
    panel.x.min = 0.0;
    panel.x.max = xmax;
    double ymax = analytic ? 1.0 : 0.0;
    for (size_t i = 0; i < mx.size(); ++i)
      if (mx[i] <= xmax && std::isfinite(my[i])) ymax = std::max(ymax, my[i]);
    for (size_t i = 0; i < px.size(); ++i)
      if (px[i] <= xmax && std::isfinite(py[i])) ymax = std::max(ymax, py[i]);
    const double ymin = std::min(0.0, *std::min_element(my.begin(), my.end()));
    panel.y.min = ymin - 0.02 * ymax;
    panel.y.max = 1.12 * ymax;
  }
  return {.panels = {std::move(panel)}, .panel_width = 700, .panel_height = 460};
}

svg::Figure load_curve_figure(const RunResult& r, const std::string& title, const std::vector<std::string>& faces,
                              const UnitsSpec& units, int dim, bool history) {
  const std::string force_unit = UnitsSpec::bracket(units.force_of_model(dim)), length_unit = UnitsSpec::bracket(units.length);
  std::vector<double> t{0}, force{0}, disp{0}, moved{0};
  std::vector<std::vector<double>> forces(faces.size(), std::vector<double>{0});  // several contacts: each one's
  double travel = 0;
  for (const auto& p : r.load_curve) {
    t.push_back(p.load_factor);
    force.push_back(p.contact_force());
    for (size_t i = 0; i < faces.size(); ++i)
      forces[i].push_back(i < p.contact_forces.size() ? p.contact_forces[i] : std::nan(""));
    disp.push_back(p.face_displacement);
    moved.push_back(p.obstacle_displacement);
    travel = std::max(travel, std::abs(p.obstacle_displacement));
  }
  // A moving obstacle drives the run: the force against how far it has moved.
  const bool driven = travel > 0;
  const svg::Series style{.marker = svg::Marker::circle, .marker_size = 3};
  svg::Panel by_load{.x = {.label = history ? "time (load curves)" : "load factor"},
                     .y = {.label = "total contact force (modelled part)" + force_unit}};
  by_load.series.push_back(style);
  by_load.series.back().x = t;
  by_load.series.back().y = force;
  svg::Panel by_motion{
      .x = {.label = (driven ? "obstacle displacement (squeeze)" : "loaded face displacement (last axis)") + length_unit},
      .y = {.label = "total contact force" + force_unit}};
  by_motion.series.push_back(style);
  by_motion.series.back().x = driven ? moved : disp;
  by_motion.series.back().y = force;
  if (history && faces.empty()) {  // loading and unloading: the steps where the displacement grows, and the others
    const std::vector<double>& x = driven ? moved : disp;
    svg::Series up = style, down = style;
    up.label = "loading";
    down.label = "unloading";
    down.dashed = true;
    down.color = kPalette[1];
    down.marker = svg::Marker::square;
    for (size_t i = 1; i < x.size(); ++i) {
      svg::Series& s = std::abs(x[i]) >= std::abs(x[i - 1]) ? up : down;
      if (s.x.empty() || s.x.back() != x[i - 1] || s.y.back() != force[i - 1]) {
        if (!s.x.empty()) s.x.push_back(std::nan("")), s.y.push_back(std::nan(""));  // a break in the line
        s.x.push_back(x[i - 1]), s.y.push_back(force[i - 1]);
      }
      s.x.push_back(x[i]), s.y.push_back(force[i]);
    }
    by_motion.series.clear();
    for (svg::Series* s : {&up, &down})
      if (!s->x.empty()) by_motion.series.push_back(std::move(*s));
  }
  if (!faces.empty()) {  // a curve per contact, in the legend by its face
    by_load.series.clear();
    by_motion.series.clear();
    by_load.y.label = by_motion.y.label = "contact force (modelled part)" + force_unit;
    for (size_t i = 0; i < faces.size(); ++i) {
      svg::Series s = style;
      s.label = "face '" + faces[i] + "'";
      s.color = kPalette[i % kPalette.size()];
      s.dashed = i % 2 == 1;  // equal forces (two plates) stay visible as two curves
      s.y = forces[i];
      s.x = t;
      by_load.series.push_back(s);
      s.x = driven ? moved : disp;
      by_motion.series.push_back(std::move(s));
    }
  }
  svg::Figure figure{.title = title, .panels = {std::move(by_load), std::move(by_motion)}, .panel_width = 500,
                     .panel_height = 400};
  // Friction: the first contact's tangential force (first tangent) against
  // the obstacle's displacement, the hysteresis loop of a load cycle.
  if (!r.load_curve.empty() && !r.load_curve.front().tangential_forces.empty() &&
      r.load_curve.front().tangential_forces.front().size() > 0) {
    svg::Panel loop{.x = {.label = (driven ? "obstacle displacement" : "time (load curves)") + length_unit},
                    .y = {.label = "tangential force (first tangent)" + force_unit}};
    svg::Series s = style;
    s.x = {0};
    s.y = {0};
    for (const auto& p : r.load_curve) {
      s.x.push_back(driven ? p.obstacle_displacement : p.load_factor);
      s.y.push_back(p.tangential_forces.empty() || p.tangential_forces.front().size() == 0 ? std::nan("")
                                                                                             : p.tangential_forces.front()[0]);
    }
    loop.series.push_back(std::move(s));
    figure.panels.push_back(std::move(loop));
  }
  return figure;
}

svg::Figure study_figure(const std::vector<double>& h, const std::vector<StudyError>& errors, const std::string& title) {
  static const std::map<std::string, std::string> labels{
      {"displacement_l2", "displacement, L2"},
      {"displacement_h1", "displacement, H1 seminorm"},
      {"pressure_l2", "pressure, L2 vs Hertz"},
      {"pressure_l2_vs_reference", "pressure, L2 vs refined"}};
  const svg::Marker markers[] = {svg::Marker::circle, svg::Marker::square, svg::Marker::diamond, svg::Marker::triangle};
  svg::Panel panel{.title = title,
                   .x = {.label = "h (largest element diameter)", .scale = svg::Scale::log},
                   .y = {.label = "error", .scale = svg::Scale::log}};
  for (size_t k = 0; k < errors.size(); ++k) {
    // The levels this error can be drawn at, finest first.
    std::vector<std::pair<double, double>> pts;
    for (size_t l = 0; l < std::min(h.size(), errors[k].values.size()); ++l) {
      const double hl = h[l], e = errors[k].values[l];
      if (std::isfinite(hl) && std::isfinite(e) && hl > 0 && e > 0) pts.emplace_back(hl, e);
    }
    if (pts.empty()) continue;
    std::sort(pts.begin(), pts.end());
    const std::string color = kPalette[k % kPalette.size()];
    const auto it = labels.find(errors[k].name);
    svg::Series s{.label = it != labels.end() ? it->second : errors[k].name, .color = color,
                  .marker = markers[k % std::size(markers)], .marker_size = 3.5};
    for (const auto& [hl, e] : pts) s.x.push_back(hl), s.y.push_back(e);
    if (pts.size() >= 2) {
      const auto [h0, e0] = pts[0];
      const auto [h1, e1] = pts[1];
      const double slope = std::log(e1 / e0) / std::log(h1 / h0);
      s.label += fmt::format("  (slope {:.2f})", slope);
      // A slope triangle below the finest segment: legs 0.6 of it in log h, and slope times that.
      const double hA = h0, hB = h0 * std::pow(h1 / h0, 0.6), eA = 0.5 * e0, eB = eA * std::pow(hB / hA, slope);
      panel.series.push_back({.color = color, .x = {hA, hB, hB, hA}, .y = {eA, eA, eB, eA}, .line_width = 0.8});
      panel.notes.push_back({.x = hB, .y = std::sqrt(eA * eB), .text = fmt::format("{:.2f}", slope), .color = color,
                             .dx = 4, .dy = 3.5});
    }
    panel.series.push_back(std::move(s));
  }
  return {.panels = {std::move(panel)}, .panel_width = 700, .panel_height = 500};
}

}  // namespace igac
