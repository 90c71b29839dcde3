// SPDX-License-Identifier: BSD-3-Clause
// Inputs a new user brings that used to hang, overflow or write non-numbers:
// a geometry "file" that is a FIFO or a device (read forever, or until the
// memory ran out), a load of 1e308 (accepted, and the failed run wrote nan
// and inf into its CSV).  Each is one line and exit 2 now, with nothing
// written; and no CSV cell igac writes is ever "nan" or "inf".
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "io/json_out.hpp"
#include "tests/support/igac_process.hpp"

namespace {

using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

constexpr int kBadInputExit = 2;  // docs/design.md, "Errors and exit codes"

// hertz2d.toml with its body read from `geometry`.
std::string case_with_geometry(const std::filesystem::path& dir, const std::string& geometry) {
  const std::string path = (dir / "case.toml").string();
  std::ofstream(path) << "[geometry]\nfile = \"" << geometry
                      << "\"\n[mesh]\ndegree = 2\nelements = [4, 4]\n[material]\nE = 1.0\nnu = 0.3\n"
                         "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"x\"\n";
  return path;
}

void expect_one_line_rejection(const Outcome& o, const std::string& says) {
  EXPECT_EQ(o.exit_code, kBadInputExit) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find(says), std::string::npos) << o.output;
}

TEST(UserInputs, GeometryFileThatIsAFifoIsRefused) {
  TempDir tmp("inputs");
  const std::string fifo = (tmp.path() / "body.xml").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const Outcome o = run_igac("run " + quote(case_with_geometry(tmp.path(), fifo)) + " --out out", tmp.path());
  expect_one_line_rejection(o, "not a regular file");
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

TEST(UserInputs, GeometryFileThatIsADeviceIsRefused) {
  TempDir tmp("inputs");
  const Outcome o = run_igac("run " + quote(case_with_geometry(tmp.path(), "/dev/zero")) + " --out out", tmp.path());
  expect_one_line_rejection(o, "not a regular file");
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

TEST(UserInputs, LoadsBeyondTheRangeOfDoublesAreRefused) {
  const std::string hertz2d = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  std::ifstream in(hertz2d);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("value = 0.003");
  ASSERT_NE(at, std::string::npos);
  for (const std::string load : {"1e308", "-1e101"}) {
    TempDir tmp("inputs");
    std::string changed = text;
    changed.replace(at, 13, "value = " + load);
    std::ofstream(tmp.path() / "case.toml") << changed;
    const Outcome o = run_igac("run case.toml --out out", tmp.path());
    expect_one_line_rejection(o, "[pressure] value");
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << load;
  }
}

TEST(UserInputs, CsvCellsAreNeverNanOrInf) {
  EXPECT_EQ(igac::csv_number(std::numeric_limits<double>::quiet_NaN()), "");
  EXPECT_EQ(igac::csv_number(std::numeric_limits<double>::infinity()), "");
  EXPECT_EQ(igac::csv_number(-std::numeric_limits<double>::infinity()), "");
  EXPECT_EQ(igac::csv_number(0.1), "0.1");
  EXPECT_EQ(igac::csv_number(1.0 / 3.0), "0.3333333333");
}

}  // namespace

namespace {

// `igac geometry --out PATH` writes a new file or replaces its own earlier
// export; it renamed over whatever PATH was (a device node, a FIFO, a
// symlink, the case file itself, a user's file).
TEST(UserInputs, GeometryExportReplacesOnlyItsOwnFiles) {
  TempDir tmp("inputs");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  // A new file, then the same file again (an earlier export): written.
  for (int i = 0; i < 2; ++i) {
    const Outcome o = run_igac("geometry " + quote(c) + " --out body.xml", tmp.path());
    EXPECT_EQ(o.exit_code, 0) << o.output;
  }
  EXPECT_TRUE(std::filesystem::is_regular_file(tmp.path() / "body.xml"));
  // A user's file, a symlink, a FIFO, a folder, the case file: refused, untouched.
  std::ofstream(tmp.path() / "notes.txt") << "my notes\n";
  std::filesystem::create_symlink(tmp.path() / "notes.txt", tmp.path() / "link.xml");
  ASSERT_EQ(mkfifo((tmp.path() / "fifo.xml").c_str(), 0600), 0);
  std::filesystem::create_directory(tmp.path() / "folder.xml");
  std::filesystem::copy_file(c, tmp.path() / "case.toml");
  for (const auto& [target, says] : std::vector<std::pair<std::string, std::string>>{
           {"notes.txt", "not written by igac"},
           {"link.xml", "not a regular file"},
           {"fifo.xml", "not a regular file"},
           {"folder.xml", "not a regular file"}}) {
    const Outcome o = run_igac("geometry " + quote(c) + " --out " + target, tmp.path());
    expect_one_line_rejection(o, says);
  }
  const Outcome self = run_igac("geometry case.toml --out case.toml", tmp.path());
  expect_one_line_rejection(self, "the case file itself");
  std::ifstream notes(tmp.path() / "notes.txt");
  std::string line;
  std::getline(notes, line);
  EXPECT_EQ(line, "my notes");
  EXPECT_TRUE(std::filesystem::is_symlink(tmp.path() / "link.xml"));
  EXPECT_EQ(igac_test::read_file(tmp.path() / "case.toml"), igac_test::read_file(c));
}

}  // namespace

namespace {

// --out DIR replaced DIR whole when it held any summary.json, deleting a
// user's notes and folders beside it.  Now only what igac wrote there (its
// .igac-manifest) may be replaced.
TEST(UserInputs, OutputFolderReplacesOnlyWhatIgacWrote) {
  TempDir tmp("inputs");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml";
  const std::string run = "run " + quote(c) + " --quiet --out out";
  ASSERT_EQ(run_igac(run, tmp.path()).exit_code, 0);
  ASSERT_TRUE(std::filesystem::exists(tmp.path() / "out" / ".igac-manifest"));
  EXPECT_EQ(run_igac(run, tmp.path()).exit_code, 0) << "its own earlier output is replaced";
  std::ofstream(tmp.path() / "out" / "notes.txt") << "my notes\n";
  std::filesystem::create_directory(tmp.path() / "out" / "photos");
  const Outcome o = run_igac(run, tmp.path());
  expect_one_line_rejection(o, "notes.txt, photos");
  EXPECT_EQ(igac_test::read_file(tmp.path() / "out" / "notes.txt"), "my notes\n");
  EXPECT_TRUE(std::filesystem::is_directory(tmp.path() / "out" / "photos"));
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "out" / "summary.json"));
  // A folder holding a summary.json of someone else's and other files.
  std::filesystem::create_directory(tmp.path() / "theirs");
  std::ofstream(tmp.path() / "theirs" / "summary.json") << "{}\n";
  std::ofstream(tmp.path() / "theirs" / "data.csv") << "1,2\n";
  expect_one_line_rejection(run_igac("run " + quote(c) + " --quiet --out theirs", tmp.path()), "data.csv");
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "theirs" / "data.csv"));
}

}  // namespace

#ifdef IGAC_WITH_PETSC
namespace {

// A Krylov solve stopped by a loose tolerance is not a solution: with
// -ksp_rtol 0.9 the run said converged, exit 0, with a contact force of
// 3.6e-12 against 0.003 applied.  The true residual is checked now.
TEST(UserInputs, PetscSolveStoppedEarlyIsNotASolution) {
  TempDir tmp("inputs");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  const Outcome loose = run_igac("run " + quote(c) + " --solver petsc --petsc-options " +
                                     quote("-ksp_type gmres -pc_type jacobi -ksp_rtol 0.9") + " --out out",
                                 tmp.path());
  EXPECT_EQ(loose.exit_code, 1) << loose.output;
  EXPECT_NE(loose.output.find("not a solution"), std::string::npos) << loose.output;
  // The same case with PETSc's default (a direct solve) is a solution.
  const Outcome direct = run_igac("run " + quote(c) + " --solver petsc --out out2", tmp.path());
  EXPECT_EQ(direct.exit_code, 0) << direct.output;
}

}  // namespace
#endif

namespace {

// A case file is data: through [solver] options it could write any file
// (-ksp_view ascii:FILE), truncate one (-log_view ascii:FILE) or print the
// first line of one (-options_file /etc/passwd).  It may give only a few
// known options with checked values now.
TEST(UserInputs, CaseFilePetscOptionsAreAKnownList) {
  const std::string hertz2d = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  std::ifstream in(hertz2d);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [options, says] : std::vector<std::pair<std::string, std::string>>{
           {"-ksp_view ascii:victim.txt", "'-ksp_view' is not among"},
           {"-log_view ascii:victim.txt", "'-log_view' is not among"},
           {"-options_file /etc/passwd", "'-options_file' is not among"},
           {"-ksp_type cg -ksp_rtol abc", "-ksp_rtol abc"},
           {"-pc_type mystery", "-pc_type mystery"}}) {
    TempDir tmp("inputs");
    std::ofstream(tmp.path() / "victim.txt") << "keep me\n";
    std::ofstream(tmp.path() / "case.toml") << text << "\n[solver]\ntype = \"petsc\"\noptions = \"" << options << "\"\n";
    const Outcome o = run_igac("run case.toml --out out", tmp.path());
    expect_one_line_rejection(o, says);
    EXPECT_EQ(o.output.find("root:"), std::string::npos) << o.output;
    EXPECT_EQ(igac_test::read_file(tmp.path() / "victim.txt"), "keep me\n");
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
  }
}

}  // namespace

namespace {

// SIGTERM ends a run at any moment, also inside a library call (METIS's
// ordering used to swallow it: a run under `timeout` went on to the end).
TEST(UserInputs, SigtermStopsARunAtAnyMoment) {
  TempDir tmp("inputs");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/hertz3d.toml";
  for (const char* after : {"0.5", "1.5", "2.5"}) {
    const std::string cmd = "cd " + quote(tmp.path().string()) + " && (" + quote(IGAC_BINARY) + " run " + quote(c) +
                            " --refine 1 --quiet --out out & p=$!; sleep " + after +
                            "; kill -TERM $p; wait $p; echo \"status $?\") 2>&1";
    FILE* pipe = popen(cmd.c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    std::string out;
    char buf[256];
    while (fgets(buf, sizeof buf, pipe)) out += buf;
    pclose(pipe);
    EXPECT_NE(out.find("igac: stopped by SIGTERM"), std::string::npos) << after << " s: " << out;
    EXPECT_NE(out.find("status 143"), std::string::npos) << after << " s: " << out;
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << "a stopped run leaves no result";
  }
}

}  // namespace

namespace {

// nu = 0.49999999 gave a peak pressure 70 % too high without a word: a run
// near the incompressible limit says that its elements lock.
TEST(UserInputs, NearlyIncompressibleMaterialIsWarnedAbout) {
  TempDir tmp("inputs");
  std::ifstream in(std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("nu = 0.3");
  ASSERT_NE(at, std::string::npos);
  std::ofstream(tmp.path() / "ok.toml") << text;
  text.replace(at, 8, "nu = 0.49999999");
  std::ofstream(tmp.path() / "near.toml") << text;
  const Outcome near = run_igac("run near.toml --no-output", tmp.path());
  EXPECT_EQ(near.exit_code, 0) << near.output;
  EXPECT_NE(near.output.find("igac: warning: near.toml: [material] nu = 0.49999999: nearly incompressible"), std::string::npos)
      << near.output;
  const Outcome ok = run_igac("run ok.toml --no-output", tmp.path());
  EXPECT_EQ(ok.output.find("warning"), std::string::npos) << ok.output;
}

// A file-size limit (ulimit -f) killed the run with SIGXFSZ and no word.
TEST(UserInputs, FileSizeLimitIsAOneLineFailure) {
  TempDir tmp("inputs");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  FILE* pipe = popen(("cd " + quote(tmp.path().string()) + " && (ulimit -f 10; " + quote(IGAC_BINARY) + " run " +
                      quote(c) + " --quiet --out out; echo \"status $?\") 2>&1")
                         .c_str(),
                     "r");
  ASSERT_NE(pipe, nullptr);
  std::string out;
  char buf[512];
  while (fgets(buf, sizeof buf, pipe)) out += buf;
  pclose(pipe);
  EXPECT_NE(out.find("igac: error:"), std::string::npos) << out;
  EXPECT_NE(out.find("cannot write"), std::string::npos) << out;
  EXPECT_NE(out.find("status 1"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

}  // namespace
