// SPDX-License-Identifier: BSD-3-Clause
// The build's layering check (cmake/check_layering.cmake) on small source
// trees of its own: app/ and io/ include, of the folders below model/, only
// the headers its allow-list names.  (The list was a list of forbidden
// kernel headers kept by hand, and had drifted: app/main.cpp included
// contact/small_strain_friction.hpp, which it did not name.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;

// cmake/check_layering.cmake run on the tree `root`.
igac_test::Outcome check(const fs::path& root) {
  return igac_test::run_command(igac_test::quote(IGAC_CMAKE_COMMAND) + " -DSOURCE_DIR=" + igac_test::quote(root.string()) +
                                    " -P " + igac_test::quote(std::string(IGAC_SOURCE_DIR) + "/cmake/check_layering.cmake"),
                                root);
}

// A tree whose one file, FILE, includes HEADER.
fs::path tree_with(const fs::path& root, const std::string& file, const std::string& header) {
  fs::remove_all(root);
  fs::create_directories((root / file).parent_path());
  std::ofstream(root / file) << "// SPDX-License-Identifier: BSD-3-Clause\n#include \"" << header << "\"\n";
  return root;
}

TEST(Layering, TheSourceTreePasses) {
  const auto o = check(IGAC_SOURCE_DIR);
  EXPECT_EQ(o.exit_code, 0) << o.output;
}

TEST(Layering, AppAndIoIncludeOnlyTheAllowedHeadersBelowModel) {
  igac_test::TempDir tmp("layering");
  // The drifted include, and a kernel header no list has ever named.
  for (const auto& [file, header] : {std::pair<std::string, std::string>{"app/main.cpp", "contact/small_strain_friction.hpp"},
                                     {"io/writer.cpp", "engine/some_new_kernel.hpp"},
                                     {"app/x.hpp", "solvers/petsc_multigrid.hpp"}}) {
    const auto o = check(tree_with(tmp.path() / "t", file, header));
    EXPECT_NE(o.exit_code, 0) << file << " including " << header;
    EXPECT_NE(o.output.find(file + ": #include \"" + header + "\" (" + file.substr(0, file.find('/')) +
                            "/ computes nothing"),
              std::string::npos)
        << o.output;
  }
  // Data, registries and model/ itself are allowed.
  for (const auto& [file, header] : {std::pair<std::string, std::string>{"app/main.cpp", "contact/friction_state.hpp"},
                                     {"io/case_file.cpp", "materials/hyperelastic.hpp"},
                                     {"app/main.cpp", "model/solve.hpp"}}) {
    const auto o = check(tree_with(tmp.path() / "t", file, header));
    EXPECT_EQ(o.exit_code, 0) << file << " including " << header << ": " << o.output;
  }
  // The folders' order stands as before: io/ does not include app/.
  const auto up = check(tree_with(tmp.path() / "t", "io/x.cpp", "app/study.hpp"));
  EXPECT_NE(up.exit_code, 0);
  EXPECT_NE(up.output.find("io/x.cpp: #include \"app/study.hpp\" (io/ must not depend on app/)"), std::string::npos)
      << up.output;
}

}  // namespace
