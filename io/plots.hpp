// SPDX-License-Identifier: BSD-3-Clause
// The plots of an output folder, drawn as SVG (io/svg_plot.hpp) from what a
// run holds in memory; the CSV files beside them hold the same numbers.
//   pressure.svg    the contact pressure (pressure_<face>.svg, one per
//                   contact, when the case has several): the
//                   multipliers (N2/S0: one constant per face element, drawn
//                   as a segment over its element), the P1 re-interpolation
//                   and, when the case has Hertz, p/p0 = sqrt(1 - (r/a)^2)
//                   against r/a, like Figure 1(b) of Antolin, Buffa & Fabre
//                   (2018); otherwise p = -lambda against r.
//   load_curve.svg  large deformation and load curves: the contact force (each contact's,
//                   when there are several) against the load factor (the time), and
//                   against the loaded face's displacement (or how far a
//                   moving obstacle has moved).
//   study.svg       a refinement study: errors against h, log-log, with the
//                   slope of the finest pair of levels in the legend and as
//                   a triangle.
#pragma once

#include <string>
#include <vector>

#include "model/model.hpp"
#include "model/run_result.hpp"
#include "io/svg_plot.hpp"

namespace igac {

// Contact `contact` (case order) of result.contacts.
// `units` name the axes' units ([units]; none: no unit on the axes).
svg::Figure pressure_figure(const RunResult& result, const std::string& title, size_t contact = 0,
                            const UnitsSpec& units = {});
// Needs result.load_curve (the origin is added as its first point).  With
// `faces` (several contacts), a curve per contact labelled with its face.
// `history` (load curves): the first panel against the curves' time, and
// with one contact the second panel draws the steps where the displacement
// decreases (unloading) as a series of their own.
svg::Figure load_curve_figure(const RunResult& result, const std::string& title,
                              const std::vector<std::string>& faces = {}, const UnitsSpec& units = {}, int dim = 2,
                              bool history = false);

// One error of a study, per level (aligned with the levels' h).
struct StudyError {
  std::string name;  // e.g. displacement_l2 (labelled in words on the plot)
  std::vector<double> values;
};
svg::Figure study_figure(const std::vector<double>& h, const std::vector<StudyError>& errors, const std::string& title);

}  // namespace igac
