#include "io/case_body.hpp"

#include <fmt/format.h>

#include "engine/geometry/shapes.hpp"
#include "io/gismo_xml.hpp"

namespace igac {

MultiPatch case_body(const CaseSpec& spec) {
  try {
    // The same shapes, with the same parameters, as build_model (io/case_run.cpp).
    Geometry g;
    if (spec.shape == "quarter_disc") g = quarter_disc(spec.radius);
    else if (spec.shape == "sphere_octant") g = sphere_octant(spec.radius);
    else if (spec.shape == "quarter_annulus") g = quarter_annulus(spec.inner_radius, spec.outer_radius);
    else if (spec.shape == "rectangle") g = rectangle(spec.size.at(0), spec.size.at(1));
    else if (spec.shape == "box") g = box(spec.size.at(0), spec.size.at(1), spec.size.at(2));
    else throw InputError(fmt::format("{}: [geometry] shape: unknown shape \"{}\"", spec.path, spec.shape));
    return single_patch_body(g.patch);
  } catch (const SplineError& e) {
    throw InputError(fmt::format("{}: [geometry] {}", spec.path, e.what()));
  } catch (const std::out_of_range&) {
    throw InputError(fmt::format("{}: [geometry] size: too few entries for a {}", spec.path, spec.shape));
  }
}

}  // namespace igac
