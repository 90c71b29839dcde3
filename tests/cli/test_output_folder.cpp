// SPDX-License-Identifier: BSD-3-Clause
// Output folders stay consistent (issue 12): a bad --out is refused before
// any work, a run killed at any moment leaves the previous complete output,
// abandoned staging folders are cleaned up, and a body held by nothing is an
// input error.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

const std::string kCases = std::string(IGAC_SOURCE_DIR) + "/cases/";

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(dir)) s.insert(e.path().filename().string());
  return s;
}

std::string summary_case(const fs::path& out) {
  std::ifstream in(out / "summary.json");
  return nlohmann::json::parse(in).value("case", "");
}

void expect_out_refused(const std::string& out, const fs::path& cwd) {
  const Outcome o = run_igac("run " + quote(kCases + "lame_cylinder.toml") + " --out " + quote(out), cwd);
  EXPECT_EQ(o.exit_code, 2) << out << ": " << o.output;
  EXPECT_EQ(o.output.rfind("igac: error: --out", 0), 0u) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
}

TEST(OutputFolder, OutThatIsAFileIsRefusedAndKept) {
  TempDir tmp("outfile");
  const fs::path file = tmp.path() / "results";
  std::ofstream(file) << "keep me";
  expect_out_refused(file.string(), tmp.path());
  std::ifstream in(file);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "keep me");
  EXPECT_EQ(listing(tmp.path()), std::set<std::string>{"results"});
}

// bench/hostile_inputs.py: `--out ""` (an unset shell variable) wrote to
// out/<name> as if no --out had been given.
TEST(OutputFolder, EmptyOutIsRefused) {
  TempDir tmp("emptyout");
  expect_out_refused("", tmp.path());
  EXPECT_TRUE(tmp.empty());
}

TEST(OutputFolder, OutUnderSystemFoldersIsRefused) {
  TempDir tmp("outsys");
  expect_out_refused("/dev/null", tmp.path());
  expect_out_refused("/proc/igac_results", tmp.path());
  expect_out_refused("/proc/self/igac", tmp.path());
  EXPECT_TRUE(tmp.empty());
}

TEST(OutputFolder, AFolderThatIsNotAnIgacOutputIsNeverReplaced) {
  TempDir tmp("foreign");
  const fs::path mine = tmp.path() / "thesis";
  fs::create_directories(mine);
  std::ofstream(mine / "chapter1.tex") << "precious";
  expect_out_refused(mine.string(), tmp.path());
  EXPECT_TRUE(fs::exists(mine / "chapter1.tex"));
  expect_out_refused(".", mine);  // the current folder
  expect_out_refused(tmp.path().string(), mine);  // a folder above it
  EXPECT_TRUE(fs::exists(mine / "chapter1.tex"));
  EXPECT_EQ(listing(mine), std::set<std::string>{"chapter1.tex"});
}

// An output written before the manifest existed is recognised by its file
// names, the per-contact ones of a case with several contacts among them.
TEST(OutputFolder, AnOutputWithoutManifestIsReplacedWithItsPerContactFiles) {
  TempDir tmp("old_output");
  const fs::path out = tmp.path() / "out";
  fs::create_directories(out);
  for (const char* f : {"summary.json", "pressure_lower.csv", "pressure_upper.svg", "contact_lower_0000.vtu",
                        "multipliers_upper_0003.vtu", "solution.pvd"})
    std::ofstream(out / f) << "old";
  const Outcome o = run_igac("run " + quote(kCases + "lame_cylinder.toml") + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(summary_case(out), "lame_cylinder");
  EXPECT_FALSE(fs::exists(out / "pressure_lower.csv"));
  // a name that only looks like one is someone else's
  std::ofstream(out / "pressure_notes.txt") << "mine";
  fs::remove(out / ".igac-manifest");
  expect_out_refused(out.string(), tmp.path());
  EXPECT_TRUE(fs::exists(out / "pressure_notes.txt"));
}

TEST(OutputFolder, BodyHeldByNothingIsAnInputError) {
  TempDir tmp("unheld");
  std::ifstream in(kCases + "lame_cylinder.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  // Drop every Dirichlet condition: nothing holds the body.
  for (size_t at; (at = s.find("[[dirichlet]]")) != std::string::npos;) s.erase(at, s.find("\n\n", at) - at);
  const fs::path c = tmp.path() / "unheld.toml";
  std::ofstream(c) << s;
  const Outcome o = run_igac("run " + quote(c.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("the body is not held"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "out")) << "nothing is written for bad input";
}

TEST(OutputFolder, StudyTooLargeIsRefusedBeforeTheFirstLevel) {
  TempDir tmp("study");
  const Outcome o = run_igac("study " + quote(kCases + "lame_cylinder.toml") + " --levels 12 --out st", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("igac: error: --levels 12:", 0), 0u) << o.output;
  EXPECT_EQ(o.output.find("level 0"), std::string::npos) << "a level was computed: " << o.output;
  EXPECT_TRUE(tmp.empty());
}

// Starts `igac run` of the large-deformation Hertz case into `out` and
// returns once its staging folder (beside `out`, under `dir`) holds a
// written step (`staged`), or after 30 s: a run to stop in the middle.
pid_t start_run_until_staged(const fs::path& dir, const fs::path& out, bool& staged) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string c = kCases + "hertz2d_neohookean_pressure.toml";
    execl(IGAC_BINARY, IGAC_BINARY, "run", c.c_str(), "--quiet", "--out", out.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  staged = false;
  for (int i = 0; i < 6000 && !staged && pid > 0; ++i) {  // up to 30 s on a loaded machine
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    for (const auto& e : fs::directory_iterator(dir))
      if (e.path().filename().string().find(".igac-tmp-") != std::string::npos && fs::exists(e.path() / "solution.pvd"))
        staged = true;
  }
  return pid;
}

// A large-deformation run killed while it writes its steps leaves the output
// folder as the previous run left it; the next run clears its staging folder.
TEST(OutputFolder, KilledRunLeavesThePreviousOutputWhole) {
  TempDir tmp("killed");
  const fs::path out = tmp.path() / "out";
  ASSERT_EQ(run_igac("run " + quote(kCases + "hertz2d.toml") + " --quiet --out " + quote(out.string()), tmp.path()).exit_code, 0);
  const auto before = listing(out);
  ASSERT_EQ(summary_case(out), "hertz2d");

  bool staged = false;
  const pid_t pid = start_run_until_staged(tmp.path(), out, staged);
  ASSERT_GE(pid, 0);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(staged) << "the second run never wrote a step";
  ASSERT_TRUE(WIFSIGNALED(status)) << "the second run ended before it was killed";
  EXPECT_EQ(summary_case(out), "hertz2d");
  EXPECT_EQ(listing(out), before) << "the previous output changed";

  // The next run removes the killed run's staging folder.
  ASSERT_EQ(run_igac("run " + quote(kCases + "hertz2d.toml") + " --quiet --out " + quote(out.string()), tmp.path()).exit_code, 0);
  EXPECT_EQ(listing(tmp.path()), std::set<std::string>{"out"});
}

}  // namespace

namespace {

// bench/hostile_inputs.py: a run stopped by SIGTERM left its staging folder
// (".out.igac-tmp-PID", half a result) beside --out until the next run.  It
// leaves it now only once it holds a completed step's state (a stopped run
// to continue with --restart, docs/design.md "Restart"): never a summary.
TEST(OutputFolder, TerminatedRunLeavesNothingBesideButItsSteps) {
  TempDir tmp("terminated");
  const fs::path out = tmp.path() / "out";
  ASSERT_EQ(run_igac("run " + quote(kCases + "hertz2d.toml") + " --quiet --out " + quote(out.string()), tmp.path()).exit_code, 0);
  const auto before = listing(out);

  bool staged = false;
  const pid_t pid = start_run_until_staged(tmp.path(), out, staged);
  ASSERT_GE(pid, 0);
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(staged) << "the second run never wrote a step";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + SIGTERM);
  const std::string stopped = ".out.igac-tmp-" + std::to_string(pid);
  std::set<std::string> beside = listing(tmp.path());
  if (beside.count(stopped)) {
    EXPECT_TRUE(fs::exists(tmp.path() / stopped / "state_0001.bin"));
    EXPECT_FALSE(fs::exists(tmp.path() / stopped / "summary.json"));
    beside.erase(stopped);
  }
  EXPECT_EQ(beside, std::set<std::string>{"out"});
  EXPECT_EQ(listing(out), before) << "the previous output changed";
  EXPECT_EQ(summary_case(out), "hertz2d");
}

}  // namespace
