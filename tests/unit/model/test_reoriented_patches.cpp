// SPDX-License-Identifier: BSD-3-Clause
// A left-handed patch (det J < 0 throughout, as about half of the patches
// of G+Smo's multi-patch files) is not a fold: build_model runs its first
// direction backwards, keeps the face names the file gives, and says which
// patches it reoriented.  It was refused as "patch 0 folds".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace {

igac::Model half_annulus(const std::string& file) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "igac_reoriented";
  std::filesystem::create_directories(dir);
  const std::string toml = (dir / (file + ".toml")).string();
  std::ofstream(toml) << "[geometry]\nfile = \"" << IGAC_SOURCE_DIR << "/tests/data/" << file
                      << "\"\n[mesh]\ndegree = 2\nelements = [4, 2]\n[material]\nE = 1.0\nnu = 0.3\n"
                         "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"x\"\n"
                         "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"y\"\n"
                         "[[pressure]]\nfaces = [\"0:east\"]\nvalue = 0.01\n";
  return igac::build_model(igac::read_case(toml));
}

// The physical side a face name stands for: its control points.
Eigen::MatrixXd side_points(const igac::Model& m, const std::string& name) {
  const igac::PatchSide side = igac::resolve_faces(m, {name}, "test").front();
  const igac::NurbsPatch& p = m.body.patch(side.patch);
  const std::vector<int> cps = p.face_control_points(side.face);
  Eigen::MatrixXd X(cps.size(), p.space_dim());
  for (size_t i = 0; i < cps.size(); ++i) X.row(i) = p.points().row(cps[i]);
  return X;
}

TEST(ReorientedPatches, LeftHandedPatchRunsWithTheFilesFaceNames) {
  const igac::Model right = half_annulus("half_annulus_double_knot.xml");   // right-handed
  const igac::Model left = half_annulus("half_annulus_left_handed.xml");    // the same body, left-handed
  EXPECT_TRUE(right.reoriented_patches.empty());
  ASSERT_EQ(left.reoriented_patches, std::vector<int>{0});
  // "0:west" is the file's u = 0 side in both: theta = 0, y = 0, 1 <= x <= 2.
  for (const igac::Model* m : {&right, &left}) {
    const Eigen::MatrixXd west = side_points(*m, "0:west");
    EXPECT_LE(west.col(1).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_GE(west.col(0).minCoeff(), 1.0 - 1e-14);
    const Eigen::MatrixXd east = side_points(*m, "0:east");  // theta = pi: x < 0
    EXPECT_LE(east.col(0).maxCoeff(), -1.0 + 1e-14);
  }
  // The same body, held and loaded on the same faces: the same solution.
  const igac::RunResult a = igac::solve_model(right), b = igac::solve_model(left);
  ASSERT_EQ(a.status, "converged");
  ASSERT_EQ(b.status, "converged");
  EXPECT_NEAR(a.u.norm(), b.u.norm(), 1e-12 * a.u.norm());
  EXPECT_GT(a.u.norm(), 0);
}

}  // namespace
