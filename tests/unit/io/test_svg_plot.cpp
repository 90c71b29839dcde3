// SPDX-License-Identifier: BSD-3-Clause
// The SVG plots (io/svg_plot.hpp, io/plots.hpp): the document parses as XML;
// data lands on the pixels the axes say (linear: proportional; log: a decade
// is a fixed number of pixels; the axis ends are the frame's edges); ticks
// step by 1-2-5 and by decades; non-finite points are never written; text
// is escaped, control characters replaced; the pressure plot of a real 2D Hertz run draws one segment
// per S0 multiplier in view and the Hertz curve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <pugixml.hpp>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "model/solve.hpp"
#include "io/case_file.hpp"
#include "io/plots.hpp"
#include "io/svg_plot.hpp"

namespace igac {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Coordinates are written with two decimals: half a unit of the last one,
// and the frame's own rounding on top.
constexpr double kPixel = 0.011;

struct Pt {
  double x, y;
};
struct Box {
  double x, y, w, h;
};

pugi::xml_document parse(const std::string& svg) {
  pugi::xml_document doc;
  const pugi::xml_parse_result ok = doc.load_string(svg.c_str());
  EXPECT_TRUE(ok) << ok.description() << " at offset " << ok.offset;
  return doc;
}

std::vector<Box> frames(const pugi::xml_document& doc) {
  std::vector<Box> out;
  for (const auto& n : doc.select_nodes("//rect[@class='frame']")) {
    const pugi::xml_node r = n.node();
    out.push_back({r.attribute("x").as_double(), r.attribute("y").as_double(), r.attribute("width").as_double(),
                   r.attribute("height").as_double()});
  }
  return out;
}

// The series group whose <title> is `label` (the first unlabelled one for "").
pugi::xml_node series(const pugi::xml_document& doc, const std::string& label) {
  for (const auto& n : doc.select_nodes("//g[@class='series']")) {
    const std::string title = n.node().child("title").text().get();
    if (title == label) return n.node();
  }
  ADD_FAILURE() << "no series '" << label << "'";
  return {};
}

// The pieces of a path made of M and L commands.
std::vector<std::vector<Pt>> pieces(const pugi::xml_node& group) {
  std::vector<std::vector<Pt>> out;
  const std::string d = group.child("path").attribute("d").value();
  const char* s = d.c_str();
  while (*s) {
    const char cmd = *s++;
    EXPECT_TRUE(cmd == 'M' || cmd == 'L') << d;
    char* end = nullptr;
    const double x = std::strtod(s, &end);
    const double y = std::strtod(end, &end);
    s = end;
    if (cmd == 'M') out.emplace_back();
    if (!out.empty()) out.back().push_back({x, y});
  }
  return out;
}

svg::Figure one_panel(svg::Axis x, svg::Axis y, std::vector<svg::Series> s) {
  svg::Panel p{.title = "t", .x = std::move(x), .y = std::move(y), .series = std::move(s)};
  return {.panels = {std::move(p)}};
}

TEST(SvgPlot, LinearTicksStepByOneTwoFive) {
  std::vector<std::string> labels;
  for (const auto& t : svg::ticks({0, 1.6}, svg::Scale::linear)) labels.push_back(t.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"0.0", "0.2", "0.4", "0.6", "0.8", "1.0", "1.2", "1.4", "1.6"}));
  labels.clear();
  for (const auto& t : svg::ticks({-0.26, 0.013}, svg::Scale::linear)) labels.push_back(t.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"-0.25", "-0.20", "-0.15", "-0.10", "-0.05", "0.00"}));
  labels.clear();
  for (const auto& t : svg::ticks({-3, 47}, svg::Scale::linear)) labels.push_back(t.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"0", "5", "10", "15", "20", "25", "30", "35", "40", "45"}));
}

TEST(SvgPlot, LogTicksAreDecades) {
  std::vector<std::string> decades;
  int grid_only = 0;
  for (const auto& t : svg::ticks({2e-10, 3e-5}, svg::Scale::log)) {
    if (t.power) decades.push_back(t.label);
    else if (t.label.empty()) ++grid_only;
  }
  EXPECT_EQ(decades, (std::vector<std::string>{"-9", "-8", "-7", "-6", "-5"}));
  EXPECT_GT(grid_only, 20) << "2..9 times each decade";
  // Under two decades in view: plain numbers at 1..9 times a power of ten.
  std::vector<std::string> plain;
  for (const auto& t : svg::ticks({0.055, 0.5}, svg::Scale::log)) plain.push_back(t.label);
  std::sort(plain.begin(), plain.end());
  EXPECT_EQ(plain, (std::vector<std::string>{"0.06", "0.07", "0.08", "0.09", "0.1", "0.2", "0.3", "0.4", "0.5"}));
}

TEST(SvgPlot, AutomaticRanges) {
  const svg::Range lin = svg::axis_range({}, {1.0, 3.0, kNaN, 2.0});
  EXPECT_DOUBLE_EQ(lin.lo, 0.9);  // 5 % margins
  EXPECT_DOUBLE_EQ(lin.hi, 3.1);
  const svg::Range lg = svg::axis_range({.scale = svg::Scale::log}, {1e-3, 0.0, -1.0, 1e1});
  EXPECT_NEAR(std::log10(lg.lo), -3.2, 1e-12);  // 5 % of four decades; 0 and -1 are not drawable
  EXPECT_NEAR(std::log10(lg.hi), 1.2, 1e-12);
  const svg::Range one = svg::axis_range({}, {2.0, 2.0});
  EXPECT_LT(one.lo, 2.0);
  EXPECT_GT(one.hi, 2.0);
  const svg::Range fixed = svg::axis_range({.min = 0.0, .max = 1.6}, {5.0, 7.0});
  EXPECT_EQ(fixed.lo, 0.0);
  EXPECT_EQ(fixed.hi, 1.6);
}

TEST(SvgPlot, LinearDataLandsOnItsPixels) {
  const std::string text = svg::render(one_panel({.min = 0.0, .max = 10.0}, {.min = 0.0, .max = 100.0},
                                                 {{.label = "data", .x = {0, 5, 10}, .y = {0, 25, 100}}}));
  const auto doc = parse(text);
  const auto f = frames(doc);
  ASSERT_EQ(f.size(), 1u);
  const auto p = pieces(series(doc, "data"));
  ASSERT_EQ(p.size(), 1u);
  ASSERT_EQ(p[0].size(), 3u);
  EXPECT_NEAR(p[0][0].x, f[0].x, kPixel) << "the axis's lower end is the frame's left edge";
  EXPECT_NEAR(p[0][0].y, f[0].y + f[0].h, kPixel) << "and its bottom";
  EXPECT_NEAR(p[0][1].x, f[0].x + 0.5 * f[0].w, kPixel);
  EXPECT_NEAR(p[0][1].y, f[0].y + 0.75 * f[0].h, kPixel);
  EXPECT_NEAR(p[0][2].x, f[0].x + f[0].w, kPixel) << "the upper end: the right edge";
  EXPECT_NEAR(p[0][2].y, f[0].y, kPixel) << "and the top";
}

TEST(SvgPlot, ADecadeIsAFixedNumberOfPixels) {
  const svg::Axis x{.scale = svg::Scale::log, .min = 1e-2, .max = 1e1}, y{.scale = svg::Scale::log, .min = 1e-6, .max = 1.0};
  const std::string text =
      svg::render(one_panel(x, y, {{.label = "data", .x = {1e-2, 1e-1, 1, 1e1}, .y = {1e-6, 1e-4, 1e-2, 1}}}));
  const auto doc = parse(text);
  const Box f = frames(doc).at(0);
  const auto p = pieces(series(doc, "data"));
  ASSERT_EQ(p.size(), 1u);
  ASSERT_EQ(p[0].size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(p[0][i].x, f.x + f.w * i / 3, kPixel) << i;
    EXPECT_NEAR(p[0][i].y, f.y + f.h * (1 - i / 3.0), kPixel) << i;
  }
  // Automatic log ranges keep it: 0.03 -> 0.3 -> 3 are equally spaced.
  const std::string auto_text = svg::render(one_panel({.scale = svg::Scale::log}, {.scale = svg::Scale::log},
                                                      {{.label = "a", .x = {0.03, 0.3, 3}, .y = {5e-9, 5e-7, 5e-5}}}));
  const auto q = pieces(series(parse(auto_text), "a"));
  ASSERT_EQ(q.size(), 1u);
  ASSERT_EQ(q[0].size(), 3u);
  EXPECT_NEAR(q[0][1].x - q[0][0].x, q[0][2].x - q[0][1].x, 2 * kPixel);
  EXPECT_NEAR(q[0][1].y - q[0][0].y, q[0][2].y - q[0][1].y, 2 * kPixel);
}

TEST(SvgPlot, NonFiniteAndUndrawablePointsAreNeverWritten) {
  const svg::Series s{.label = "gaps", .x = {1, 2, 3, 4, 5, 6}, .y = {1, kNaN, 3, 4, kInf, 6},
                      .marker = svg::Marker::circle};
  const svg::Series lg{.label = "log", .x = {1, 2, 3, 4}, .y = {1e-3, 0.0, -1.0, 1e-1}, .marker = svg::Marker::square};
  svg::Figure fig = one_panel({}, {}, {s});
  fig.panels.push_back({.x = {}, .y = {.scale = svg::Scale::log}, .series = {lg}});
  const std::string text = svg::render(fig);
  std::string lower = text;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  EXPECT_EQ(lower.find("nan"), std::string::npos);
  EXPECT_EQ(lower.find("inf"), std::string::npos);
  const auto doc = parse(text);
  const auto p = pieces(series(doc, "gaps"));
  ASSERT_EQ(p.size(), 1u) << "only 3 - 4 has two finite ends";
  EXPECT_EQ(p[0].size(), 2u);
  EXPECT_EQ(series(doc, "gaps").select_nodes(".//circle").size(), 4u) << "a marker per finite point";
  EXPECT_TRUE(pieces(series(doc, "log")).empty()) << "0 and -1 cannot be drawn on a log axis: no two neighbours can";
  EXPECT_EQ(series(doc, "log").select_nodes(".//rect").size(), 2u);
}

TEST(SvgPlot, TextIsEscaped) {
  const std::string title = "a<b & \"c\" 'd' >";
  svg::Figure fig = one_panel({.label = "x & y"}, {.label = "<y>"}, {{.label = "s<1>", .x = {0, 1}, .y = {0, 1}}});
  fig.title = title;
  const std::string text = svg::render(fig);
  EXPECT_EQ(text.find("a<b"), std::string::npos);
  EXPECT_NE(text.find("a&lt;b &amp; &quot;c&quot; &apos;d&apos; &gt;"), std::string::npos);
  const auto doc = parse(text);
  EXPECT_EQ(std::string(doc.child("svg").find_child_by_attribute("text", "class", "title").text().get()), title);
  EXPECT_EQ(std::string(doc.select_node("//text[@class='xlabel']").node().text().get()), "x & y");
  EXPECT_TRUE(series(doc, "s<1>"));
}

// Issue 35: a control character in a label (a unit's name, a face's) was
// written as it is, and XML 1.0 holds none but tab, line feed and carriage
// return (not even as &#1;): the plot was not XML.  U+FFFD stands for it.
TEST(SvgPlot, ControlCharactersNeverReachTheDocument) {
  std::string label = "mm";
  for (int c = 1; c < 32; ++c) label += char(c);
  label += "N";
  svg::Figure fig = one_panel({.label = label}, {.label = "y"}, {{.label = "s", .x = {0, 1}, .y = {0, 1}}});
  fig.title = label;
  const std::string text = svg::render(fig);
  for (const char c : text)
    EXPECT_FALSE((unsigned char)c < 32 && c != '\t' && c != '\n' && c != '\r') << "control character " << int(c);
  EXPECT_EQ(svg::escape("a\x01" "b\tc"), "a\xEF\xBF\xBD" "b\tc");
  EXPECT_TRUE(parse(text).child("svg"));
}

TEST(SvgPlot, SegmentsAreDisconnectedAndLinesClippedToTheFrame) {
  const svg::Series seg{.label = "seg", .x = {0, 1, 1, 2, 2, 3}, .y = {1, 1, 2, 2, 2, 2}, .segments = true};
  const svg::Series far{.label = "far", .x = {1, 1e6}, .y = {1, 1}};
  const std::string text = svg::render(one_panel({.min = 0.0, .max = 3.0}, {.min = 0.0, .max = 3.0}, {seg, far}));
  const auto doc = parse(text);
  const Box f = frames(doc).at(0);
  const auto s = pieces(series(doc, "seg"));
  ASSERT_EQ(s.size(), 3u) << "one piece per pair, even where two pairs touch";
  for (const auto& piece : s) EXPECT_EQ(piece.size(), 2u);
  const auto c = pieces(series(doc, "far"));
  ASSERT_EQ(c.size(), 1u);
  ASSERT_EQ(c[0].size(), 2u);
  EXPECT_NEAR(c[0][1].x, f.x + f.w, kPixel) << "clipped where it leaves the frame";
  EXPECT_NEAR(c[0][1].y, f.y + 2 * f.h / 3, kPixel);
}

TEST(SvgPlot, DeterministicOutput) {
  const auto fig = one_panel({}, {}, {{.label = "d", .x = {0.1, 0.2, 0.35}, .y = {3, 1, 2}}});
  EXPECT_EQ(svg::render(fig), svg::render(fig));
}

// A real 2D Hertz run (cases/hertz2d.toml, N2/S0): its pressure plot.
TEST(SvgPlot, Hertz2DPressurePlot) {
  CaseSpec spec = read_case(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml");
  const Model model = build_model(spec);
  const RunResult r = solve_model(model);
  ASSERT_EQ(r.status, "converged");
  ASSERT_TRUE(r.contact && r.hertz);
  const auto& rep = r.contacts.front().report;
  ASSERT_EQ(rep.p1.size(), rep.multipliers.size() + 1) << "S0: one constant per face element";

  const svg::Figure fig = pressure_figure(r, spec.name);
  ASSERT_EQ(fig.panels.size(), 1u);
  const svg::Panel& panel = fig.panels[0];
  ASSERT_TRUE(panel.x.max && panel.y.min && panel.y.max);
  const double xmax = *panel.x.max, ylo = *panel.y.min, yhi = *panel.y.max;
  EXPECT_EQ(xmax, 1.6) << "r/a up to 1.6";
  // The segments in view: those that start left of r/a = 1.6.
  std::vector<double> breaks;
  for (const auto& p : rep.p1) breaks.push_back(p.r / r.hertz->a);
  const long in_view = std::count_if(breaks.begin(), breaks.end() - 1, [&](double x) { return x < xmax; });
  ASSERT_GT(in_view, 10);

  const auto doc = parse(svg::render(fig));
  EXPECT_EQ(std::string(doc.select_node("//text[@class='title']").node().text().get()), "hertz2d");
  const Box f = frames(doc).at(0);
  const auto segs = pieces(series(doc, "multipliers (constant per element)"));
  EXPECT_EQ(long(segs.size()), in_view) << "one segment per multiplier in view";
  for (const auto& s : segs) {
    ASSERT_EQ(s.size(), 2u);
    EXPECT_NEAR(s[0].y, s[1].y, 1e-9) << "a constant";
  }
  const auto hertz = pieces(series(doc, "Hertz: p/p0 = √(1 − (r/a)²)"));
  ASSERT_EQ(hertz.size(), 1u);
  EXPECT_GT(hertz[0].size(), 300u);
  // Back from pixels to (r/a, p/p0): every vertex on the Hertz curve, to
  // the pixel rounding in y and in x times the curve's slope (away from its
  // kink at r = a).
  const double dx = 2 * kPixel * xmax / f.w, dy = 2 * kPixel * (yhi - ylo) / f.h;
  int checked = 0;
  for (const Pt& q : hertz[0]) {
    const double x = (q.x - f.x) / f.w * xmax, y = ylo + (f.y + f.h - q.y) / f.h * (yhi - ylo);
    if (std::abs(x - 1) < 0.01) continue;
    const double expected = x < 1 ? std::sqrt(1 - x * x) : 0.0, slope = x < 1 ? x / expected : 0.0;
    EXPECT_NEAR(y, expected, dy + slope * dx) << "r/a = " << x;
    ++checked;
  }
  EXPECT_GT(checked, 390);
}

}  // namespace
}  // namespace igac

// A load history (load curves): the first panel is against the time, and
// the second draws the steps where the squeeze grows and those where it
// shrinks as two series, joined at the turn, the unloading one dashed.
TEST(SvgPlot, LoadHistoryDrawsLoadingAndUnloadingApart) {
  igac::RunResult r;
  const double squeeze[] = {0.1, 0.2, 0.3, 0.2, 0.1, 0.0};
  for (int i = 0; i < 6; ++i) {
    igac::LoadCurvePoint p;
    p.load_factor = 0.5 * (i + 1);
    p.obstacle_displacement = squeeze[i];
    p.contact_forces = {10 * squeeze[i]};
    r.load_curve.push_back(p);
  }
  const igac::svg::Figure f = igac::load_curve_figure(r, "history", {}, {}, 2, true);
  ASSERT_EQ(f.panels.size(), 2u);
  EXPECT_EQ(f.panels[0].x.label, "time (load curves)");
  const auto& series = f.panels[1].series;
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].label, "loading");
  EXPECT_EQ(series[1].label, "unloading");
  EXPECT_TRUE(series[1].dashed);
  EXPECT_EQ(series[0].x, (std::vector<double>{0.0, 0.1, 0.2, 0.3}));  // from the origin to the turn
  EXPECT_EQ(series[1].x, (std::vector<double>{0.3, 0.2, 0.1, 0.0}));  // from the turn back
  EXPECT_EQ(series[1].y, (std::vector<double>{3.0, 2.0, 1.0, 0.0}));
  // Without a history: one series, against the load factor, as before.
  const igac::svg::Figure g = igac::load_curve_figure(r, "ramp");
  EXPECT_EQ(g.panels[0].x.label, "load factor");
  EXPECT_EQ(g.panels[1].series.size(), 1u);
}
