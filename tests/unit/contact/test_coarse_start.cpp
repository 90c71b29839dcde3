// SPDX-License-Identifier: BSD-3-Clause
// The start of the active-set iteration from the solution one mesh coarser
// (contact/coarse_start): the coarse multiplier field is reproduced on the
// fine face to round-off for p = 2 and 3 (checked at random face points),
// the predicted active set of 2D and 3D Hertz differs from the fine mesh's
// converged one only on the rim of the contact zone, and a solve started
// from it reaches the same solution in fewer active-set iterations.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "model/model.hpp"
#include "model/solve.hpp"
#include "contact/coarse_start.hpp"
#include "engine/linear_static.hpp"
#include "engine/prolongation.hpp"
#include "io/case_file.hpp"

namespace {

using namespace igac;

constexpr double kRoundOff = 1e-13;
// The prolongated coarse displacement against the fine solution: apart by
// the coarse mesh's discretisation error (measured: 0.4 % in 2D, 2.2 % in
// 3D, printed by the test).  5 % (was 10 %), a margin of 2.3 on the 3D value.
constexpr double kCoarseAgainstFine = 0.05;
// Two direct solves of the same discrete problem that end on the same
// active set: the same solution up to the round-off of their Schur solves.
constexpr double kSameSolution = 1e-10;

Model model_at(const std::string& file, int refine, std::vector<int> elements, int degree) {
  CaseSpec spec = read_case(std::string(IGAC_SOURCE_DIR) + "/" + file);
  spec.elements = std::move(elements);
  spec.refine = refine;
  spec.degree = degree;
  return build_model(spec);
}

std::vector<const ContactFace*> faces_of(const Model& m) {
  std::vector<const ContactFace*> out;
  for (const auto& c : m.contacts) out.push_back(c.face.get());
  return out;
}

// sum_K lambda_K B_K at parameter xi of side `side` of the face.
double field(const ContactFace& f, const Eigen::VectorXd& lambda, int side, const Eigen::VectorXd& xi) {
  std::vector<int> idx;
  std::vector<double> val;
  const ContactSide& s = f.sides[side];
  s.space.basis(xi, idx, val);
  double v = 0;
  for (size_t j = 0; j < idx.size(); ++j) v += lambda[s.first_multiplier + idx[j]] * val[j];
  return v;
}

// Largest difference between a random coarse multiplier field and its
// prolongation, over random points of every side, relative to its size.
double multiplier_field_difference(const Model& coarse, const Model& fine) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::VectorXd lc(coarse.num_multipliers());
  for (auto& v : lc) v = unit(gen) - 0.5;
  const Eigen::VectorXd lf = prolongated_multipliers(faces_of(coarse), faces_of(fine), lc);
  EXPECT_EQ(lf.size(), fine.num_multipliers());
  const ContactFace &cf = *coarse.contacts.front().face, &ff = *fine.contacts.front().face;
  double worst = 0;
  for (int side = 0; side < int(ff.sides.size()); ++side) {
    const int d = int(ff.sides[side].space.knots().size());
    for (int s = 0; s < 300; ++s) {
      Eigen::VectorXd xi(d);
      for (int k = 0; k < d; ++k) xi[k] = unit(gen);
      worst = std::max(worst, std::abs(field(cf, lc, side, xi) - field(ff, lf, side, xi)));
    }
  }
  return worst / lc.cwiseAbs().maxCoeff();
}

TEST(ProlongatedMultipliers, ReproduceTheCoarseFieldForDegreesTwoAndThree) {
  for (int p : {2, 3}) {
    EXPECT_LT(multiplier_field_difference(model_at("cases/hertz2d.toml", 0, {8, 2}, p),
                                          model_at("cases/hertz2d.toml", 1, {8, 2}, p)),
              kRoundOff)
        << "2D, p = " << p;
    EXPECT_LT(multiplier_field_difference(model_at("cases/hertz3d_study.toml", 0, {4, 2, 4}, p),
                                          model_at("cases/hertz3d_study.toml", 1, {4, 2, 4}, p)),
              kRoundOff)
        << "3D, p = " << p;
  }
}

TEST(ProlongatedMultipliers, RefuseMultipliersOfAnotherMesh) {
  const Model c = model_at("cases/hertz2d.toml", 0, {8, 2}, 2), f = model_at("cases/hertz2d.toml", 1, {8, 2}, 2);
  EXPECT_THROW(prolongated_multipliers(faces_of(c), faces_of(f), Eigen::VectorXd::Zero(f.num_multipliers())),
               std::invalid_argument);
  EXPECT_THROW(prolongated_multipliers(faces_of(c), {}, Eigen::VectorXd::Zero(c.num_multipliers())),
               std::invalid_argument);
}

// The coarse solution's prediction against the fine solution (both solved
// directly): the same multipliers active but for a few on the rim of the
// contact zone, where the coarse mesh cannot tell.
void expect_start_near_the_fine_solution(const std::string& file, std::vector<int> elements, int refine,
                                         int at_most_differ) {
  const Model coarse = model_at(file, refine - 1, elements, 2), fine = model_at(file, refine, elements, 2);
  const RunResult rc = solve_model(coarse), rf = solve_model(fine);
  ASSERT_TRUE(rc.contact && rf.contact);
  ASSERT_TRUE(rc.contact->solution.converged && rf.contact->solution.converged);
  const auto P = prolongation(coarse.body, *coarse.dofs, fine.body, *fine.dofs);
  const RigidModes modes = free_rigid_modes(fine.body, *fine.dofs);
  const double cn = fine.spec.E / fine.mesh_size;
  const ActiveSetStart s = start_from_coarse(faces_of(coarse), faces_of(fine), P, rc.contact->solution,
                                             rf.contact->op, int(modes.modes.cols()), cn);
  const std::vector<char>& want = rf.contact->solution.active;
  ASSERT_EQ(s.active.size(), want.size());
  int differ = 0, active = 0;
  for (size_t K = 0; K < want.size(); ++K) {
    differ += s.active[K] != want[K];
    active += want[K];
  }
  EXPECT_LE(differ, at_most_differ) << file << ": " << differ << " of " << active << " active multipliers differ";
  EXPECT_GT(active, 4 * at_most_differ) << file;  // the zone is resolved: the rim is a small part of it
  // The first guess is the coarse solution itself: close to the fine one.
  const Eigen::VectorXd& uf = rf.contact->solution.u;
  std::printf("%s: coarse start against the fine solution %.3g relative\n", file.c_str(), (s.u - uf).norm() / uf.norm());
  EXPECT_LT((s.u - uf).norm(), kCoarseAgainstFine * uf.norm()) << file;
}

TEST(CoarseStart, PredictsTheFineActiveSetButForItsRim) {
  // Measured: 0 of 30 (2D) and 0 of 20 (3D) differ; 2 of 79 on the 3D
  // study's level 2 (too slow for a test).
  expect_start_near_the_fine_solution("cases/hertz2d.toml", {16, 4}, 2, 2);
  expect_start_near_the_fine_solution("cases/hertz3d_study.toml", {4, 2, 4}, 2, 3);
}

// The direct path takes the start when it is at hand (a study's previous
// level, solve_model's CoarserRun): the same solution in fewer active-set
// iterations than from the closed gaps.
TEST(CoarseStart, AStudyLevelStartsFromTheLevelBelow) {
  const Model coarse = model_at("cases/hertz2d.toml", 1, {16, 4}, 2), fine = model_at("cases/hertz2d.toml", 2, {16, 4}, 2);
  const RunResult rc = solve_model(coarse);
  RunControl from_coarse;
  from_coarse.coarser = CoarserRun{&coarse, &rc};
  const RunResult plain = solve_model(fine), nested = solve_model(fine, from_coarse);
  ASSERT_TRUE(plain.contact && nested.contact);
  ASSERT_EQ(nested.status, "converged");
  const auto& p = plain.contact->solution;
  const auto& n = nested.contact->solution;
  EXPECT_LE(n.active_set_sizes.size(), 2u);
  EXPECT_LT(n.active_set_sizes.size(), p.active_set_sizes.size());
  EXPECT_EQ(n.active, p.active);
  EXPECT_LT((n.u - p.u).norm(), kSameSolution * p.u.norm());
}

}  // namespace
