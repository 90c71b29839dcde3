// SPDX-License-Identifier: BSD-3-Clause
// Plots written as SVG text by igac itself: a figure of panels side by side,
// each with a title, axis labels, linear or logarithmic axes with "nice"
// ticks, a light grid, a legend, and series drawn as lines, markers, dashed
// lines or disconnected segments.  What the output folder needs
// (pressure.svg, load_curve.svg, study.svg: io/plots.hpp) and no more.
//
// Ticks: a linear axis steps by 1, 2 or 5 times a power of ten, the
// smallest such step that gives at most 10 intervals over the range; a
// logarithmic axis ticks the decades (every k-th when there are more than
// 10) with a light grid line at 2..9 times each (when the range spans at
// most 6 decades), and labels those too when fewer than two decades show.
// A label that would overlap one already placed is left out (decades
// first).  A range not set is taken from the data: its extent with 5 %
// margins, in log10 on a logarithmic axis.  On a logarithmic axis a decade
// is the same number of pixels everywhere in a panel.
//
// The file is deterministic and small: coordinates in pixels with at most two
// decimals, no timestamps, no ids.  A data point that is not finite (or not
// positive on a logarithmic axis) is never written: it breaks a line, and a
// segment or marker that uses it is left out.  Lines are clipped to the
// frame (Liang-Barsky), markers outside it are left out.  All text is
// XML-escaped.  Text widths are estimated (0.6 em a character): SVG has no
// way to measure them, and the viewer draws the fonts.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace igac::svg {

enum class Scale { linear, log };
enum class Marker { none, circle, square, diamond, triangle };
enum class Corner { best, upper_right, upper_left, lower_left, lower_right };

struct Series {
  std::string label{};  // shown in the legend; empty: not in the legend
  std::string color = "#1f77b4";
  std::vector<double> x{}, y{};  // the same length
  bool line = true;          // the points joined in order
  bool dashed = false;
  bool segments = false;     // instead of one line: points in pairs, one segment each
  Marker marker = Marker::none;
  double marker_size = 3;  // px, from the centre
  double line_width = 1.5;  // px
};

// A text at a data point, moved by (dx, dy) px; left out when the point is
// outside the frame.
struct Note {
  double x = 0, y = 0;
  std::string text{}, color = "#000000";
  double dx = 0, dy = 0;
};

struct Axis {
  std::string label{};
  Scale scale = Scale::linear;
  std::optional<double> min{}, max{};  // unset: from the data (see above)
};

struct Panel {
  std::string title{};
  Axis x{}, y{};
  std::vector<Series> series{};
  std::vector<Note> notes{};
  Corner legend = Corner::best;  // best: the corner whose box covers the fewest drawn points
};

struct Figure {
  std::string title{};  // above all panels; empty: none
  std::vector<Panel> panels{};  // side by side, left to right
  double panel_width = 560, panel_height = 400;  // px
};

// The whole SVG document.
std::string render(const Figure& figure);

// The pieces, for the tests.
struct Range {
  double lo = 0, hi = 1;
};
// The range an axis shows: its min and max where set, the rest from the
// values (those of the data points that can be drawn on this axis).
Range axis_range(const Axis& axis, const std::vector<double>& values);
struct Tick {
  double value = 0;
  std::string label;  // empty: a grid line only
  bool power = false;  // label is the exponent k of 10^k (a decade of a log axis)
};
std::vector<Tick> ticks(Range range, Scale scale);
// v in [range.lo, range.hi] onto [from, to] px (to < from for a y axis);
// NaN when v cannot be drawn (not finite, or not positive on a log axis).
double to_pixel(double v, Range range, Scale scale, double from, double to);
// & < > " ' as XML entities, and the control characters XML 1.0 cannot hold
// (all but tab, line feed and carriage return) as U+FFFD.
std::string escape(std::string_view text);

}  // namespace igac::svg
