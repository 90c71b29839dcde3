// SPDX-License-Identifier: BSD-3-Clause
// The stabilised element-constant projection of the mixed formulation
// (engine/volumetric_projection.hpp), against an analytic energy.
//
// One quadratic element on the unit square (cube), u = (x^2 - x, 0 (, 0)):
// eps_xx = 2x - 1, whose element mean is 0, so the projection sees nothing
// of it (Pi_e tr eps = 0) and only the deviatoric energy and the
// stabilisation hold it.  With the 3D deviator (plane strain included),
// |dev eps|^2 = (2/3) eps_xx^2, int (2x - 1)^2 = 1/3:
//   u^T K u = int 2 mu |dev eps|^2 + K (Pi tr eps)^2 + mu ((I - Pi) tr eps)^2
//           = 4 mu / 9 + 0 + mu / 3 = 7 mu / 9
// whatever K (without the stabilisation it would be 4 mu / 9: this mode
// is what let one element of the O-ring at K/G = 2000 change its volume by
// 30 %).  The same number from the small-strain B-bar stiffness with
// constants per element (mixed_element) and from the large-deformation
// tangent at rest (Mooney-Rivlin, Neo-Hookean), 2D and 3D.  The sub-grid
// space (mixed: multilinear on the one element) sees the mode: with the
// row-sum mass, sum_A (int N_A tr eps)^2 / m_A = K / 9 more (2D: N_A =
// (1 - x or x)(1 - y or y), int N_A (2x - 1) = -+1 / 12, m_A = 1 / 4; 3D
// the same with a factor 1/2 on both per direction).
#include <gtest/gtest.h>

#include <cmath>

#include "engine/assembly.hpp"
#include "engine/pressure_space.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/total_lagrangian.hpp"
#include "engine/volumetric_projection.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {
namespace {

// Sums of a few dozen O(K) terms: round-off relative to the bulk modulus.
constexpr double kRoundoff = 1e-11;

// The Bernstein coefficients of x^2 - x on [0, 1] at degree 2 are 0, -1/2, 0:
// the control point at X has -2 X (1 - X) (X in {0, 1/2, 1}).
Eigen::VectorXd zero_mean_dilatation(const NurbsPatch& patch) {
  const int dim = patch.space_dim();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(patch.num_control_points() * dim);
  for (int a = 0; a < patch.num_control_points(); ++a) {
    const double X = patch.points()(a, 0);
    u[a * dim] = -2 * X * (1 - X);
  }
  return u;
}

NurbsPatch unit_element(int dim) {
  return elevate_to(dim == 2 ? rectangle(1, 1).patch : box(1, 1, 1).patch, 2);
}

TEST(VolumetricProjection, StabilisationHoldsTheModesTheProjectionDoesNotSee) {
  const double mu = 0.96, bulk = 2000 * mu;
  const double expected = 7 * mu / 9;
  for (int dim : {2, 3}) {
    const NurbsPatch patch = unit_element(dim);
    ASSERT_EQ(patch.num_elements(), 1);
    const DofMap dofs(patch, {});
    const Eigen::VectorXd u = zero_mean_dilatation(patch);
    // small strain: E, nu of (K, mu)
    const double E = 9 * bulk * mu / (3 * bulk + mu), nu = (3 * bulk - 2 * mu) / (2 * (3 * bulk + mu));
    const LinearSystem bbar = assemble_linear_elasticity(patch, dofs, LinearElastic{E, nu},
                                                         Eigen::VectorXd::Zero(dim), {}, Formulation::mixed_element);
    EXPECT_NEAR(u.dot(bbar.K * u), expected, kRoundoff * bulk) << dim << "D, small strain";
    const LinearSystem sub_grid = assemble_linear_elasticity(patch, dofs, LinearElastic{E, nu},
                                                             Eigen::VectorXd::Zero(dim), {}, Formulation::mixed);
    EXPECT_NEAR(u.dot(sub_grid.K * u), expected + bulk / 9, kRoundoff * bulk) << dim << "D, sub-grid space";
    const LinearSystem plain = assemble_linear_elasticity(patch, dofs, LinearElastic{E, nu}, Eigen::VectorXd::Zero(dim));
    EXPECT_GT(u.dot(plain.K * u), 100 * expected) << dim << "D: the displacement formulation sees it with K";
    // large deformation, the tangent at rest
    const MaterialParameters mooney{NAN, NAN, {{"C10", 0.37}, {"C01", 0.11}, {"bulk_modulus", bulk}}};
    const MaterialParameters neo{E, nu, {}};
    for (const auto& [name, parameters] : {std::pair{"mooney_rivlin", mooney}, std::pair{"neo_hookean", neo}}) {
      const auto law = make_law(name, parameters);
      EXPECT_NEAR(stabilisation_modulus(*law, dim), mu, 1e-12 * mu) << name;
      for (const Formulation formulation : {Formulation::mixed_element, Formulation::mixed}) {
        const TotalLagrangianAssembler tl(patch, dofs, *law, formulation);
        Eigen::VectorXd f;
        Eigen::SparseMatrix<double> K;
        ASSERT_TRUE(tl.assemble(Eigen::MatrixXd::Zero(patch.num_control_points(), dim), f, &K));
        // the sub-grid space sees the mode, as in small strain
        EXPECT_NEAR(u.dot(K * u), expected + (formulation == Formulation::mixed ? bulk / 9 : 0.0), kRoundoff * bulk)
            << dim << "D, " << name << ", " << formulation_name(formulation);
      }
    }
  }
}

// A law without a split has no stabilisation modulus.
TEST(VolumetricProjection, NoSplitNoStabilisation) {
  const auto law = make_law("saint_venant_kirchhoff", MaterialParameters{1.0, 0.3, {}});
  EXPECT_EQ(stabilisation_modulus(*law, 2), 0.0);
  EXPECT_EQ(stabilisation_modulus(*law, 3), 0.0);
}

}  // namespace

// ---------------------------------------------------------------------------
// The small-strain mixed stiffness over the pressure space
// (assemble_linear_elasticity, pressure_space.hpp) against the Hessian of
// its discrete energy, computed here point by point on every dof, with the
// space's functions N_A evaluated at the Gauss points:
//   E(u) = int mu |dev eps|^2 dX                          (3D deviator)
//        + sum_A K / 2 (int N_A tr eps dX)^2 / m_A         (m_A = int N_A dX)
//        + sum_e mu / 2 int_e (tr eps - Pi_e tr eps)^2    (the stabilisation)
// on mixed patches, int mu |dev eps|^2 + K / 2 (tr eps)^2 on the others.
// Constants per element (mixed_element) are the element-constant
// formulation; degree 0 on coarsened breakpoints the 2 x 2 blocks of before.

namespace {

// The Hessian of E on all dofs (n_cp dim x n_cp dim), dense.
Eigen::MatrixXd energy_hessian(const Body& body, const std::vector<LinearElastic>& materials,
                               const std::vector<Formulation>& formulations, const PressureSpace& space) {
  const int dim = body.space_dim(), n = body.num_control_points() * dim;
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  const size_t n_functions = size_t(space.num_functions());
  std::vector<Eigen::VectorXd> function_g(n_functions, Eigen::VectorXd::Zero(n));
  std::vector<double> function_mass(n_functions, 0.0), function_bulk(n_functions, 0.0);
  ElementData ed;
  PressureSpace::Scratch scratch;
  std::vector<double> values;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, true);
    const int k = quad.patch_of(e);
    const LinearElastic& mat = materials[materials.size() == 1 ? 0 : size_t(k)];
    const bool mixed = is_mixed(formulations[formulations.size() == 1 ? 0 : size_t(k)]);
    const double mu = mat.mu(), bulk = mat.lambda() + 2 * mu / 3;
    const int nl = int(ed.cps.size()), nd = nl * dim, nq = int(ed.JxW.size());
    std::vector<int> dof(static_cast<size_t>(nd));
    for (int a = 0; a < nl; ++a)
      for (int i = 0; i < dim; ++i) dof[size_t(a * dim + i)] = ed.cps[size_t(a)] * dim + i;
    Eigen::MatrixXd He = Eigen::MatrixXd::Zero(nd, nd);
    Eigen::MatrixXd tr(nq, nd);  // tr eps at each point, as a row on the element's dofs
    for (int q = 0; q < nq; ++q) {
      // eps_ij as rows: eps_ij = (dN_a/dX_j u_ai + dN_a/dX_i u_aj) / 2, 3 x 3 (plane strain: zz = 0)
      std::array<std::array<Eigen::RowVectorXd, 3>, 3> eps;
      for (auto& row : eps)
        for (auto& x : row) x = Eigen::RowVectorXd::Zero(nd);
      for (int a = 0; a < nl; ++a)
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j) {
            eps[i][j][a * dim + i] += ed.dN[size_t(q)](a, j) / 2;
            eps[j][i][a * dim + i] += ed.dN[size_t(q)](a, j) / 2;
          }
      const Eigen::RowVectorXd t = eps[0][0] + eps[1][1] + eps[2][2];
      tr.row(q) = t;
      const double w = ed.JxW[q];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const Eigen::RowVectorXd dev = i == j ? Eigen::RowVectorXd(eps[i][j] - t / 3) : eps[i][j];
          He += 2 * mu * w * dev.transpose() * dev;
        }
      if (!mixed) He += bulk * w * t.transpose() * t;
    }
    if (mixed) {
      const Eigen::RowVectorXd mean = ed.JxW.transpose() * tr / ed.JxW.sum();
      for (int q = 0; q < nq; ++q) He += mu * ed.JxW[q] * (tr.row(q) - mean).transpose() * (tr.row(q) - mean);
      for (int q = 0; q < nq; ++q) {
        double xi[3] = {0, 0, 0};
        for (int d = 0; d < ed.xi.cols(); ++d) xi[d] = ed.xi(q, d);
        space.values(e, xi, values, scratch);
        for (int i = 0; i < space.num_element_functions(e); ++i) {
          const size_t a = size_t(space.functions_begin(e)[i]);
          const double wN = ed.JxW[q] * values[size_t(i)];
          for (int c = 0; c < nd; ++c) function_g[a][dof[size_t(c)]] += wN * tr(q, c);
          function_mass[a] += wN;
          function_bulk[a] = bulk;
        }
      }
    }
    for (int r = 0; r < nd; ++r)
      for (int c = 0; c < nd; ++c) H(dof[size_t(r)], dof[size_t(c)]) += He(r, c);
  }
  for (size_t a = 0; a < n_functions; ++a)
    if (function_mass[a] > 0) H += function_bulk[a] / function_mass[a] * function_g[a] * function_g[a].transpose();
  return H;
}

// A patch with its control points moved by a smooth map (coincident points
// stay coincident, so an interface stays conforming).
NurbsPatch distorted(const NurbsPatch& patch, double shift_x) {
  std::vector<KnotVector> knots;
  for (int d = 0; d < patch.param_dim(); ++d) knots.push_back(patch.knots(d));
  Eigen::MatrixXd x = patch.points();
  for (int a = 0; a < x.rows(); ++a) {
    x(a, 0) += shift_x;
    const double X = x(a, 0), Y = x(a, 1);
    x(a, 0) += 0.08 * std::sin(2 * Y + X);
    x(a, 1) += 0.06 * std::cos(3 * X) * Y;
  }
  return NurbsPatch(std::move(knots), x, patch.weights());
}

// Checks the assembled K (free x free) and the lift f = -K_fp u_p of a
// prescribed value against the Hessian; `space` null: the formulations' own
// (mixed_pressure_space).
void expect_hessian(const Body& body, const std::vector<LinearElastic>& materials,
                    const std::vector<Formulation>& formulations, const PressureSpace* space, const char* what) {
  const int dim = body.space_dim();
  // the west side of patch 0 clamped in x, moved in y by 0.01
  const DofMap dofs(body, {{{PatchSide{0, Face{0, false}}}, 0, 0.0}, {{PatchSide{0, Face{0, false}}}, 1, 0.01}});
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  const PressureSpace own = mixed_pressure_space(quad, formulations);
  const PressureSpace& used = space ? *space : own;
  const LinearSystem s = space ? assemble_linear_elasticity(body, dofs, materials, Eigen::VectorXd::Zero(dim), {},
                                                            formulations, *space)
                               : assemble_linear_elasticity(body, dofs, materials, Eigen::VectorXd::Zero(dim), {},
                                                            formulations);
  const Eigen::MatrixXd H = energy_hessian(body, materials, formulations, used);
  const int n = dofs.num_dofs(), nf = dofs.num_free();
  Eigen::MatrixXd Hff = Eigen::MatrixXd::Zero(nf, nf);
  Eigen::VectorXd lift = Eigen::VectorXd::Zero(nf);
  for (int r = 0; r < n; ++r) {
    if (dofs.equation(r) < 0) continue;
    for (int c = 0; c < n; ++c) {
      if (dofs.equation(c) >= 0)
        Hff(dofs.equation(r), dofs.equation(c)) += H(r, c);
      else
        lift[dofs.equation(r)] -= H(r, c) * dofs.prescribed_value(c);
    }
  }
  const Eigen::MatrixXd K = Eigen::MatrixXd(s.K);
  EXPECT_LE((K - Hff).norm(), 1e-12 * Hff.norm()) << what;
  EXPECT_LE((s.f - lift).norm(), 1e-12 * lift.norm()) << what;
  EXPECT_GT(lift.norm(), 0.0) << what;
}

}  // namespace

TEST(VolumetricProjection, MixedStiffnessIsTheHessianOfTheEnergy) {
  const LinearElastic rubber{3.0, 0.4999}, steel{200.0, 0.3};
  // one rational patch of 5 x 5 elements: pressure spans of 2 and 3 elements,
  // linear C^0 pressure, 3 x 3 functions with overlapping supports
  const Body annulus(subdivide(elevate_to(quarter_annulus(1.0, 2.0).patch, 2), 5));
  {
    const BodyQuadrature quad(annulus, 3);
    const PressureSpace space = mixed_pressure_space(quad, {Formulation::mixed});
    ASSERT_EQ(space.num_functions(), 9);
    ASSERT_FALSE(space.disjoint());
    ASSERT_EQ(space.support_end(8) - space.support_begin(8), 9);  // the last span's 3 x 3 elements
  }
  expect_hessian(annulus, {rubber}, {Formulation::mixed}, nullptr, "annulus, sub-grid space");
  // two patches joined C0, the first mixed (5 x 5: odd), the second not
  const NurbsPatch square = subdivide(elevate_to(rectangle(1, 1).patch, 2), 5);
  const Body two({distorted(square, 0.0), distorted(square, 1.0)},
                 {PatchInterface{PatchSide{0, Face{0, true}}, PatchSide{1, Face{0, false}}}});
  ASSERT_LT(two.num_control_points(), 2 * square.num_control_points());  // joined
  expect_hessian(two, {rubber, steel}, {Formulation::mixed, Formulation::displacement}, nullptr,
                 "two patches, one mixed");
  // 3D: 5 x 5 x 5 elements, trilinear pressure on spans of 2 and 3
  const Body cube(distorted(subdivide(elevate_to(box(1, 1, 1).patch, 2), 5), 0.0));
  expect_hessian(cube, {rubber}, {Formulation::mixed}, nullptr, "3D box");
}

// Constants per element (mixed_element): the element projection Pi_e, with
// the element pattern; constants per 2 x 2 block (degree 0 on coarsened
// breakpoints: the blocks of before) through the same code.
TEST(VolumetricProjection, ConstantSpacesAreTheElementAndBlockProjections) {
  const LinearElastic rubber{3.0, 0.4999};
  const Body annulus(subdivide(elevate_to(quarter_annulus(1.0, 2.0).patch, 2), 5));
  const BodyQuadrature quad(annulus, 3);
  expect_hessian(annulus, {rubber}, {Formulation::mixed_element}, nullptr, "constants per element");
  const PressureSpace blocks(quad, {{0, 0, 0}}, {2});
  ASSERT_TRUE(blocks.disjoint());
  ASSERT_EQ(blocks.num_functions(), 4);
  expect_hessian(annulus, {rubber}, {Formulation::mixed}, &blocks, "constants per 2 x 2 block");
  const DofMap dofs(annulus, {});
  const LinearSystem element = assemble_linear_elasticity(annulus, dofs, rubber, Eigen::VectorXd::Zero(2), {},
                                                          Formulation::mixed_element);
  const LinearSystem sub_grid = assemble_linear_elasticity(annulus, dofs, rubber, Eigen::VectorXd::Zero(2), {},
                                                           Formulation::mixed);
  const LinearSystem disp = assemble_linear_elasticity(annulus, dofs, rubber, Eigen::VectorXd::Zero(2));
  EXPECT_EQ(element.K.nonZeros(), disp.K.nonZeros());
  EXPECT_GT(sub_grid.K.nonZeros(), disp.K.nonZeros());  // the pattern widened to the supports
}

// A distributed solve's element ranges: any cuts, even through supports; a
// range adds the functions whose first support element it holds, so the
// parts' matrices and loads sum to the whole.
TEST(VolumetricProjection, ElementRangesCutAnywhereSumToTheWhole) {
  const LinearElastic rubber{3.0, 0.4999};
  const Body annulus(subdivide(elevate_to(quarter_annulus(1.0, 2.0).patch, 2), 5));
  const DofMap dofs(annulus, {{{PatchSide{0, Face{0, false}}}, 1, 0.01}});
  const Eigen::Vector2d g(0.1, -0.2);
  for (Formulation formulation : {Formulation::mixed, Formulation::mixed_element}) {
    const LinearSystem whole = assemble_linear_elasticity(annulus, dofs, rubber, g, {}, formulation);
    Eigen::SparseMatrix<double> K(whole.K.rows(), whole.K.cols());
    Eigen::VectorXd f = Eigen::VectorXd::Zero(whole.f.size());
    // 5 x 5 elements, first direction fastest: 3 and 8 cut rows, 12 a support's middle
    for (const auto& [b, e] : {std::pair{0, 3}, std::pair{3, 8}, std::pair{8, 12}, std::pair{12, -1}}) {
      const LinearSystem part = assemble_linear_elasticity(annulus, dofs, rubber, g, {b, e}, formulation);
      K += part.K;
      f += part.f;
    }
    EXPECT_LE((Eigen::SparseMatrix<double>(K - whole.K)).norm(), 1e-13 * whole.K.norm())
        << formulation_name(formulation);
    EXPECT_LE((f - whole.f).norm(), 1e-13 * whole.f.norm()) << formulation_name(formulation);
  }
}

}  // namespace igac
