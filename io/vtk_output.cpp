// SPDX-License-Identifier: BSD-3-Clause
#include "io/vtk_output.hpp"

#include <cerrno>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <stdexcept>
#include <unistd.h>

#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDoubleArray.h>
#include <vtkHigherOrderHexahedron.h>
#include <vtkHigherOrderQuadrilateral.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "model/field_recovery.hpp"
#include "io/json_out.hpp"

namespace igac {

// ---------------------------------------------------------------- VTK grids

namespace {

// Position in VTK's Bezier cell ordering (corners, edges, faces, interior;
// vtkHigherOrder*::PointIndexFromIJK) of every lexicographic local point.
std::vector<int> vtk_ordering(const BezierMesh& m) {
  std::vector<int> pos(m.num_local());
  const int p0 = m.degree(0), p1 = m.degree(1), p2 = m.degree(2);
  for (int c = 0; c <= p2; ++c)
    for (int b = 0; b <= p1; ++b)
      for (int a = 0; a <= p0; ++a) {
        const int l = m.local_index(a, b, c);
        if (m.param_dim() == 1) {
          pos[l] = a == 0 ? 0 : a == p0 ? 1 : a + 1;
        } else if (m.param_dim() == 2) {
          const int order[2] = {p0, p1};
          pos[l] = vtkHigherOrderQuadrilateral::PointIndexFromIJK(a, b, order);
        } else {
          const int order[3] = {p0, p1, p2};
          pos[l] = vtkHigherOrderHexahedron::PointIndexFromIJK(a, b, c, order);
        }
      }
  return pos;
}

int bezier_cell_type(int param_dim) {
  return param_dim == 1 ? VTK_BEZIER_CURVE : param_dim == 2 ? VTK_BEZIER_QUADRILATERAL : VTK_BEZIER_HEXAHEDRON;
}

vtkSmartPointer<vtkDoubleArray> make_array(const char* name, int components, vtkIdType tuples) {
  auto a = vtkSmartPointer<vtkDoubleArray>::New();
  a->SetName(name);
  a->SetNumberOfComponents(components);
  a->SetNumberOfTuples(tuples);
  return a;
}

// Points, cells, RationalWeights, HigherOrderDegrees and "displacement"
// (field 0, padded to 3 components) of an extracted mesh.
vtkSmartPointer<vtkUnstructuredGrid> bezier_grid(const BezierMesh& m) {
  const int nl = m.num_local(), np = m.num_points(), sd = m.space_dim();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(np);
  auto weights = make_array("RationalWeights", 1, np);
  auto disp = make_array("displacement", 3, np);
  auto degrees = make_array("HigherOrderDegrees", 3, m.num_elements());
  const std::vector<int> pos = vtk_ordering(m);
  std::vector<vtkIdType> ids(nl);
  grid->Allocate(m.num_elements());
  for (int e = 0; e < m.num_elements(); ++e) {
    const BezierElement& el = m.element(e);
    for (int l = 0; l < nl; ++l) {
      const vtkIdType id = vtkIdType(e) * nl + l;
      double x[3] = {0, 0, 0}, u[3] = {0, 0, 0};
      for (int d = 0; d < sd; ++d) {
        x[d] = el.points(l, d);
        if (!el.fields.empty()) u[d] = el.fields[0](l, d);
      }
      pts->SetPoint(id, x);
      disp->SetTuple(id, u);
      weights->SetValue(id, el.weights[l]);
      ids[pos[l]] = id;
    }
    grid->InsertNextCell(bezier_cell_type(m.param_dim()), nl, ids.data());
    const double deg[3] = {double(m.degree(0)), double(m.degree(1)), double(m.degree(2))};
    degrees->SetTuple(e, deg);
  }
  grid->SetPoints(pts);
  grid->GetPointData()->SetRationalWeights(weights);
  grid->GetPointData()->AddArray(disp);
  grid->GetPointData()->SetActiveVectors("displacement");
  grid->GetCellData()->SetHigherOrderDegrees(degrees);
  return grid;
}

void check_finite(vtkDataSetAttributes* attrs, const std::string& file) {
  for (int a = 0; a < attrs->GetNumberOfArrays(); ++a) {
    vtkDataArray* arr = attrs->GetArray(a);
    if (!arr) continue;
    const vtkIdType n = arr->GetNumberOfValues();
    for (vtkIdType i = 0; i < n; ++i)
      if (!std::isfinite(arr->GetComponent(i / arr->GetNumberOfComponents(), int(i % arr->GetNumberOfComponents()))))
        throw std::runtime_error(fmt::format("{}: array '{}' has a value that is not finite; nothing written", file,
                                             arr->GetName() ? arr->GetName() : "?"));
  }
}

void write_grid(vtkUnstructuredGrid* grid, const std::string& dir, const std::string& name) {
  const std::string path = dir + "/" + name;
  check_finite(grid->GetPointData(), path);
  check_finite(grid->GetCellData(), path);
  if (grid->GetPoints()) {
    vtkDataArray* p = grid->GetPoints()->GetData();
    for (vtkIdType i = 0; i < p->GetNumberOfTuples(); ++i)
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(p->GetComponent(i, c)))
          throw std::runtime_error(fmt::format("{}: a point coordinate is not finite; nothing written", path));
  }
  const std::string tmp = fmt::format("{}.tmp{}", path, getpid());
  vtkNew<vtkXMLUnstructuredGridWriter> w;
  w->SetFileName(tmp.c_str());
  w->SetInputData(grid);
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  // LZ4, not zlib: the doubles of a field hardly compress, and zlib cost
  // more than the rest of the step (docs/benchmarks.md, "Output").  ParaView
  // reads it since 5.5.
  w->SetCompressorTypeToLZ4();
  w->SetGlobalWarningDisplay(0);  // a failure is one line of ours, not VTK's multi-line dump
  errno = 0;
  const bool written = w->Write() == 1 && w->GetErrorCode() == 0;
  const int err = errno;
  std::error_code ec;
  if (!written || std::filesystem::file_size(tmp, ec) == 0 || ec) {
    std::filesystem::remove(tmp, ec);
    throw std::runtime_error(fmt::format("cannot write {}: {}", path, why_not_written(path, written ? 0 : err)));
  }
  std::filesystem::rename(tmp, path);
}

// Body: Bezier cells with displacement and recovered stress.
vtkSmartPointer<vtkUnstructuredGrid> body_grid(const Model& model, const RunResult& r) {
  const Body& body = model.body;
  if (r.u.rows() != body.num_control_points() || r.u.cols() != body.space_dim())
    throw std::runtime_error(fmt::format("VTK output: displacement is {} x {} for {} control points in {}D", r.u.rows(),
                                         r.u.cols(), body.num_control_points(), body.space_dim()));
  std::vector<int> patch_of;  // per element
  const BezierMesh mesh = body_bezier_mesh(body, r.u, 0, -1, &patch_of);  // every patch's elements, one after the other
  auto grid = bezier_grid(mesh);
  const vtkIdType np = mesh.num_points();
  // The stress and strain, J = det F and the hydrostatic pressure in one
  // pass (model/field_recovery.hpp); a mixed patch's stress takes its
  // volumetric part from that pressure.
  RecoveredFields fields;
  if (r.u.isZero(0.0) && r.element_pressures.isZero(0.0)) {  // the undeformed body (step 0): nothing to recover
    fields.stress.stress.setZero(np, 6);
    fields.stress.strain.setZero(np, 6);
    fields.stress.principal.setZero(np, 3);
    fields.stress.von_mises.setZero(np);
    fields.stress.magnitude.setZero(np);
    fields.volume.jacobian.setOnes(np);
    fields.volume.pressure.setZero(np);
  } else {
    fields = recover_body_fields(mesh, model, r.element_pressures);
  }
  const RecoveredStress& s = fields.stress;
  const RecoveredVolume& v = fields.volume;
  const char* names[6] = {"XX", "YY", "ZZ", "XY", "YZ", "XZ"};
  auto stress = make_array("stress", 6, np);
  auto strain = make_array("strain", 6, np);
  for (int c = 0; c < 6; ++c) {
    stress->SetComponentName(c, names[c]);
    strain->SetComponentName(c, names[c]);
  }
  auto principal = make_array("principal_stress", 3, np);
  auto vm = make_array("von_mises", 1, np);
  auto mag = make_array("stress_magnitude", 1, np);
  auto patch_point = make_array("patch", 1, np);
  for (vtkIdType i = 0; i < np; ++i) {
    for (int c = 0; c < 6; ++c) {
      stress->SetComponent(i, c, s.stress(i, c));
      strain->SetComponent(i, c, s.strain(i, c));
    }
    for (int c = 0; c < 3; ++c) principal->SetComponent(i, c, s.principal(i, c));
    vm->SetValue(i, s.von_mises[i]);
    mag->SetValue(i, s.magnitude[i]);
    patch_point->SetValue(i, patch_of[i / mesh.num_local()]);
  }
  auto patch_cell = make_array("patch", 1, mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e) patch_cell->SetValue(e, patch_of[e]);
  // The body of each element: its [[body]] table's index (0 for a case of one body).
  std::vector<int> body_of_patch(size_t(body.num_patches()), 0);
  for (size_t k = 0; k < model.parts.size(); ++k)
    for (int p = 0; p < model.parts[k].num_patches; ++p) body_of_patch[size_t(model.parts[k].first_patch + p)] = int(k);
  auto body_cell = make_array("body", 1, mesh.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e) body_cell->SetValue(e, body_of_patch[size_t(patch_of[e])]);
  auto jac = make_array("J", 1, np);
  auto hyd = make_array("hydrostatic_pressure", 1, np);
  for (vtkIdType i = 0; i < np; ++i) {
    jac->SetValue(i, v.jacobian[i]);
    hyd->SetValue(i, v.pressure[i]);
  }
  for (auto* a : {stress.Get(), strain.Get(), principal.Get(), vm.Get(), mag.Get(), patch_point.Get(), jac.Get(), hyd.Get()})
    grid->GetPointData()->AddArray(a);
  grid->GetCellData()->AddArray(patch_cell);
  grid->GetCellData()->AddArray(body_cell);
  grid->GetPointData()->SetActiveScalars("von_mises");
  return grid;
}

// Contact face: Bezier curves / quadrilaterals with the pressure, weighted
// gap and active flag (see the header for what is exact).
// Contact `i`'s block of the stacked multipliers, numbered from 0 on its face.
ContactSolution contact_block(const RunResult& r, size_t i) {
  const ContactResult& c = r.contacts[i];
  const ContactSolution& all = r.contact->solution;
  ContactSolution s;
  s.lambda = all.lambda.segment(c.first_multiplier, c.num_multipliers);
  s.weighted_gap = all.weighted_gap.segment(c.first_multiplier, c.num_multipliers);
  s.active.assign(all.active.begin() + c.first_multiplier, all.active.begin() + c.first_multiplier + c.num_multipliers);
  return s;
}

vtkSmartPointer<vtkUnstructuredGrid> contact_grid(const Model& model, const RunResult& r, size_t i, double load_factor) {
  const ContactFace& cf = *model.contacts[i].face;
  const ContactSolution sol = contact_block(r, i);
  BezierMesh mesh;                          // every side's elements, one after the other
  std::vector<const ContactSide*> side_of;  // per element
  for (const ContactSide& side : cf.sides) {
    Eigen::MatrixXd u_face(side.face_cps.size(), r.u.cols());
    for (size_t i = 0; i < side.face_cps.size(); ++i) u_face.row(i) = r.u.row(side.face_cps[i]);
    const BezierMesh part(side.face_patch, {u_face});
    side_of.insert(side_of.end(), part.num_elements(), &side);
    mesh.append(part);
  }
  auto grid = bezier_grid(mesh);
  const int ne = mesh.num_elements(), sd = mesh.space_dim();
  auto p_point = make_array("pressure", 1, mesh.num_points());
  auto t_point = make_array("traction", 3, mesh.num_points());
  auto p_cell = make_array("pressure", 1, ne);
  auto g_cell = make_array("weighted_gap", 1, ne);
  auto gap_cell = make_array("normal_gap", 1, ne);
  auto a_cell = make_array("active", 1, ne);

  const ContactPartFields fields = recover_contact_fields(mesh, side_of, sol, contact_partner(model, i, r.u, load_factor));
  for (vtkIdType i = 0; i < mesh.num_points(); ++i) {
    p_point->SetValue(i, fields.point_pressure[i]);
    double t[3] = {0, 0, 0};
    for (int c = 0; c < sd; ++c) t[c] = fields.point_traction(i, c);
    t_point->SetTuple(i, t);
  }
  for (int e = 0; e < ne; ++e) {
    p_cell->SetValue(e, fields.cell_pressure[e]);
    g_cell->SetValue(e, fields.cell_weighted_gap[e]);
    gap_cell->SetValue(e, fields.cell_gap[e]);
    a_cell->SetValue(e, fields.cell_active[e] ? 1.0 : 0.0);
  }
  grid->GetPointData()->AddArray(p_point);
  grid->GetPointData()->AddArray(t_point);
  auto gap_point = make_array("normal_gap", 1, mesh.num_points());
  for (vtkIdType i = 0; i < mesh.num_points(); ++i) gap_point->SetValue(i, fields.point_gap[i]);
  grid->GetPointData()->AddArray(gap_point);
  grid->GetPointData()->SetActiveScalars("pressure");
  grid->GetCellData()->AddArray(p_cell);
  grid->GetCellData()->AddArray(g_cell);
  grid->GetCellData()->AddArray(gap_cell);
  grid->GetCellData()->AddArray(a_cell);
  return grid;
}

// Friction: per multiplier its state (0 open, 1 stick, 2 slip), the
// tangential traction -lambda_t and the accumulated slip along the
// obstacle's tangents (one component in 2D, two in 3D).
void add_friction_fields(const RunResult& r, int first, int m, vtkUnstructuredGrid& grid) {
  const ContactSolution& s = r.contact->solution;
  if (s.lambda_t.size() == 0) return;
  const int nt = int(s.lambda_t.size() / s.lambda.size());
  auto state = make_array("friction_state", 1, m);
  auto traction = make_array("tangential_traction", nt, m);
  auto slip = make_array("slip", nt, m);
  for (int K = 0; K < m; ++K) {
    state->SetValue(K, s.friction_state[first + K]);
    for (int j = 0; j < nt; ++j) {
      traction->SetComponent(K, j, -s.lambda_t[(first + K) * nt + j]);
      slip->SetComponent(K, j, s.slip[(first + K) * nt + j]);
    }
  }
  for (auto* a : {state.Get(), traction.Get(), slip.Get()}) grid.GetPointData()->AddArray(a);
}

// One vertex per multiplier at its anchor on the reference face: its
// multiplier, weighted gap (Pi g)_K (the B_K-weighted mean of g_n, a length)
// and the normal gap g_n(X + u) to the partner at the anchor itself.
vtkSmartPointer<vtkUnstructuredGrid> multiplier_grid(const Model& model, const RunResult& r, size_t i,
                                                     double load_factor) {
  const ContactFace& cf = *model.contacts[i].face;
  const ContactSolution sol = contact_block(r, i);
  const Eigen::VectorXd weights = r.contact->op.weights.segment(r.contacts[i].first_multiplier, cf.num_multipliers());
  const int m = cf.num_multipliers(), sd = model.body.space_dim();
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(m);
  auto lambda = make_array("lambda", 1, m);
  auto pressure = make_array("pressure", 1, m);
  auto gap = make_array("weighted_gap", 1, m);
  auto active = make_array("active", 1, m);
  auto weight = make_array("weight", 1, m);
  auto normal_gap = make_array("normal_gap", 1, m);
  auto disp = make_array("displacement", 3, m);
  const ContactPartner partner = contact_partner(model, i, r.u, load_factor);
  grid->Allocate(m);
  for (const ContactSide& side : cf.sides) {
    Eigen::MatrixXd u_face(side.face_cps.size(), r.u.cols());
    for (size_t i = 0; i < side.face_cps.size(); ++i) u_face.row(i) = r.u.row(side.face_cps[i]);
    for (int k = 0; k < side.space.size(); ++k) {
      const int K = side.first_multiplier + k;
      const Eigen::VectorXd xi = side.space.anchor(k);
      const Eigen::VectorXd X = side.face_patch.point(xi), u = side.face_patch.field(u_face, xi);
      double x[3] = {0, 0, 0}, d[3] = {0, 0, 0};
      for (int c = 0; c < sd; ++c) x[c] = X[c], d[c] = u[c];
      pts->SetPoint(K, x);
      disp->SetTuple(K, d);
      lambda->SetValue(K, sol.lambda[K]);
      pressure->SetValue(K, -sol.lambda[K]);
      gap->SetValue(K, sol.weighted_gap[K]);
      active->SetValue(K, sol.active[K] ? 1.0 : 0.0);
      weight->SetValue(K, weights[K]);
      normal_gap->SetValue(K, partner(X + u).gap);
      const vtkIdType id = K;
      grid->InsertNextCell(VTK_VERTEX, 1, &id);
    }
  }
  grid->SetPoints(pts);
  for (auto* a : {lambda.Get(), pressure.Get(), gap.Get(), normal_gap.Get(), active.Get(), weight.Get(), disp.Get()})
    grid->GetPointData()->AddArray(a);
  grid->GetPointData()->SetActiveScalars("pressure");
  grid->GetPointData()->SetActiveVectors("displacement");
  add_friction_fields(r, r.contacts[i].first_multiplier, m, *grid);
  return grid;
}

}  // namespace

VtkStep write_vtk(const std::string& dir, const Model& model, const RunResult& result, int step_index,
                  double load_factor) {
  if (!std::isfinite(load_factor)) throw std::runtime_error("VTK output: the load factor is not finite");
  std::filesystem::create_directories(dir);
  VtkStep step{step_index, load_factor, {}, {}};
  // Build every grid first: a failure (a NaN) leaves no file of this step.
  std::vector<vtkSmartPointer<vtkUnstructuredGrid>> grids{body_grid(model, result)};
  step.files.push_back(fmt::format("solution_{:04d}.vtu", step_index));
  step.parts.push_back("body");
  if (result.contact && result.contacts.size() == model.contacts.size()) {
    const std::vector<std::string> tags = contact_file_tags(model);
    for (size_t i = 0; i < model.contacts.size(); ++i) {
      const std::string tag = tags[i].empty() ? "" : "_" + tags[i];
      grids.push_back(contact_grid(model, result, i, load_factor));
      step.files.push_back(fmt::format("contact{}_{:04d}.vtu", tag, step_index));
      step.parts.push_back("contact_face" + tag);
      grids.push_back(multiplier_grid(model, result, i, load_factor));
      step.files.push_back(fmt::format("multipliers{}_{:04d}.vtu", tag, step_index));
      step.parts.push_back("multipliers" + tag);
    }
  }
  for (size_t k = 0; k < grids.size(); ++k) write_grid(grids[k], dir, step.files[k]);
  return step;
}

void write_pvd(const std::string& dir, const std::vector<VtkStep>& steps) {
  std::string s =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const VtkStep& st : steps) {
    if (!std::isfinite(st.load_factor)) throw std::runtime_error("VTK output: a load factor is not finite");
    for (size_t k = 0; k < st.files.size(); ++k)
      s += fmt::format("    <DataSet timestep=\"{}\" part=\"{}\" name=\"{}\" file=\"{}\"/>\n", st.load_factor, k,
                       k < st.parts.size() ? st.parts[k] : std::string("part"), st.files[k]);
  }
  s += "  </Collection>\n</VTKFile>\n";
  std::filesystem::create_directories(dir);
  write_file_atomically(dir + "/solution.pvd", s);
}

const VtkStep& VtkSeries::write_step(const Model& model, const RunResult& result, double load_factor) {
  steps_.push_back(write_vtk(dir_, model, result, int(steps_.size()), load_factor));
  write_pvd(dir_, steps_);
  return steps_.back();
}

}  // namespace igac
