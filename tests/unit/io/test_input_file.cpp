// SPDX-License-Identifier: BSD-3-Clause
// The guarded reader of input files (io/input_file.hpp): a regular file is
// read whole, a symbolic link to one too; a folder, a FIFO (which would be
// waited on forever), a device (/dev/zero: read until the memory ran out),
// a file larger than its kind holds, a missing file and a path with a NUL
// in it are each one InputError naming the path and why.  FNV-1a against
// its published test vectors.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/input_file.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;

std::string refusal(const std::string& path, const InputFileKind& kind) {
  try {
    read_input_file(path, kind);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

TEST(InputFile, RegularFilesOnlyEachRefusalInOneLine) {
  const fs::path dir = fs::temp_directory_path() / ("igac_test_input_file_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "folder.toml");
  std::ofstream(dir / "case.toml", std::ios::binary) << "name = \"x\"\n";
  fs::create_symlink(dir / "case.toml", dir / "link.toml");
  ASSERT_EQ(mkfifo((dir / "fifo.toml").c_str(), 0600), 0);
  const std::string p = dir.string();
  EXPECT_EQ(read_input_file(p + "/case.toml", kCaseFile), "name = \"x\"\n");
  EXPECT_EQ(read_input_file(p + "/link.toml", kCaseFile), "name = \"x\"\n");
  const std::string not_regular = ": not a regular file (a folder, FIFO or device): a case file must be a regular file";
  EXPECT_EQ(refusal(p + "/folder.toml", kCaseFile), p + "/folder.toml" + not_regular);
  EXPECT_EQ(refusal(p + "/fifo.toml", kCaseFile), p + "/fifo.toml" + not_regular);
  EXPECT_EQ(refusal("/dev/zero", kCaseFile), "/dev/zero" + not_regular);
  EXPECT_EQ(refusal(p + "/none.toml", kCaseFile), p + "/none.toml: no such case file");
  EXPECT_EQ(refusal(p + "/case.toml/x", kCaseFile), p + "/case.toml/x: cannot read the case file (Not a directory)");
  EXPECT_EQ(refusal(p + "/case.toml", InputFileKind{"tiny file", 4}),
            p + "/case.toml: 11 bytes, more than a tiny file holds (at most 4)");
  // The system would open the path up to the NUL: another file.
  EXPECT_EQ(refusal(p + "/case.toml" + std::string(1, '\0') + "x", kCaseFile),
            "\"" + p + "/case.toml\\x00x\": a file name with a NUL character in it: not a case file");
  fs::remove_all(dir);
}

TEST(InputFile, Fnv1aMatchesItsTestVectors) {
  // http://www.isthe.com/chongo/tech/comp/fnv/ (FNV-1a, 64 bits)
  EXPECT_EQ(fnv1a64(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a64("foobar"), 0x85944171f73967e8ull);
}

}  // namespace
}  // namespace igac
