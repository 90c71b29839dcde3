// SPDX-License-Identifier: BSD-3-Clause
// One body's tables of a case file: [geometry], [mesh] and [material], at
// the top level of a one-body case or in each [[body]] table.
#include <algorithm>
#include <filesystem>
#include <memory>

#include "engine/geometry/shapes.hpp"
#include "io/case_section.hpp"
#include "io/gismo_xml.hpp"
#include "materials/hyperelastic.hpp"

namespace igac::case_reading {

void read_body_tables(const std::string& path, const Section& owner, const std::string& where, BodySpec& c) {
  // The shape names a registered built-in shape (engine/geometry/shapes.hpp),
  // which declares its keys: those, and only those, go with it.
  const toml::table& gt = owner.sub("geometry");
  const ShapeType* kind = find_shape_type(gt["shape"].value_or(std::string()));
  std::set<std::string> geo_keys = kGeometryKeys;
  if (kind)
    for (const ShapeKey& k : kind->keys) geo_keys.insert(std::string(k.key));
  if (gt.contains("file")) geo_keys.insert(kGeometryFileKeys.begin(), kGeometryFileKeys.end());
  if (!kind && !gt.contains("file"))
    for (const ShapeType* t : shape_types())
      for (const ShapeKey& k : t->keys) geo_keys.insert(std::string(k.key));
  const Section geo(path, where + "geometry", gt, geo_keys);
  if (geo.has("file")) {
    if (geo.has("shape")) geo.fail("file", "give either a shape or a file, not both");
    const std::filesystem::path f = geo.string("file");
    c.geometry_file = (f.is_absolute() ? f : std::filesystem::path(path).parent_path() / f).lexically_normal().string();
    if (std::error_code ec; !std::filesystem::exists(c.geometry_file, ec))
      geo.fail("file", fmt::format("no such file: {} (a relative file is read from the case file's folder)",
                                   std::filesystem::absolute(c.geometry_file).lexically_normal().string()));
    auto read = std::make_shared<const MultiPatch>(read_gismo_xml(c.geometry_file));  // one-line errors naming the file's line
    const MultiPatch& body = *read;
    c.file_body = read;
    c.dimension = body.patches.front().space_dim();
    if (body.patches.front().param_dim() != c.dimension)
      geo.fail("file", fmt::format("{}: a {}D patch in {}D space is not a solid body", c.geometry_file,
                                   body.patches.front().param_dim(), c.dimension));
    c.shape = "file";
    c.radius = geo.has("radius") ? geo.scale("radius", "the radius a Hertz reference uses") : 0.0;
    c.inner_radius = geo.has("inner_radius") ? geo.scale("inner_radius", "the inner radius a Lame reference uses") : 0.0;
    c.outer_radius = geo.has("outer_radius") ? geo.scale("outer_radius", "the outer radius a Lame reference uses") : 0.0;
    if (c.inner_radius > 0 && c.outer_radius > 0 && !(c.outer_radius > c.inner_radius))
      geo.fail("outer_radius", "must be larger than inner_radius");
  } else {
    c.shape = geo.string("shape");
    if (kind) c.dimension = kind->dim;
    if (!kind) {
      std::vector<std::string> names;
      for (const ShapeType* t : shape_types()) names.emplace_back(t->name);
      geo.fail("shape", fmt::format("unknown shape '{}' ({}; or file = \"body.xml\")", c.shape, fmt::join(names, ", ")));
    }
    for (const ShapeKey& k : kind->keys) {
      const std::string key(k.key);
      std::vector<double> v;
      if (k.length == 1) {
        v = {geo.scale(key, std::string(k.meaning).c_str())};
      } else {
        v = geo.numbers(key, size_t(k.length));
        for (double x : v)
          if (!(x >= 1e-100 && x <= 1e100))
            geo.fail(key, fmt::format("every length must be positive and within [1e-100, 1e100] (got {:g})", x));
      }
      c.shape_values[key] = v;
    }
    try {
      static_cast<void>(kind->make(c.shape_values));  // the shape's own cross-checks (outer > inner radius, ...)
    } catch (const SplineError& e) {
      geo.fail(std::string(kind->keys.back().key), e.what());
    }
    // The reference solutions read these (Hertz: radius; Lame: the radii).
    if (c.shape_values.count("radius")) c.radius = c.shape_values["radius"][0];
    if (c.shape_values.count("inner_radius")) c.inner_radius = c.shape_values["inner_radius"][0];
    if (c.shape_values.count("outer_radius")) c.outer_radius = c.shape_values["outer_radius"][0];
    if (c.shape_values.count("size")) c.size = c.shape_values["size"];
  }
  const int dim = c.dim();
  // Where the body stands: its shape or file moved by a translation (two
  // built-in shapes side by side, a file's body placed against another).
  if (geo.has("translate")) c.translate = geo.loads("translate", size_t(dim));
  if (geo.has("scale")) {
    c.scale = geo.scale("scale", "the factor every coordinate is multiplied by");
    // the radii a reference reads are the body's as it stands
    c.radius *= c.scale, c.inner_radius *= c.scale, c.outer_radius *= c.scale;
  }
  if (geo.has("mirror")) {
    const toml::node* n = geo.node("mirror");
    std::vector<std::string> axes;
    if (const auto* one = n->as_string()) axes.push_back(one->get());
    else if (const auto* list = n->as_array())
      for (const toml::node& a : *list)
        if (const auto* word = a.as_string()) axes.push_back(word->get());
        else geo.fail("mirror", "the list holds axis names (\"x\", \"y\"" + std::string(dim == 3 ? ", \"z\"" : "") + "), not numbers");
    if (axes.empty()) geo.fail("mirror", "give an axis (\"x\", \"y\"" + std::string(dim == 3 ? ", \"z\"" : "") +
                                         ") or a list of them: its coordinate changes sign");
    for (const std::string& a : axes) {
      const int axis = a == "x" ? 0 : a == "y" ? 1 : a == "z" && dim == 3 ? 2 : -1;
      if (axis < 0)
        geo.fail("mirror", fmt::format("unknown axis '{}' (\"x\", \"y\"{}: the coordinate that changes sign)", a,
                                       dim == 3 ? ", \"z\"" : ""));
      c.mirror.push_back(axis);
    }
  }
  if (geo.has("rotate")) {
    if (dim == 2) {
      if (!geo.node("rotate")->is_number())
        geo.fail("rotate", "in 2D one angle in degrees, counter-clockwise about the origin");
      c.rotate = {geo.load("rotate")};
    } else {
      c.rotate = geo.loads("rotate", 3);  // about x, then y, then z
    }
    for (double a : c.rotate)
      if (!(std::abs(a) <= 3600)) geo.fail("rotate", fmt::format("{:g} degrees: give an angle between -3600 and 3600", a));
  }

  const Section mesh(path, where + "mesh", owner.sub("mesh"), kMeshKeys);
  c.degree = mesh.integer("degree");
  if (c.degree < 1) mesh.fail("degree", fmt::format("degree {} must be at least 1", c.degree));
  if (c.degree > 10) mesh.fail("degree", fmt::format("degree {} is above the supported 10", c.degree));
  if (c.degree < 2 && kind && kind->curved)
    mesh.fail("degree", fmt::format("degree {}: a {} has exact circular arcs, quadratic NURBS; the degree must be at "
                                    "least 2", c.degree, c.shape));
  for (double e : mesh.numbers("elements", dim)) {
    if (e != std::floor(e) || e < 1 || e > 1e6) mesh.fail("elements", "entries must be whole numbers from 1 to 1e6");
    c.elements.push_back(int(e));
  }
  c.refine = mesh.integer("refine", 0);
  if (c.refine < 0) mesh.fail("refine", "must be >= 0");
  if (mesh.has("grading")) {
    // one table, or an array of tables (one per graded direction)
    std::vector<const toml::table*> gts;
    const toml::node* gn = mesh.node("grading");
    if (gn->is_table()) gts.push_back(gn->as_table());
    else if (gn->is_array_of_tables())
      for (const auto& e : *gn->as_array()) gts.push_back(e.as_table());
    else mesh.fail("grading", "must be a table [mesh.grading] or tables [[mesh.grading]]");
    for (const auto* gt : gts) {
      const Section g(path, where + "mesh.grading", *gt, kGradingKeys);
      GradingSpec gs;
      const std::string d = g.string("direction");
      if (d != "u" && d != "v" && !(d == "w" && dim == 3))
        g.fail("direction", fmt::format("'{}' is not a parametric direction (u, v{})", d, dim == 3 ? ", w" : ""));
      gs.direction = d == "u" ? 0 : d == "v" ? 1 : 2;
      for (const auto& other : c.gradings)
        if (other.direction == gs.direction) g.fail("direction", fmt::format("direction '{}' is graded twice", d));
      const std::string t = g.string("toward", "start");
      if (t != "start" && t != "end") g.fail("toward", "must be \"start\" or \"end\"");
      gs.at_start = t == "start";
      gs.span_fraction = g.number("span_fraction");
      gs.range_fraction = g.number("range_fraction");
      const std::string coarse = g.string("coarse", "uniform");
      if (coarse != "uniform" && coarse != "geometric") g.fail("coarse", "must be \"uniform\" or \"geometric\"");
      gs.geometric_coarse = coarse == "geometric";
      if (!(gs.span_fraction > 0 && gs.span_fraction < 1)) g.fail("span_fraction", "must lie in (0, 1)");
      if (!(gs.range_fraction > 0 && gs.range_fraction < 1)) g.fail("range_fraction", "must lie in (0, 1)");
      if (c.elements[gs.direction] < 2) g.fail("direction", "a graded direction needs at least 2 elements");
      c.gradings.push_back(gs);
    }
  }

  {
    // The model names a registered law; the law declares its parameters
    // (materials/hyperelastic.hpp): those, and only those, are the table's
    // other keys.  linear_elastic runs the small-deformation path.
    const toml::table& mt = owner.sub("material");
    const auto laws = law_names();
    const std::string model = mt["model"].value_or(std::string("linear_elastic"));
    std::set<std::string> keys{"model", "formulation", "incompressible"};
    const bool known = std::find(laws.begin(), laws.end(), model) != laws.end();
    if (known)
      for (const LawParameter& p : law_parameters(model)) keys.insert(std::string(p.key));
    const Section mat(path, where + "material", mt, known ? keys : std::set<std::string>{"model", "formulation", "E", "nu"});
    c.model = mat.string("model", "linear_elastic");
    if (!known)
      mat.fail("model", fmt::format("unknown material model '{}' (available: {}; linear_elastic is small deformation)",
                                    c.model, fmt::join(laws, ", ")));
    {  // engine/volumetric_projection.hpp
      const std::string f = mat.string("formulation", "displacement");
      const auto parsed = parse_formulation(f);
      if (!parsed) mat.fail("formulation", fmt::format("unknown formulation '{}' (available: displacement, mixed, mixed_element)", f));
      c.formulation = *parsed;
      c.incompressible = mat.boolean("incompressible", false);
      if (c.incompressible && !is_mixed(c.formulation))
        mat.fail("incompressible", "incompressible = true is the limit of formulation = \"mixed\" (K = infinity, the "
                                   "element pressures as multipliers): give formulation = \"mixed\"");
      if (c.incompressible && !c.finite_strain())
        mat.fail("incompressible", "incompressible = true runs the large-deformation laws (neo_hookean, mooney_rivlin); "
                                   "linear_elastic takes nu < 0.5 with formulation = \"mixed\"");
      if (c.incompressible && !where.empty())
        mat.fail("incompressible", "incompressible = true is read in the [material] of a one-body case, not in [[body]] tables");
    }
    MaterialParameters given;
    for (const LawParameter& p : law_parameters(model)) {
      const bool modulus = p.lower == 0 && std::isinf(p.upper);  // a stiffness: within the computable range
      const double v = modulus ? mat.scale(std::string(p.key), std::string(p.meaning).c_str()) : mat.number(std::string(p.key));
      if (!modulus && std::abs(v) > 1e100)  // a law's own constant (C10): the same range as a modulus
        mat.fail(std::string(p.key), fmt::format("{} = {:g} is outside [-1e100, 1e100], where the computation "
                                                 "overflows; choose units that bring it near 1", p.key, v));
      if (p.key == "E") given.E = v;
      else if (p.key == "nu") given.nu = v;
      else given.values[std::string(p.key)] = v;
    }
    try {
      const MaterialParameters linear = small_strain_equivalent(model, given);
      const auto law = make_law(model, given);  // the law's own cross-checks (e.g. C10 + C01 > 0)
      // mixed: the small-strain path needs only K and mu; large deformation the law's split
      if (is_mixed(c.formulation) && c.finite_strain() && !law->has_volumetric_split())
        mat.fail("formulation", fmt::format("formulation = \"{}\" needs a law with an isochoric/volumetric split "
                                            "(neo_hookean, mooney_rivlin, or linear_elastic in small deformation); "
                                            "'{}' declares none", formulation_name(c.formulation), model));
      try {  // its stiffness at F = I, as both paths use it: blamed on the keys the user gave
        static_cast<void>(small_strain_material(*law, dim));
      } catch (const MaterialParameterError&) {
        throw;
      } catch (const MaterialError& e) {
        std::vector<std::string> keys;
        for (const LawParameter& p : law_parameters(model)) keys.push_back(fmt::format("{} = {:g}", p.key, given.value(p.key)));
        mat.fail(std::string(law_parameters(model).front().key),
                 fmt::format("{} give a small-strain stiffness that is not usable ({})", fmt::join(keys, ", "), e.what()));
      }
      c.E = linear.E;
      c.nu = linear.nu;
      c.material_parameters = given;
    } catch (const MaterialParameterError& e) {
      mat.fail(e.key(), e.what());
    }
  }
}

}  // namespace igac::case_reading
