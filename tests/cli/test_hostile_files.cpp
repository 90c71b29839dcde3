// SPDX-License-Identifier: BSD-3-Clause
// Issue 35, the files a run reads and writes beside its case file: each of
// these failed before its fix.  A restart folder whose solution.pvd names a
// file outside it (the restart deleted that file), whose state files say a
// time or an increment the case never takes (NaN: "converged" after 3 of 8
// steps; dt = 0: a run without end), whose state file is damaged (a flipped
// bit was taken), or whose files are folders, FIFOs or /dev/zero (exit 3,
// exit 1 in a library's words, a run that hung); a file put into --out
// during a run (deleted when it ended); an empty --restart (a fresh run,
// silently); --from-step 0 (a range of 309 digits).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "io/state_file.hpp"
#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

// A run that does not stop on its own fails the test (exit 124) instead of
// hanging it, and one that reads without end (/dev/zero) runs out of its
// own 2 GB of address space, not the machine's memory.
const std::string kTimeout = "ulimit -v 2000000; timeout 300";

const std::string kCase = quote(std::string(IGAC_SOURCE_DIR) + "/tests/data/curve_block_neohookean.toml");

// The earlier run a restart reads: the large-deformation block (5 steps,
// ParaView files) stopped after step 3, in dir/a0; each check works on a
// copy, dir/a.
void stopped_run(const TempDir& tmp) {
  const Outcome o = run_igac("run " + kCase + " --quiet --out a0 --stop-after-step 3", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
}

// `--restart a` from a fresh copy of a0 edited by `edit`: exit 2, the line
// it says is `line` exactly (the only line), and nothing written.
void expect_restart_refused(const TempDir& tmp, const std::function<void(const fs::path&)>& edit, const std::string& line) {
  fs::remove_all(tmp.path() / "a");
  fs::copy(tmp.path() / "a0", tmp.path() / "a", fs::copy_options::recursive);
  edit(tmp.path() / "a");
  const Outcome o = run_igac("run " + kCase + " --quiet --out b --restart a", tmp.path(), kTimeout);
  EXPECT_EQ(o.exit_code, 2) << line << "\n" << o.output;
  EXPECT_EQ(o.output, "igac: error: " + line + "\n");
  EXPECT_FALSE(fs::exists(tmp.path() / "b"));
}

void replace_in(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = igac_test::read_file(file);
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::trunc) << text;
}

// The state file of step k with `change` made, written whole (its checksum
// right): what the reader checks beyond the checksum.
void change_state(const fs::path& dir, int k, const std::function<void(igac::StepState&)>& change) {
  const std::string path = (dir / igac::state_file_name(k)).string();
  igac::StateOrigin origin;
  igac::StepState s = igac::read_state_file(path, origin);
  change(s);
  igac::write_state_file(path, origin, s);
}

TEST(HostileFiles, RestartNeverTouchesFilesOutsideItsFolders) {
  TempDir tmp("outside");
  stopped_run(tmp);
  std::ofstream(tmp.path() / "x_0001.vtu") << "the user's";
  for (const std::string& named : std::vector<std::string>{"../x_0001.vtu", (tmp.path() / "x_0001.vtu").string()})
    expect_restart_refused(
        tmp, [&](const fs::path& a) { replace_in(a / "solution.pvd", "file=\"solution_0001.vtu\"", "file=\"" + named + "\""); },
        "a/solution.pvd:5: file=\"" + named + "\" is not the name of a ParaView file igac writes (NAME_NNNN.vtu in "
        "the run's own folder)");
  EXPECT_EQ(igac_test::read_file(tmp.path() / "x_0001.vtu"), "the user's");
}

TEST(HostileFiles, RestartRefusesAStateOffTheCasesSchedule) {
  TempDir tmp("schedule");
  stopped_run(tmp);
  // Steps 2 and 3 ended at t = 0.625 and 1 (of the block's 5, t in (0, 2]).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::string state3 = "a/state_0003.bin: not a state of this case: ";
  for (const double t : {nan, 1e300, 0.5})
    expect_restart_refused(
        tmp, [&](const fs::path& a) { change_state(a, 3, [&](igac::StepState& s) { s.driver.t = t; }); },
        state3 + fmt::format("t = {}, where step 3 lies in (0.625, 2]", t));
  // A next increment of 0, below 0 or below the smallest cut-back never
  // reached the end; NaN or beyond the largest is no increment [loading] gives.
  for (const double dt : {0.0, -0.1, 1e-300, nan, 1e300})
    expect_restart_refused(
        tmp, [&](const fs::path& a) { change_state(a, 3, [&](igac::StepState& s) { s.driver.dt = dt; }); },
        state3 + fmt::format("the next increment dt = {} lies outside [0.0001, 1.5], where [loading] puts it", dt));
  expect_restart_refused(
      tmp, [&](const fs::path& a) { change_state(a, 3, [&](igac::StepState& s) { s.driver.dt_old = nan; }); },
      state3 + "the last increment dt_old = nan lies outside [0, 1]");
  expect_restart_refused(
      tmp, [&](const fs::path& a) { change_state(a, 3, [&](igac::StepState& s) { s.driver.x[0] = nan; }); },
      state3 + "its unknowns hold a number that is not finite");
  expect_restart_refused(
      tmp, [&](const fs::path& a) { change_state(a, 2, [&](igac::StepState& s) { s.record.load_factor = 0.5; }); },
      "a/state_0002.bin: not a state of this case: its step's record is at t = 0.5 and 0.625, its state at 0.625");
  // Untouched, the same folder continues.
  fs::remove_all(tmp.path() / "a");
  fs::copy(tmp.path() / "a0", tmp.path() / "a", fs::copy_options::recursive);
  const Outcome o = run_igac("run " + kCase + " --quiet --out b --restart a", tmp.path(), kTimeout);
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(igac_test::read_summary(tmp.path() / "b")["load_steps"].size(), 5u);
}

// Small deformation along load curves: each step's time is the case's own.
TEST(HostileFiles, RestartRefusesATimeTheLoadCurvesDoNotHave) {
  TempDir tmp("curve_schedule");
  const std::string c = quote(std::string(IGAC_SOURCE_DIR) + "/tests/data/curve_contact.toml");
  ASSERT_EQ(run_igac("run " + c + " --quiet --out a --stop-after-step 2", tmp.path()).exit_code, 0);
  change_state(tmp.path() / "a", 2, [](igac::StepState& s) { s.driver.t = s.record.load_factor = s.point.load_factor = 0.75; });
  const Outcome o = run_igac("run " + c + " --quiet --out b --restart a", tmp.path(), kTimeout);
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output, "igac: error: a/state_0002.bin: not a state of this case: t = 0.75, where this case has step 2 "
                      "at t = 1\n");
}

// One bit of a number flipped (the lowest of x's first mantissa): the state
// differs, and the restart went on from it.
TEST(HostileFiles, RestartRefusesADamagedStateFile) {
  TempDir tmp("damaged");
  stopped_run(tmp);
  expect_restart_refused(
      tmp,
      [](const fs::path& a) {
        const fs::path state = a / "state_0003.bin";
        std::string bytes = igac_test::read_file(state);
        igac::StateOrigin origin;
        const igac::StepState s = igac::read_state_file(state.string(), origin);
        // x starts after the magic, version, hash, options, step, t, dt, dt_old and x's length
        const size_t x0 = 16 + 8 + origin.case_hash.size() + 8 + origin.options.size() + 8 + 24 + 8;
        double first;
        std::memcpy(&first, bytes.data() + x0, 8);
        ASSERT_EQ(first, s.driver.x[0]);
        bytes[x0] = char(bytes[x0] ^ 1);
        std::ofstream(state, std::ios::binary | std::ios::trunc) << bytes;
      },
      "a/state_0003.bin: not a state file igac can restart from (damaged: its checksum does not match its contents, "
      "cut short or altered)");
}

TEST(HostileFiles, RestartFolderEntriesThatAreNotFilesAreRefusedInOneLine) {
  TempDir tmp("entries");
  stopped_run(tmp);
  const std::string not_regular = ": not a regular file (a folder, FIFO or device): a ";
  // exit 3, "internal error: stod"
  expect_restart_refused(
      tmp, [](const fs::path& a) { replace_in(a / "solution.pvd", "timestep=\"0.25\"", "timestep=\"abc\""); },
      "a/solution.pvd:5: timestep=\"abc\" is not a number");
  // exit 1, "basic_filebuf::underflow error reading the file: Is a directory"
  expect_restart_refused(tmp, [](const fs::path& a) { fs::remove(a / "state_0002.bin"), fs::create_directory(a / "state_0002.bin"); },
                         "a/state_0002.bin" + not_regular + "state file must be a regular file");
  // these waited forever (a FIFO) or read until the memory ran out (/dev/zero)
  expect_restart_refused(tmp, [](const fs::path& a) { fs::remove(a / "state_0002.bin"), mkfifo((a / "state_0002.bin").c_str(), 0600); },
                         "a/state_0002.bin" + not_regular + "state file must be a regular file");
  expect_restart_refused(tmp, [](const fs::path& a) { fs::remove(a / "state_0003.bin"), fs::create_symlink("/dev/zero", a / "state_0003.bin"); },
                         "a/state_0003.bin" + not_regular + "state file must be a regular file");
  expect_restart_refused(tmp, [](const fs::path& a) { fs::remove(a / "solution.pvd"), mkfifo((a / "solution.pvd").c_str(), 0600); },
                         "a/solution.pvd" + not_regular + "ParaView collection (.pvd) must be a regular file");
  expect_restart_refused(tmp, [](const fs::path& a) { fs::remove(a / "solution.pvd"), fs::create_symlink("/dev/zero", a / "solution.pvd"); },
                         "a/solution.pvd" + not_regular + "ParaView collection (.pvd) must be a regular file");
  // a step's file the .pvd names and the folder lacks (a filesystem error, exit 1)
  expect_restart_refused(tmp, [](const fs::path& a) { fs::remove(a / "solution_0002.vtu"); },
                         "a/solution.pvd:6: a/solution_0002.vtu is not there, or not a regular file");
}

TEST(HostileFiles, EmptyRestartAndStepZeroAreRefusedInOneLine) {
  TempDir tmp("options");
  stopped_run(tmp);
  const Outcome empty = run_igac("run " + kCase + " --quiet --out b --restart ''", tmp.path());
  EXPECT_EQ(empty.exit_code, 2) << empty.output;
  EXPECT_EQ(empty.output, "igac: error: --restart: an empty folder name (give the output folder of the run to continue)\n");
  EXPECT_FALSE(fs::exists(tmp.path() / "b")) << "a fresh run, silently";
  for (const std::string option : {"--from-step", "--stop-after-step"}) {
    const Outcome zero = run_igac("run " + kCase + " --quiet --out b --restart a0 " + option + " 0", tmp.path());
    EXPECT_EQ(zero.exit_code, 2) << zero.output;
    EXPECT_EQ(zero.output, "igac: error: " + option + ": \"0\" is not a step number (1, 2, ...) (see igac run --help)\n");
  }
}

// The check that --out holds nothing but igac's files runs when the run
// starts; what the user put there later was removed with the previous
// output when the run ended.  Now only igac's files go: another file moves
// into the new output (and the next run refuses the folder, naming it), or,
// where the run wrote a file of its name, stays with the previous output in
// a folder beside, and the run says where.
TEST(HostileFiles, AFileAddedToOutDuringTheRunIsNeverDeleted) {
  TempDir tmp("added");
  const std::string hertz = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml";
  ASSERT_EQ(run_igac("run " + quote(hertz) + " --quiet --out out", tmp.path()).exit_code, 0);
  ASSERT_FALSE(fs::exists(tmp.path() / "out" / "load_curve.csv"));
  const std::string stepped = std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d_neohookean_pressure.toml";
  // The run, held (SIGSTOP) once its first step is written, so that the files
  // come after its start and before its end whatever the machine's speed.
  int pipe_fd[2];
  ASSERT_EQ(pipe(pipe_fd), 0);
  const pid_t pid = fork();
  if (pid == 0) {
    if (chdir(tmp.path().c_str()) != 0) _exit(127);
    dup2(pipe_fd[1], STDERR_FILENO);
    close(pipe_fd[0]);
    execl(IGAC_BINARY, IGAC_BINARY, "run", stepped.c_str(), "--quiet", "--out", "out", static_cast<char*>(nullptr));
    _exit(127);
  }
  close(pipe_fd[1]);
  const fs::path first = tmp.path() / (".out.igac-tmp-" + std::to_string(pid)) / "state_0001.bin";
  int status = 0;
  bool ended = false;
  for (int i = 0; i < 240000 && !fs::exists(first) && !ended; ++i) {  // up to 2 minutes on a loaded machine
    ended = waitpid(pid, &status, WNOHANG) == pid;
    std::this_thread::sleep_for(std::chrono::microseconds(500));
  }
  ASSERT_FALSE(ended) << "the run ended before its first step was written";
  kill(pid, SIGSTOP);
  std::ofstream(tmp.path() / "out" / "notes.txt") << "mine";
  std::ofstream(tmp.path() / "out" / "load_curve.csv") << "mine too";
  kill(pid, SIGCONT);
  waitpid(pid, &status, 0);
  std::string said;
  char buf[4096];
  for (ssize_t n; (n = read(pipe_fd[0], buf, sizeof buf)) > 0;) said.append(buf, size_t(n));
  close(pipe_fd[0]);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << said;
  const fs::path out = tmp.path() / "out", kept = tmp.path() / ("out.igac-kept-" + std::to_string(pid));
  EXPECT_EQ(igac_test::read_file(out / "notes.txt"), "mine");
  EXPECT_EQ(igac_test::read_summary(out)["case"], "hertz2d_neohookean_pressure");
  EXPECT_NE(igac_test::read_file(out / "load_curve.csv"), "mine too");
  EXPECT_EQ(igac_test::read_file(kept / "load_curve.csv"), "mine too");
  EXPECT_EQ(igac_test::read_summary(kept)["case"], "hertz2d") << "the previous output, kept with it";
  EXPECT_EQ(said, "igac: warning: --out '" + out.string() + "': load_curve.csv put there during the run, where the "
                  "run wrote a file of the same name: kept in " + kept.string() + ", with the previous output\n");
  // notes.txt is not igac's: the next run into out refuses to replace it.
  const Outcome next = run_igac("run " + quote(hertz) + " --quiet --out out", tmp.path());
  EXPECT_EQ(next.exit_code, 2) << next.output;
  EXPECT_NE(next.output.find("exists and holds what igac did not write (notes.txt)"), std::string::npos) << next.output;
  EXPECT_EQ(igac_test::read_file(out / "notes.txt"), "mine");
}

}  // namespace
