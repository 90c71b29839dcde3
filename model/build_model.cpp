// SPDX-License-Identifier: BSD-3-Clause
// From a CaseSpec to a Model: the coarse patches refined as [mesh] asks,
// joined into one body, the named faces, the dofs, the law, the contacts.
#include "model/model.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <tuple>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/geometry/side_names.hpp"
#include "engine/geometry/topology.hpp"
#include "engine/quadrature.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/spline/split.hpp"
#include "contact/mortar_gap.hpp"
#include "materials/plane_stress.hpp"
#include "model/case_body.hpp"
#include "model/partial_faces.hpp"

namespace igac {

namespace {

}  // namespace

std::vector<PatchSide> resolve_faces(const Model& m, const std::vector<std::string>& names, const char* section) {
  // The key that names them: [faces] NAME, [contact] master, else faces.
  const std::string table = section, key = table == "faces" ? "*" : table == "contact" ? "master" : "faces";
  std::vector<PatchSide> out;
  for (const auto& n : names) {
    auto f = find_faces(m, n);
    if (!f)
      throw InputError(fmt::format("{}: [{}] faces: unknown face '{}' on a {} (known: {})",
                                   m.spec.where({.table = table, .key = key, .word = n}), section, n, m.spec.shape,
                                   fmt::join(face_names(m), ", ")));
    for (const PatchSide& side : *f)
      for (const PatchInterface& itf : m.body.interfaces())
        if (side == itf.first || side == itf.second)
          throw InputError(fmt::format("{}: [{}] faces: '{}' is the interface {} - {} inside the body, not a face on "
                                       "its boundary",
                                       m.spec.where({.table = table, .key = key, .word = n}), section, n, m.body.describe(side_in_file(m, itf.first)),
                                       m.body.describe(side_in_file(m, itf.second))));
    out.insert(out.end(), f->begin(), f->end());
  }
  for (auto it = out.begin(); it != out.end(); ++it)  // a load counted twice, multipliers made twice over
    if (std::find(out.begin(), it, *it) != it)
      throw InputError(fmt::format("{}: [{}] faces {}: the side {} is listed twice",
                                   m.spec.where({.table = table, .key = key, .word = names.front()}), section,
                                   fmt::join(names, ", "), m.body.describe(*it)));
  return out;
}

namespace {

double largest_element_diameter(const NurbsPatch& p) {
  const int pd = p.param_dim();
  std::array<std::vector<double>, 3> b;
  std::array<int, 3> ne{1, 1, 1};
  for (int d = 0; d < pd; ++d) {
    b[d] = p.knots(d).breakpoints();
    ne[d] = int(b[d].size()) - 1;
  }
  double h = 0;
  for (int k = 0; k < ne[2]; ++k)
    for (int j = 0; j < ne[1]; ++j)
      for (int i = 0; i < ne[0]; ++i) {
        std::vector<Eigen::VectorXd> corners;
        for (int c = 0; c < (1 << pd); ++c) {
          Eigen::VectorXd xi(pd);
          const std::array<int, 3> e{i, j, k};
          for (int d = 0; d < pd; ++d) xi[d] = b[d][e[d] + ((c >> d) & 1)];
          corners.push_back(p.point(xi));
        }
        for (size_t a = 0; a < corners.size(); ++a)
          for (size_t c = a + 1; c < corners.size(); ++c) h = std::max(h, (corners[a] - corners[c]).norm());
      }
  return h;
}

// Refines one coarse patch as the case asks: degree elevation to
// [mesh] degree, then per direction the uniform or graded knots (with the
// patch's own interior knots kept), subdivided `refine` times.
// `backwards`: the patch was reoriented (its first direction runs backwards),
// so a grading of that direction toward the start is toward its new end.
NurbsPatch refine_patch(const CaseSpec& c, const BodySpec& spec, const NurbsPatch& coarse, const std::string& which,
                        bool backwards = false) {
  for (int d = 0; d < coarse.param_dim(); ++d)
    if (coarse.degree(d) > spec.degree)
      throw InputError(fmt::format("{}: [mesh] degree = {} is below the geometry's degree {} in direction {}{}: igac "
                                   "raises the degree, never lowers it, so that the geometry stays exact",
                                   c.where(spec, "mesh", "degree"), spec.degree, coarse.degree(d), "uvw"[d], which));
  NurbsPatch patch = elevate_to(coarse, spec.degree);
  for (int d = 0; d < patch.param_dim(); ++d) {
    const GradingSpec* g = nullptr;
    for (const auto& gs : spec.gradings)
      if (gs.direction == d) g = &gs;
    KnotVector target;
    try {
      const bool at_start = g && (d == 0 && backwards ? !g->at_start : g->at_start);
      target = g ? KnotVector::graded(spec.degree, spec.elements[d], g->span_fraction, g->range_fraction, at_start,
                                      g->geometric_coarse ? KnotVector::CoarseSpans::geometric
                                                          : KnotVector::CoarseSpans::uniform)
                 : KnotVector::uniform(spec.degree, spec.elements[d]);
      if (spec.refine > 0) target = target.subdivided(1 << spec.refine);
    } catch (const SplineError& e) {
      if (!g) throw;
      throw InputError(fmt::format("{}: [mesh.grading] range_fraction = {:g}: the graded spans are too short to be "
                                   "told apart ({}); use a larger range_fraction or fewer elements",
                                   c.where(spec, "mesh.grading", "range_fraction"), g->range_fraction, e.what()));
    }
    try {
      patch = refine_to(patch, d, target.united_with(patch.knots(d)));
    } catch (const SplineError& e) {
      throw InputError(fmt::format("{}: [mesh] refining direction {}{}{}: {}", c.where(spec, "mesh", "elements"), "uvw"[d], which,
                                   spec.geometry_file.empty() ? "" : " of " + spec.geometry_file, e.what()));
    }
  }
  return patch;
}

// A geometry file's patch must map its parameter cube onto the body without
// folding: det J > 0 at every Gauss point.  Names the patch and the place.
void check_patch_map(const CaseSpec& c, const BodySpec& spec, const NurbsPatch& patch, int k) {
  const PatchQuadrature quad(patch, gauss_points_for(spec.degree));
  ElementData ed;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, false);
    if (ed.min_det_J > 0) continue;
    for (int q = 0; q < ed.JxW.size(); ++q)
      if (!(ed.JxW[q] > 0))
        throw InputError(fmt::format("{}: [geometry] file {}: patch {} folds: its Jacobian determinant is not positive "
                                     "at parameter ({:.4g}), point ({:.4g})",
                                     c.where(spec, "geometry", "file"), spec.geometry_file, k, fmt::join(ed.xi.row(q), ", "),
                                     fmt::join(ed.X.row(q), ", ")));
  }
}

// +1 when det J > 0 at every Gauss point of the patch, -1 when det J < 0 at
// every one (a left-handed patch, as about half of G+Smo's multi-patch files
// hold), 0 when it changes sign or vanishes (a fold: check_patch_map says where).
int orientation(const NurbsPatch& patch, int points) {
  const PatchQuadrature quad(patch, points);
  ElementData ed;
  bool positive = false, negative = false;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, false);
    for (int q = 0; q < ed.JxW.size(); ++q) {
      if (ed.JxW[q] > 0) positive = true;
      else if (ed.JxW[q] < 0) negative = true;
      else positive = negative = true;
    }
  }
  return positive == negative ? 0 : positive ? 1 : -1;
}

// Joins the sides of a geometry file that coincide and that its topology
// leaves apart: the seam of a closed patch, every interface of a file that
// gives no <interfaces> (engine/geometry/topology.hpp).  A side the file
// lists in its <boundary> stays a boundary (a slit the file asks for), with
// a warning; so do sides that share only their corners.
void join_coincident_sides(MultiPatch& coarse, Model& m, const BodySpec& body, int offset) {
  const CaseSpec& spec = m.spec;
  auto listed = [](const auto& sides, const PatchSide& s) { return std::find(sides.begin(), sides.end(), s) != sides.end(); };
  // A side of this body's patches as the file names it, in the model's
  // patch numbers (the bodies' patches follow one another).
  auto in_file = [&](PatchSide s) {
    s.patch += offset;
    return side_in_file(m, s);
  };
  std::vector<PatchSide> in_interface, candidates;
  for (const PatchInterface& itf : coarse.interfaces) in_interface.insert(in_interface.end(), {itf.first, itf.second});
  for (int k = 0; k < int(coarse.patches.size()); ++k)
    for (int s = 1; s <= 2 * coarse.patches[k].param_dim(); ++s)
      if (const PatchSide side{k, face_of_gismo_side(s)}; !listed(in_interface, side)) candidates.push_back(side);
  // The faces of a contact between two bodies touch where the bodies do:
  // they are never joined.  (Of several [[body]] tables, a face of this one
  // is "NAME:PATCH:SIDE".)
  const std::string prefix = body.body_name.empty() ? "" : body.body_name + ":";
  std::vector<PatchSide> contact_sides;
  for (const ContactSpec& cs : spec.contacts) {
    if (cs.master.empty()) continue;
    for (const std::string& name : {cs.face, cs.master}) {
      for (const std::string& member : spec.face_members(name)) {
        if (!member.starts_with(prefix)) continue;
        if (auto side = parametric_side(member.substr(prefix.size()), int(coarse.patches.size()),
                                        coarse.patches[0].param_dim())) {
          PatchSide local = in_file(*side);
          local.patch -= offset;
          contact_sides.push_back(local);
        }
      }
    }
  }
  std::erase_if(candidates, [&](const PatchSide& s) { return listed(contact_sides, s); });
  const CoincidentSides found = find_coincident_sides(coarse.patches, candidates);
  for (const PatchInterface& itf : found.coincide) {
    PatchInterface named{in_file(itf.first), in_file(itf.second)};
    if (named.first.patch == named.second.patch && gismo_side_of(named.second.face) < gismo_side_of(named.first.face))
      std::swap(named.first, named.second);
    if (listed(coarse.boundary, itf.first) || listed(coarse.boundary, itf.second)) {
      m.warnings.push_back(fmt::format("{}: [geometry] file {}: sides {} and {} coincide, but the file's <boundary> "
                                       "lists them: they stay apart (a slit in the body)",
                                       spec.path, body.geometry_file, side_label(named.first), side_label(named.second)));
      continue;
    }
    coarse.interfaces.push_back(itf);
    m.joined_sides.push_back(named);
  }
  for (const PatchInterface& itf : found.corners_only)
    m.warnings.push_back(fmt::format("{}: [geometry] file {}: sides {} and {} share their corners but not the points "
                                     "between them: they stay apart (a slit in the body)",
                                     spec.path, body.geometry_file, side_label(in_file(itf.first)),
                                     side_label(in_file(itf.second))));
}

}  // namespace

namespace {
// A case of [[body]] tables (one or several): faces are named through their body.
bool named_bodies(const Model& m) { return !m.parts.empty() && !m.parts.front().name.empty(); }
}  // namespace

std::optional<std::vector<PatchSide>> find_faces(const Model& m, const std::string& name) {
  if (auto it = m.faces.find(name); it != m.faces.end()) return it->second;
  // (A reoriented patch runs its first direction backwards: the file's west
  // is its east, and side_in_file swaps them back.)
  // (A patch cut for a partial face is its pieces: sides_of_pieces.)
  if (!named_bodies(m)) {
    if (auto side = parametric_side(name, m.parts.empty() ? m.body.num_patches() : m.parts.front().file_patches,
                                    m.spec.dim()))
      return sides_of_pieces(m, side_in_file(m, *side));
    return std::nullopt;
  }
  // [[body]] tables: "NAME:PATCH:SIDE" (or "NAME:SIDE" of a one-patch body).
  for (const Model::Part& part : m.parts)
    if (name.starts_with(part.name + ":"))
      if (auto side = parametric_side(name.substr(part.name.size() + 1), part.file_patches, m.spec.dim())) {
        side->patch += part.first_patch;
        return sides_of_pieces(m, side_in_file(m, *side));
      }
  return std::nullopt;
}

std::vector<std::string> face_names(const Model& m) {
  std::vector<std::string> out;
  for (const auto& [k, v] : m.faces) out.push_back(k);
  if (!named_bodies(m)) {
    for (auto& n : parametric_side_names(m.parts.empty() ? m.body.num_patches() : m.parts.front().file_patches,
                                         m.spec.dim()))
      out.push_back(std::move(n));
    return out;
  }
  for (const Model::Part& part : m.parts)
    for (auto& n : parametric_side_names(part.file_patches, m.spec.dim())) out.push_back(part.name + ":" + n);
  return out;
}

namespace {

// The diagonal of the bounding box of the faces' control points.
double face_extent(const Body& body, const std::vector<PatchSide>& faces) {
  Eigen::VectorXd lo = Eigen::VectorXd::Constant(body.space_dim(), std::numeric_limits<double>::infinity());
  Eigen::VectorXd hi = -lo;
  for (const PatchSide& s : faces)
    for (int i : body.side_control_points(s)) {
      const Eigen::VectorXd X = body.points().row(i).head(body.space_dim()).transpose();
      lo = lo.cwiseMin(X);
      hi = hi.cwiseMax(X);
    }
  return (hi - lo).norm();
}

// One body's refined patches, appended to `patches` (its interfaces, in the
// model's patch numbers, to `interfaces`), its named faces to m.faces.
void add_body(Model& m, const BodySpec& b, std::vector<NurbsPatch>& patches, std::vector<PatchInterface>& interfaces) {
  const CaseSpec& spec = m.spec;
  const int offset = int(patches.size());
  const std::string prefix = b.body_name.empty() ? "" : b.body_name + ":";
  // The coarse body: a built-in shape (one patch, with its face names) or
  // the patches of a geometry file.
  MultiPatch coarse;
  if (b.geometry_file.empty()) {
    Geometry g = body_geometry(spec, b);
    // A mirrored shape is left-handed: its first direction runs backwards,
    // its faces keep their names (as a file's patch below).
    if (orientation(g.patch, gauss_points_for(b.degree)) < 0) {
      g.patch = reversed(g.patch, 0);
      m.reoriented_patches.push_back(offset);
      for (auto& [name, sides] : g.faces)
        for (PatchSide& side : sides)
          if (side.face.direction == 0) side.face.at_end = !side.face.at_end;
    }
    coarse = MultiPatch{{g.patch}, {}, {}};
    for (const auto& [name, sides] : g.faces) {
      std::vector<PatchSide> shifted = sides;
      for (PatchSide& side : shifted) side.patch += offset;
      m.faces[prefix + name] = shifted;
    }
  } else {
    coarse = body_patches(spec, b);
    for (auto& p : coarse.patches) p = normalised(p);  // knots on [0, 1], geometry unchanged
    // A left-handed patch is not folded: run its first direction backwards
    // (faces keep the names the file gives them: find_faces).
    for (size_t k = 0; k < coarse.patches.size(); ++k) {
      if (orientation(coarse.patches[k], gauss_points_for(b.degree)) >= 0) continue;
      coarse.patches[k] = reversed(coarse.patches[k], 0);
      m.reoriented_patches.push_back(offset + int(k));
      auto flip = [k](PatchSide& side) {
        if (side.patch == int(k) && side.face.direction == 0) side.face.at_end = !side.face.at_end;
      };
      for (PatchInterface& itf : coarse.interfaces) flip(itf.first), flip(itf.second);
      for (PatchSide& side : coarse.boundary) flip(side);
    }
    join_coincident_sides(coarse, m, b, offset);
  }
  const bool several = coarse.patches.size() > 1;
  std::vector<NurbsPatch> own;
  for (size_t k = 0; k < coarse.patches.size(); ++k) {
    const std::string which = several ? fmt::format(" of patch {}", k) : "";
    const bool backwards =
        std::count(m.reoriented_patches.begin(), m.reoriented_patches.end(), offset + int(k)) > 0;
    own.push_back(refine_patch(spec, b, coarse.patches[k], b.body_name.empty() ? which : which + " of body '" + b.body_name + "'",
                               backwards));
    if (!b.geometry_file.empty()) check_patch_map(spec, b, own.back(), int(k));
  }
  for (InsertedKnots knots : make_interfaces_conform(own, coarse.interfaces)) {
    knots.patch += offset;
    m.interface_knots.push_back(knots);
  }
  const int file_patches = int(coarse.patches.size());
  cut_partial_faces(m, b, offset, file_patches, own, coarse.interfaces);
  for (const PatchInterface& itf : coarse.interfaces) {
    PatchInterface shifted = itf;
    shifted.first.patch += offset;
    shifted.second.patch += offset;
    interfaces.push_back(shifted);
  }
  m.parts.push_back({b.body_name, offset, int(own.size()), file_patches, LinearElastic{1.0, 0.0}, nullptr, b.formulation});
  for (auto& p : own) patches.push_back(std::move(p));
}

// The axisymmetric model: every patch is the section (x = r >= 0) of a
// solid of revolution about the y axis (engine/spline/nurbs_patch.hpp).
void revolve(const CaseSpec& spec, std::vector<NurbsPatch>& patches) {
  for (NurbsPatch& p : patches) try {
      p.set_revolved(true);
    } catch (const SplineError& e) {
      throw InputError(fmt::format("{}: [model] kind = \"axisymmetric\": {}: move the section to x >= 0 (x is the radius, the "
                                   "y axis the axis of revolution)",
                                   spec.where({.table = "model", .key = "kind"}), e.what()));
    }
}

// The sides of the body's patches that lie on the axis x = 0.
std::vector<PatchSide> sides_on_the_axis(const Body& body) {
  const Eigen::MatrixXd& X = body.points();
  const double tol = 1e-10 * (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
  std::vector<PatchSide> out;
  for (int k = 0; k < body.num_patches(); ++k)
    for (int d = 0; d < body.param_dim(); ++d)
      for (const bool end : {false, true}) {
        const PatchSide side{k, Face{d, end}};
        const std::vector<int> cps = body.side_control_points(side);
        if (std::all_of(cps.begin(), cps.end(), [&](int i) { return std::abs(X(i, 0)) <= tol; })) out.push_back(side);
      }
  return out;
}

}  // namespace

Model build_model(const CaseSpec& spec) {
  Model m;
  m.spec = spec;
  std::vector<NurbsPatch> patches;
  std::vector<PatchInterface> interfaces;
  const std::vector<BodySpec> bodies = spec.body_list();
  for (const BodySpec& b : bodies) add_body(m, b, patches, interfaces);
  check_partial_faces_found(m);
  if (spec.axisymmetric()) revolve(spec, patches);
  try {
    m.body = patches.size() > 1 || !interfaces.empty() ? Body(std::move(patches), interfaces)
                                                       : Body(std::move(patches.front()));
  } catch (const BodyError& e) {
    throw InputError(fmt::format("{}: [geometry] file {}: {}", spec.where({.table = "geometry", .key = "file"}),
                                 spec.geometry_file, e.what()));
  }
  double h = 0;
  for (const auto& p : m.body.patches()) h = std::max(h, largest_element_diameter(p));
  m.mesh_size = h;

  for (const auto& [name, members] : spec.face_sets) {  // [faces]: names of the user's own
    if (find_faces(m, name))
      throw InputError(fmt::format("{}: [faces] {}: the name is taken by a face of the body",
                                   spec.where({.table = "faces", .key = name}), name));
    m.faces[name] = resolve_faces(m, members, "faces");
  }

  std::vector<DirichletCondition> dc;
  for (const auto& d : spec.dirichlet)
    dc.push_back({resolve_faces(m, d.faces, "dirichlet"), d.component, d.value});
  if (spec.axisymmetric())  // a point on the axis stays on it (u_r = 0): the hoop strain u_r / r is finite
    if (std::vector<PatchSide> axis = sides_on_the_axis(m.body); !axis.empty()) dc.push_back({std::move(axis), 0, 0.0});
  for (const auto& p : spec.pressure) resolve_faces(m, p.faces, "pressure");
  for (const auto& p : spec.traction) resolve_faces(m, p.faces, "traction");
  // The same face and component held at two values: the conditions are
  // applied in order, so the last one wins; say so.
  for (size_t a = 0; a < spec.dirichlet.size(); ++a)
    for (size_t b = a + 1; b < spec.dirichlet.size(); ++b) {
      const auto &da = spec.dirichlet[a], &db = spec.dirichlet[b];
      if (da.component != db.component || da.value == db.value) continue;
      for (const auto& fa : da.faces)
        if (std::find(db.faces.begin(), db.faces.end(), fa) != db.faces.end())
          m.warnings.push_back(fmt::format("{}: [[dirichlet]] face '{}' component {} is given two values ({} and {}); "
                                           "the last one applies", spec.path, fa, "xyz"[da.component], da.value,
                                           db.value));
    }
  m.dofs = std::make_unique<DofMap>(m.body, dc);
  // The case's law: the Newton path's material, and the stress of the
  // ParaView output in both paths (small strain: the linear law's P is sigma).
  // (A CaseSpec made in code may give only E and nu.)  Several bodies: each
  // its own.
  auto law_of = [&](const BodySpec& b) -> std::unique_ptr<HyperelasticLaw> {
    const MaterialParameters& given = b.material_parameters;
    std::unique_ptr<HyperelasticLaw> law =
        make_law(b.model, std::isnan(given.E) && given.values.empty() ? MaterialParameters{b.E, b.nu, {}} : given);
    // Plane stress: the law with sigma_zz = 0, in both paths (its tangent at
    // F = I is the plane stress elasticity the small-deformation path takes).
    if (spec.plane_stress()) law = std::make_unique<PlaneStressLaw>(std::shared_ptr<const HyperelasticLaw>(std::move(law)));
    return law;
  };
  m.law = law_of(spec);
  for (size_t i = 0; i < m.parts.size(); ++i) {
    const BodySpec& b = bodies[i];
    Model::Part& part = m.parts[i];
    part.law = bodies.size() == 1 ? std::shared_ptr<const HyperelasticLaw>(m.law.get(), [](const HyperelasticLaw*) {})
                                  : std::shared_ptr<const HyperelasticLaw>(law_of(b));
    const std::string table = b.body_name.empty() ? "[material]" : fmt::format("[body.material] (body '{}')", b.body_name);
    // The small-deformation path assembles with the law's own elasticity at
    // F = I (materials/hyperelastic.hpp): a law is written once.
    try {
      part.material = small_strain_material(*part.law, m.body.space_dim());
    } catch (const MaterialError& e) {
      throw InputError(fmt::format("{}: {} {}", spec.where(b, "material", "model"), table, e.what()));
    }
    // Near nu = 0.5 the pure displacement formulation locks (too stiff a
    // body): say so rather than let a result pass unremarked.
    part.formulation = b.formulation;
    if (b.nu >= 0.499 && b.formulation == Formulation::displacement)
      m.warnings.push_back(fmt::format("{}: {} nu = {}: nearly incompressible: igac's pure displacement "
                                       "elements lock as nu nears 0.5 (the body turns too stiff; docs/benchmarks.md "
                                       "measures by how much): formulation = \"mixed\" does not",
                                       spec.path, table, b.nu));
  }
  m.material = bodies.size() == 1 ? m.parts.front().material : small_strain_material(*m.law, m.body.space_dim());

  int obstacles = -1;  // the [contact.obstacle] tables so far
  for (const ContactSpec& cs : spec.contacts) {
    const std::string at_face = spec.where({.table = "contact", .key = "face", .word = cs.face}),
                      at_master = spec.where({.table = "contact", .key = "master", .word = cs.master});
    const auto faces = find_faces(m, cs.face);
    if (!faces)
      throw InputError(fmt::format("{}: [contact] face: unknown face '{}' on a {} (known: {})", at_face, cs.face,
                                   spec.shape, fmt::join(face_names(m), ", ")));
    Model::Contact c;
    c.face_name = cs.face;
    try {
      c.face = std::make_unique<ContactFace>(m.body, *faces);
    } catch (const SplineError& e) {
      throw InputError(fmt::format("{}: [contact] face '{}': {}", at_face, cs.face, e.what()));
    }
    if (!cs.master.empty()) {  // a second deformable body (contact/mortar_gap.hpp)
      // (resolve_faces refuses an unknown face, a side inside the body, a side twice)
      const std::vector<PatchSide> master = resolve_faces(m, {cs.master}, "contact");
      for (const PatchSide& s : master)
        if (std::find(faces->begin(), faces->end(), s) != faces->end())
          throw InputError(fmt::format("{}: [contact] master '{}' and face '{}' share the side {}", at_master,
                                       cs.master, cs.face, m.body.describe(s)));
      // Self-contact: a master on the slave's own body (a C-seal closing, the
      // arms of a U pressed together).  The mortar pairs two faces whatever
      // body holds them; it cannot move the master's body apart from the
      // slave's, nor hold that body's rigid motions (their relative motion is
      // nil: check_body_is_held says so).
      const std::vector<int> part = m.body.parts();
      c.self_contact = std::any_of(master.begin(), master.end(), [&](const PatchSide& s) {
        return std::any_of(faces->begin(), faces->end(), [&](const PatchSide& f) { return part[s.patch] == part[f.patch]; });
      });
      if (c.self_contact && !cs.master_motion.empty())
        throw InputError(fmt::format("{}: [contact] master_motion moves the master's body, and master '{}' is on the "
                                     "body of face '{}' (self-contact); move the body by its [[dirichlet]] conditions",
                                     at_master, cs.master, cs.face));
      c.master_name = cs.master;
      c.friction = cs.friction;
      if (!cs.law.empty()) c.law = &interface_law(cs.law);
      c.integration = cs.integration;
      // The master body moved rigidly with its supports: its motion enters
      // the gaps (assemble_contact_operator) and, after the solve, its
      // displacement (add_master_motions).
      if (!cs.master_motion.empty()) {
        c.motion = Eigen::Map<const Eigen::VectorXd>(cs.master_motion.data(), Eigen::Index(cs.master_motion.size()));
        c.curve = cs.obstacle.curve;  // master_curve (a case with curves: ramp and hold without one)
      }
      c.master = std::make_unique<MasterSurface>(m.body, master);
      // The reports read the master as an obstacle at its reference position.
      c.obstacle = std::make_unique<MasterAsObstacle>(*c.master, cs.master);
      if (auto why = contact_cannot_happen(*c.face, *c.obstacle))
        throw InputError(fmt::format("{}: [contact] face '{}' and its master '{}': {}", at_face, cs.face, cs.master,
                                     *why));
      // Two bodies that start inside one another: a geometry placed wrong
      // (a translate forgotten), not a load.  Touching to round-off, or a
      // fit tighter than kOverlapTolerance of the face's size, is allowed.
      // An intended overlap (interference = true) is removed over the load.
      constexpr double kOverlapTolerance = 1e-3;
      const Penetration overlap = deepest_penetration(*c.face, *c.obstacle);
      const double extent = face_extent(m.body, *faces);
      c.interference = cs.interference;
      if (c.self_contact && !cs.interference && overlap.depth > kOverlapTolerance * extent)
        throw InputError(fmt::format("{}: [contact] face '{}' and its master '{}' are faces of one body that face each "
                                     "other through it ({:.3g} deep at ({:.4g})): self-contact pairs faces across a "
                                     "gap, as the arms of a U", at_face, cs.face, cs.master, overlap.depth,
                                     fmt::join(overlap.point, ", ")));
      if (!cs.interference && overlap.depth > kOverlapTolerance * extent)
        throw InputError(fmt::format("{}: [contact] face '{}' starts inside the body of its master '{}': {:.3g} deep at "
                                     "({:.4g}), more than {:g} x the face's size {:.3g} = {:.3g}; place the bodies apart "
                                     "([body.geometry] translate), or declare a fit with interference = true in this "
                                     "[contact] table", at_face, cs.face, cs.master, overlap.depth,
                                     fmt::join(overlap.point, ", "), kOverlapTolerance, extent, kOverlapTolerance * extent));
      if (c.interference && !spec.finite_strain())  // where the master stands before any load
        c.interference_overlap = (-assemble_mortar_gaps(*m.dofs, *c.face, *c.master, c.integration).g0).cwiseMax(0.0);
      m.contacts.push_back(std::move(c));
      continue;
    }
    const auto& o = cs.obstacle;
    ++obstacles;
    c.friction = cs.friction;
    c.interference = cs.interference;
    if (!cs.law.empty()) c.law = &interface_law(cs.law);
    try {
      c.obstacle = find_obstacle_type(o.type)->make(o.values);
    } catch (const std::exception& e) {
      throw InputError(fmt::format("{}: [contact.obstacle] {}",
                                   spec.where({.table = "contact.obstacle", .key = "type", .index = obstacles}),
                                   e.what()));
    }
    if (c.interference && !spec.finite_strain())  // the obstacle before its motion
      c.interference_overlap = (-assemble_weighted_gaps(*m.dofs, *c.face, *c.obstacle).g0).cwiseMax(0.0);
    if (!o.motion.empty()) {
      c.motion = Eigen::Map<const Eigen::VectorXd>(o.motion.data(), Eigen::Index(o.motion.size()));
      c.curve = o.curve;
      // Small deformation: the obstacle stands where its motion puts it.
      if (!spec.finite_strain()) c.obstacle = std::make_unique<TranslatedObstacle>(std::move(c.obstacle), c.motion);
    }
    // A Dirichlet condition on the contact face along the obstacle's normal
    // leaves the contact nothing to do there.
    const Eigen::VectorXd n = initial_contact_point(*c.face, *c.obstacle).second;
    for (const auto& d : spec.dirichlet)
      if (std::find(d.faces.begin(), d.faces.end(), cs.face) != d.faces.end() && n.size() > d.component &&
          std::abs(n[d.component]) > 0.5)
        m.warnings.push_back(fmt::format("{}: [[dirichlet]] holds component {} of the contact face '{}', along the "
                                         "obstacle's normal: the contact cannot act where it holds",
                                         spec.path, "xyz"[d.component], cs.face));
    if (auto why = contact_cannot_happen(*c.face, *c.obstacle))
      throw InputError(fmt::format("{}: [contact] face '{}' and its obstacle: {}", at_face, cs.face, *why));
    m.contacts.push_back(std::move(c));
  }
  return m;
}

namespace {
// Symmetry planes of the case: a face held along one axis only, to zero,
// whose control points all lie in one plane normal to that axis (a roller
// condition; a face also held along another axis is clamped, not a plane
// of symmetry).  The number of axes with such a plane, each halving the
// body; -1 when an axis has two parallel ones (a repeated cell, not a
// fraction of a body).
int symmetry_planes(const Model& m) {
  const Body& b = m.body;
  const double size = (b.points().colwise().maxCoeff() - b.points().colwise().minCoeff()).norm();
  using SideKey = std::tuple<int, int, bool>;  // patch, direction, at_end
  std::map<SideKey, std::set<int>> held;      // per side: the axes held
  std::map<SideKey, bool> to_zero;            // per side: every condition's value is 0
  for (const auto& d : m.spec.dirichlet)
    for (const auto& name : d.faces)
      for (const PatchSide& s : find_faces(m, name).value_or(std::vector<PatchSide>{})) {
        const SideKey k{s.patch, s.face.direction, s.face.at_end};
        held[k].insert(d.component);
        auto [it, fresh] = to_zero.emplace(k, d.value == 0);
        if (!fresh) it->second = it->second && d.value == 0;
      }
  std::set<std::pair<int, long long>> planes;
  for (const auto& [k, axes] : held) {
    if (axes.size() != 1 || !to_zero[k]) continue;
    const int c = *axes.begin();
    const auto [patch, direction, at_end] = k;
    const std::vector<int> cps = b.side_control_points(PatchSide(patch, Face{direction, at_end}));
    if (cps.empty()) continue;
    double lo = b.points()(cps[0], c), hi = lo;
    for (int i : cps) lo = std::min(lo, b.points()(i, c)), hi = std::max(hi, b.points()(i, c));
    if (hi - lo > 1e-10 * size) continue;
    planes.insert({c, std::llround(0.5 * (lo + hi) / (1e-8 * size))});
  }
  std::set<int> axes;
  for (const auto& [axis, position] : planes)
    if (!axes.insert(axis).second) return -1;
  return int(axes.size());
}
}  // namespace

std::optional<std::string> modelled_part(const Model& m) {
  if (m.spec.axisymmetric()) return "solid of revolution (forces per full circumference)";
  const bool plane = m.body.space_dim() == 2;
  // The Hertz bodies are a quarter disc and a sphere octant whatever holds
  // them: the pressure on the flat face stands for the other half.
  const std::string& shape = m.spec.shape;
  if (shape == "quarter_disc" || (plane && m.spec.reference == "hertz"))
    return "quarter (forces per unit thickness of the modelled quarter)";
  if (shape == "sphere_octant" || m.spec.reference == "hertz") return "modelled part (symmetry)";
  static const char* part[] = {"whole", "half", "quarter", "eighth"};
  const int k = symmetry_planes(m);
  if (plane) {
    if (k == 0) return "whole cross-section (forces per unit thickness)";
    if (k == 1 || k == 2) return fmt::format("{0} (forces per unit thickness of the modelled {0})", part[k]);
    return "modelled part (symmetry; forces per unit thickness)";
  }
  if (k == 0) return std::nullopt;
  if (k >= 1 && k <= 3) return fmt::format("{} (symmetry)", part[k]);
  return "modelled part (symmetry)";
}

}  // namespace igac
