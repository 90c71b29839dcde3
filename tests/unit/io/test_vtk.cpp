// SPDX-License-Identifier: BSD-3-Clause
// ParaView output, mathematics first:
//  - Bezier extraction is exact: each rational Bezier element evaluates to
//    the patch (geometry and a carried field) at the mapped parameter;
//  - the element-local L2 stress projection passes the patch test (a linear
//    displacement u = A X gives the constant stress everywhere, to round-off);
//  - the written files, read back with VTK's own XML reader and evaluated with
//    VTK's own Bezier cells (its point ordering, rational weights and degrees),
//    reproduce the patch: the quarter disc's arc lies on x^2 + y^2 = R^2;
//    there is no NaN, the point counts are the extraction's, and the .pvd
//    lists files that exist;
//  - `[output] vtk = false` writes no .vtu and --no-output no file at all.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <unistd.h>
#include <string>
#include <vector>

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "engine/spline/bezier_extraction.hpp"
#include "engine/spline/refinement.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "io/vtk_output.hpp"
#include "model/field_recovery.hpp"
#include "tests/support/vtu_file.hpp"

namespace {

using namespace igac;
namespace fs = std::filesystem;

const std::string kSourceDir = IGAC_SOURCE_DIR;

// Extraction is knot insertion (exact in exact arithmetic): agreement with
// the patch to 1e-12 on geometry of size ~1 leaves a factor ~1000 over the
// round-off of a few convex combinations.
constexpr double kExtractionExact = 1e-12;
// The brief: boundary points of the quarter disc on the circle to 1e-12.
constexpr double kOnCircle = 1e-12;
// Patch test: the projected constant stress differs from the exact one by
// the round-off of a small dense Cholesky solve (condition ~1e3 for p <= 3
// Bernstein mass matrices): 1e-10 relative.
constexpr double kPatchTestRel = 1e-10;

// A patch with random knots (interior multiplicities 1..2), points on a
// perturbed grid and weights in [0.5, 2]: curved, rational, non-uniform.
NurbsPatch random_patch(std::mt19937& rng, std::vector<int> degrees) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<KnotVector> kv;
  std::array<int, 3> n{1, 1, 1};
  for (size_t d = 0; d < degrees.size(); ++d) {
    const int p = degrees[d];
    std::vector<double> k(p + 1, 0.0);
    k.push_back(0.2 + 0.1 * U(rng));
    k.push_back(0.5);
    if (p >= 2) k.push_back(0.5);  // a C^{p-2} knot
    k.push_back(0.7 + 0.1 * U(rng));
    k.insert(k.end(), p + 1, 1.0);
    kv.emplace_back(p, k);
    n[d] = kv.back().num_basis();
  }
  const int dim = int(degrees.size()), ncp = n[0] * n[1] * n[2];
  Eigen::MatrixXd P(ncp, dim);
  Eigen::VectorXd w(ncp);
  for (int c = 0; c < ncp; ++c) {
    const std::array<int, 3> i{c % n[0], (c / n[0]) % n[1], c / (n[0] * n[1])};
    for (int d = 0; d < dim; ++d) P(c, d) = (i[d] + 0.25 * (U(rng) - 0.5)) / (n[d] - 1) * (1.0 + d);
    w[c] = 0.5 + 1.5 * U(rng);
  }
  return NurbsPatch(kv, P, w);
}

Eigen::VectorXd random_local(std::mt19937& rng, int d) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::VectorXd s(d);
  for (int i = 0; i < d; ++i) s[i] = U(rng);
  return s;
}

// Extraction equals direct evaluation, for geometry and a field.
void expect_extraction_exact(const NurbsPatch& patch, std::mt19937& rng) {
  std::normal_distribution<double> N(0.0, 1.0);
  Eigen::MatrixXd u(patch.num_control_points(), 3);
  for (int i = 0; i < u.size(); ++i) u.data()[i] = N(rng);
  const BezierMesh mesh(patch, {u});
  ASSERT_EQ(mesh.num_elements(), patch.num_elements());
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int t = 0; t < 5; ++t) {
      const Eigen::VectorXd s = random_local(rng, patch.param_dim());
      const Eigen::VectorXd xi = mesh.element(e).parameter(s);
      EXPECT_LT((mesh.point(e, s) - patch.point(xi)).norm(), kExtractionExact) << "element " << e;
      EXPECT_LT((mesh.field(e, 0, s) - patch.field(u, xi)).norm(), kExtractionExact * u.norm()) << "element " << e;
    }
}

TEST(VtkBezierExtraction, RandomRationalPatchesAreReproduced) {
  std::mt19937 rng(7);
  expect_extraction_exact(random_patch(rng, {2}), rng);
  expect_extraction_exact(random_patch(rng, {3}), rng);
  expect_extraction_exact(random_patch(rng, {2, 3}), rng);
  expect_extraction_exact(random_patch(rng, {4, 2}), rng);
  expect_extraction_exact(random_patch(rng, {2, 3, 2}), rng);
}

TEST(VtkBezierExtraction, QuarterDiscArcStaysOnTheCircle) {
  const double R = 1.0;
  const NurbsPatch patch = subdivide(elevate_to(quarter_disc(R).patch, 3), 4);
  const BezierMesh mesh(patch);
  // Elements along v = 0 carry the arc: every point of their bottom edge,
  // evaluated through the rational Bezier form, is on the circle.
  std::mt19937 rng(3);
  for (const auto& el : mesh.elements()) {
    if (el.index[1] != 0) continue;
    for (int t = 0; t < 7; ++t) {
      Eigen::VectorXd s = random_local(rng, 2);
      s[1] = 0;
      const int e = int(&el - mesh.elements().data());
      EXPECT_NEAR(mesh.point(e, s).norm(), R, kOnCircle);
    }
  }
}

TEST(VtkBezierExtraction, BernsteinIsAPartitionOfUnityWithDerivativesSummingToZero) {
  double v[8], d[8];
  for (int p = 0; p <= 6; ++p)
    for (double s : {0.0, 0.17, 0.5, 0.93, 1.0}) {
      bernstein(p, s, v, d);
      double sv = 0, sd = 0;
      for (int i = 0; i <= p; ++i) sv += v[i], sd += d[i];
      // sums of p+1 terms in [0, 1] (values) and of size <= p (derivatives)
      EXPECT_NEAR(sv, 1.0, 1e-15);
      EXPECT_NEAR(sd, 0.0, 1e-13);
      // end values: B_0(0) = 1, B_p(1) = 1
      if (s == 0.0) {
        EXPECT_EQ(v[0], 1.0);
      }
      if (s == 1.0) {
        EXPECT_EQ(v[p], 1.0);
      }
    }
}

// A linear displacement u = A X (exactly representable: the coefficients
// are A X_A) has the constant strain sym(A): the element-local projection
// must give the constant stress at every Bezier point of every element.
void expect_patch_test(const NurbsPatch& patch) {
  const int dim = patch.space_dim();
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d full;
  full << 0.01, -0.02, 0.005, 0.03, -0.015, 0.002, -0.004, 0.006, 0.02;
  A.topLeftCorner(dim, dim) = full.topLeftCorner(dim, dim);
  const Eigen::MatrixXd u = patch.points() * A.topLeftCorner(dim, dim).transpose();
  const double lambda = 0.5769230769, mu = 0.3846153846;
  const StressLaw law = linear_elastic_stress(lambda, mu);
  const Eigen::Matrix3d sigma = law(A);
  const RecoveredStress rs = recover_stress(BezierMesh(patch, {u}), law);
  const int comp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  const double scale = sigma.norm();
  for (int i = 0; i < rs.stress.rows(); ++i) {
    for (int c = 0; c < 6; ++c) ASSERT_NEAR(rs.stress(i, c), sigma(comp[c][0], comp[c][1]), kPatchTestRel * scale);
    ASSERT_NEAR(rs.von_mises[i], von_mises(sigma), kPatchTestRel * scale);
    ASSERT_NEAR(rs.magnitude[i], sigma.norm(), kPatchTestRel * scale);
  }
  if (dim == 2) {  // plane strain: sigma_zz = lambda tr(eps)
    EXPECT_NEAR(sigma(2, 2), lambda * A.trace(), 1e-15);
  }
}

TEST(VtkStressRecovery, PatchTestOnCurvedRationalGeometry) {
  expect_patch_test(subdivide(elevate_to(quarter_disc(1.0).patch, 2), 3));
  expect_patch_test(subdivide(elevate_to(quarter_disc(1.0).patch, 3), 2));
  std::mt19937 rng(11);
  expect_patch_test(random_patch(rng, {2, 2, 3}));
}

// ---------------------------------------------------------------- files

using igac_test::read_vtu;

void expect_no_nan(vtkDataSetAttributes* attrs, const std::string& what) {
  for (int a = 0; a < attrs->GetNumberOfArrays(); ++a) {
    vtkDataArray* arr = attrs->GetArray(a);
    ASSERT_NE(arr, nullptr);
    for (vtkIdType t = 0; t < arr->GetNumberOfTuples(); ++t)
      for (int c = 0; c < arr->GetNumberOfComponents(); ++c)
        ASSERT_TRUE(std::isfinite(arr->GetComponent(t, c))) << what << " array " << arr->GetName();
  }
}

// VTK's evaluation of cell c at pcoords: position and the interpolation
// weights (for point data).
Eigen::Vector3d vtk_evaluate(vtkUnstructuredGrid* g, vtkGenericCell* cell, vtkIdType c, const Eigen::Vector3d& pc,
                             std::vector<double>& w) {
  g->GetCell(c, cell);
  w.resize(cell->GetNumberOfPoints());
  int sub = 0;
  double x[3];
  double p[3] = {pc[0], pc[1], pc[2]};
  cell->EvaluateLocation(sub, p, x, w.data());
  return {x[0], x[1], x[2]};
}

Eigen::Vector3d vtk_interpolate(vtkUnstructuredGrid* g, vtkGenericCell* cell, const char* name,
                                const std::vector<double>& w) {
  vtkDataArray* a = g->GetPointData()->GetArray(name);
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (vtkIdType k = 0; k < cell->GetNumberOfPoints(); ++k)
    for (int c = 0; c < std::min(3, a->GetNumberOfComponents()); ++c)
      v[c] += w[k] * a->GetComponent(cell->GetPointId(k), c);
  return v;
}

Eigen::Vector3d pad3(const Eigen::VectorXd& v) {
  Eigen::Vector3d o = Eigen::Vector3d::Zero();
  o.head(v.size()) = v;
  return o;
}

// Every .vtu a run wrote: Bezier cells (vertices for the multipliers), no
// NaN; the .pvd names only files that exist, with finite timesteps.
void expect_files_sound(const std::string& dir, int expected_steps) {
  std::ifstream in(dir + "/solution.pvd");
  ASSERT_TRUE(in.good()) << dir << "/solution.pvd";
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string pvd = ss.str();
  const std::regex entry("<DataSet timestep=\"([^\"]+)\"[^>]*file=\"([^\"]+)\"");
  int entries = 0;
  std::set<std::string> listed;
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator(); ++it) {
    ++entries;
    EXPECT_TRUE(std::isfinite(std::stod((*it)[1]))) << (*it)[0];
    // The shortest digits that read back to the load factor ("0.1", not
    // "0.10000000000000001").
    EXPECT_EQ((*it)[1].str(), fmt::format("{}", std::stod((*it)[1]))) << (*it)[0];
    const std::string f = (*it)[2];
    listed.insert(f);
    EXPECT_TRUE(fs::exists(dir + "/" + f)) << f;
  }
  EXPECT_GE(entries, expected_steps);
  int vtu = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.path().extension() != ".vtu") continue;
    ++vtu;
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(listed.count(name)) << name << " is not in solution.pvd";
    auto g = read_vtu(e.path().string());
    ASSERT_GT(g->GetNumberOfCells(), 0) << name;
    for (vtkIdType c = 0; c < g->GetNumberOfCells(); ++c) {
      const int t = g->GetCellType(c);
      if (name.rfind("multipliers_", 0) == 0) ASSERT_EQ(t, VTK_VERTEX) << name;
      else ASSERT_TRUE(t == VTK_BEZIER_CURVE || t == VTK_BEZIER_QUADRILATERAL || t == VTK_BEZIER_HEXAHEDRON) << name;
    }
    expect_no_nan(g->GetPointData(), name);
    expect_no_nan(g->GetCellData(), name);
    vtkDataArray* pts = g->GetPoints()->GetData();
    for (vtkIdType i = 0; i < pts->GetNumberOfTuples(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_TRUE(std::isfinite(pts->GetComponent(i, c))) << name;
  }
  EXPECT_EQ(vtu, int(listed.size()));
}

std::string fresh_dir(const std::string& name) {
  const std::string d = (fs::temp_directory_path() / fmt::format("igac_test_vtk_{}_{}", name, ::getpid())).string();
  fs::remove_all(d);
  return d;
}

TEST(VtkOutput, HertzFilesReadBackExactly) {
  CaseSpec spec = read_case(kSourceDir + "/cases/hertz2d.toml");
  spec.elements = {16, 4};
  const Model model = build_model(spec);
  const RunResult r = solve_model(model);
  ASSERT_EQ(r.status, "converged");
  const std::string dir = fresh_dir("hertz");
  VtkSeries series(dir);
  series.write_step(model, r, 0.5);  // two steps, so the .pvd has a series
  series.write_step(model, r, 1.0);
  expect_files_sound(dir, 2);

  const NurbsPatch& patch = model.body.patch(0);
  const BezierMesh body(patch);
  auto g = read_vtu(dir + "/solution_0001.vtu");
  ASSERT_EQ(g->GetNumberOfPoints(), body.num_points());
  ASSERT_EQ(g->GetNumberOfCells(), body.num_elements());
  ASSERT_NE(g->GetPointData()->GetRationalWeights(), nullptr);
  ASSERT_NE(g->GetCellData()->GetHigherOrderDegrees(), nullptr);
  for (const char* a : {"displacement", "stress", "von_mises", "stress_magnitude"})
    ASSERT_NE(g->GetPointData()->GetArray(a), nullptr) << a;
  EXPECT_EQ(g->GetPointData()->GetArray("displacement")->GetNumberOfComponents(), 3);

  // VTK's own Bezier evaluation equals the patch, geometry and displacement,
  // at random points of every cell; and the arc (v = 0) is on the circle.
  vtkNew<vtkGenericCell> cell;
  std::vector<double> w;
  std::mt19937 rng(5);
  const double R = spec.radius;
  double worst_circle = 0;
  for (int e = 0; e < body.num_elements(); ++e) {
    for (int t = 0; t < 3; ++t) {
      const Eigen::VectorXd s = random_local(rng, 2);
      const Eigen::VectorXd xi = body.element(e).parameter(s);
      const Eigen::Vector3d x = vtk_evaluate(g, cell, e, {s[0], s[1], 0}, w);
      ASSERT_LT((x - pad3(patch.point(xi))).norm(), kExtractionExact) << "cell " << e;
      const Eigen::Vector3d u = vtk_interpolate(g, cell, "displacement", w);
      ASSERT_LT((u - pad3(patch.field(r.u, xi))).norm(), kExtractionExact * r.u.norm()) << "cell " << e;
    }
    if (body.element(e).index[1] == 0)
      for (double s : {0.0, 0.1, 0.37, 0.5, 0.81, 1.0}) {
        const Eigen::Vector3d x = vtk_evaluate(g, cell, e, {s, 0, 0}, w);
        worst_circle = std::max(worst_circle, std::abs(x.head<2>().norm() - R));
      }
  }
  EXPECT_LT(worst_circle, kOnCircle);

  // The contact face: Bezier curves on the same circle, one per face element;
  // pressure cell data = -lambda_K for S0 (p = 2), active flags as solved.
  const ContactFace& cf = *model.contacts.front().face;
  const BezierMesh face(cf.sides[0].face_patch);
  auto c = read_vtu(dir + "/contact_0001.vtu");
  ASSERT_EQ(c->GetNumberOfPoints(), face.num_points());
  ASSERT_EQ(c->GetNumberOfCells(), face.num_elements());
  worst_circle = 0;
  for (int e = 0; e < face.num_elements(); ++e) {
    ASSERT_EQ(c->GetCellType(e), VTK_BEZIER_CURVE);
    for (double s : {0.0, 0.23, 0.5, 0.77, 1.0})
      worst_circle = std::max(worst_circle, std::abs(vtk_evaluate(c, cell, e, {s, 0, 0}, w).head<2>().norm() - R));
  }
  EXPECT_LT(worst_circle, kOnCircle);
  ASSERT_EQ(cf.sides[0].space.size(), face.num_elements());  // S0: one multiplier per face element
  const auto& sol = r.contact->solution;
  vtkDataArray* p = c->GetCellData()->GetArray("pressure");
  vtkDataArray* a = c->GetCellData()->GetArray("active");
  vtkDataArray* gap = c->GetCellData()->GetArray("weighted_gap");
  ASSERT_TRUE(p && a && gap);
  const double pscale = std::max(1e-300, r.contacts.front().report.max_pressure);
  for (int K = 0; K < cf.sides[0].space.size(); ++K) {
    EXPECT_NEAR(p->GetComponent(K, 0), -sol.lambda[K], 1e-12 * pscale) << K;
    EXPECT_EQ(a->GetComponent(K, 0), sol.active[K] ? 1.0 : 0.0) << K;
    EXPECT_NEAR(gap->GetComponent(K, 0), sol.weighted_gap[K], 1e-12 + 1e-10 * std::abs(sol.weighted_gap[K])) << K;
  }
  auto m = read_vtu(dir + "/multipliers_0001.vtu");
  EXPECT_EQ(m->GetNumberOfPoints(), cf.sides[0].space.size());
  fs::remove_all(dir);
}

// 3D: a curved rational patch with a linear displacement, written and read
// back: VTK's hexahedron ordering reproduces the patch, and the stress array
// is the constant stress (patch test through the file).
TEST(VtkOutput, CurvedHexahedraReadBackExactly) {
  std::mt19937 rng(13);
  Model model;
  model.body = Body(random_patch(rng, {3, 3, 3}));
  model.material = LinearElastic(1.0, 0.3);
  const NurbsPatch& patch = model.body.patch(0);
  Eigen::Matrix3d A;
  A << 0.01, -0.02, 0.005, 0.03, -0.015, 0.002, -0.004, 0.006, 0.02;
  RunResult r;
  r.u = patch.points() * A.transpose();
  const std::string dir = fresh_dir("hex");
  VtkSeries(dir).write_step(model, r, 1.0);
  expect_files_sound(dir, 1);
  const BezierMesh mesh(patch);
  auto g = read_vtu(dir + "/solution_0000.vtu");
  ASSERT_EQ(g->GetNumberOfPoints(), mesh.num_points());
  vtkNew<vtkGenericCell> cell;
  std::vector<double> w;
  for (int e = 0; e < mesh.num_elements(); ++e) {
    ASSERT_EQ(g->GetCellType(e), VTK_BEZIER_HEXAHEDRON);
    for (int t = 0; t < 4; ++t) {
      const Eigen::VectorXd s = random_local(rng, 3);
      const Eigen::VectorXd xi = mesh.element(e).parameter(s);
      const Eigen::Vector3d x = vtk_evaluate(g, cell, e, {s[0], s[1], s[2]}, w);
      ASSERT_LT((x - patch.point(xi)).norm(), kExtractionExact) << "cell " << e;
      const Eigen::Vector3d u = vtk_interpolate(g, cell, "displacement", w);
      ASSERT_LT((u - A * patch.point(xi)).norm(), kExtractionExact) << "cell " << e;
    }
  }
  const Eigen::Matrix3d sigma = linear_elastic_stress(model.material.lambda(), model.material.mu())(A);
  vtkDataArray* st = g->GetPointData()->GetArray("stress");
  vtkDataArray* vm = g->GetPointData()->GetArray("von_mises");
  const int comp[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  for (vtkIdType i = 0; i < g->GetNumberOfPoints(); ++i) {
    for (int c = 0; c < 6; ++c)
      ASSERT_NEAR(st->GetComponent(i, c), sigma(comp[c][0], comp[c][1]), kPatchTestRel * sigma.norm());
    ASSERT_NEAR(vm->GetComponent(i, 0), von_mises(sigma), kPatchTestRel * sigma.norm());
  }
  fs::remove_all(dir);
}

TEST(VtkOutput, NaNIsNeverWritten) {
  Model model;
  model.body = Body(subdivide(elevate_to(quarter_disc(1.0).patch, 2), 2));
  model.material = LinearElastic(1.0, 0.3);
  RunResult r;
  r.u = Eigen::MatrixXd::Zero(model.body.patch(0).num_control_points(), 2);
  r.u(3, 1) = std::nan("");
  const std::string dir = fresh_dir("nan");
  EXPECT_THROW(write_vtk(dir, model, r, 0, 1.0), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir + "/solution_0000.vtu"));
  fs::remove_all(dir);
}

// The command line: vtk = false in the case writes no .vtu (and so recovers
// no stress); --no-output writes no file at all.
TEST(VtkOutput, OutputSwitches) {
  const std::string dir = fresh_dir("cli");
  fs::create_directories(dir);
  std::ifstream in(kSourceDir + "/cases/hertz2d.toml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = std::regex_replace(ss.str(), std::regex("elements = \\[64, 16\\]"), "elements = [16, 4]");
  const std::string case_path = dir + "/small.toml";
  std::ofstream(case_path) << text << "\n[output]\nvtk = false\n";
  const std::string out = dir + "/out";
  ASSERT_EQ(std::system(fmt::format("'{}' run '{}' --out '{}' --quiet", IGAC_BINARY, case_path, out).c_str()), 0);
  EXPECT_TRUE(fs::exists(out + "/summary.json"));
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(e.path().extension(), ".vtu") << e.path();
  EXPECT_FALSE(fs::exists(out + "/solution.pvd"));

  const std::string out2 = dir + "/out2";
  std::ofstream(case_path) << text;
  ASSERT_EQ(std::system(fmt::format("'{}' run '{}' --out '{}' --quiet", IGAC_BINARY, case_path, out2).c_str()), 0);
  expect_files_sound(out2, 1);

  const std::string out3 = dir + "/out3";
  ASSERT_EQ(std::system(fmt::format("'{}' run '{}' --out '{}' --quiet --no-output", IGAC_BINARY, case_path, out3).c_str()),
            0);
  EXPECT_FALSE(fs::exists(out3));
  fs::remove_all(dir);
}

}  // namespace
