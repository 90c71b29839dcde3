// SPDX-License-Identifier: BSD-3-Clause
// The restart state file (io/state_file.hpp): what is written is read back
// bit for bit, and a file that is not one (cut short, another magic) is an
// InputError naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/state_file.hpp"

namespace igac {
namespace {

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
  // Cut short: refused, naming the file.
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size - 3);
  try {
    read_state_file(path, hash);
    ADD_FAILURE() << "a file cut short was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": not a state file igac can restart from (cut short)"), std::string::npos)
        << e.what();
  }
  std::ofstream(path) << "a text file";
  EXPECT_THROW(read_state_file(path, hash), InputError);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace igac
