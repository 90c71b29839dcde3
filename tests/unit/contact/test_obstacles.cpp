// SPDX-License-Identifier: BSD-3-Clause
// Obstacles (contact/obstacle.hpp, one file per type under contact/obstacles/):
// the registry, the cylinder's gap and normal against finite differences, a
// rigid plate that moves onto a block (small and large deformation) with its
// reaction against the closed form, and bad obstacle keys.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>
#include <string>

#include "contact/obstacle.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;
const std::string kSource = IGAC_SOURCE_DIR;

TEST(ObstacleRegistry, ListsEveryTypeOnceAndFindsIt) {
  std::vector<std::string> names;
  for (const ObstacleType* t : obstacle_types()) names.emplace_back(t->name);
  EXPECT_EQ(names, (std::vector<std::string>{"plane", "sphere", "cylinder", "edge"}));
  for (const auto& n : names) EXPECT_EQ(find_obstacle_type(n)->name, n);
  EXPECT_EQ(find_obstacle_type("torus"), nullptr);
}

TEST(ObstacleCylinder, GapNormalAndNormalDerivativeMatchFiniteDifferences) {
  const RigidCylinder roller(Eigen::Vector3d(0.2, -0.1, 1.5), Eigen::Vector3d(1.0, 0.5, 0.2), 0.7);
  const Eigen::Vector3d x(0.9, 0.4, 0.3);
  const ObstacleProbe p = roller.probe(x, true);
  const Eigen::Vector3d a = Eigen::Vector3d(1.0, 0.5, 0.2).normalized();
  EXPECT_NEAR(p.normal.norm(), 1.0, 1e-15);
  EXPECT_NEAR(p.normal.dot(a), 0.0, 1e-15) << "the normal is radial";
  const double h = 1e-6;
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[j] = h;
    const ObstacleProbe pp = roller.probe(x + e), pm = roller.probe(x - e);
    EXPECT_NEAR((pp.gap - pm.gap) / (2 * h), p.normal[j], 1e-9) << "dg/dx = n";
    const Eigen::Vector3d dn = (pp.normal - pm.normal) / (2 * h);
    EXPECT_LE((dn - p.normal_derivative.col(j)).norm(), 1e-8) << "dn/dx column " << j;
  }
  // A point at distance r from the axis: gap r - R.
  const Eigen::Vector3d on_axis = Eigen::Vector3d(0.2, -0.1, 1.5) + 2.0 * a;
  Eigen::Vector3d radial = a.cross(Eigen::Vector3d::UnitZ()).normalized();
  EXPECT_NEAR(roller.probe(on_axis + 1.2 * radial).gap, 0.5, 1e-14);
}

TEST(ObstacleTranslated, MovesTheGapAndKeepsTheNormal) {
  const RigidPlane floor(Eigen::Vector2d(0, 0), Eigen::Vector2d(0, 1));
  const TranslatedObstacle lifted(floor, Eigen::Vector2d(0.3, 0.1));
  const Eigen::Vector2d x(0.5, 0.4);
  EXPECT_NEAR(lifted.probe(x).gap, 0.3, 1e-15);
  EXPECT_EQ(lifted.probe(x).normal, floor.probe(x).normal);
}

// The contact patch-test block (tests/data/contact_flat_block.toml) held on
// top (u_y = 0) and pushed by the plate below, which moves up by delta: the
// uniform plane-strain compression sigma_yy = -E / (1 - nu^2) delta / H, so
// the reaction is that times the width, to round-off in small deformation.
CaseSpec block_squeezed_by_moving_plate(double delta, const std::string& model) {
  CaseSpec spec = read_case(kSource + "/tests/data/contact_flat_block.toml");
  spec.pressure.clear();
  spec.dirichlet.push_back({{"top"}, 1, 0.0});
  spec.contacts.at(0).obstacle.motion = {0.0, delta};
  if (model != "linear_elastic") {
    spec.model = model;
    spec.loading.steps = 2;
  }
  return spec;
}

TEST(MovingObstacle, PlateMovingOntoABlockGivesTheClosedFormReaction) {
  const double delta = 0.01, E = 1, nu = 0.3, H = 0.5, W = 1.0;
  const double reaction = E / (1 - nu * nu) * delta / H * W;
  Model m = build_model(block_squeezed_by_moving_plate(delta, "linear_elastic"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  EXPECT_NEAR(r.contacts.front().report.total_force / reaction, 1.0, 1e-10);
  // The reaction is the sum of the contact pressures: -sum_K lambda_K K_K.
  const double sum = -r.contact->solution.lambda.dot(r.contact->op.weights);
  EXPECT_NEAR(sum / reaction, 1.0, 1e-10);
  // Every multiplier carries the same pressure.
  for (int K = 0; K < r.contact->solution.lambda.size(); ++K)
    EXPECT_NEAR(-r.contact->solution.lambda[K], reaction / W, 1e-10 * reaction);
}

TEST(MovingObstacle, LargeDeformationRampsTheMotionWithTheLoad) {
  // A small motion: Neo-Hookean agrees with the closed form of the linear solid.
  const double delta = 1e-4, E = 1, nu = 0.3, H = 0.5, W = 1.0;
  const double reaction = E / (1 - nu * nu) * delta / H * W;
  Model m = build_model(block_squeezed_by_moving_plate(delta, "neo_hookean"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  EXPECT_NEAR(r.contacts.front().report.total_force / reaction, 1.0, 1e-3);
  ASSERT_FALSE(r.load_curve.empty());
  EXPECT_NEAR(r.load_curve.back().obstacle_displacement, delta, 1e-15);
  // The load curve rises with the motion.
  for (size_t i = 1; i < r.load_curve.size(); ++i)
    EXPECT_GT(r.load_curve[i].contact_force(), r.load_curve[i - 1].contact_force());
}

TEST(MovingObstacle, ShippedORingConverges) {
  Model m = build_model(read_case(kSource + "/cases/oring.toml"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  EXPECT_GT(r.contacts.front().report.total_force, 0.0);
  int cut_backs = 0;
  for (const auto& st : r.load_steps->steps) cut_backs += st.cut_backs;
  EXPECT_EQ(cut_backs, 0);
  EXPECT_NEAR(r.load_curve.back().obstacle_displacement, 0.25 * 5.33 / 2, 1e-12);
}

// The block between two plates: the fixed one below (the patch test's) and a
// second one above that moves down by delta; nothing else holds it
// vertically.  The two obstacles' forces balance, and equal the closed form.
CaseSpec block_between_two_plates(double delta, const std::string& model) {
  CaseSpec spec = read_case(kSource + "/tests/data/contact_flat_block.toml");
  spec.pressure.clear();
  ContactSpec top;
  top.face = "top";
  top.obstacle.type = "plane";
  top.obstacle.values = {{"point", {0.0, 0.5}}, {"normal", {0.0, -1.0}}};
  top.obstacle.motion = {0.0, -delta};
  spec.contacts.push_back(top);
  if (model != "linear_elastic") {
    spec.model = model;
    spec.loading.steps = 2;
  }
  return spec;
}

TEST(SeveralObstacles, TwoPlatesOnOneBlockBalance) {
  const double delta = 0.01, E = 1, nu = 0.3, H = 0.5, W = 1.0;
  const double closed_form = E / (1 - nu * nu) * delta / H * W;
  Model m = build_model(block_between_two_plates(delta, "linear_elastic"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  ASSERT_EQ(r.reactions.size(), 2u);
  EXPECT_EQ(r.reactions[0].face, "bottom");
  EXPECT_EQ(r.reactions[1].face, "top");
  EXPECT_NEAR(r.reactions[0].normal_force / r.reactions[1].normal_force, 1.0, 1e-10) << "the plates balance";
  EXPECT_NEAR(r.reactions[1].normal_force / closed_form, 1.0, 1e-10);
  EXPECT_EQ(m.num_multipliers(), int(r.contact->solution.lambda.size()));
}

TEST(SeveralObstacles, TwoPlatesBalanceInLargeDeformation) {
  const double delta = 0.02;
  Model m = build_model(block_between_two_plates(delta, "neo_hookean"));
  const RunResult r = solve_model(m, quiet_run());
  ASSERT_EQ(r.status, "converged");
  ASSERT_EQ(r.reactions.size(), 2u);
  EXPECT_GT(r.reactions[0].normal_force, 0.0);
  EXPECT_NEAR(r.reactions[0].normal_force / r.reactions[1].normal_force, 1.0, 1e-8) << "the plates balance";
}

TEST(SeveralObstacles, SummaryListsEveryObstacle) {
  igac_test::TempDir tmp("two");
  std::string s = igac_test::read_file(kSource + "/tests/data/contact_flat_block.toml");
  // [contact] -> [[contact]] twice; the pressure replaced by the upper plate's motion.
  s.replace(s.find("[contact]\n"), 10, "[[contact]]\n");
  s.replace(s.find("[[pressure]]"), std::string("[[pressure]]\nfaces = [\"top\"]\nvalue = 0.01\n").size(), "");
  s.replace(s.find("[reference]"), 11,
            "[[contact]]\nface = \"top\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [0.0, 0.5]\n"
            "normal = [0.0, -1.0]\nmotion = [0.0, -0.01]\n\n[reference]");
  std::ofstream(tmp.path() / "two.toml") << s;
  const auto o = igac_test::run_igac("run two.toml --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output << s;
  EXPECT_NE(o.output.find("contact       face 'top'"), std::string::npos) << o.output;  // a block per contact
  std::ifstream js(tmp.path() / "out" / "summary.json");
  const auto j = nlohmann::json::parse(js);
  ASSERT_EQ(j["obstacles"].size(), 2u);
  EXPECT_NEAR(j["obstacles"][0]["normal_force"].get<double>() / j["obstacles"][1]["normal_force"].get<double>(), 1.0,
              1e-10);
}

struct BadObstacle {
  std::string name, obstacle;
  std::vector<std::string> fragments;
};
void PrintTo(const BadObstacle& b, std::ostream* os) { *os << b.name; }
class ObstacleBadInput : public ::testing::TestWithParam<BadObstacle> {};

TEST_P(ObstacleBadInput, OneLineNamingTheKey) {
  igac_test::TempDir tmp("obst");
  std::string s = igac_test::read_file(kSource + "/cases/hertz2d.toml");
  const auto a = s.find("[contact.obstacle]"), b = s.find("[reference]");
  s.replace(a, b - a, "[contact.obstacle]\n" + GetParam().obstacle + "\n\n");
  std::ofstream(tmp.path() / "c.toml") << s;
  const auto o = igac_test::run_igac("run c.toml", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  for (const auto& f : GetParam().fragments) EXPECT_NE(o.output.find(f), std::string::npos) << f << " in " << o.output;
}

INSTANTIATE_TEST_SUITE_P(
    Obstacle, ObstacleBadInput,
    ::testing::Values(
        BadObstacle{"unknown_type", "type = \"torus\"", {"[contact.obstacle] type:", "plane, sphere, cylinder, edge"}},
        BadObstacle{"cylinder_in_2d", "type = \"cylinder\"\npoint = [0, 0]\naxis = [0, 1]\nradius = 1",
                    {"[contact.obstacle] type:", "3D body"}},
        BadObstacle{"zero_normal", "type = \"plane\"\npoint = [0, -1]\nnormal = [0, 0]", {"[contact.obstacle] normal:", "zero"}},
        BadObstacle{"edge_parallel_normals",
                    "type = \"edge\"\npoint = [0, -1]\nnormal = [0, 1]\nsecond_normal = [0, -2]\nradius = 0.1",
                    {"[contact.obstacle]", "parallel"}},
        BadObstacle{"sphere_radius", "type = \"sphere\"\ncentre = [0, -3]\nradius = -1",
                    {"[contact.obstacle] radius:", "positive"}},
        BadObstacle{"key_of_another_type", "type = \"plane\"\npoint = [0, -1]\nnormal = [0, 1]\nradius = 2",
                    {"[contact.obstacle] radius: unknown key", "normal"}},
        BadObstacle{"motion_length", "type = \"plane\"\npoint = [0, -1]\nnormal = [0, 1]\nmotion = [0, 1, 2]",
                    {"[contact.obstacle] motion:"}}),
    [](const ::testing::TestParamInfo<BadObstacle>& info) { return info.param.name; });

}  // namespace
}  // namespace igac
