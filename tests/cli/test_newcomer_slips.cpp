// SPDX-License-Identifier: BSD-3-Clause
// Slips a newcomer makes get the name they meant: a mistyped command
// (`igac rn`) or key (`Ee`, `center` for `centre`) is still a one-line
// error with exit code 2, and says "did you mean".  A word far from every
// name gets no guess.
#include <gtest/gtest.h>

#include <fstream>

#include "io/case_file.hpp"
#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

TEST(NewcomerSlips, MistypedCommandNamesTheCommandMeant) {
  igac_test::TempDir tmp("slips_command");
  const auto o = igac_test::run_igac("rn case.toml", tmp.path());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(o.output, "igac: error: unknown command 'rn'; did you mean 'run'? (run, study or geometry; see igac --help)\n");
  const auto far = igac_test::run_igac("zzzzz case.toml", tmp.path());
  EXPECT_EQ(far.exit_code, 2);
  EXPECT_EQ(far.output.find("did you mean"), std::string::npos) << far.output;
}

TEST(NewcomerSlips, MistypedKeyNamesTheKeyMeant) {
  igac_test::TempDir tmp("slips_key");
  std::string text = igac_test::read_file(fs::path(IGAC_SOURCE_DIR) / "cases" / "hertz2d.toml");
  text.replace(text.find("\nnu = 0.3"), 9, "\nnuu = 0.3");
  std::ofstream(tmp.path() / "case.toml") << text;
  const auto o = igac_test::run_igac("run case.toml --out result", tmp.path());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find("[material] nuu: unknown key; did you mean 'nu'?"), std::string::npos) << o.output;
}

TEST(NewcomerSlips, NearestNameGuessesOnlyCloseWords) {
  const std::vector<std::string> keys{"centre", "radius", "motion", "type"};
  EXPECT_EQ(igac::nearest_name("center", keys), "centre");
  EXPECT_EQ(igac::nearest_name("raduis", keys), "radius");
  EXPECT_EQ(igac::nearest_name("colour", keys), std::nullopt);
  EXPECT_EQ(igac::nearest_name("x", {"y", "z"}), "y");  // one letter off a one-letter name
}

}  // namespace

namespace {

TEST(NewcomerSlips, GeometrySaysWhatItWroteAndWhereItsHelpIs) {
  igac_test::TempDir tmp("slips_geometry");
  const std::string case_file = (fs::path(IGAC_SOURCE_DIR) / "cases" / "two_blocks.toml").string();
  const auto missing = igac_test::run_igac("geometry " + case_file, tmp.path());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("(see igac geometry --help)"), std::string::npos) << missing.output;
  const auto wrote = igac_test::run_igac("geometry " + case_file + " --out body.xml", tmp.path());
  EXPECT_EQ(wrote.exit_code, 0);
  EXPECT_EQ(wrote.output, "igac: wrote body.xml: 2 patch(es), 0 interface(s), before refinement\n");
  EXPECT_TRUE(fs::is_regular_file(tmp.path() / "body.xml"));
}

TEST(NewcomerSlips, MissingGeometryFileNamesTheCaseAndTheResolvedPath) {
  igac_test::TempDir tmp("slips_missing_file");
  std::string text = igac_test::read_file(fs::path(IGAC_SOURCE_DIR) / "cases" / "two_blocks.toml");
  text.replace(text.find("file = \"two_blocks.xml\""), 23, "file = \"nowhere.xml\"");
  std::ofstream(tmp.path() / "case.toml") << text;
  const auto o = igac_test::run_igac("run case.toml --out result", tmp.path());
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("case.toml:"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("[geometry] file: no such file: " + (tmp.path() / "nowhere.xml").string()),
            std::string::npos) << o.output;
}

TEST(NewcomerSlips, StudyWithoutOutWritesBesideTheRuns) {
  igac_test::TempDir tmp("slips_study_out");
  const fs::path cases = fs::path(IGAC_SOURCE_DIR) / "cases";
  const auto o = igac_test::run_igac("study " + (cases / "two_blocks.toml").string() + " --levels 4 --quiet", tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_TRUE(fs::is_regular_file(tmp.path() / "out" / "two_blocks_study" / "study.json"));
}

}  // namespace

namespace {

// A failed large-deformation run counts the cut-backs it made after its
// last converged step (the console said "0 cut-backs" after two).
TEST(NewcomerSlips, FailedRunCountsItsLastCutBacks) {
  igac_test::TempDir tmp("slips_cut_backs");
  std::string text = igac_test::read_file(fs::path(IGAC_SOURCE_DIR) / "cases" / "hertz2d_neohookean_pressure.toml");
  ASSERT_NE(text.find("[loading]"), std::string::npos);
  // One Newton iteration per step cannot converge: 0.1 -> 0.05 -> 0.025, below 0.04.
  text.replace(text.find("[loading]"), 9, "[loading]\nmax_newton_iterations = 1\nmin_increment = 0.04");
  std::ofstream(tmp.path() / "case.toml") << text;
  const auto o = igac_test::run_igac("run case.toml --out result", tmp.path());
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("(0 load steps, 0 Newton iterations, 2 cut-backs)"), std::string::npos) << o.output;
  EXPECT_EQ(igac_test::read_summary(tmp.path() / "result")["cut_backs_before_stopping"], 2);
  // Nothing converged: no contact zone is reported (it said "half width
  // 0.0235" at load factor 0, from the multipliers primed for Newton).
  EXPECT_EQ(o.output.find("half width"), std::string::npos) << o.output;
  EXPECT_FALSE(igac_test::read_summary(tmp.path() / "result").contains("contact"));
}

}  // namespace

namespace {

// A file written into a folder that is not there said "disk full or not
// writable?" (issue 25: a missing output folder is not blamed on the disk);
// it names the missing folder now, and a full file system what the system says.
TEST(NewcomerSlips, MissingFolderIsNotBlamedOnTheDisk) {
  igac_test::TempDir tmp("slips_folder");
  const std::string c = igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml");
  const auto o = igac_test::run_igac("geometry " + c + " --out missing/body.xml", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find("cannot write missing/body.xml: the folder missing does not exist"), std::string::npos)
      << o.output;
  EXPECT_EQ(o.output.find("disk"), std::string::npos) << o.output;
  // A file-size limit: the system's reason, not a guess.
  const auto big = igac_test::run_igac("run " + c + " --quiet --out out", tmp.path(), "ulimit -f 10;");
  EXPECT_EQ(big.exit_code, 1) << big.output;
  EXPECT_NE(big.output.find("File too large"), std::string::npos) << big.output;
}

}  // namespace
