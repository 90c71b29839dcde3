// SPDX-License-Identifier: BSD-3-Clause
#include "io/svg_plot.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <limits>

namespace igac::svg {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Layout, in px.
constexpr double kFigureTitleBand = 30;       // above the panels, when the figure has a title
constexpr double kPanelTitleBand = 28;        // above a frame with a title (12 without)
constexpr double kRightMargin = 20, kBottomMargin = 46;
constexpr double kTitleFont = 14, kLabelFont = 12, kTickFont = 11, kLegendFont = 11, kNoteFont = 10;
constexpr double kCharWidth = 0.6;            // estimated advance of a character, in font sizes
constexpr int kMaxIntervals = 10;             // ticks: at most this many intervals
constexpr int kMaxMinorDecades = 6;           // log axes: 2..9 grid lines up to this many decades
constexpr double kSnap = 1e-9;                // relative slack when a range ends on a tick

const char* kFont = "DejaVu Sans, Helvetica, Arial, sans-serif";

// Pixels with at most two decimals, no trailing zeros, never "-0".
std::string num(double v) {
  v = std::round(v * 100) / 100;
  if (v == 0) v = 0;
  std::string s = fmt::format("{:.2f}", v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

double text_width(std::string_view s, double font) {
  int chars = 0;
  for (unsigned char c : s) chars += (c & 0xC0) != 0x80;  // UTF-8: count code points
  return chars * kCharWidth * font;
}

double tick_label_width(const Tick& t) {
  return t.power ? text_width("10", kTickFont) + 0.75 * text_width(t.label, kTickFont) : text_width(t.label, kTickFont);
}

struct Point {
  double x = 0, y = 0;
  bool operator==(const Point&) const = default;
};

struct Frame {
  double x = 0, y = 0, w = 0, h = 0;
  bool contains(Point p, double slack) const {
    return p.x >= x - slack && p.x <= x + w + slack && p.y >= y - slack && p.y <= y + h + slack;
  }
};

// A panel's data onto its frame.
struct Mapping {
  Range xr, yr;
  Scale xs, ys;
  Frame f;
  Point operator()(double x, double y) const {
    return {to_pixel(x, xr, xs, f.x, f.x + f.w), to_pixel(y, yr, ys, f.y + f.h, f.y)};
  }
};

// Liang-Barsky: the part of segment ab inside the frame; false when none.
// An end inside the frame is kept exactly (so consecutive pieces join).
bool clip(Point& a, Point& b, const Frame& f) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const std::array<double, 4> p{-dx, dx, -dy, dy};
  const std::array<double, 4> q{a.x - f.x, f.x + f.w - a.x, a.y - f.y, f.y + f.h - a.y};
  double t0 = 0, t1 = 1;
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
    if (t0 > t1) return false;
  }
  const Point a0 = a;
  if (t0 > 0) a = {a0.x + t0 * dx, a0.y + t0 * dy};
  if (t1 < 1) b = {a0.x + t1 * dx, a0.y + t1 * dy};
  return true;
}

void marker_shape(std::string& out, Marker m, Point c, double s) {
  const auto P = [](double x, double y) { return fmt::format("{},{}", num(x), num(y)); };
  switch (m) {
    case Marker::none: return;
    case Marker::circle:
      fmt::format_to(std::back_inserter(out), "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"/>", num(c.x), num(c.y), num(s));
      return;
    case Marker::square:
      fmt::format_to(std::back_inserter(out), "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>", num(c.x - s),
                     num(c.y - s), num(2 * s), num(2 * s));
      return;
    case Marker::diamond: {
      const double d = 1.3 * s;
      fmt::format_to(std::back_inserter(out), "<polygon points=\"{} {} {} {}\"/>", P(c.x, c.y - d), P(c.x + d, c.y),
                     P(c.x, c.y + d), P(c.x - d, c.y));
      return;
    }
    case Marker::triangle:
      fmt::format_to(std::back_inserter(out), "<polygon points=\"{} {} {}\"/>", P(c.x, c.y - 1.3 * s),
                     P(c.x + 1.15 * s, c.y + 0.75 * s), P(c.x - 1.15 * s, c.y + 0.75 * s));
      return;
  }
}

std::string dash(const Series& s) { return s.dashed ? " stroke-dasharray=\"6 4\"" : ""; }

// One series: its lines as one path, its markers; the pixels it covers go
// to `drawn` (for the legend's placement).
void draw_series(std::string& out, const Series& s, const Mapping& map, std::vector<Point>& drawn) {
  const size_t n = std::min(s.x.size(), s.y.size());
  std::vector<Point> px(n);
  std::vector<char> ok(n);
  for (size_t i = 0; i < n; ++i) {
    px[i] = map(s.x[i], s.y[i]);
    ok[i] = std::isfinite(px[i].x) && std::isfinite(px[i].y);
  }
  out += "<g class=\"series\">";
  if (!s.label.empty()) fmt::format_to(std::back_inserter(out), "<title>{}</title>", escape(s.label));
  std::string d;
  std::optional<Point> end;  // where the path's current piece ends
  const auto add = [&](Point a, Point b, bool join) {
    if (!clip(a, b, map.f)) return;
    if (!(join && end && *end == a)) fmt::format_to(std::back_inserter(d), "M{} {}", num(a.x), num(a.y));
    fmt::format_to(std::back_inserter(d), "L{} {}", num(b.x), num(b.y));
    end = b;
    const int k = std::min(200, int(std::ceil(std::hypot(b.x - a.x, b.y - a.y) / 6)));
    for (int j = 0; j <= k; ++j)
      drawn.push_back({a.x + (b.x - a.x) * j / std::max(k, 1), a.y + (b.y - a.y) * j / std::max(k, 1)});
  };
  if (s.segments) {
    for (size_t i = 0; i + 1 < n; i += 2)
      if (ok[i] && ok[i + 1]) add(px[i], px[i + 1], false);
  } else if (s.line) {
    for (size_t i = 1; i < n; ++i)
      if (ok[i - 1] && ok[i]) add(px[i - 1], px[i], true);
  }
  if (!d.empty())
    fmt::format_to(std::back_inserter(out),
                   "<path d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"{}/>", d,
                   escape(s.color), num(s.line_width), dash(s));
  if (s.marker != Marker::none) {
    fmt::format_to(std::back_inserter(out), "<g fill=\"{}\">", escape(s.color));
    for (size_t i = 0; i < n; ++i)
      if (ok[i] && map.f.contains(px[i], 0.5)) {
        marker_shape(out, s.marker, px[i], s.marker_size);
        drawn.push_back(px[i]);
      }
    out += "</g>";
  }
  out += "</g>\n";
}

void draw_legend(std::string& out, const Panel& p, const Frame& f, const std::vector<Point>& drawn) {
  std::vector<const Series*> entries;
  double tw = 0;
  for (const auto& s : p.series)
    if (!s.label.empty()) {
      entries.push_back(&s);
      tw = std::max(tw, text_width(s.label, kLegendFont));
    }
  if (entries.empty()) return;
  constexpr double pad = 7, row = 17, sample = 26, inset = 8;
  const double w = pad + sample + 6 + tw + pad, h = 2 * pad + row * entries.size() - 4;
  const auto origin = [&](Corner c) -> Point {
    const double left = f.x + inset, right = f.x + f.w - inset - w, top = f.y + inset, bottom = f.y + f.h - inset - h;
    switch (c) {
      case Corner::upper_left: return {left, top};
      case Corner::lower_left: return {left, bottom};
      case Corner::lower_right: return {right, bottom};
      default: return {right, top};
    }
  };
  Corner corner = p.legend;
  if (corner == Corner::best) {  // the fewest drawn points under the box; ties: this order
    size_t fewest = std::numeric_limits<size_t>::max();
    for (Corner c : {Corner::upper_right, Corner::upper_left, Corner::lower_left, Corner::lower_right}) {
      const Point o = origin(c);
      const Frame box{o.x, o.y, w, h};
      const size_t under = std::count_if(drawn.begin(), drawn.end(), [&](Point q) { return box.contains(q, 2); });
      if (under < fewest) fewest = under, corner = c;
    }
  }
  const Point o = origin(corner);
  fmt::format_to(std::back_inserter(out),
                 "<g class=\"legend\" font-size=\"{}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" rx=\"3\" "
                 "fill=\"#ffffff\" fill-opacity=\"0.85\" stroke=\"#cccccc\"/>",
                 num(kLegendFont), num(o.x), num(o.y), num(w), num(h));
  for (size_t i = 0; i < entries.size(); ++i) {
    const Series& s = *entries[i];
    const double y = o.y + pad + row * i + row / 2 - 2, x = o.x + pad;
    if (s.line || s.segments)
      fmt::format_to(std::back_inserter(out), "<path d=\"M{} {}H{}\" stroke=\"{}\" stroke-width=\"{}\"{}/>", num(x),
                     num(y), num(x + sample), escape(s.color), num(s.line_width), dash(s));
    if (s.marker != Marker::none) {
      fmt::format_to(std::back_inserter(out), "<g fill=\"{}\">", escape(s.color));
      marker_shape(out, s.marker, {x + sample / 2, y}, s.marker_size);
      out += "</g>";
    }
    fmt::format_to(std::back_inserter(out), "<text x=\"{}\" y=\"{}\">{}</text>", num(x + sample + 6),
                   num(y + 0.35 * kLegendFont), escape(s.label));
  }
  out += "</g>\n";
}

// Which ticks show their label: in the order ticks() gives them (decades
// first), each one unless it would overlap a label already shown.
std::vector<char> fitting_labels(const std::vector<Tick>& ticks, Range r, Scale scale, double from, double to,
                                 bool horizontal) {
  std::vector<char> shown(ticks.size(), 0);
  std::vector<std::pair<double, double>> taken;  // pixel intervals
  for (size_t i = 0; i < ticks.size(); ++i) {
    if (ticks[i].label.empty()) continue;
    const double at = to_pixel(ticks[i].value, r, scale, from, to);
    const double half = horizontal ? tick_label_width(ticks[i]) / 2 + 4 : kTickFont / 2 + 2;
    const bool clear = std::none_of(taken.begin(), taken.end(),
                                    [&](const auto& iv) { return at - half < iv.second && at + half > iv.first; });
    if (!clear || !std::isfinite(at)) continue;
    taken.emplace_back(at - half, at + half);
    shown[i] = 1;
  }
  return shown;
}

std::string tick_text(const Tick& t) {
  return t.power ? fmt::format("10<tspan dy=\"-5\" font-size=\"8\">{}</tspan>", escape(t.label)) : escape(t.label);
}

void draw_panel(std::string& out, const Panel& p, double x0, double y0, double width, double height) {
  const bool xlog = p.x.scale == Scale::log, ylog = p.y.scale == Scale::log;
  std::vector<double> xs, ys;  // the points that can be drawn, for the ranges not set
  for (const auto& s : p.series)
    for (size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && (!xlog || s.x[i] > 0) && (!ylog || s.y[i] > 0)) {
        xs.push_back(s.x[i]);
        ys.push_back(s.y[i]);
      }
  const Range xr = axis_range(p.x, xs), yr = axis_range(p.y, ys);
  const std::vector<Tick> xt = ticks(xr, p.x.scale), yt = ticks(yr, p.y.scale);
  double label_w = 0;
  for (const auto& t : yt) label_w = std::max(label_w, tick_label_width(t));
  const double left = std::clamp(label_w + 34, 56.0, 200.0);
  const double top = y0 + (p.title.empty() ? 12 : kPanelTitleBand);
  const Frame f{x0 + left, top, std::max(width - left - kRightMargin, 10.0),
                std::max(height - (top - y0) - kBottomMargin, 10.0)};
  const Mapping map{xr, yr, p.x.scale, p.y.scale, f};

  out += "<g class=\"panel\">\n";
  if (!p.title.empty())
    fmt::format_to(std::back_inserter(out), "<text class=\"title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"{}\">{}</text>\n",
                   num(f.x + f.w / 2), num(f.y - 9), num(kTitleFont), escape(p.title));
  // The grid: decades and labelled ticks darker than the 2..9 lines of a log axis.
  std::string major, minor;
  for (const auto& t : xt) {
    const double x = to_pixel(t.value, xr, p.x.scale, f.x, f.x + f.w);
    fmt::format_to(std::back_inserter(t.label.empty() ? minor : major), "M{} {}V{}", num(x), num(f.y), num(f.y + f.h));
  }
  for (const auto& t : yt) {
    const double y = to_pixel(t.value, yr, p.y.scale, f.y + f.h, f.y);
    fmt::format_to(std::back_inserter(t.label.empty() ? minor : major), "M{} {}H{}", num(f.x), num(y), num(f.x + f.w));
  }
  if (!minor.empty())
    fmt::format_to(std::back_inserter(out), "<path class=\"grid\" d=\"{}\" stroke=\"#000000\" stroke-opacity=\"0.06\"/>\n", minor);
  if (!major.empty())
    fmt::format_to(std::back_inserter(out), "<path class=\"grid\" d=\"{}\" stroke=\"#000000\" stroke-opacity=\"0.15\"/>\n", major);
  fmt::format_to(std::back_inserter(out),
                 "<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#333333\"/>\n",
                 num(f.x), num(f.y), num(f.w), num(f.h));
  // Tick marks and labels.
  std::string marks, labels;
  const std::vector<char> xfit = fitting_labels(xt, xr, p.x.scale, f.x, f.x + f.w, true);
  for (size_t i = 0; i < xt.size(); ++i) {
    if (!xfit[i]) continue;
    const double x = to_pixel(xt[i].value, xr, p.x.scale, f.x, f.x + f.w);
    fmt::format_to(std::back_inserter(marks), "M{} {}v4", num(x), num(f.y + f.h));
    labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>", num(x), num(f.y + f.h + 17),
                          tick_text(xt[i]));
  }
  const std::vector<char> yfit = fitting_labels(yt, yr, p.y.scale, f.y + f.h, f.y, false);
  for (size_t i = 0; i < yt.size(); ++i) {
    if (!yfit[i]) continue;
    const double y = to_pixel(yt[i].value, yr, p.y.scale, f.y + f.h, f.y);
    fmt::format_to(std::back_inserter(marks), "M{} {}h-4", num(f.x), num(y));
    labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{}</text>", num(f.x - 7),
                          num(y + 0.35 * kTickFont), tick_text(yt[i]));
  }
  if (!marks.empty()) fmt::format_to(std::back_inserter(out), "<path class=\"ticks\" d=\"{}\" stroke=\"#333333\"/>\n", marks);
  fmt::format_to(std::back_inserter(out), "<g class=\"tick-labels\" font-size=\"{}\" fill=\"#222222\">{}</g>\n",
                 num(kTickFont), labels);
  fmt::format_to(std::back_inserter(out), "<text class=\"xlabel\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"{}\">{}</text>\n",
                 num(f.x + f.w / 2), num(f.y + f.h + 38), num(kLabelFont), escape(p.x.label));
  const double lx = f.x - label_w - 16, ly = f.y + f.h / 2;
  fmt::format_to(std::back_inserter(out),
                 "<text class=\"ylabel\" x=\"{0}\" y=\"{1}\" transform=\"rotate(-90 {0} {1})\" text-anchor=\"middle\" "
                 "font-size=\"{2}\">{3}</text>\n",
                 num(lx), num(ly), num(kLabelFont), escape(p.y.label));
  std::vector<Point> drawn;
  for (const auto& s : p.series) draw_series(out, s, map, drawn);
  for (const auto& n : p.notes) {
    const Point q = map(n.x, n.y);
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !f.contains(q, 0.5)) continue;
    fmt::format_to(std::back_inserter(out), "<text class=\"note\" x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{}\">{}</text>\n",
                   num(q.x + n.dx), num(q.y + n.dy), num(kNoteFont), escape(n.color), escape(n.text));
  }
  draw_legend(out, p, f, drawn);
  out += "</g>\n";
}

}  // namespace

std::string escape(std::string_view text) {
  std::string s;
  s.reserve(text.size());
  for (char c : text) switch (c) {
      case '&': s += "&amp;"; break;
      case '<': s += "&lt;"; break;
      case '>': s += "&gt;"; break;
      case '"': s += "&quot;"; break;
      case '\'': s += "&apos;"; break;
      default:
        // XML 1.0 has no control characters but tab, line feed and carriage
        // return, not even as &#N;: U+FFFD, the replacement character, instead
        if ((unsigned char)c < 32 && c != '\t' && c != '\n' && c != '\r') s += "\xEF\xBF\xBD";
        else s += c;
    }
  return s;
}

double to_pixel(double v, Range r, Scale scale, double from, double to) {
  if (!std::isfinite(v) || (scale == Scale::log && v <= 0)) return kNaN;
  const double t = scale == Scale::log ? (std::log10(v) - std::log10(r.lo)) / (std::log10(r.hi) - std::log10(r.lo))
                                       : (v - r.lo) / (r.hi - r.lo);
  const double px = from + t * (to - from);
  return std::isfinite(px) ? px : kNaN;
}

Range axis_range(const Axis& a, const std::vector<double>& values) {
  const bool log = a.scale == Scale::log;
  const auto usable = [&](double v) { return std::isfinite(v) && (!log || v > 0); };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values)
    if (usable(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (lo > hi) lo = log ? 1 : 0, hi = log ? 10 : 1;  // no data
  Range r;
  if (log) {
    const double l0 = std::log10(lo), l1 = std::log10(hi);
    r.lo = std::pow(10.0, l0 - 0.05 * (l1 - l0));
    r.hi = std::pow(10.0, l1 + 0.05 * (l1 - l0));
  } else {
    r.lo = lo - 0.05 * (hi - lo);
    r.hi = hi + 0.05 * (hi - lo);
  }
  if (a.min && usable(*a.min)) r.lo = *a.min;
  if (a.max && usable(*a.max)) r.hi = *a.max;
  if (!(r.hi > r.lo)) {  // one value, or limits that cross: around the lower one
    const double c = r.lo;
    r = log ? Range{c / 10, c * 10} : Range{c - (c != 0 ? 0.1 * std::abs(c) : 1), c + (c != 0 ? 0.1 * std::abs(c) : 1)};
  }
  if (!std::isfinite(r.lo) || !std::isfinite(r.hi) || !(r.hi > r.lo) || (log && !(r.lo > 0)))
    r = log ? Range{1, 10} : Range{0, 1};
  return r;
}

std::vector<Tick> ticks(Range r, Scale scale) {
  std::vector<Tick> out;
  if (scale == Scale::linear) {
    const double raw = (r.hi - r.lo) / kMaxIntervals;
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = 10 * mag;
    for (double m : {1.0, 2.0, 5.0})
      if (m * mag >= raw * (1 - kSnap)) {
        step = m * mag;
        break;
      }
    const int decimals = std::max(0, -int(std::floor(std::log10(step) + kSnap)));
    const bool fixed = decimals <= 5 && std::max(std::abs(r.lo), std::abs(r.hi)) < 1e6;
    const double k0 = std::ceil(r.lo / step - kSnap), k1 = std::floor(r.hi / step + kSnap);
    for (double k = k0; k <= k1 && out.size() <= 2 * kMaxIntervals; ++k) {
      const double v = k == 0 ? 0.0 : k * step;  // integer multiples: no drift
      out.push_back({v, fixed ? fmt::format("{:.{}f}", v, decimals) : fmt::format("{:.3g}", v)});
    }
    return out;
  }
  const double l0 = std::log10(r.lo), l1 = std::log10(r.hi);
  const int e0 = int(std::ceil(l0 - kSnap)), e1 = int(std::floor(l1 + kSnap));
  const int decades = e1 - e0 + 1;  // decades inside the range
  const int stride = std::max(1, (decades - 1 + kMaxIntervals - 1) / kMaxIntervals);
  // Too few decades to read the axis by: 2..9 times a power of ten are
  // labelled too, all in plain numbers.
  const bool few = decades < 2;
  for (int e = e0; e <= e1; ++e) {
    const double v = std::pow(10.0, e);
    if (few) out.push_back({v, fmt::format("{:g}", v)});
    else out.push_back({v, (e - e0) % stride == 0 ? std::to_string(e) : std::string(), true});
  }
  if (l1 - l0 <= kMaxMinorDecades + kSnap)
    for (int e = int(std::floor(l0)); e <= e1; ++e)
      for (int m = 2; m <= 9; ++m) {
        const double v = m * std::pow(10.0, e);
        if (v < r.lo * (1 - kSnap) || v > r.hi * (1 + kSnap)) continue;
        out.push_back({v, few ? fmt::format("{:g}", v) : std::string()});
      }
  return out;
}

std::string render(const Figure& fig) {
  const double top = fig.title.empty() ? 0 : kFigureTitleBand;
  const double width = fig.panel_width * std::max<size_t>(1, fig.panels.size()), height = top + fig.panel_height;
  std::string out = fmt::format(
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0}\" height=\"{1}\" viewBox=\"0 0 {0} {1}\" "
      "font-family=\"{2}\">\n<rect width=\"{0}\" height=\"{1}\" fill=\"#ffffff\"/>\n",
      num(width), num(height), kFont);
  if (!fig.title.empty())
    fmt::format_to(std::back_inserter(out), "<text class=\"title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"{}\">{}</text>\n",
                   num(width / 2), num(20), num(kTitleFont + 1), escape(fig.title));
  for (size_t i = 0; i < fig.panels.size(); ++i)
    draw_panel(out, fig.panels[i], i * fig.panel_width, top, fig.panel_width, fig.panel_height);
  out += "</svg>\n";
  return out;
}

}  // namespace igac::svg
