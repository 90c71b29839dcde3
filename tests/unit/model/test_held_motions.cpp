// SPDX-License-Identifier: BSD-3-Clause
// Near-mechanisms (model/held_motions.hpp): a motion the stiffness or the
// contact barely holds is warned about, on the console and in
// summary.json's "warnings", naming the motion.  The issue: a plate that
// could rotate about its contact gave a tangential force of about 0 and no
// word.  Checked, independently of any condition estimate's value:
//  - a wedge clamped on a face 1e-4 of its length turns about it: "the
//    stiffness is nearly singular: a rotation about (~0, ~0)"; the same
//    wedge on a wide root, and shipped linear cases, are not warned about
//    (every shipped linear case measured: pivot ratios 3.7 ... 1950, far
//    below 1e7; four of them run here);
//  - the contact's hold on the free rigid motions, on operators made to
//    hold one of them 1e-6 times less than the others (named: the rotation
//    about the centroid, the translation), and not at 1e-3;
//  - the motion in words: rigid motions in 2D and 3D, and a deformation.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "io/case_file.hpp"
#include "model/held_motions.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

namespace fs = std::filesystem;

// A degree-1 wedge: its left side, of height `root`, clamped at x = 0; its
// right side 0.2 high at x = 1; a pressure on its top.
fs::path wedge_case(const fs::path& dir, double root) {
  std::ofstream(dir / "wedge.xml") << "<?xml version=\"1.0\"?>\n<xml>\n <Geometry type=\"TensorBSpline2\" id=\"0\">\n"
                                      "  <Basis type=\"TensorBSplineBasis2\">\n"
                                      "   <Basis type=\"BSplineBasis\" index=\"0\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>\n"
                                      "   <Basis type=\"BSplineBasis\" index=\"1\"><KnotVector degree=\"1\">0 0 1 1</KnotVector></Basis>\n"
                                      "  </Basis>\n  <coefs geoDim=\"2\">\n0 "
                                   << -root / 2 << "\n1 -0.1\n0 " << root / 2 << "\n1 0.1\n</coefs>\n </Geometry>\n</xml>\n";
  std::ofstream(dir / "wedge.toml") << "[geometry]\nfile = \"wedge.xml\"\n[mesh]\ndegree = 2\nelements = [32, 4]\n"
                                       "[material]\nE = 1.0\nnu = 0.3\n"
                                       "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"x\"\n"
                                       "[[dirichlet]]\nfaces = [\"0:west\"]\ncomponent = \"y\"\n"
                                       "[[pressure]]\nfaces = [\"0:north\"]\nvalue = 1e-4\n";
  return dir / "wedge.toml";
}

const std::string kStiffness = "the stiffness is nearly singular: a rotation about (";

TEST(HeldMotions, WedgeHingedOnATinyFaceTurnsAboutIt) {
  igac_test::TempDir tmp("hinge");
  wedge_case(tmp.path(), 1e-4);
  const auto o = igac_test::run_igac("run wedge.toml --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const size_t at = o.output.find("igac: warning: wedge.toml: " + kStiffness);
  ASSERT_NE(at, std::string::npos) << o.output;
  // The centre of the rotation is the hinge (0, 0), within the root's
  // neighbourhood (a 100th of the wedge's length).
  double x = 1, y = 1;
  ASSERT_EQ(std::sscanf(o.output.c_str() + at + std::string("igac: warning: wedge.toml: " + kStiffness).size(),
                        "%lf, %lf)", &x, &y), 2)
      << o.output;
  EXPECT_LT(std::abs(x), 0.01) << o.output;
  EXPECT_LT(std::abs(y), 0.01) << o.output;
  const auto j = igac_test::read_summary(tmp.path() / "out");
  bool in_summary = false;
  for (const auto& w : j["warnings"]) in_summary = in_summary || w.get<std::string>().find(kStiffness) != std::string::npos;
  EXPECT_TRUE(in_summary) << j["warnings"];
  // On a root as high as its tip is, nothing is nearly singular.
  igac_test::TempDir wide("root");
  wedge_case(wide.path(), 0.2);
  const auto w = igac_test::run_igac("run wedge.toml --no-output", wide.path());
  ASSERT_EQ(w.exit_code, 0) << w.output;
  EXPECT_EQ(w.output.find("nearly singular"), std::string::npos) << w.output;
}

TEST(HeldMotions, ShippedLinearCasesAreNotWarnedAbout) {
  for (const std::string c : {"hertz2d", "two_blocks", "lame_cylinder", "roller_on_block"}) {
    Model m = build_model(read_case(std::string(IGAC_SOURCE_DIR) + "/cases/" + c + ".toml"));
    const RunResult r = solve_model(m, quiet_run());
    ASSERT_EQ(r.status, "converged") << c;
    for (const std::string& w : r.warnings) {
      EXPECT_EQ(w.find("nearly singular"), std::string::npos) << c << ": " << w;
      EXPECT_EQ(w.find("barely holds"), std::string::npos) << c << ": " << w;
    }
  }
}

// A block [0, 1] x [0, 0.25] free of Dirichlet conditions: three free rigid
// modes (x, y, the rotation about the centroid, orthonormal, in that order),
// and an "active set" of three rows seeing them scaled by `hold`.
struct Held {
  Model model;
  RigidModes modes;
  WeightedGapOperator op;
  ContactSolution s;
  explicit Held(const Eigen::Vector3d& hold)
      : model(build_model(read_case_text("[geometry]\nshape = \"rectangle\"\nsize = [1.0, 0.25]\n"
                                         "[mesh]\ndegree = 2\nelements = [8, 2]\n[material]\nE = 1.0\nnu = 0.3\n"))),
        modes(free_rigid_modes(model.body, *model.dofs)) {
    const Eigen::MatrixXd rows = hold.asDiagonal() * modes.modes.transpose();
    op.G = rows.sparseView();
    op.weights = Eigen::VectorXd::Ones(3);
    op.g0 = Eigen::VectorXd::Zero(3);
    s.active.assign(3, 1);
  }
  static CaseSpec read_case_text(const std::string& text) {
    const fs::path p = fs::temp_directory_path() / ("igac_held_" + std::to_string(getpid()) + ".toml");
    std::ofstream(p) << text;
    CaseSpec spec = read_case(p.string());
    fs::remove(p);
    return spec;
  }
};

TEST(HeldMotions, ContactBarelyHoldingARigidMotionNamesIt) {
  ASSERT_EQ(Held({1, 1, 1}).modes.modes.cols(), 3);
  const auto rotation = [] {
    Held h({1, 1, 1e-6});
    return contact_hold_warning(h.model, h.op, h.s, h.modes);
  }();
  ASSERT_TRUE(rotation);
  EXPECT_NE(rotation->find("the contact barely holds a rotation about (0.5, 0.125): the active multipliers resist it "
                           "1e+06 times less"),
            std::string::npos)
      << *rotation;
  Held translation({1, 1e-6, 1});
  const auto t = contact_hold_warning(translation.model, translation.op, translation.s, translation.modes);
  ASSERT_TRUE(t);
  EXPECT_TRUE(t->find("the contact barely holds a translation along (0, 1)") != std::string::npos ||
              t->find("the contact barely holds a translation along (0, -1)") != std::string::npos)
      << *t;
  Held enough({1, 1, 1e-3});  // held 1e3 times less: a B^T B ratio of 1e6, inside 1e7
  EXPECT_FALSE(contact_hold_warning(enough.model, enough.op, enough.s, enough.modes));
}

TEST(HeldMotions, MotionInWords) {
  const Held h({1, 1, 1});
  const Body& body = h.model.body;
  const Eigen::MatrixXd& X = body.points();
  Eigen::MatrixXd u(X.rows(), 2);
  for (int a = 0; a < X.rows(); ++a) u.row(a) << -(X(a, 1) - 0.25), X(a, 0) - 2.0;  // about (2, 0.25)
  EXPECT_EQ(describe_motion(body, 1e-3 * u), "a rotation about (2, 0.25)");
  for (int a = 0; a < X.rows(); ++a) u.row(a) << 3.0, -4.0;
  EXPECT_EQ(describe_motion(body, u), "a translation along (0.6, -0.8)");
  for (int a = 0; a < X.rows(); ++a) u.row(a) << 0.0, X(a, 0) * X(a, 0) * X(a, 0);  // bending, largest at x = 1
  EXPECT_EQ(describe_motion(body, u).rfind("a deformation largest at (1, ", 0), 0u) << describe_motion(body, u);
  // 3D: about the axis z through (2, 0.5): the point of the axis nearest
  // the centroid (0.5, 0.5, 0.125).
  const Model box = build_model(Held::read_case_text("[geometry]\nshape = \"box\"\nsize = [1.0, 1.0, 0.25]\n"
                                                     "[mesh]\ndegree = 2\nelements = [2, 2, 1]\n"
                                                     "[material]\nE = 1.0\nnu = 0.3\n"));
  const Eigen::MatrixXd& Y = box.body.points();
  Eigen::MatrixXd v(Y.rows(), 3);
  for (int a = 0; a < Y.rows(); ++a) v.row(a) << -(Y(a, 1) - 0.5), Y(a, 0) - 2.0, 0.0;
  EXPECT_EQ(describe_motion(box.body, v), "a rotation about the axis (0, 0, 1) through (2, 0.5, 0.125)");
}

}  // namespace
}  // namespace igac
