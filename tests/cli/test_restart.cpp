// SPDX-License-Identifier: BSD-3-Clause
// igac run --restart (app/restart.hpp, io/state_file.hpp): a run stopped
// after step k (--stop-after-step) and continued from its output ends where
// an uninterrupted run ends: every number of the final summary.json equal
// to 1e-12 relative (the issue's bar; the steps are the same, bit for bit),
// in small deformation (load curves, contact) and in large deformation
// (the Newton driver, its increments and predictor state carried over);
// --from-step continues from an earlier step of a finished run; a restart
// against another case file, or with other options (--refine, --degree),
// is refused in one line.  Frictional and incompressible runs too: their
// slip history and element pressures are in the state files.  And for real: a run killed (SIGKILL) or stopped
// (SIGTERM, SIGINT) once the state file of step K exists is continued from
// the folder it was writing to, to the uninterrupted run's numbers; the
// earlier finished output there survives the kill untouched.
#include <algorithm>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string data(const std::string& name) { return igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/tests/data/" + name); }

// What measures the machine or names the folder, not the result; and the
// condition estimate, of the last matrix the run factorised (a restarted run
// that has no step left to solve factorises none).
const std::regex kNotResults("time|timing|seconds|_s$|memory|resident|path|folder|condition_estimate");

// Every number of `a` equals `b`'s to 1e-12 relative, every other value exactly.
void expect_same(const json& a, const json& b, const std::string& where, int& numbers) {
  ASSERT_EQ(a.type() == json::value_t::number_unsigned ? json::value_t::number_integer : a.type(),
            b.type() == json::value_t::number_unsigned ? json::value_t::number_integer : b.type())
      << where;
  if (a.is_object()) {
    const auto results = [](const json& o) {
      return std::count_if(o.items().begin(), o.items().end(),
                           [](const auto& kv) { return !std::regex_search(kv.key(), kNotResults); });
    };
    ASSERT_EQ(results(a), results(b)) << where;
    for (const auto& [k, v] : a.items()) {
      if (std::regex_search(k, kNotResults)) continue;
      ASSERT_TRUE(b.contains(k)) << where << "." << k;
      expect_same(v, b[k], where + "." + k, numbers);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (size_t i = 0; i < a.size(); ++i) expect_same(a[i], b[i], where + "[" + std::to_string(i) + "]", numbers);
  } else if (a.is_number_float()) {
    constexpr double kRelative = 1e-12;  // issue 25's bar
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_LE(std::abs(x - y), kRelative * std::max(std::abs(x), std::abs(y))) << where;
    ++numbers;
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

// Every .csv file of `a` (load_curve.csv; pressure.csv, with friction its
// tangential traction, slip and stick/slip state per multiplier) and every
// state file (the steps' x, histories and records: the bits) is in `b`,
// byte for byte.
void expect_same_files(const fs::path& a, const fs::path& b) {
  int files = 0;
  for (const auto& e : fs::directory_iterator(a))
    if (e.path().extension() == ".csv" || e.path().extension() == ".bin") {
      ++files;
      EXPECT_EQ(igac_test::read_file(e.path()), igac_test::read_file(b / e.path().filename())) << e.path().filename();
    }
  EXPECT_GT(files, 0);
}

// Runs the case `quoted_path` whole, then to step k and on from there; the
// two final summaries agree (and with `vtk`, the .pvd).
void expect_restart_matches_at(const std::string& quoted_path, int k, bool vtk) {
  igac_test::TempDir tmp("restart");
  const auto whole = igac_test::run_igac("run " + quoted_path + " --quiet --out whole", tmp.path());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const auto part = igac_test::run_igac(
      "run " + quoted_path + " --quiet --out part --stop-after-step " + std::to_string(k), tmp.path());
  ASSERT_EQ(part.exit_code, 0) << part.output;
  const json stopped = igac_test::read_summary(tmp.path() / "part");
  EXPECT_EQ(stopped["load_steps"].size(), size_t(k));
  EXPECT_EQ(stopped["status"], "stopped after step " + std::to_string(k) + " (as asked)");
  const auto resumed = igac_test::run_igac("run " + quoted_path + " --quiet --out part --restart part", tmp.path());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  const json a = igac_test::read_summary(tmp.path() / "whole"), b = igac_test::read_summary(tmp.path() / "part");
  int numbers = 0;
  expect_same(a, b, "summary.json", numbers);
  EXPECT_GT(numbers, 20);
  expect_same_files(tmp.path() / "whole", tmp.path() / "part");
  // The .pvd plays every step, the earlier ones copied.
  const std::string pvd_a = igac_test::read_file(tmp.path() / "whole" / "solution.pvd");
  EXPECT_EQ(pvd_a.empty(), !vtk);
  EXPECT_EQ(pvd_a, igac_test::read_file(tmp.path() / "part" / "solution.pvd"));
  for (int step = 0; vtk && step <= k + 1; ++step)
    EXPECT_TRUE(fs::exists(tmp.path() / "part" / ("solution_000" + std::to_string(step) + ".vtu"))) << step;
  // And from an earlier step of the finished run.
  const auto from = igac_test::run_igac(
      "run " + quoted_path + " --quiet --out from --restart whole --from-step " + std::to_string(k - 1), tmp.path());
  ASSERT_EQ(from.exit_code, 0) << from.output;
  numbers = 0;
  expect_same(a, igac_test::read_summary(tmp.path() / "from"), "summary.json (--from-step)", numbers);
  expect_same_files(tmp.path() / "whole", tmp.path() / "from");
  // And from its last step: nothing left to solve, the final state taken up again.
  const auto last = igac_test::run_igac("run " + quoted_path + " --quiet --out last --restart whole", tmp.path());
  ASSERT_EQ(last.exit_code, 0) << last.output;
  numbers = 0;
  expect_same(a, igac_test::read_summary(tmp.path() / "last"), "summary.json (the last step)", numbers);
  expect_same_files(tmp.path() / "whole", tmp.path() / "last");
}

void expect_restart_matches(const std::string& case_file, int k, bool vtk) {
  expect_restart_matches_at(data(case_file), k, vtk);
}

// A case of tests/data (or cases/) with a few lines replaced, written into `dir`:
// its path, quoted.
std::string variant(const igac_test::TempDir& dir, const std::string& file,
                    const std::vector<std::pair<std::string, std::string>>& replace) {
  std::string text = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/" + file);
  for (const auto& [from, to] : replace) {
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  const fs::path path = dir.path() / fs::path(file).filename();
  std::ofstream(path) << text;
  return igac_test::quote(path.string());
}

TEST(Restart, LargeDeformationContinuesAsIfUninterrupted) { expect_restart_matches("curve_block_neohookean.toml", 3, true); }

TEST(Restart, SmallDeformationContinuesAsIfUninterrupted) { expect_restart_matches("curve_contact.toml", 2, false); }

TEST(Restart, AnotherCaseFileIsRefusedInOneLine) {
  igac_test::TempDir tmp("restart");
  ASSERT_EQ(igac_test::run_igac("run " + data("curve_block.toml") + " --quiet --out a", tmp.path()).exit_code, 0);
  const auto o = igac_test::run_igac("run " + data("curve_contact.toml") + " --quiet --out b --restart a", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  EXPECT_NE(o.output.find("--restart a: that run was of another case file"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "b"));
  // A step the run did not write, and a case solved in one step: one line each.
  const auto beyond = igac_test::run_igac("run " + data("curve_block.toml") + " --quiet --out c --restart a --from-step 99",
                                          tmp.path());
  EXPECT_EQ(beyond.exit_code, 2) << beyond.output;
  EXPECT_NE(beyond.output.find("--from-step 99: the run in a wrote the states of steps 1 to 5"), std::string::npos)
      << beyond.output;
  const auto one_step = igac_test::run_igac(
      "run " + igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/cases/lame_cylinder.toml") + " --quiet --restart a",
      tmp.path());
  EXPECT_EQ(one_step.exit_code, 2) << one_step.output;
  EXPECT_NE(one_step.output.find("need a run in steps"), std::string::npos) << one_step.output;
}

// Friction: the slip history (and, in small deformation, each multiplier's
// stick or slip, its slip direction and the Schur columns computed so far)
// is in the state files, so a frictional run stopped after step k goes on
// as if it had not stopped: the sliding block dragged there and back (its
// slip reverses after the stop), in small and large deformation, and two
// bodies (a slider on a base, its top dragged there and back).
TEST(Restart, FrictionalRunContinuesAsIfUninterrupted) {
  expect_restart_matches("curve_friction_block.toml", 3, false);
}

// Large deformation: 4 steps (t = 0.5, 1, 2, 3), stopped at the corner t = 2
// before the slip reverses.
TEST(Restart, LargeDeformationFrictionalRunContinuesAsIfUninterrupted) {
  igac_test::TempDir dir("variant");
  expect_restart_matches_at(
      variant(dir, "tests/data/curve_friction_block.toml", {{R"(model = "linear_elastic")", R"(model = "neo_hookean")"}}),
      3, false);
}

TEST(Restart, TwoBodyFrictionalRunsContinueAsIfUninterrupted) {
  expect_restart_matches("curve_friction_two_blocks.toml", 3, false);
  igac_test::TempDir dir("variant");
  const std::string nh = R"(model = "neo_hookean")", linear = R"(model = "linear_elastic")";
  expect_restart_matches_at(variant(dir, "tests/data/curve_friction_two_blocks.toml", {{linear, nh}, {linear, nh}}), 3,
                            false);
}

// 3D: two tangential multipliers per point, the slip direction on the disc
// (and b / |xi| of its linearised slip law) carried over: a box dragged
// obliquely there and back, small and large deformation.
TEST(Restart, ThreeDimensionalFrictionalRunsContinueAsIfUninterrupted) {
  expect_restart_matches("curve_friction_box.toml", 3, false);
  igac_test::TempDir dir("variant");
  expect_restart_matches_at(
      variant(dir, "tests/data/curve_friction_box.toml", {{R"(model = "linear_elastic")", R"(model = "neo_hookean")"}}),
      2, false);
}

// The incompressible limit: each pressure block's multiplier (the
// augmented Lagrangian's) where the step ended is in the state file; the
// O-ring of real rubber at K = infinity, coarsened (4 steps since the
// mixed Newton carries the block dilatations; stopped after 2).
TEST(Restart, IncompressibleRunContinuesAsIfUninterrupted) {
  igac_test::TempDir dir("variant");
  expect_restart_matches_at(
      variant(dir, "cases/oring_rubber.toml",
              {{R"(file = "oring_quarter.xml")", "file = \"" + std::string(IGAC_SOURCE_DIR) + "/cases/oring_quarter.xml\""},
               {R"(formulation = "mixed")", "formulation = \"mixed\"\nincompressible = true"},
               {"elements = [32, 16]", "elements = [16, 8]"},
               {"steps = 20", "steps = 8"},
               {"[loading]", "[output]\nvtk = false\n[loading]"}}),
      2, false);
}

// A restart with another --refine or --degree than the run it continues
// would mix two meshes: refused in one line naming what differs; with the
// same ones it goes on (another solver may continue it: PetscRestart).
TEST(Restart, OtherOptionsAreRefusedInOneLine) {
  igac_test::TempDir tmp("restart");
  const std::string c = data("curve_contact.toml");
  ASSERT_EQ(igac_test::run_igac("run " + c + " --quiet --refine 1 --out a --stop-after-step 2", tmp.path()).exit_code, 0);
  const auto other = igac_test::run_igac("run " + c + " --quiet --out b --restart a", tmp.path());
  EXPECT_EQ(other.exit_code, 2) << other.output;
  EXPECT_EQ(std::count(other.output.begin(), other.output.end(), '\n'), 1) << other.output;
  EXPECT_NE(other.output.find("igac: error: --restart a: that run had other options: refine '1' there, '0' here "
                              "(--refine); a restart continues a run with the options it had: give the same ones"),
            std::string::npos) << other.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "b"));
  const auto degree = igac_test::run_igac("run " + c + " --quiet --refine 1 --degree 3 --out b --restart a", tmp.path());
  EXPECT_EQ(degree.exit_code, 2) << degree.output;
  EXPECT_NE(degree.output.find("degree '2' there, '3' here (--degree)"), std::string::npos) << degree.output;
  const auto same = igac_test::run_igac("run " + c + " --quiet --refine 1 --out b --restart a", tmp.path());
  EXPECT_EQ(same.exit_code, 0) << same.output;
}

// `igac run ARGS` started in `cwd` as a child process, ended by `sig` once
// the state file of step `k` stands in its staging folder beside `out`.
// Returns false (and says why) when the run ended before.
bool run_and_stop_at(const std::vector<std::string>& args, const fs::path& cwd, const std::string& out, int k, int sig) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(cwd.c_str()) != 0) _exit(127);
    std::vector<char*> argv{const_cast<char*>(IGAC_BINARY)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(IGAC_BINARY, argv.data());
    _exit(127);
  }
  if (pid < 0) return false;
  // igac re-executes itself once (the signal mask): the same process id.
  char name[32];
  std::snprintf(name, sizeof name, "state_%04d.bin", k);
  const fs::path state = cwd / ("." + out + ".igac-tmp-" + std::to_string(pid)) / name;
  int status = 0;
  bool ended = false;
  for (int i = 0; i < 120000 && !ended; ++i) {  // up to 2 minutes on a loaded machine
    if (fs::exists(state)) break;
    ended = waitpid(pid, &status, WNOHANG) == pid;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  if (ended) {
    ADD_FAILURE() << "the run ended before step " << k << " was written";
    return false;
  }
  kill(pid, sig);
  waitpid(pid, &status, 0);
  if (sig == SIGKILL) EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "the run ended before the kill";
  else EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + sig) << "status " << status;
  return true;
}

std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(dir)) s.insert(e.path().filename().string());
  return s;
}

// An uninterrupted run, then a finished run of hertz2d into `part`, then
// the case run into `part` and ended by `sig` after step k: `part` is still
// the hertz2d output, a stopped run (no summary.json) stands beside it, and
// `--restart part` continues it to the uninterrupted run's numbers (1e-12).
void expect_stopped_run_continues(const std::string& case_file, const std::vector<std::string>& options, int k, int sig) {
  igac_test::TempDir tmp("stopped");
  const std::string c = std::string(IGAC_SOURCE_DIR) + "/" + case_file, opts = [&] {
    std::string s;
    for (const auto& o : options) s += " " + o;
    return s;
  }();
  const auto whole = igac_test::run_igac("run " + igac_test::quote(c) + opts + " --quiet --out whole", tmp.path());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  const auto earlier = igac_test::run_igac(
      "run " + igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml") + " --quiet --out part", tmp.path());
  ASSERT_EQ(earlier.exit_code, 0) << earlier.output;
  const std::set<std::string> before = listing(tmp.path() / "part");
  const std::string earlier_summary = igac_test::read_file(tmp.path() / "part" / "summary.json");

  std::vector<std::string> args{"run", c, "--quiet", "--out", "part"};
  args.insert(args.end(), options.begin(), options.end());
  ASSERT_TRUE(run_and_stop_at(args, tmp.path(), "part", k, sig));
  // The earlier output is whole; the stopped run is hidden beside it, without a summary.
  EXPECT_EQ(listing(tmp.path() / "part"), before);
  EXPECT_EQ(igac_test::read_file(tmp.path() / "part" / "summary.json"), earlier_summary);
  std::vector<fs::path> stopped;
  for (const auto& e : fs::directory_iterator(tmp.path()))
    if (e.path().filename().string().rfind(".part.igac-tmp-", 0) == 0) stopped.push_back(e.path());
  ASSERT_EQ(stopped.size(), 1u) << "one stopped run beside part";
  EXPECT_FALSE(fs::exists(stopped[0] / "summary.json"));
  EXPECT_TRUE(fs::exists(stopped[0] / "state_0001.bin"));

  const auto resumed = igac_test::run_igac("run " + igac_test::quote(c) + opts + " --out part --restart part", tmp.path());
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("igac: continuing after step "), std::string::npos) << resumed.output;
  int numbers = 0;
  expect_same(igac_test::read_summary(tmp.path() / "whole"), igac_test::read_summary(tmp.path() / "part"),
              "summary.json", numbers);
  EXPECT_GT(numbers, 20);
  EXPECT_EQ(igac_test::read_file(tmp.path() / "whole" / "load_curve.csv"),
            igac_test::read_file(tmp.path() / "part" / "load_curve.csv"));
  EXPECT_EQ(listing(tmp.path()), (std::set<std::string>{"part", "whole"})) << "the stopped run is taken in";
}

// Large deformation: the shipped Neo-Hookean Hertz case (8 load steps).
TEST(Restart, KilledLargeDeformationRunContinues) {
  expect_stopped_run_continues("cases/hertz2d_neohookean_pressure.toml", {}, 3, SIGKILL);
}

// Small deformation along a load curve: the disc pushed and released, 4
// steps of about 0.15 s each at --refine 3 (time to kill it in between).
TEST(Restart, KilledSmallDeformationRunContinues) {
  expect_stopped_run_continues("tests/data/curve_contact.toml", {"--refine", "3"}, 2, SIGKILL);
}

// Friction along load curves: Cattaneo-Mindlin cycled (32 steps of about
// 30 ms), killed in the first drag and continued with its slip history.
TEST(Restart, KilledFrictionalRunContinues) {
  expect_stopped_run_continues("cases/cattaneo_mindlin_cycle.toml", {}, 11, SIGKILL);
}

// SIGTERM and SIGINT (Ctrl-C) end the run at once (app/launcher.hpp), and
// leave it to be continued as a SIGKILL does.
TEST(Restart, TerminatedRunContinues) {
  expect_stopped_run_continues("tests/data/curve_contact.toml", {"--refine", "3"}, 1, SIGTERM);
}

TEST(Restart, InterruptedRunContinues) {
  expect_stopped_run_continues("tests/data/curve_contact.toml", {"--refine", "3"}, 2, SIGINT);
}

}  // namespace
