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
// 30 %).  The same number from the small-strain B-bar stiffness and from the
// large-deformation tangent at rest (Mooney-Rivlin, Neo-Hookean), 2D and 3D.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/assembly.hpp"
#include "engine/pressure_blocks.hpp"
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
                                                         Eigen::VectorXd::Zero(dim), {}, Formulation::mixed);
    EXPECT_NEAR(u.dot(bbar.K * u), expected, kRoundoff * bulk) << dim << "D, small strain";
    const LinearSystem plain = assemble_linear_elasticity(patch, dofs, LinearElastic{E, nu}, Eigen::VectorXd::Zero(dim));
    EXPECT_GT(u.dot(plain.K * u), 100 * expected) << dim << "D: the displacement formulation sees it with K";
    // large deformation, the tangent at rest
    const MaterialParameters mooney{NAN, NAN, {{"C10", 0.37}, {"C01", 0.11}, {"bulk_modulus", bulk}}};
    const MaterialParameters neo{E, nu, {}};
    for (const auto& [name, parameters] : {std::pair{"mooney_rivlin", mooney}, std::pair{"neo_hookean", neo}}) {
      const auto law = make_law(name, parameters);
      EXPECT_NEAR(stabilisation_modulus(*law, dim), mu, 1e-12 * mu) << name;
      const TotalLagrangianAssembler tl(patch, dofs, *law, Formulation::mixed);
      Eigen::VectorXd f;
      Eigen::SparseMatrix<double> K;
      ASSERT_TRUE(tl.assemble(Eigen::MatrixXd::Zero(patch.num_control_points(), dim), f, &K));
      EXPECT_NEAR(u.dot(K * u), expected, kRoundoff * bulk) << dim << "D, " << name;
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
// The small-strain mixed stiffness with one pressure per block
// (assemble_linear_elasticity, pressure_blocks.hpp) against the Hessian of
// its discrete energy, computed here point by point on every dof:
//   E(u) = int mu |dev eps|^2 dX                         (3D deviator)
//        + sum_b K / 2 (int_b tr eps)^2 / V_b            (K V_b (Pi_b tr eps)^2 / 2)
//        + sum_e mu / 2 int_e (tr eps - Pi_e tr eps)^2   (the stabilisation)
// on mixed patches, int mu |dev eps|^2 + K / 2 (tr eps)^2 on the others.
// Width 1 is the element-constant formulation of before the blocks.

namespace {

// The Hessian of E on all dofs (n_cp dim x n_cp dim), dense.
Eigen::MatrixXd energy_hessian(const Body& body, const std::vector<LinearElastic>& materials,
                               const std::vector<Formulation>& formulations, const ElementBlocks& blocks) {
  const int dim = body.space_dim(), n = body.num_control_points() * dim;
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  std::vector<Eigen::VectorXd> block_g(size_t(blocks.num_blocks()), Eigen::VectorXd::Zero(n));
  std::vector<double> block_volume(size_t(blocks.num_blocks()), 0.0);
  std::vector<double> block_bulk(size_t(blocks.num_blocks()), 0.0);
  ElementData ed;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, true);
    const int k = quad.patch_of(e);
    const LinearElastic& mat = materials[materials.size() == 1 ? 0 : size_t(k)];
    const bool mixed = formulations[formulations.size() == 1 ? 0 : size_t(k)] == Formulation::mixed;
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
      const size_t b = size_t(blocks.block_of[size_t(e)]);
      const Eigen::RowVectorXd ge = ed.JxW.transpose() * tr;
      for (int c = 0; c < nd; ++c) block_g[b][dof[size_t(c)]] += ge[c];
      block_volume[b] += ed.JxW.sum();
      block_bulk[b] = bulk;
    }
    for (int r = 0; r < nd; ++r)
      for (int c = 0; c < nd; ++c) H(dof[size_t(r)], dof[size_t(c)]) += He(r, c);
  }
  for (size_t b = 0; b < block_g.size(); ++b)
    if (block_volume[b] > 0) H += block_bulk[b] / block_volume[b] * block_g[b] * block_g[b].transpose();
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
// prescribed value against the Hessian.
void expect_hessian(const Body& body, const std::vector<LinearElastic>& materials,
                    const std::vector<Formulation>& formulations, const ElementBlocks* blocks, const char* what) {
  const int dim = body.space_dim();
  // the west side of patch 0 clamped in x, moved in y by 0.01
  const DofMap dofs(body, {{{PatchSide{0, Face{0, false}}}, 0, 0.0}, {{PatchSide{0, Face{0, false}}}, 1, 0.01}});
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  const ElementBlocks own = mixed_pressure_blocks(quad, formulations);
  const ElementBlocks& used = blocks ? *blocks : own;
  const LinearSystem s = blocks ? assemble_linear_elasticity(body, dofs, materials, Eigen::VectorXd::Zero(dim), {},
                                                             formulations, *blocks)
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

TEST(VolumetricProjection, BlockStiffnessIsTheHessianOfTheBlockEnergy) {
  const LinearElastic rubber{3.0, 0.4999}, steel{200.0, 0.3};
  // one rational patch of 5 x 5 elements: blocks of 2 x 2, 2 x 3, 3 x 2, 3 x 3
  const Body annulus(subdivide(elevate_to(quarter_annulus(1.0, 2.0).patch, 2), 5));
  {
    const BodyQuadrature quad(annulus, 3);
    const ElementBlocks blocks = mixed_pressure_blocks(quad, {Formulation::mixed});
    ASSERT_EQ(blocks.num_blocks(), 4);
    ASSERT_EQ(blocks.start[4] - blocks.start[3], 9);
  }
  expect_hessian(annulus, {rubber}, {Formulation::mixed}, nullptr, "annulus, 2 x 2 blocks");
  // two patches joined C0, the first mixed (5 x 5: odd), the second not
  const NurbsPatch square = subdivide(elevate_to(rectangle(1, 1).patch, 2), 5);
  const Body two({distorted(square, 0.0), distorted(square, 1.0)},
                 {PatchInterface{PatchSide{0, Face{0, true}}, PatchSide{1, Face{0, false}}}});
  ASSERT_LT(two.num_control_points(), 2 * square.num_control_points());  // joined
  expect_hessian(two, {rubber, steel}, {Formulation::mixed, Formulation::displacement}, nullptr,
                 "two patches, one mixed");
  // 3D: 4 x 4 x 4 elements, 8 blocks of 8
  const Body cube(distorted(subdivide(elevate_to(box(1, 1, 1).patch, 2), 4), 0.0));
  expect_hessian(cube, {rubber}, {Formulation::mixed}, nullptr, "3D box");
}

// Blocks of one element: the element-constant formulation of before the
// blocks (the Hessian with Pi_e for Pi_b), and its pattern is the element's.
TEST(VolumetricProjection, BlocksOfOneElementAreTheElementProjection) {
  const LinearElastic rubber{3.0, 0.4999};
  const Body annulus(subdivide(elevate_to(quarter_annulus(1.0, 2.0).patch, 2), 5));
  const BodyQuadrature quad(annulus, 3);
  const ElementBlocks ones = block_elements(quad, {1});
  expect_hessian(annulus, {rubber}, {Formulation::mixed}, &ones, "width 1");
  const DofMap dofs(annulus, {});
  const LinearSystem one = assemble_linear_elasticity(annulus, dofs, {rubber}, Eigen::VectorXd::Zero(2), {},
                                                      {Formulation::mixed}, ones);
  const LinearSystem two = assemble_linear_elasticity(annulus, dofs, rubber, Eigen::VectorXd::Zero(2), {},
                                                      Formulation::mixed);
  const LinearSystem disp = assemble_linear_elasticity(annulus, dofs, rubber, Eigen::VectorXd::Zero(2));
  EXPECT_EQ(one.K.nonZeros(), disp.K.nonZeros());
  EXPECT_GT(two.K.nonZeros(), disp.K.nonZeros());  // the pattern widened to the blocks
}

// A distributed solve's element ranges (whole_blocks): the cuts move to
// the next cut between blocks, the parts' matrices and loads sum to the
// whole, and a range that splits a block is refused.
TEST(VolumetricProjection, ElementRangesHoldWholeBlocks) {
  const LinearElastic rubber{3.0, 0.4999};
  const Body annulus(subdivide(elevate_to(quarter_annulus(1.0, 2.0).patch, 2), 5));
  const BodyQuadrature quad(annulus, 3);
  const ElementBlocks blocks = mixed_pressure_blocks(quad, {Formulation::mixed});
  // 5 x 5 elements, first direction fastest: blocks of rows 0-1 (elements 0 ... 9) and rows 2-4
  EXPECT_EQ(whole_blocks(blocks, {0, 3}).end, 10);
  EXPECT_EQ(whole_blocks(blocks, {3, 12}).begin, 10);
  EXPECT_EQ(whole_blocks(blocks, {3, 12}).end, 25);
  EXPECT_EQ(whole_blocks(blocks, {10, -1}).begin, 10);
  EXPECT_EQ(whole_blocks(blocks, {10, -1}).end, -1);
  const DofMap dofs(annulus, {{{PatchSide{0, Face{0, false}}}, 1, 0.01}});
  const Eigen::Vector2d g(0.1, -0.2);
  const LinearSystem whole = assemble_linear_elasticity(annulus, dofs, rubber, g, {}, Formulation::mixed);
  Eigen::SparseMatrix<double> K(whole.K.rows(), whole.K.cols());
  Eigen::VectorXd f = Eigen::VectorXd::Zero(whole.f.size());
  for (const auto& [b, e] : {std::pair{0, 8}, std::pair{8, -1}}) {
    const ElementRange r = whole_blocks(blocks, {b, e});
    const LinearSystem part = assemble_linear_elasticity(annulus, dofs, rubber, g, r, Formulation::mixed);
    K += part.K;
    f += part.f;
  }
  EXPECT_LE((Eigen::SparseMatrix<double>(K - whole.K)).norm(), 1e-13 * whole.K.norm());
  EXPECT_LE((f - whole.f).norm(), 1e-13 * whole.f.norm());
  EXPECT_THROW(assemble_linear_elasticity(annulus, dofs, rubber, g, {0, 8}, Formulation::mixed), std::logic_error);
}

}  // namespace igac
