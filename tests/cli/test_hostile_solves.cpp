// SPDX-License-Identifier: BSD-3-Clause
// Hostile inputs that ran wrong (issue 35): each test failed before its fix.
// --solver petsc on a case the PETSc path cannot run (it ran a frictional
// case frictionless, exit 0, no word of it); load curves and increments
// that make billions of load steps (4.2 GB allocated, or an int overflowed
// and a segment was done in one step); messages of checks made after
// reading that named no line (overlapping bodies, a body not held, an
// unknown contact face, the memory guard, which also named [mesh] refine
// for a [body.mesh] key).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

const fs::path kSource = IGAC_SOURCE_DIR;

// The text of a file of the source tree.
std::string source_text(const std::string& relative) { return igac_test::read_file(kSource / relative); }

int lines_of(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

// The PETSc path runs every case; its spline multigrid preconditions the
// frictionless solves: the Newton steps of large deformation and the
// small-deformation active set without load curves.  A case it
// cannot precondition is refused in one line, for the same reason, whether
// the case file or the command line asks for it (run and study), and
// nothing is written.
TEST(PetscRefusal, SameReasonFromTheFileAndTheCommandLine) {
  struct Refused {
    std::string file, reason;
  };
  const std::vector<Refused> cases = {
      {"cases/cattaneo_mindlin.toml",
       "the spline multigrid needs the multipliers apart from the displacements, and the friction = 0.3 of contact "
       "face 'arc' solves them in one block with the displacements; leave preconditioner at \"options\" (default "
       "MUMPS LU)"},
      {"tests/data/curve_contact.toml",
       "the spline multigrid preconditions a small-deformation run without load curves only (the case has a curve); "
       "leave preconditioner at \"options\""},
      {"cases/oring_friction.toml",
       "the spline multigrid needs the multipliers apart from the displacements, and the friction = 0.3 of contact "
       "face 'outside' solves them in one block with the displacements; leave preconditioner at \"options\" (default "
       "MUMPS LU)"},
  };
  for (const Refused& r : cases) {
    TempDir tmp("petscrefused");
    // the case with [solver] type = "petsc" (its geometry file named whole)
    const fs::path from = kSource / r.file, c = tmp.path() / "case.toml";
    std::string text = source_text(r.file);
    if (const auto at = text.find("file = \""); at != std::string::npos)
      text.insert(at + 8, from.parent_path().string() + "/");
    std::ofstream(c) << text << "\n[solver]\ntype = \"petsc\"\npreconditioner = \"spline_multigrid\"\n";
    const int solver_line = lines_of(text) + 3;
    const std::string asks = " --solver petsc --preconditioner spline_multigrid";
    for (const std::string& args : {"run " + quote(from.string()) + " --out out" + asks,
                                    "study " + quote(from.string()) + " --levels 2 --out out" + asks,
                                    "run " + quote(c.string()) + " --out out"}) {
      const Outcome o = run_igac(args, tmp.path());
      const bool in_file = args.find("--solver") == std::string::npos;
      const std::string expected =
          in_file ? "igac: error: " + c.string() + ":" + std::to_string(solver_line) + ": [solver] type: " + r.reason
                  : "igac: error: " + from.string() + ": --solver petsc: " + r.reason;
      EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;
      EXPECT_EQ(o.output, expected + "\n") << args;
      EXPECT_FALSE(fs::exists(tmp.path() / "out")) << args;
    }
  }
}

// tests/data/curve_contact.toml (its top face pushed along a curve to t =
// 2, [loading] steps = 2 per unit time) with its curve ending at `end` and
// `steps` in place of its [loading] table, in dir/case.toml.
fs::path long_curve_case(const std::string& end, const std::string& steps, const fs::path& dir) {
  std::string text = source_text("tests/data/curve_contact.toml");
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"[2, 0]]", "[" + end + ", 0]]"},
                                 {"[loading]\nsteps = 2\n", steps}}) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  std::ofstream(dir / "case.toml") << text;
  return dir / "case.toml";
}

// The count of load steps is bounded (kMaxLoadSteps, 100000), and a case
// beyond it is refused on the key that sets it: [loading] steps or
// max_increment when given, else the curve that ends last.
TEST(LoadSteps, TooManyAreRefusedOnTheKeyThatSetsThem) {
  struct Refused {
    std::string end, steps, message;
  };
  const std::string why = "(each writes a ParaView step and a state file); give fewer steps per unit time or shorter "
                          "curves";
  const std::vector<Refused> cases = {
      {"2e6", "[loading]\nsteps = 1000\n",
       "case.toml:30: [loading] steps: steps = 1000 per unit time along load curves that end at t = 2e+06 make "
       "2e+09 load steps, more than 100000 " + why},
      {"2e6", "",  // the default 10 per unit time: the curve is named
       "case.toml:22: [dirichlet] curve: steps = 10 per unit time along load curves that end at t = 2e+06 make "
       "2e+07 load steps, more than 100000 " + why},
      {"3e9", "[loading]\nsteps = 1\n",  // 3e9 steps in one segment: beyond an int
       "case.toml:30: [loading] steps: steps = 1 per unit time along load curves that end at t = 3e+09 make 3e+09 "
       "load steps, more than 100000 " + why},
  };
  for (const Refused& r : cases) {
    TempDir tmp("steps");
    long_curve_case(r.end, r.steps, tmp.path());
    const Outcome o = run_igac("run case.toml --out out", tmp.path());
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(o.output, "igac: error: " + r.message + "\n");
    EXPECT_FALSE(fs::exists(tmp.path() / "out"));
  }
  // large deformation: at least one step per max_increment
  TempDir tmp("increments");
  std::string text = source_text("cases/hertz2d_neohookean_pressure.toml");
  text.replace(text.find("[loading]\n"), 10, "[loading]\nmax_increment = 1e-6\nmin_increment = 1e-7\n");
  std::ofstream(tmp.path() / "case.toml") << text;
  const int line = lines_of(text.substr(0, text.find("max_increment = 1e-6"))) + 1;
  const Outcome o = run_igac("run case.toml --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output, "igac: error: case.toml:" + std::to_string(line) +
                          ": [loading] max_increment: max_increment = 1e-06 makes at least 1e+06 load steps, more than "
                          "100000 (each writes a ParaView step and a state file); give a larger max_increment\n");
}

// cases/NAME.toml with each `from` replaced by its `to` (each must occur),
// in dir/case.toml; returns the text.
std::string edited_case(const std::string& name, const std::vector<std::pair<std::string, std::string>>& edits,
                        const fs::path& dir) {
  std::string text = source_text("cases/" + name + ".toml");
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  }
  std::ofstream(dir / "case.toml") << text;
  return text;
}

// The 1-based line of the first line of `text` holding `marker`.
int line_of(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << marker;
  return lines_of(text.substr(0, at)) + 1;
}

// Checks made after reading (build_model, the held-body check, the memory
// guard) name the line of the key that causes them, as the reader's do.
TEST(MessagesAfterReading, NameTheLineOfTheirKey) {
  struct Refused {
    std::string name;
    std::vector<std::pair<std::string, std::string>> edits;
    std::string marker, message;  // the line holding `marker` prefixes `message`
    std::string args = "";
  };
  const std::vector<Refused> cases = {
      {"roller_on_block",
       {{"translate = [0.0, -5.0]", "translate = [0.0, -4.9]"}},
       "face = \"roller:curved\"",
       ": [contact] face 'roller:curved' starts inside the body of its master 'block:top': 0.1 deep at (0, -1), more "
       "than 0.001 x the face's size 1.41 = 0.00141; place the bodies apart ([body.geometry] translate), or declare a fit "
       "with interference = true in this [contact] table\n"},
      {"hertz2d",
       {{"value = 0.003", "value = -0.003"}},
       "value = -0.003",
       ": the load pulls the body away from the obstacle: only the contact holds it along its free rigid motion, and "
       "the load opens every gap (is the load's sign reversed?)\n"},
      {"hertz2d",
       {{"face = \"curved\"", "face = \"curvd\""}},
       "face = \"curvd\"",
       ": [contact] face: unknown face 'curvd' on a quarter_disc (known: curved, left, top, u0, u1, v0, v1, 0:west, "
       "0:east, 0:south, 0:north)\n"},
      {"roller_on_block",
       {{"elements = [48, 24]", "elements = [48, 24]\nrefine = 12"}},
       "refine = 12",
       ": [body.mesh] refine = 12 (body 'block'): "},  // (then the machine's memory)
  };
  for (const Refused& r : cases) {
    TempDir tmp("lines");
    const std::string text = edited_case(r.name, r.edits, tmp.path());
    const Outcome o = run_igac("run case.toml --out out", tmp.path());
    const std::string expected = "igac: error: case.toml:" + std::to_string(line_of(text, r.marker)) + r.message;
    EXPECT_EQ(o.exit_code, 2) << o.output;
    EXPECT_EQ(o.output.substr(0, expected.size()), expected);
    EXPECT_EQ(lines_of(o.output), 1) << o.output;
    EXPECT_FALSE(fs::exists(tmp.path() / "out"));
  }
  // --refine on the command line is named as such, not as a key of the file
  TempDir tmp("refine");
  const Outcome o = run_igac("run " + quote((kSource / "cases/hertz2d.toml").string()) + " --refine 40 --out out",
                             tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("igac: error: " + (kSource / "cases/hertz2d.toml").string() + ": --refine 40: ", 0), 0u)
      << o.output;
}

}  // namespace
