// SPDX-License-Identifier: BSD-3-Clause
// The restart state file (io/state_file.hpp): what is written is read back
// bit for bit (the friction and incompressible histories too), and a file
// that is not one (cut short, another magic) or of an older version (3:
// the mixed formulation's values per element, not per pressure block) is an
// InputError naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/state_file.hpp"

namespace igac {
namespace {

// Reading `path` is refused in one InputError naming it and saying `why`.
void expect_refused(const std::string& path, const std::string& why) {
  StateOrigin origin;
  try {
    read_state_file(path, origin);
    ADD_FAILURE() << path << " was read (expected: " << why << ")";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": not a state file igac can restart from (" + why + ")"),
              std::string::npos)
        << e.what();
  }
}

TEST(StateFile, RoundTripIsBitForBit) {
  StepState s;
  s.step = 7;
  s.driver = {1.25, 0.1 / 3, 0.0625, Eigen::VectorXd::LinSpaced(5, -1.0 / 3, 2.0 / 7), Eigen::VectorXd::Random(5)};
  s.record = {1.25, 4, {1.0, 1e-3 / 3, 2.2e-14}, {3, 4, 4, 4}, 2};
  s.point.load_factor = 1.25;
  s.point.contact_forces = {0.1 / 7, 2.0 / 3};
  s.point.face_displacement = -1e-3 / 9;
  s.point.obstacle_displacement = 0.3;
  s.point.dirichlet_reactions = {{"left", Eigen::Vector2d(1.0 / 3, 0.0)}, {"mid plane", Eigen::Vector2d(0.0, -5.5)}};
  s.point.tangential_forces = {Eigen::Vector2d(0.1 / 3, -2.0 / 7)};
  s.record.augmentations = 3;
  s.friction.position = Eigen::VectorXd::Random(4);
  s.friction.slip = Eigen::VectorXd::Random(4) / 3;
  s.friction.direction = Eigen::VectorXd::Random(4);
  s.friction.alpha = Eigen::VectorXd::Random(2);
  s.friction.state = {kStick, kSlip};
  s.friction.schur_batches = {{0, 3}, {1}};
  s.friction.from = 0.7;
  s.pressure_multipliers = Eigen::VectorXd::Random(6) * 1e3 / 7;
  const auto path = (std::filesystem::temp_directory_path() / "igac_test_state_0007.bin").string();
  write_state_file(path, {"0123456789abcdef", "refine=1\ndegree=3\n"}, s);
  StateOrigin hash;
  const StepState r = read_state_file(path, hash);
  EXPECT_EQ(hash.case_hash, "0123456789abcdef");
  EXPECT_EQ(hash.options, "refine=1\ndegree=3\n");
  EXPECT_EQ(r.step, 7);
  EXPECT_EQ(r.driver.t, s.driver.t);
  EXPECT_EQ(r.driver.dt, s.driver.dt);
  EXPECT_EQ(r.driver.dt_old, s.driver.dt_old);
  EXPECT_EQ(r.driver.x, s.driver.x);
  EXPECT_EQ(r.driver.x_old, s.driver.x_old);
  EXPECT_EQ(r.record.residual_norms, s.record.residual_norms);
  EXPECT_EQ(r.record.active_set_sizes, s.record.active_set_sizes);
  EXPECT_EQ(r.record.newton_iterations, 4);
  EXPECT_EQ(r.record.cut_backs, 2);
  EXPECT_EQ(r.point.contact_forces, s.point.contact_forces);
  EXPECT_EQ(r.point.face_displacement, s.point.face_displacement);
  ASSERT_EQ(r.point.dirichlet_reactions.size(), 2u);
  EXPECT_EQ(r.point.dirichlet_reactions[1].face, "mid plane");
  EXPECT_EQ(r.point.dirichlet_reactions[0].force, s.point.dirichlet_reactions[0].force);
  ASSERT_EQ(r.point.tangential_forces.size(), 1u);
  EXPECT_EQ(r.point.tangential_forces[0], s.point.tangential_forces[0]);
  EXPECT_EQ(r.record.augmentations, 3);
  const FrictionHistory &h = r.friction, &w = s.friction;
  for (const auto& [read, written] : {std::pair{&h.position, &w.position}, {&h.slip, &w.slip},
                                      {&h.direction, &w.direction}, {&h.alpha, &w.alpha},
                                      {&r.pressure_multipliers, &s.pressure_multipliers}})
    EXPECT_EQ(*read, *written);
  EXPECT_EQ(h.state, w.state);
  EXPECT_EQ(h.schur_batches, w.schur_batches);
  EXPECT_EQ(h.from, 0.7);
  // An older version (3: dilatations and multipliers per element, not per
  // pressure block): refused, saying so.
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    const int64_t three = 3;
    f.seekp(8);  // after the magic
    f.write(reinterpret_cast<const char*>(&three), sizeof three);
  }
  expect_refused(path, "written by an older igac: state-file version 3, this igac reads 4; run the case again");
  write_state_file(path, {"0123456789abcdef", "refine=1\ndegree=3\n"}, s);
  // Cut short: refused, naming the file.
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size - 3);
  expect_refused(path, "cut short");
  std::ofstream(path) << "a text file";
  EXPECT_THROW(read_state_file(path, hash), InputError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace igac
