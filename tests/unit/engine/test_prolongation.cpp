// SPDX-License-Identifier: BSD-3-Clause
// The prolongation between nested discretisations (engine/prolongation):
// a coarse displacement and its prolongation are the same function (checked
// at random points of every patch, to round-off), on the graded sphere
// octant (NURBS, Dirichlet faces eliminated), on a two-patch quarter disc
// (a shared interface) and on every level of 2D Hertz's graded mesh up to
// the one where its multigrid is slow (docs/petsc.md); between a mesh and itself it is the identity (also
// where the octant's degenerate edge ties coincident points to one equation).
#include <gtest/gtest.h>

#include <random>

#include "model/model.hpp"
#include "engine/prolongation.hpp"
#include "io/case_file.hpp"

namespace {

using namespace igac;

// Knot insertion is exact: the two evaluations differ by round-off only.
constexpr double kRoundOff = 1e-12;

Model model_at(const std::string& file, int refine, std::vector<int> elements) {
  CaseSpec spec = read_case(std::string(IGAC_SOURCE_DIR) + "/" + file);
  spec.elements = std::move(elements);
  spec.refine = refine;
  return build_model(spec);
}

// Largest difference, over random points of every patch, between the coarse
// field u_c and the fine field P u_c (relative to the field's size).
double largest_difference(const Model& coarse, const Model& fine) {
  const auto P = prolongation(coarse.body, *coarse.dofs, fine.body, *fine.dofs);
  EXPECT_EQ(P.rows(), fine.dofs->num_free());
  EXPECT_EQ(P.cols(), coarse.dofs->num_free());
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd uc(coarse.dofs->num_free());
  for (auto& v : uc) v = unit(gen) - 0.5;
  const Eigen::VectorXd uf = P * uc;
  const Eigen::MatrixXd Uc = coarse.dofs->expand(uc), Uf = fine.dofs->expand(uf);
  double worst = 0;
  for (int k = 0; k < fine.body.num_patches(); ++k) {
    const NurbsPatch& p = fine.body.patch(k);
    const Eigen::MatrixXd ck = coarse.body.patch_field(k, Uc), fk = fine.body.patch_field(k, Uf);
    for (int s = 0; s < 200; ++s) {
      Eigen::VectorXd xi(p.param_dim());
      for (int d = 0; d < p.param_dim(); ++d) xi[d] = p.knots(d).first() + unit(gen) * (p.knots(d).last() - p.knots(d).first());
      worst = std::max(worst, (coarse.body.patch(k).field(ck, xi) - p.field(fk, xi)).norm());
    }
  }
  return worst;
}

TEST(Prolongation, ReproducesACoarseFieldOnTheGradedSphereOctant) {
  const Model c = model_at("cases/hertz3d_study.toml", 0, {4, 2, 4});
  const Model f = model_at("cases/hertz3d_study.toml", 1, {4, 2, 4});
  ASSERT_GT(f.dofs->num_free(), 4 * c.dofs->num_free());
  EXPECT_LT(largest_difference(c, f), kRoundOff);
}

TEST(Prolongation, ReproducesACoarseFieldAcrossTwoRefinementsAndTwoPatches) {
  const Model c = model_at("cases/hertz2d_two_patches.toml", 0, {4, 4});
  const Model f = model_at("cases/hertz2d_two_patches.toml", 2, {4, 4});
  ASSERT_EQ(f.body.num_patches(), 2);
  EXPECT_LT(largest_difference(c, f), kRoundOff);
}

TEST(Prolongation, ReproducesACoarseFieldOnEveryLevelOfTheGradedHertz2d) {
  for (int r = 1; r <= 3; ++r) {
    const Model c = model_at("cases/hertz2d.toml", r - 1, {64, 16});
    const Model f = model_at("cases/hertz2d.toml", r, {64, 16});
    EXPECT_LT(largest_difference(c, f), kRoundOff) << "refine " << r;
  }
}

TEST(Prolongation, IsTheIdentityWhereNothingIsRefined) {
  const Model m = model_at("cases/hertz3d_study.toml", 0, {4, 2, 4});
  const Eigen::SparseMatrix<double, Eigen::RowMajor> P = prolongation(m.body, *m.dofs, m.body, *m.dofs);
  Eigen::SparseMatrix<double, Eigen::RowMajor> I(P.rows(), P.cols());
  I.setIdentity();
  EXPECT_EQ(P.nonZeros(), P.rows());
  EXPECT_LT((P - I).norm(), kRoundOff);
}

TEST(Prolongation, RefusesBodiesThatAreNotNested) {
  const Model a = model_at("cases/hertz3d_study.toml", 0, {4, 2, 4});
  const Model b = model_at("cases/hertz3d_study.toml", 0, {3, 2, 4});
  EXPECT_THROW(prolongation(a.body, *a.dofs, b.body, *b.dofs), SplineError);
}

}  // namespace
