// SPDX-License-Identifier: BSD-3-Clause
#include "io/gismo_xml.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <pugixml.hpp>
#include <set>
#include <sstream>

#include "io/case_file.hpp"
#include "io/input_file.hpp"
#include "io/json_out.hpp"

namespace igac {
namespace {

// Corners of two sides that meet agree to round-off relative to the body's size.
constexpr double kCornerTolerance = 1e-10;

// ---------------------------------------------------------------- reading



// Where a node sits in the file (for messages), and the one-line errors.
class Source {
 public:
  Source(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {}
  const std::string& text() const { return text_; }
  int line_at(std::ptrdiff_t offset) const {
    if (offset < 0) return 0;
    offset = std::min<std::ptrdiff_t>(offset, std::ptrdiff_t(text_.size()));
    return 1 + int(std::count(text_.begin(), text_.begin() + offset, '\n'));
  }
  [[noreturn]] void fail(pugi::xml_node node, const std::string& element, const std::string& reason) const {
    const int line = node ? line_at(node.offset_debug()) : 0;
    if (line > 0) throw InputError(fmt::format("{}:{}: {}: {}", path_, line, element, reason));
    throw InputError(fmt::format("{}: {}: {}", path_, element, reason));
  }

 private:
  std::string path_, text_;
};

// Whitespace-separated tokens of an element's text.
std::vector<std::string_view> tokens(const char* s) {
  std::vector<std::string_view> out;
  std::string_view v(s);
  size_t i = 0;
  while (i < v.size()) {
    while (i < v.size() && std::isspace(static_cast<unsigned char>(v[i]))) ++i;
    size_t j = i;
    while (j < v.size() && !std::isspace(static_cast<unsigned char>(v[j]))) ++j;
    if (j > i) out.push_back(v.substr(i, j - i));
    i = j;
  }
  return out;
}

void check_text_format(const Source& src, pugi::xml_node node, const std::string& element) {
  const std::string f = node.attribute("format").value();
  std::string lower = f;
  for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (!f.empty() && lower != "ascii")
    src.fail(node, element, fmt::format("format=\"{}\" is not supported: igac reads numbers written as text", f));
}

std::vector<double> numbers(const Source& src, pugi::xml_node node, const std::string& element) {
  check_text_format(src, node, element);
  std::vector<double> out;
  for (std::string_view t : tokens(node.child_value())) {
    std::string_view u = t.size() > 1 && t[0] == '+' ? t.substr(1) : t;
    double x = 0;
    auto [end, ec] = std::from_chars(u.data(), u.data() + u.size(), x);
    if (ec != std::errc() || end != u.data() + u.size())
      src.fail(node, element, fmt::format("\"{}\" (entry {}) is not a number", t, out.size()));
    if (!std::isfinite(x)) src.fail(node, element, fmt::format("entry {} is not finite ({})", out.size(), t));
    out.push_back(x);
  }
  return out;
}

std::vector<long> integers(const Source& src, pugi::xml_node node, const std::string& element) {
  std::vector<long> out;
  for (std::string_view t : tokens(node.child_value())) {
    long x = 0;
    auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (ec != std::errc() || end != t.data() + t.size())
      src.fail(node, element, fmt::format("\"{}\" (entry {}) is not an integer", t, out.size()));
    out.push_back(x);
  }
  return out;
}

// An integer attribute; nullopt when absent.
std::optional<long> int_attribute(const Source& src, pugi::xml_node node, const char* name, const std::string& element) {
  pugi::xml_attribute a = node.attribute(name);
  if (!a) return std::nullopt;
  std::string_view t = a.value();
  long x = 0;
  auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
  if (t.empty() || ec != std::errc() || end != t.data() + t.size())
    src.fail(node, element, fmt::format("{}=\"{}\" is not an integer", name, t));
  return x;
}

std::string geometry_name(pugi::xml_node g, int position) {
  if (g.attribute("id")) return fmt::format("<Geometry id=\"{}\">", g.attribute("id").value());
  return fmt::format("<Geometry> (number {} in the file)", position);
}

// The geometry types igac reads: parametric dimension and rationality.
struct GeometryType {
  int dim;
  bool rational;
};
const std::map<std::string, GeometryType>& geometry_types() {
  static const std::map<std::string, GeometryType> t = {{"TensorBSpline2", {2, false}},
                                                        {"TensorNurbs2", {2, true}},
                                                        {"TensorBSpline3", {3, false}},
                                                        {"TensorNurbs3", {3, true}}};
  return t;
}

NurbsPatch read_geometry(const Source& src, pugi::xml_node g, const std::string& name) {
  const std::string type = g.attribute("type").value();
  if (type.empty()) src.fail(g, name, "no type attribute (TensorBSpline2, TensorNurbs2, TensorBSpline3 or TensorNurbs3)");
  auto it = geometry_types().find(type);
  if (it == geometry_types().end())
    src.fail(g, name,
             fmt::format("unknown geometry type \"{}\" (igac reads TensorBSpline2, TensorNurbs2, TensorBSpline3, "
                         "TensorNurbs3)", type));
  const int d = it->second.dim;
  const bool rational = it->second.rational;

  pugi::xml_node basis = g.child("Basis");
  if (!basis) src.fail(g, name, "no <Basis>");
  pugi::xml_node tensor = basis, weights_node;
  const std::string nurbs_basis = fmt::format("TensorNurbsBasis{}", d);
  const std::string bspline_basis = fmt::format("TensorBSplineBasis{}", d);
  if (rational) {
    if (basis.attribute("type").value() != nurbs_basis)
      src.fail(basis, name + " <Basis>",
               fmt::format("type \"{}\" where a {} needs \"{}\"", basis.attribute("type").value(), type, nurbs_basis));
    tensor = basis.child("Basis");
    weights_node = basis.child("weights");
    if (!tensor) src.fail(basis, name + " <Basis>", fmt::format("no inner <Basis type=\"{}\">", bspline_basis));
    if (!weights_node) src.fail(basis, name + " <Basis>", "no <weights>");
  }
  if (tensor.attribute("type").value() != bspline_basis)
    src.fail(tensor, name + " <Basis>",
             fmt::format("type \"{}\" where a {} needs \"{}\"", tensor.attribute("type").value(), type, bspline_basis));

  std::vector<KnotVector> knots(d);
  std::vector<bool> seen(d, false);
  int count = 0;
  for (pugi::xml_node b : tensor.children("Basis")) {
    const std::string where = fmt::format("{} <Basis type=\"BSplineBasis\"> (number {})", name, count);
    if (std::string(b.attribute("type").value()) != "BSplineBasis")
      src.fail(b, where, fmt::format("type \"{}\" where a tensor basis needs \"BSplineBasis\"", b.attribute("type").value()));
    const long index = int_attribute(src, b, "index", where).value_or(count);
    if (index < 0 || index >= d) src.fail(b, where, fmt::format("index {} is not a direction of a {}D patch (0..{})", index, d, d - 1));
    if (seen[index]) src.fail(b, where, fmt::format("a second basis for direction {}", index));
    seen[index] = true;
    ++count;
    const std::string kv_name = fmt::format("{} <KnotVector> of direction {}", name, index);
    pugi::xml_node kv = b.child("KnotVector");
    if (!kv) src.fail(b, where, "no <KnotVector>");
    const auto degree = int_attribute(src, kv, "degree", kv_name);
    if (!degree) src.fail(kv, kv_name, "no degree attribute");
    if (*degree < 1 || *degree > 20) src.fail(kv, kv_name, fmt::format("degree {} must lie in 1..20", *degree));
    try {
      knots[index] = KnotVector(int(*degree), numbers(src, kv, kv_name));
    } catch (const SplineError& e) {
      src.fail(kv, kv_name, e.what());
    }
  }
  if (count != d) src.fail(tensor, name + " <Basis>", fmt::format("{} univariate bases where a {}D patch needs {}", count, d, d));

  int n = 1;
  std::string sizes;
  for (int k = 0; k < d; ++k) {
    n *= knots[k].num_basis();
    sizes += (k ? " x " : "") + std::to_string(knots[k].num_basis());
  }

  pugi::xml_node coefs = g.child("coefs");
  const std::string coefs_name = name + " <coefs>";
  if (!coefs) src.fail(g, name, "no <coefs>");
  const auto geo_dim = int_attribute(src, coefs, "geoDim", coefs_name);
  if (!geo_dim) src.fail(coefs, coefs_name, "no geoDim attribute");
  // A planar patch may be stored in 3D with z = 0 (as G+Smo's planar files
  // often are): read in the plane when every z is 0 to round-off.
  const bool planar_in_3d = d == 2 && *geo_dim == 3;
  if (*geo_dim != d && !planar_in_3d)
    src.fail(coefs, coefs_name,
             fmt::format("geoDim {} differs from the parametric dimension {} of a {}: igac reads solid bodies "
                         "(a 2D patch in the plane, a 3D patch in space)", *geo_dim, d, type));
  const int gd = *geo_dim;
  const std::vector<double> c = numbers(src, coefs, coefs_name);
  if (int(c.size()) != n * gd)
    src.fail(coefs, coefs_name,
             fmt::format("{} numbers where {} control points (the basis sizes {}) of geoDim {} need {}", c.size(), n,
                         sizes, gd, n * gd));
  if (auto rows = int_attribute(src, coefs, "rows", coefs_name); rows && *rows != n)
    src.fail(coefs, coefs_name, fmt::format("rows=\"{}\" where the basis has {} functions", *rows, n));
  if (auto cols = int_attribute(src, coefs, "cols", coefs_name); cols && *cols != gd)
    src.fail(coefs, coefs_name, fmt::format("cols=\"{}\" differs from geoDim {}", *cols, gd));
  Eigen::MatrixXd P(n, d);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < d; ++k) P(i, k) = c[size_t(i) * gd + k];
  // Beyond 1e100 the Jacobians and strains overflow (a fold would be
  // reported where the numbers ran out): the same range as a case's lengths.
  for (int i = 0; i < n; ++i)
    if (P.row(i).cwiseAbs().maxCoeff() > 1e100)
      src.fail(coefs, coefs_name, fmt::format("control point {} has a coordinate beyond 1e100 ({:g}), where the "
                                              "computation overflows; choose units that bring it near 1",
                                              i, P.row(i).cwiseAbs().maxCoeff()));
  if (planar_in_3d) {
    const double extent = std::max(1e-300, P.cwiseAbs().maxCoeff());
    for (int i = 0; i < n; ++i)
      if (const double z = c[size_t(i) * gd + 2]; !(std::abs(z) <= 1e-12 * extent))
        src.fail(coefs, coefs_name,
                 fmt::format("a 2D patch stored in 3D whose control point {} has z = {:g}: igac reads a planar "
                             "body only in the plane z = 0", i, z));
  }

  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  if (rational) {
    const std::string wname = name + " <weights>";
    const std::vector<double> wv = numbers(src, weights_node, wname);
    if (int(wv.size()) != n)
      src.fail(weights_node, wname,
               fmt::format("{} weights where the basis (sizes {}) has {} functions", wv.size(), sizes, n));
    if (auto rows = int_attribute(src, weights_node, "rows", wname); rows && *rows != n)
      src.fail(weights_node, wname, fmt::format("rows=\"{}\" where the basis has {} functions", *rows, n));
    if (auto cols = int_attribute(src, weights_node, "cols", wname); cols && *cols != 1)
      src.fail(weights_node, wname, fmt::format("cols=\"{}\": weights are one column", *cols));
    for (int i = 0; i < n; ++i) {
      if (!(wv[i] > 0)) src.fail(weights_node, wname, fmt::format("weight {} of control point {} is not positive", wv[i], i));
      w[i] = wv[i];
    }
    // Only the weights' ratios matter; beyond 1e100 apart they overflow.
    if (w.maxCoeff() > 1e100 * w.minCoeff())
      src.fail(weights_node, wname, fmt::format("the weights range from {:g} to {:g}, more than 1e100 apart, where the "
                                                "rational basis overflows", w.minCoeff(), w.maxCoeff()));
  }
  try {
    return NurbsPatch(std::move(knots), std::move(P), std::move(w));
  } catch (const SplineError& e) {
    src.fail(g, name, e.what());
  }
}

// The corners of two sides of an interface coincide (open knot vectors
// interpolate there), to round-off of the body's size.  The engine matches
// the sides' control points after refinement; this catches a wrong patch or
// side number at once, with the file's line.
void check_sides_meet(const Source& src, pugi::xml_node node, const std::string& element, const MultiPatch& body,
                      const PatchInterface& pi, const std::string& what) {
  const NurbsPatch& a = body.patches[pi.first.patch];
  const NurbsPatch& b = body.patches[pi.second.patch];
  double extent = 0;
  for (const NurbsPatch* p : {&a, &b})
    extent = std::max(extent, (p->points().colwise().maxCoeff() - p->points().colwise().minCoeff()).norm());
  const int nt = a.param_dim() - 1;
  for (int ca = 0; ca < (1 << nt); ++ca) {
    std::vector<int> bits_a(nt);
    for (int k = 0; k < nt; ++k) bits_a[k] = (ca >> k) & 1;
    const Eigen::VectorXd x = face_corner(a, pi.first.face, bits_a);
    bool found = false;
    for (int cb = 0; cb < (1 << nt) && !found; ++cb) {
      std::vector<int> bits_b(nt);
      for (int k = 0; k < nt; ++k) bits_b[k] = (cb >> k) & 1;
      found = (face_corner(b, pi.second.face, bits_b) - x).norm() <= kCornerTolerance * extent;
    }
    if (!found)
      src.fail(node, element,
               fmt::format("{}: side {} ({}) of patch {} and side {} ({}) of patch {} do not meet: the corner ({:.6g}) "
                           "of the first is no corner of the second (without <interfaces>, igac joins the sides that coincide)", what, gismo_side_of(pi.first.face),
                           gismo_side_name(gismo_side_of(pi.first.face)), pi.first.patch, gismo_side_of(pi.second.face),
                           gismo_side_name(gismo_side_of(pi.second.face)), pi.second.patch, fmt::join(x, ", ")));
  }
}

// Reads the <MultiPatch> topology into `body` (whose patches are already read
// in the order of `ids`).
void read_topology(const Source& src, pugi::xml_node mp, const std::map<long, int>& index_of_id, int dim,
                   MultiPatch& body) {
  const int n_sides = 2 * dim;
  std::string id_list;
  for (const auto& [id, idx] : index_of_id) id_list += (id_list.empty() ? "" : ", ") + std::to_string(id);
  auto patch_of = [&](pugi::xml_node node, const std::string& element, long id, const std::string& what) {
    auto it = index_of_id.find(id);
    if (it == index_of_id.end())
      src.fail(node, element, fmt::format("{}: patch {} does not exist (the <patches> have ids {})", what, id, id_list));
    return it->second;
  };
  auto side_of = [&](pugi::xml_node node, const std::string& element, long side, const std::string& what) {
    if (side < 1 || side > n_sides)
      src.fail(node, element, fmt::format("{}: side {} is not a side of a {}D patch (1..{})", what, side, dim, n_sides));
    return face_of_gismo_side(int(side));
  };
  std::set<std::pair<int, int>> used;  // (patch, side)
  auto use = [&](pugi::xml_node node, const std::string& element, const PatchSide& s, long id, const std::string& what) {
    if (!used.insert({s.patch, gismo_side_of(s.face)}).second)
      src.fail(node, element,
               fmt::format("{}: side {} ({}) of patch {} is already listed in an interface or the boundary", what,
                           gismo_side_of(s.face), gismo_side_name(gismo_side_of(s.face)), id));
  };

  // G+Smo writes an interface as: patch side patch side, a direction map of
  // `dim` and `dim` orientation flags.  Older files give patch side patch
  // side and dim - 1 orientation flags (five numbers in 2D).  igac matches
  // the sides geometrically, so only the first four numbers matter; a list
  // is read in the form whose every group makes sense.  (A list both forms
  // read would need 40 integers in 2D, 30 in 3D, each group plausible both
  // ways; a random search of 2M such lists found none, and the current form
  // is then taken.)
  const int group = 4 + 2 * dim, old_group = 4 + dim - 1;
  auto fits = [&](const std::vector<long>& v, int size) {
    if (v.empty() || v.size() % size != 0) return false;
    for (size_t g = 0; g < v.size(); g += size) {
      for (int k : {0, 2})
        if (!index_of_id.count(v[g + k]) || v[g + k + 1] < 1 || v[g + k + 1] > n_sides) return false;
      const int flags = size == group ? dim : dim - 1;
      for (int k = 0; k < flags; ++k)
        if (v[g + size - flags + k] != 0 && v[g + size - flags + k] != 1) return false;
      if (size == group) {
        std::vector<bool> hit(dim, false);
        for (int k = 0; k < dim; ++k) {
          if (v[g + 4 + k] < 0 || v[g + 4 + k] >= dim || hit[v[g + 4 + k]]) return false;
          hit[v[g + 4 + k]] = true;
        }
        if (v[g + 4 + (v[g + 1] - 1) / 2] != (v[g + 3] - 1) / 2) return false;
      }
    }
    return true;
  };
  int k_interface = 0;
  for (pugi::xml_node node : mp.children("interfaces")) {
    const std::string element = "<MultiPatch> <interfaces>";
    const std::vector<long> v = integers(src, node, element);
    const bool now = fits(v, group), older = fits(v, old_group);
    // (A list only the older form divides is read in it, for its errors.)
    if ((older && !now) || (!now && v.size() % group != 0 && !v.empty() && v.size() % old_group == 0)) {
      for (size_t g = 0; g < v.size(); g += old_group, ++k_interface) {
        const std::string what = fmt::format("interface {}", k_interface);
        for (int k = 4; k < old_group; ++k)
          if (v[g + k] != 0 && v[g + k] != 1)
            src.fail(node, element, fmt::format("{}: orientation flag {} is not 0 or 1", what, v[g + k]));
        PatchInterface pi;
        pi.first = PatchSide{patch_of(node, element, v[g], what), side_of(node, element, v[g + 1], what)};
        pi.second = PatchSide{patch_of(node, element, v[g + 2], what), side_of(node, element, v[g + 3], what)};
        use(node, element, pi.first, v[g], what);
        use(node, element, pi.second, v[g + 2], what);
        check_sides_meet(src, node, element, body, pi, what);
        body.interfaces.push_back(pi);
      }
      continue;
    }
    if (v.size() % group != 0)
      src.fail(node, element,
               fmt::format("{} integers do not make whole interfaces of {} (patch side patch side, a direction map "
                           "of {} and {} orientation flags), nor of the older form's {}", v.size(), group, dim, dim,
                           old_group));
    for (size_t g = 0; g < v.size(); g += group, ++k_interface) {
      const std::string what = fmt::format("interface {}", k_interface);
      PatchInterface pi;
      pi.first = PatchSide{patch_of(node, element, v[g], what), side_of(node, element, v[g + 1], what)};
      pi.second = PatchSide{patch_of(node, element, v[g + 2], what), side_of(node, element, v[g + 3], what)};
      use(node, element, pi.first, v[g], what);
      use(node, element, pi.second, v[g + 2], what);
      // The direction map must be a permutation sending the first side's
      // normal direction to the second's; the flags are 0 or 1.
      std::vector<bool> hit(dim, false);
      for (int k = 0; k < dim; ++k) {
        const long m = v[g + 4 + k];
        if (m < 0 || m >= dim || hit[m])
          src.fail(node, element, fmt::format("{}: the direction map {} is not a permutation of 0..{}", what,
                                              fmt::join(v.begin() + g + 4, v.begin() + g + 4 + dim, " "), dim - 1));
        hit[m] = true;
        const long flag = v[g + 4 + dim + k];
        if (flag != 0 && flag != 1)
          src.fail(node, element, fmt::format("{}: orientation flag {} is not 0 or 1", what, flag));
      }
      if (v[g + 4 + pi.first.face.direction] != pi.second.face.direction)
        src.fail(node, element,
                 fmt::format("{}: the direction map sends the normal direction {} of side {} to {}, not to the normal "
                             "direction {} of side {}", what, pi.first.face.direction, v[g + 1],
                             v[g + 4 + pi.first.face.direction], pi.second.face.direction, v[g + 3]));
      check_sides_meet(src, node, element, body, pi, what);
      body.interfaces.push_back(pi);
    }
  }
  int k_boundary = 0;
  for (pugi::xml_node node : mp.children("boundary")) {
    const std::string element = "<MultiPatch> <boundary>";
    const std::vector<long> v = integers(src, node, element);
    if (v.size() % 2 != 0) src.fail(node, element, fmt::format("{} integers do not make whole (patch, side) pairs", v.size()));
    for (size_t g = 0; g < v.size(); g += 2, ++k_boundary) {
      const std::string what = fmt::format("boundary entry {}", k_boundary);
      PatchSide s{patch_of(node, element, v[g], what), side_of(node, element, v[g + 1], what)};
      use(node, element, s, v[g], what);
      body.boundary.push_back(s);
    }
  }
}

}  // namespace


MultiPatch read_gismo_xml(const std::string& path) {
  // (io/input_file.hpp: a FIFO would be read forever, /dev/zero until the memory runs out)
  const Source src(path, read_input_file(path, kGeometryFile));

  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer(src.text().data(), src.text().size());
  if (!parsed)
    throw InputError(fmt::format("{}:{}: malformed XML: {}", path, src.line_at(parsed.offset), parsed.description()));
  pugi::xml_node root = doc.child("xml");
  if (!root) {
    pugi::xml_node top = doc.document_element();
    src.fail(top, fmt::format("<{}>", top.name()), "the root element of a G+Smo file is <xml>");
  }

  std::vector<pugi::xml_node> multipatches;
  for (pugi::xml_node m : root.children("MultiPatch")) multipatches.push_back(m);
  if (multipatches.size() > 1) src.fail(multipatches[1], "<MultiPatch>", "a second <MultiPatch>: igac reads one body per file");
  // Ids are references from the <MultiPatch>: without one they name nothing
  // (G+Smo's own volumes/cube.xml gives seven patches the same id).
  std::vector<pugi::xml_node> geometries;
  std::map<long, pugi::xml_node> by_id;
  for (pugi::xml_node g : root.children("Geometry")) {
    const std::string name = geometry_name(g, int(geometries.size()));
    if (auto id = int_attribute(src, g, "id", name); id && !multipatches.empty()) {
      if (by_id.count(*id)) src.fail(g, name, fmt::format("a second <Geometry> with id {}", *id));
      by_id[*id] = g;
    }
    geometries.push_back(g);
  }

  MultiPatch body;
  if (multipatches.empty()) {
    // Patches without a topology: the engine joins the sides that coincide
    // (engine/geometry/topology.hpp), as G+Smo's computeTopology does.
    if (geometries.empty()) {
      std::string held;
      for (pugi::xml_node c : root.children())
        if (c.type() == pugi::node_element && held.find(std::string("<") + c.name() + ">") == std::string::npos)
          held += fmt::format("{}<{}>", held.empty() ? "" : ", ", c.name());
      src.fail(root, "<xml>", fmt::format("no <Geometry> and no <MultiPatch>: the file describes no body{}",
                                          held.empty() ? std::string() : " igac reads (it holds " + held +
                                          "; igac reads tensor-product NURBS patches, not trimmed or curve-bounded "
                                          "domains)"));
    }
    for (size_t k = 0; k < geometries.size(); ++k) {
      const std::string name = geometry_name(geometries[k], int(k));
      body.patches.push_back(read_geometry(src, geometries[k], name));
      if (body.patches.back().param_dim() != body.patches.front().param_dim())
        src.fail(geometries[k], name, fmt::format("a {}D patch among {}D patches", body.patches.back().param_dim(),
                                                  body.patches.front().param_dim()));
    }
    return body;
  }

  pugi::xml_node mp = multipatches[0];
  const auto par_dim = int_attribute(src, mp, "parDim", "<MultiPatch>");
  pugi::xml_node patches = mp.child("patches");
  if (!patches) src.fail(mp, "<MultiPatch>", "no <patches>");
  const std::string ptype = patches.attribute("type").value();
  const std::vector<long> listed = integers(src, patches, "<MultiPatch> <patches>");
  std::vector<long> ids;
  if (ptype == "id_range") {
    if (listed.size() != 2 || listed[0] > listed[1])
      src.fail(patches, "<MultiPatch> <patches>", "type=\"id_range\" needs two ids, first <= last");
    if (listed[1] - listed[0] >= 100000) src.fail(patches, "<MultiPatch> <patches>", "more than 100000 patches");
    for (long id = listed[0]; id <= listed[1]; ++id) ids.push_back(id);
  } else if (ptype == "id_index") {
    ids = listed;
    if (ids.empty()) src.fail(patches, "<MultiPatch> <patches>", "no patch ids");
  } else {
    src.fail(patches, "<MultiPatch> <patches>", fmt::format("type \"{}\" is neither \"id_range\" nor \"id_index\"", ptype));
  }
  std::map<long, int> index_of_id;
  for (long id : ids) {
    auto it = by_id.find(id);
    if (it == by_id.end()) src.fail(patches, "<MultiPatch> <patches>", fmt::format("no <Geometry> with id {}", id));
    if (!index_of_id.emplace(id, int(body.patches.size())).second)
      src.fail(patches, "<MultiPatch> <patches>", fmt::format("patch id {} is listed twice", id));
    body.patches.push_back(read_geometry(src, it->second, geometry_name(it->second, 0)));
    const int d = body.patches.back().param_dim();
    if (par_dim && *par_dim != d)
      src.fail(it->second, geometry_name(it->second, 0),
               fmt::format("a {}D patch in a <MultiPatch parDim=\"{}\">", d, *par_dim));
    if (d != body.patches.front().param_dim())
      src.fail(it->second, geometry_name(it->second, 0),
               fmt::format("a {}D patch among {}D patches", d, body.patches.front().param_dim()));
  }
  read_topology(src, mp, index_of_id, body.patches.front().param_dim(), body);
  return body;
}

// ---------------------------------------------------------------- writing

namespace {

std::string join_numbers(const std::vector<double>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += fmt::format("{}{}", i ? " " : "", v[i]);
  return s;
}

// G+Smo's direction map and orientation flags of an interface (gsBoundary.h
// boundaryInterface): direction i of the first patch runs along direction
// dir_map[i] of the second, in the same sense when flag[i] = 1.  Found by
// matching the sides' corner control points (open knot vectors interpolate
// there).
std::pair<std::vector<int>, std::vector<int>> interface_map(const std::string& path, const MultiPatch& body,
                                                            const PatchInterface& pi, int index, double tol) {
  const NurbsPatch& a = body.patches[pi.first.patch];
  const NurbsPatch& b = body.patches[pi.second.patch];
  const int dim = a.param_dim();
  const Face fa = pi.first.face, fb = pi.second.face;
  const auto ta = face_directions(dim, fa), tb = face_directions(dim, fb);
  const int nt = dim - 1, n_corners = 1 << nt;
  auto bits_of = [&](int c) {
    std::vector<int> bits(nt);
    for (int k = 0; k < nt; ++k) bits[k] = (c >> k) & 1;
    return bits;
  };
  auto match = [&](const std::vector<int>& bits_a) -> std::vector<int> {
    const Eigen::VectorXd x = face_corner(a, fa, bits_a);
    for (int c = 0; c < n_corners; ++c)
      if ((face_corner(b, fb, bits_of(c)) - x).norm() <= tol) return bits_of(c);
    throw InputError(fmt::format("{}: interface {}: side {} of patch {} and side {} of patch {} do not meet at "
                                 "their corners", path, index, gismo_side_of(fa), pi.first.patch, gismo_side_of(fb), pi.second.patch));
  };
  std::vector<int> dir_map(dim), flag(dim);
  dir_map[fa.direction] = fb.direction;
  flag[fa.direction] = fa.at_end != fb.at_end;
  const std::vector<int> ref = match(std::vector<int>(nt, 0));
  for (int k = 0; k < nt; ++k) {
    std::vector<int> bits(nt, 0);
    bits[k] = 1;
    const std::vector<int> m = match(bits);
    int moved = -1;
    for (int j = 0; j < nt; ++j)
      if (m[j] != ref[j]) moved = moved == -1 ? j : -2;
    if (moved < 0)
      throw InputError(fmt::format("{}: interface {}: side {} of patch {} is degenerate (its corners coincide), so "
                                   "its orientation is undefined", path, index, gismo_side_of(fa), pi.first.patch));
    dir_map[ta[k]] = tb[moved];
    flag[ta[k]] = ref[moved] == 0;
  }
  return {dir_map, flag};
}

}  // namespace

void write_gismo_xml(const MultiPatch& body, const std::string& path) {
  if (body.patches.empty()) throw InputError(fmt::format("{}: no patches to write", path));
  const int dim = body.patches.front().param_dim();
  double extent = 0;
  for (size_t i = 0; i < body.patches.size(); ++i) {
    const NurbsPatch& p = body.patches[i];
    if (p.param_dim() != dim || p.space_dim() != dim)
      throw InputError(fmt::format("{}: patch {} is a {}D patch in {}D where the body is {}D", path, i, p.param_dim(),
                                   p.space_dim(), dim));
    extent = std::max(extent, (p.points().colwise().maxCoeff() - p.points().colwise().minCoeff()).norm());
  }
  const int n = int(body.patches.size());
  for (const auto& pi : body.interfaces)
    for (const PatchSide& s : {pi.first, pi.second})
      if (s.patch < 0 || s.patch >= n) throw InputError(fmt::format("{}: an interface names patch {} of {}", path, s.patch, n));
  for (const PatchSide& s : body.boundary)
    if (s.patch < 0 || s.patch >= n) throw InputError(fmt::format("{}: the boundary names patch {} of {}", path, s.patch, n));
  {  // each side at most once: the reader rejects a file that lists one twice
    std::set<std::pair<int, int>> seen;
    auto once = [&](const PatchSide& s) {
      if (!seen.insert({s.patch, gismo_side_of(s.face)}).second)
        throw InputError(fmt::format("{}: side {} of patch {} is listed twice in the interfaces and boundary", path,
                                     gismo_side_of(s.face), s.patch));
    };
    for (const auto& pi : body.interfaces) {
      once(pi.first);
      once(pi.second);
    }
    for (const PatchSide& s : body.boundary) once(s);
  }

  pugi::xml_document doc;
  pugi::xml_node decl = doc.append_child(pugi::node_declaration);
  decl.append_attribute("version") = "1.0";
  decl.append_attribute("encoding") = "UTF-8";
  doc.append_child(pugi::node_comment).set_value(" written by igac (G+Smo XML geometry) ");
  pugi::xml_node root = doc.append_child("xml");

  for (int i = 0; i < n; ++i) {
    const NurbsPatch& p = body.patches[i];
    const bool rational = (p.weights().array() != 1.0).any();
    pugi::xml_node g = root.append_child("Geometry");
    g.append_attribute("type") = fmt::format("{}{}", rational ? "TensorNurbs" : "TensorBSpline", dim).c_str();
    g.append_attribute("id") = i;
    pugi::xml_node basis = g.append_child("Basis");
    pugi::xml_node tensor = basis;
    if (rational) {
      basis.append_attribute("type") = fmt::format("TensorNurbsBasis{}", dim).c_str();
      tensor = basis.append_child("Basis");
    }
    tensor.append_attribute("type") = fmt::format("TensorBSplineBasis{}", dim).c_str();
    for (int d = 0; d < dim; ++d) {
      pugi::xml_node b = tensor.append_child("Basis");
      b.append_attribute("type") = "BSplineBasis";
      b.append_attribute("index") = d;
      pugi::xml_node kv = b.append_child("KnotVector");
      kv.append_attribute("degree") = p.degree(d);
      kv.text() = join_numbers(p.knots(d).knots()).c_str();
    }
    if (rational) {
      std::vector<double> w(p.weights().data(), p.weights().data() + p.weights().size());
      basis.append_child("weights").text() = join_numbers(w).c_str();
    }
    std::string rows = "\n";
    for (int a = 0; a < p.num_control_points(); ++a) {
      std::vector<double> r(dim);
      for (int k = 0; k < dim; ++k) r[k] = p.points()(a, k);
      rows += join_numbers(r) + "\n";
    }
    pugi::xml_node coefs = g.append_child("coefs");
    coefs.append_attribute("geoDim") = dim;
    coefs.text() = rows.c_str();
  }

  pugi::xml_node mp = root.append_child("MultiPatch");
  mp.append_attribute("parDim") = dim;
  mp.append_attribute("id") = n;
  pugi::xml_node patches = mp.append_child("patches");
  patches.append_attribute("type") = "id_range";
  patches.text() = fmt::format("0 {}", n - 1).c_str();
  const double tol = kCornerTolerance * std::max(extent, 1e-300);
  std::set<std::pair<int, int>> in_interface;
  if (!body.interfaces.empty()) {
    std::string text = "\n";
    for (size_t k = 0; k < body.interfaces.size(); ++k) {
      const PatchInterface& pi = body.interfaces[k];
      const auto [dir_map, flag] = interface_map(path, body, pi, int(k), tol);
      text += fmt::format("{} {} {} {} {} {}\n", pi.first.patch, gismo_side_of(pi.first.face), pi.second.patch,
                          gismo_side_of(pi.second.face), fmt::join(dir_map, " "), fmt::join(flag, " "));
      in_interface.insert({pi.first.patch, gismo_side_of(pi.first.face)});
      in_interface.insert({pi.second.patch, gismo_side_of(pi.second.face)});
    }
    mp.append_child("interfaces").text() = text.c_str();
  }
  std::vector<PatchSide> boundary = body.boundary;
  if (boundary.empty())  // every side not in an interface (multipatch.hpp)
    for (int i = 0; i < n; ++i)
      for (int s = 1; s <= 2 * dim; ++s)
        if (!in_interface.count({i, s})) boundary.push_back(PatchSide{i, face_of_gismo_side(s)});
  std::string text = "\n";
  for (const PatchSide& s : boundary) text += fmt::format("{} {}\n", s.patch, gismo_side_of(s.face));
  mp.append_child("boundary").text() = text.c_str();

  std::ostringstream out;
  doc.save(out, " ", pugi::format_default, pugi::encoding_utf8);
  try {
    write_file_atomically(path, out.str());
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: cannot write the geometry file ({})", path, e.what()));
  }
}

}  // namespace igac
