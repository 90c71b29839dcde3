// SPDX-License-Identifier: BSD-3-Clause
// What the console and the summary tell a user while and after a run
// (issue 25): the header before the progress lines, a line per active-set
// iteration, --quiet quiet; the [units] labels; the progress bar of the
// step lines on a terminal, and not in a pipe.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <pty.h>
#include <sys/wait.h>
#include <unistd.h>
#include <string>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

// cases/hertz2d.toml with `extra` appended, written to dir/hertz2d.toml.
fs::path hertz_with(const std::string& extra, const fs::path& dir) {
  const fs::path p = dir / "hertz2d.toml";
  std::ofstream(p) << igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml") << "\n" << extra;
  return p;
}

size_t count_of(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Console, HeaderFirstThenALinePerActiveSetIteration) {
  igac_test::TempDir tmp("progress");
  const fs::path c = hertz_with("", tmp.path());
  const auto o = igac_test::run_igac("run " + igac_test::quote(c.string()) + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = igac_test::read_summary(tmp.path() / "out");
  EXPECT_EQ(o.output.rfind("igac: hertz2d — 2D", 0), 0u) << o.output;  // the very first line
  const size_t first = o.output.find("active set   1: ");
  ASSERT_NE(first, std::string::npos) << o.output;
  EXPECT_LT(first, o.output.find("  status        converged")) << o.output;
  EXPECT_EQ(count_of(o.output, "\nactive set "), j["contact"]["active_set_iterations"].get<size_t>()) << o.output;
  EXPECT_NE(o.output.find(" active, 0 changing ("), std::string::npos) << o.output;  // the last one settles

  const auto q = igac_test::run_igac("run " + igac_test::quote(c.string()) + " --out out2 --quiet", tmp.path());
  ASSERT_EQ(q.exit_code, 0) << q.output;
  EXPECT_EQ(q.output, "");
}

TEST(Console, UnitsAreLabelsEchoedInTheSummaryConsoleAndPlots) {
  igac_test::TempDir tmp("units");
  const fs::path c = hertz_with("[units]\nsystem = \"mm-N-MPa\"\n", tmp.path());
  const auto o = igac_test::run_igac("run " + igac_test::quote(c.string()) + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const auto j = igac_test::read_summary(tmp.path() / "out");
  EXPECT_EQ(j["units"], nlohmann::json::parse(R"({"system": "mm-N-MPa", "length": "mm", "force": "N", "stress": "MPa"})"));
  EXPECT_NE(o.output.find("  units         length mm, force N, stress MPa (labels only"), std::string::npos) << o.output;

  // Without the table: "consistent units"; the plots' axes name no unit.
  const fs::path plain = hertz_with("", tmp.path());
  const auto p = igac_test::run_igac("run " + igac_test::quote(plain.string()) + " --out plain --quiet", tmp.path());
  ASSERT_EQ(p.exit_code, 0) << p.output;
  EXPECT_EQ(igac_test::read_summary(tmp.path() / "plain")["units"]["system"], "consistent units");

  // One key overrides the system's name; an unknown system, or key, is refused.
  const fs::path own = hertz_with("[units]\nsystem = \"SI\"\nstress = \"GPa\"\n", tmp.path());
  ASSERT_EQ(igac_test::run_igac("run " + igac_test::quote(own.string()) + " --out own --quiet", tmp.path()).exit_code, 0);
  const auto u = igac_test::read_summary(tmp.path() / "own")["units"];
  EXPECT_EQ(u["length"], "m");
  EXPECT_EQ(u["stress"], "GPa");
  const fs::path bad = hertz_with("[units]\nsystem = \"imperial\"\n", tmp.path());
  const auto b = igac_test::run_igac("run " + igac_test::quote(bad.string()) + " --no-output", tmp.path());
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_NE(b.output.find("unknown system 'imperial'"), std::string::npos) << b.output;
  const fs::path typo = hertz_with("[units]\nlenght = \"mm\"\n", tmp.path());
  const auto t = igac_test::run_igac("run " + igac_test::quote(typo.string()) + " --no-output", tmp.path());
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_NE(t.output.find("length"), std::string::npos) << t.output;  // did you mean
}

// The pressure plot of a case against a plane (no Hertz scale) names its
// axes' units.
TEST(Console, PlotAxesCarryTheUnits) {
  igac_test::TempDir tmp("axes");
  std::string s = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/hertz2d.toml");
  s.replace(s.find("solution = \"hertz\""), 18, "solution = \"none\"");
  std::ofstream(tmp.path() / "plain.toml") << s << "\n[units]\nsystem = \"mm-N-MPa\"\n";
  const auto o = igac_test::run_igac("run plain.toml --out out --quiet", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const std::string svg = igac_test::read_file(tmp.path() / "out" / "pressure.svg");
  EXPECT_NE(svg.find("[MPa]"), std::string::npos);
  EXPECT_NE(svg.find("[mm]"), std::string::npos);
}

// `igac ARGS` in `cwd` with its output on a pseudo-terminal, as `script`
// runs it: what a person at a terminal sees (the pty writes \r\n).
igac_test::Outcome run_on_terminal(const std::string& args, const fs::path& cwd) {
  igac_test::Outcome o;
  int master = -1;
  const std::string cmd = "cd " + igac_test::quote(cwd.string()) + " && exec " + igac_test::quote(IGAC_BINARY) + " " + args;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid < 0) {
    ADD_FAILURE() << "forkpty failed";
    return o;
  }
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  char buf[4096];
  for (ssize_t n; (n = read(master, buf, sizeof buf)) > 0;) o.output.append(buf, size_t(n));  // EIO once it ends
  close(master);
  int status = 0;
  waitpid(pid, &status, 0);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

// The bar showed only in the heartbeat, after 4 s without a line, so a run
// whose steps come faster never showed it (tried under `script`).  Now every
// step line ends with it on a terminal: the load steps of large
// deformation and the steps of a small-deformation load history, the last
// at 100 %; in a pipe the lines stay plain.
TEST(Console, StepLinesEndWithTheBarOnATerminal) {
  igac_test::TempDir tmp("bar");
  for (const std::string c : {"curve_block_neohookean.toml", "curve_block.toml"}) {
    const std::string args = "run " + igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/tests/data/" + c) + " --no-output";
    const auto t = run_on_terminal(args, tmp.path());
    ASSERT_EQ(t.exit_code, 0) << c << ": " << t.output;
    EXPECT_NE(t.output.find("step   1: time "), std::string::npos) << t.output;
    EXPECT_NE(t.output.find("%\r\n"), std::string::npos) << c << ": " << t.output;  // a step line ends with a bar
    EXPECT_NE(t.output.find("  [####################] 100 %\r\n"), std::string::npos) << c << ": " << t.output;
    const auto p = igac_test::run_igac(args, tmp.path());
    ASSERT_EQ(p.exit_code, 0) << p.output;
    EXPECT_NE(p.output.find("step   1: time "), std::string::npos) << p.output;
    EXPECT_EQ(p.output.find("[#"), std::string::npos) << c << ": " << p.output;
    EXPECT_EQ(p.output.find("%\n"), std::string::npos) << c << ": " << p.output;
  }
}

}  // namespace
