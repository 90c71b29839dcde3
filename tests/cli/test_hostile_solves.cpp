// SPDX-License-Identifier: BSD-3-Clause
// Hostile inputs that ran wrong (issue 35): each test failed before its fix.
// --solver petsc on a case the PETSc path cannot run (it ran a frictional
// case frictionless, exit 0, no word of it).
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

// The PETSc path runs solve_model's small-deformation solve, frictionless and
// without load curves.  A case it cannot run is refused in one line, for the
// same reason, whether [solver] type = "petsc" or --solver petsc asks for it
// (run and study), and nothing is written.
TEST(PetscRefusal, SameReasonFromTheFileAndTheCommandLine) {
  struct Refused {
    std::string file, reason;
  };
  const std::vector<Refused> cases = {
      {"cases/cattaneo_mindlin.toml",
       "the PETSc solver runs frictionless contact only, not the friction = 0.3 of contact face 'arc'; use the "
       "direct solver"},
      {"tests/data/curve_contact.toml",
       "the PETSc solver runs without load curves only (the case has a curve); use the direct solver"},
      {"cases/hertz2d_neohookean_pressure.toml",
       "the PETSc solver runs small deformation (linear_elastic) only, not the neo_hookean law; use the direct solver"},
  };
  for (const Refused& r : cases) {
    TempDir tmp("petscrefused");
    // the case with [solver] type = "petsc" (its geometry file named whole)
    const fs::path from = kSource / r.file, c = tmp.path() / "case.toml";
    std::string text = source_text(r.file);
    if (const auto at = text.find("file = \""); at != std::string::npos)
      text.insert(at + 8, from.parent_path().string() + "/");
    std::ofstream(c) << text << "\n[solver]\ntype = \"petsc\"\n";
    const int solver_line = lines_of(text) + 3;
    for (const std::string& args : {"run " + quote(from.string()) + " --out out --solver petsc",
                                    "study " + quote(from.string()) + " --levels 2 --out out --solver petsc",
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

}  // namespace
