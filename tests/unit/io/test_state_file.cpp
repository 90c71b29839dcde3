// SPDX-License-Identifier: BSD-3-Clause
// The restart state file (io/state_file.hpp): what is written is read back
// bit for bit (the friction and incompressible histories too), and a file
// that is not one (cut short, another magic, a folder or a FIFO), of an
// older version (3: the mixed formulation's values per element, not per
// pressure block; 4: no checksum) or damaged (any one bit flipped: its
// checksum) is an InputError naming it.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

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
  expect_refused(path, "written by an older igac: state-file version 3, this igac reads 5; run the case again");
  write_state_file(path, {"0123456789abcdef", "refine=1\ndegree=3\n"}, s);
  // Cut short: refused, naming the file (by its checksum; before the checksum, by its size).
  const auto size = std::filesystem::file_size(path);
  std::filesystem::resize_file(path, size - 3);
  expect_refused(path, "damaged: its checksum does not match its contents, cut short or altered");
  std::filesystem::resize_file(path, 20);
  expect_refused(path, "cut short");
  std::ofstream(path) << "a text file";
  EXPECT_THROW(read_state_file(path, hash), InputError);
  std::filesystem::remove(path);
}

StepState some_state() {
  StepState s;
  s.step = 3;
  s.driver = {0.625, 0.5625, 0.375, Eigen::VectorXd::LinSpaced(7, -1.0 / 3, 2.0 / 7), Eigen::VectorXd::LinSpaced(7, 0.1, 0.2)};
  s.record = {0.625, 4, {1.0, 1e-3 / 3, 2.2e-14}, {3, 4, 4, 4}, 0};
  s.point.load_factor = 0.625;
  s.point.contact_forces = {0.1 / 7};
  return s;
}

// Issue 35: a state file carried no checksum, and a flipped bit of a number
// (its mantissa, its exponent) gave another state that the restart took.
// Now a bit flipped anywhere past the magic and version is refused: one per
// byte, each bit position in turn.
TEST(StateFile, AnyFlippedBitIsRefused) {
  const auto path = (std::filesystem::temp_directory_path() / "igac_test_state_flipped.bin").string();
  write_state_file(path, {"0123456789abcdef", "refine=0\n"}, some_state());
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const size_t head = 16;  // the magic and the version: refused for what they are
  ASSERT_GT(bytes.size(), head + 8);
  int refused = 0;
  for (size_t at = head; at < bytes.size(); ++at) {
    const int bit = int(at % 8);  // each bit position, across the bytes
    {
      std::string flipped = bytes;
      flipped[at] = char(flipped[at] ^ (1 << bit));
      std::ofstream(path, std::ios::binary | std::ios::trunc) << flipped;
      StateOrigin origin;
      try {
        read_state_file(path, origin);
        ADD_FAILURE() << "byte " << at << " bit " << bit << " flipped: read";
      } catch (const InputError& e) {
        refused += std::string(e.what()).find("damaged: its checksum does not match its contents") != std::string::npos;
      }
    }
  }
  EXPECT_EQ(refused, int(bytes.size() - head));
  std::filesystem::remove(path);
}

// A state file of version 4 (no checksum) is refused in one line, not read
// on trust.
TEST(StateFile, VersionFourWithoutChecksumIsRefused) {
  const auto path = (std::filesystem::temp_directory_path() / "igac_test_state_v4.bin").string();
  write_state_file(path, {"0123456789abcdef", "refine=0\n"}, some_state());
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    const int64_t four = 4;
    f.seekp(8);
    f.write(reinterpret_cast<const char*>(&four), sizeof four);
  }
  expect_refused(path, "written by an older igac: state-file version 4, this igac reads 5; run the case again");
  std::filesystem::remove(path);
}

// A folder or a FIFO named as a state file: one line naming it (a folder
// gave the library's "basic_filebuf::underflow error reading the file: Is a
// directory", a FIFO waited for a writer forever).
TEST(StateFile, FolderOrFifoIsRefusedInOneLine) {
  const auto dir = std::filesystem::temp_directory_path() / ("igac_test_state_special_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir / "state_0001.bin");
  ASSERT_EQ(mkfifo((dir / "state_0002.bin").c_str(), 0600), 0);
  for (const char* name : {"state_0001.bin", "state_0002.bin"}) {
    const std::string path = (dir / name).string();
    StateOrigin origin;
    try {
      read_state_file(path, origin);
      ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                path + ": not a regular file (a folder, FIFO or device): a state file must be a regular file");
    }
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace igac
