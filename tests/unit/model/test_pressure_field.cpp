// SPDX-License-Identifier: BSD-3-Clause
// The ParaView `hydrostatic_pressure` field of the mixed formulations
// (recover_volume, model/field_recovery.hpp): p(x) = -sum_A N_A(x)
// U'(theta_A) over the pressure space (mixed_pressure_space), theta_A =
// int N_A J / int N_A (small strain: tr eps, U' = K theta).  Checked: the
// Bezier elements' reference points are the pressure space's local
// coordinates (the map the recovery relies on); a uniform dilatation gives
// the constant U'(J) to round-off; for "mixed" the field is continuous across
// elements and is the sum computed here from the assembly's own quadrature;
// for "mixed_element" it is one constant per element; the run's own
// pressures (the incompressible limit) are shown as they are.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "engine/assembly.hpp"
#include "engine/body.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/pressure_space.hpp"
#include "engine/spline/refinement.hpp"
#include "io/case_file.hpp"
#include "model/field_recovery.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

// theta_A = int N_A v / int N_A, v = tr eps (small strain) or J of u, with
// the assembly's quadrature and the pressure space at the patch parameters.
std::vector<double> function_means(const Model& m, const Eigen::MatrixXd& u, const PressureSpace& space, bool small) {
  const BodyQuadrature quad(m.body, gauss_points_for(m.body.degree()));
  const int dim = m.body.space_dim();
  std::vector<double> integral(size_t(space.num_functions()), 0.0), mass(integral);
  ElementData ed;
  PressureSpace::Scratch scratch;
  std::vector<double> N;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, true);
    for (int q = 0; q < int(ed.JxW.size()); ++q) {
      Eigen::MatrixXd grad = Eigen::MatrixXd::Zero(dim, dim);  // du_i/dX_j
      for (size_t a = 0; a < ed.cps.size(); ++a) grad += u.row(ed.cps[a]).transpose() * ed.dN[size_t(q)].row(Eigen::Index(a));
      const double value = small ? grad.trace() : (Eigen::MatrixXd::Identity(dim, dim) + grad).determinant();
      const Eigen::VectorXd xi = ed.xi.row(q).transpose();
      space.values(e, xi.data(), N, scratch);
      for (size_t i = 0; i < N.size(); ++i) {
        integral[size_t(space.functions_begin(e)[i])] += ed.JxW[q] * N[i] * value;
        mass[size_t(space.functions_begin(e)[i])] += ed.JxW[q] * N[i];
      }
    }
  }
  for (size_t a = 0; a < integral.size(); ++a) integral[a] /= mass[a];
  return integral;
}

// The recovered field's value at local point s of element e.
double field_at(const RecoveredVolume& v, const BezierMesh& mesh, int e, const Eigen::VectorXd& s) {
  Eigen::VectorXd R;
  mesh.basis(mesh.element(e), s, R);
  return R.dot(v.pressure.segment(e * mesh.num_local(), mesh.num_local()));
}

// sum_A N_A(xi) p_A at local point s of element e.
double sum_at(const PressureSpace& space, const std::vector<double>& p, int e, const Eigen::VectorXd& s) {
  PressureSpace::Scratch scratch;
  std::vector<double> N;
  space.values_local(e, s.data(), N, scratch);
  double sum = 0;
  for (size_t i = 0; i < N.size(); ++i) sum += N[i] * p[size_t(space.functions_begin(e)[i])];
  return sum;
}

// A few local points of [0, 1]^d, corners and edges among them.
std::vector<Eigen::VectorXd> sample_points(int d) {
  const double t[] = {0.0, 0.3, 0.85, 1.0};
  std::vector<Eigen::VectorXd> out;
  for (int i2 = 0; i2 < (d > 2 ? 4 : 1); ++i2)
    for (int i1 = 0; i1 < 4; ++i1)
      for (int i0 = 0; i0 < 4; ++i0) {
        Eigen::VectorXd s(d);
        s[0] = t[i0];
        s[1] = t[i1];
        if (d > 2) s[2] = t[i2];
        out.push_back(s);
      }
  return out;
}

// Element e of body_bezier_mesh at its reference point s is the point of the
// quadrature's element e at the patch parameters lo + s (hi - lo) (its knot
// span, first direction first), and the pressure space's values_local(e, s)
// are its values(e, xi) there.  Checked at the quadrature's Gauss points of
// patches whose geometry has no symmetry (a swapped or reversed direction,
// or another element order, would move the point).
void expect_reference_points_are_patch_parameters(const Body& body, const std::vector<Formulation>& formulations) {
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  const BezierMesh mesh = body_bezier_mesh(body, Eigen::MatrixXd::Zero(body.num_control_points(), body.space_dim()));
  ASSERT_EQ(mesh.num_elements(), quad.num_elements());
  const PressureSpace space = mixed_pressure_space(quad, formulations);
  PressureSpace::Scratch scratch;
  std::vector<double> local, global;
  ElementData ed;
  const int pd = body.param_dim();
  double size = body.points().cwiseAbs().maxCoeff();
  for (int e = 0; e < quad.num_elements(); ++e) {
    const int k = quad.patch_of(e);
    const PatchQuadrature& pq = quad.patch_quadrature(k);
    const std::array<int, 3> ei = pq.element_index(e - quad.first_element(k));
    quad.evaluate(e, ed, false);
    for (int q = 0; q < int(ed.JxW.size()); ++q) {
      Eigen::VectorXd xi = ed.xi.row(q).transpose(), s(pd);
      for (int d = 0; d < pd; ++d) {
        const std::vector<double> bp = pq.patch().knots(d).breakpoints();
        const double lo = bp[size_t(ei[size_t(d)])], hi = bp[size_t(ei[size_t(d)]) + 1];
        s[d] = (xi[d] - lo) / (hi - lo);
      }
      ASSERT_LT((mesh.point(e, s) - ed.X.row(q).transpose()).norm(), 1e-13 * size) << "element " << e << ", point " << q;
      ASSERT_LT((pq.patch().point(xi) - ed.X.row(q).transpose()).norm(), 1e-13 * size);
      space.values_local(e, s.data(), local, scratch);
      space.values(e, xi.data(), global, scratch);
      ASSERT_EQ(local.size(), global.size());
      for (size_t i = 0; i < local.size(); ++i) ASSERT_NEAR(local[i], global[i], 1e-14) << "element " << e;
    }
  }
}

TEST(PressureField, BezierReferencePointsAreThePressureSpaceLocalCoordinates) {
  // Cook's membrane (a quadrilateral without symmetry), 5 x 3 elements
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.elements = {5, 3};
  spec.write_vtk = false;
  const Model cook = build_model(spec);
  expect_reference_points_are_patch_parameters(cook.body, cook.patch_formulations());
  // a rational cube of degree 2 bent out of every symmetry, 3 x 3 x 3 elements
  const NurbsPatch cube = subdivide(elevate_to(box(1, 2, 3).patch, 2), 3);
  Eigen::MatrixXd x = cube.points();
  Eigen::VectorXd w = cube.weights();
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    const Eigen::Vector3d p = x.row(i).transpose();
    x.row(i) += 0.2 * Eigen::RowVector3d(p.y() * p.y(), p.x() * p.z(), p.x() * p.x() + 0.3 * p.y());
    w[i] *= 1.0 + 0.1 * double(i % 3);
  }
  expect_reference_points_are_patch_parameters(Body(NurbsPatch(cube.all_knots(), x, w)), {Formulation::mixed});
}

// u = eps0 X (small strain) or (s - 1) X (F = s I, J = s^2 in plane
// strain): theta_A is the same for every function, and since the space is a
// partition of unity the field is the constant -U' everywhere.
TEST(PressureField, UniformDilatationGivesTheConstantPressure) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.elements = {5, 4};
  spec.write_vtk = false;
  for (const Formulation f : {Formulation::mixed, Formulation::mixed_element}) {
    spec.formulation = f;
    const Model m = build_model(spec);
    const Eigen::MatrixXd u = 1e-3 * m.body.points();
    const RecoveredVolume v = recover_volume(body_bezier_mesh(m.body, u), m);
    const double expected = -(m.material.lambda() + 2 * m.material.mu() / 3) * 2e-3;
    EXPECT_LT((v.pressure.array() - expected).abs().maxCoeff(), 1e-12 * std::abs(expected));
    EXPECT_LT((v.jacobian.array() - 1.001 * 1.001).abs().maxCoeff(), 1e-12);
  }
  CaseSpec large = spec;
  large.model = "neo_hookean";
  large.material_parameters = {spec.E, spec.nu, {}};
  large.formulation = Formulation::mixed;
  const Model m = build_model(large);
  ASSERT_TRUE(m.spec.finite_strain());
  const double stretch = 0.9;
  const Eigen::MatrixXd u = (stretch - 1) * m.body.points();
  VolumetricValues vol;
  ASSERT_TRUE(m.law->volumetric(stretch * stretch, vol));
  ASSERT_GT(std::abs(vol.dU), 1.0);
  const RecoveredVolume v = recover_volume(body_bezier_mesh(m.body, u), m);
  EXPECT_LT((v.pressure.array() + vol.dU).abs().maxCoeff(), 1e-11 * std::abs(vol.dU));
  EXPECT_LT((v.jacobian.array() - stretch * stretch).abs().maxCoeff(), 1e-12);
}

// Cook's membrane solved on 5 x 5 elements (p = 2: the pressure bilinear,
// C^0, on spans of 2 and 3 elements).  Its bilinear geometry makes N_A tr eps
// det J a polynomial both Gauss rules integrate exactly, so the field is
// -K sum_A N_A theta_A to round-off; the Bezier basis (polynomial, degree 2)
// holds it exactly, so both sides of every interior element boundary agree
// to round-off.  mixed_element: one constant -K theta_e per element, which
// jumps across the boundaries.
TEST(PressureField, MixedIsContinuousAndMixedElementIsConstantPerElement) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.elements = {5, 5};
  spec.write_vtk = false;
  const Model m = build_model(spec);
  ASSERT_EQ(m.patch_formulations().at(0), Formulation::mixed);
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  const BodyQuadrature quad(m.body, gauss_points_for(m.body.degree()));
  const double bulk = m.material.lambda() + 2 * m.material.mu() / 3;
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  const int n = 5;  // elements per direction; element e = i + n j
  for (const Formulation f : {Formulation::mixed, Formulation::mixed_element}) {
    CaseSpec fspec = spec;
    fspec.formulation = f;
    const Model fm = build_model(fspec);
    const PressureSpace space = mixed_pressure_space(quad, fm.patch_formulations());
    EXPECT_EQ(space.num_functions(), f == Formulation::mixed ? 3 * 3 : n * n);
    std::vector<double> p = function_means(fm, r.u, space, true);
    double scale = 0;
    for (double& x : p) {
      x *= -bulk;
      scale = std::max(scale, std::abs(x));
    }
    ASSERT_GT(scale, 0.0);
    const RecoveredVolume v = recover_volume(mesh, fm);
    for (int e = 0; e < mesh.num_elements(); ++e)
      for (const Eigen::VectorXd& s : sample_points(2))
        ASSERT_NEAR(field_at(v, mesh, e, s), sum_at(space, p, e, s), 1e-10 * scale) << "element " << e;
    // the two sides of each interior boundary, at the same physical point
    double jump = 0;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int d = 0; d < 2; ++d) {
          if ((d == 0 ? i : j) == n - 1) continue;
          const int e = i + n * j, next = d == 0 ? e + 1 : e + n;
          for (const double t : {0.0, 0.4, 1.0}) {
            Eigen::VectorXd s(2), s_next(2);
            s[d] = 1;
            s_next[d] = 0;
            s[1 - d] = s_next[1 - d] = t;
            ASSERT_LT((mesh.point(e, s) - mesh.point(next, s_next)).norm(), 1e-12 * 60);
            jump = std::max(jump, std::abs(field_at(v, mesh, e, s) - field_at(v, mesh, next, s_next)));
          }
        }
    std::cout << "  Cook 5 x 5, " << (f == Formulation::mixed ? "mixed" : "mixed_element")
              << ": pressure up to " << scale << ", largest jump across elements " << jump << "\n";
    if (f == Formulation::mixed) {
      EXPECT_LT(jump, 1e-10 * scale);
    } else {
      EXPECT_GT(jump, 1e-2 * scale);
      // one constant per element: every Bezier coefficient of e is -K theta_e
      for (int e = 0; e < mesh.num_elements(); ++e)
        for (int a = 0; a < mesh.num_local(); ++a)
          ASSERT_NEAR(v.pressure[e * mesh.num_local() + a], p[size_t(e)], 1e-10 * scale) << "element " << e;
    }
  }
  // the run's own pressures, one per function (the incompressible limit's
  // U'), are shown as they are: -sum_A N_A given_A
  const PressureSpace space = mixed_pressure_space(quad, m.patch_formulations());
  Eigen::VectorXd given(space.num_functions());
  std::vector<double> minus_given(size_t(space.num_functions()));
  for (int a = 0; a < space.num_functions(); ++a) minus_given[size_t(a)] = -(given[a] = 10.0 + a);
  const RecoveredVolume vg = recover_volume(mesh, m, given);
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (const Eigen::VectorXd& s : sample_points(2))
      ASSERT_NEAR(field_at(vg, mesh, e, s), sum_at(space, minus_given, e, s), 1e-12 * 20) << "element " << e;
  // one per element (a run that numbered them so) is read per element
  Eigen::VectorXd per_element = Eigen::VectorXd::LinSpaced(n * n, 1.0, 25.0);
  const RecoveredVolume ve = recover_volume(mesh, m, per_element);
  for (int e = 0; e < mesh.num_elements(); ++e)
    EXPECT_NEAR(ve.pressure[e * mesh.num_local()], -per_element[e], 1e-12 * 25);
  EXPECT_THROW(recover_volume(mesh, m, Eigen::VectorXd::Ones(7)), std::invalid_argument);
  // the displacement formulation: the pointwise -tr sigma / 3, not the space's
  CaseSpec disp_spec = spec;
  disp_spec.formulation = Formulation::displacement;
  const Model d = build_model(disp_spec);
  const RecoveredVolume vd = recover_volume(body_bezier_mesh(d.body, r.u), d);
  EXPECT_GT(vd.pressure.maxCoeff() - vd.pressure.minCoeff(), 0.0);
  EXPECT_THROW(recover_volume(body_bezier_mesh(m.body, r.u, 0, 0), m), std::invalid_argument);
}

// The Lame cylinder inflated (Neo-Hookean, K/mu = 5000, mixed): -sum_A N_A
// U'(theta_A), theta_A the weighted mean of J.  The recovery integrates J
// with its own rule (p + 3 points per direction against the assembly's
// p + 1) on the rational geometry, so the two differ by quadrature error,
// far below the pressure.
TEST(PressureField, LargeDeformationIsUPrimeOfTheWeightedMeansOfJ) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/lame_cylinder.toml");
  spec.model = "neo_hookean";
  const double nu = 0.4999, mu = 1.0;
  spec.E = 2 * mu * (1 + nu);
  spec.nu = nu;
  spec.material_parameters = {spec.E, nu, {}};
  spec.formulation = Formulation::mixed;
  spec.write_vtk = false;
  spec.pressure.at(0).value = 0.2;
  spec.loading.steps = 2;
  spec.reference = "none";
  apply_overrides(spec, 2, 1);
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  const BodyQuadrature quad(m.body, gauss_points_for(m.body.degree()));
  const PressureSpace space = mixed_pressure_space(quad, m.patch_formulations());
  ASSERT_FALSE(space.disjoint());
  std::vector<double> p = function_means(m, r.u, space, false);
  double scale = 0;
  for (double& theta : p) {
    VolumetricValues v;
    ASSERT_TRUE(m.law->volumetric(theta, v));
    theta = -v.dU;
    scale = std::max(scale, std::abs(theta));
  }
  ASSERT_GT(scale, 0.01);
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  const RecoveredVolume v = recover_volume(mesh, m);
  double error = 0;
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (const Eigen::VectorXd& s : sample_points(2))
      error = std::max(error, std::abs(field_at(v, mesh, e, s) - sum_at(space, p, e, s)));
  std::cout << "  inflated tube: pressure up to " << scale << ", recovered field off by up to " << error << "\n";
  EXPECT_LT(error, 1e-3 * scale);
}

}  // namespace
}  // namespace igac
