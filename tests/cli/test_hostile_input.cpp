// SPDX-License-Identifier: BSD-3-Clause
// Regression tests for what a hostile or clumsy user found (issue 12): each
// of these failed before its fix.  Shell injection through the case name or
// --out, names that climb out of out/, a converged run called failed because
// its name contains "null", zero and tiny loads, obstacles the body can never
// touch, and exceptions thrown inside KINSOL's callbacks.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/load_stepping.hpp"
#include "engine/numerical_failure.hpp"
#include "tests/support/igac_process.hpp"

namespace {

namespace fs = std::filesystem;
using igac_test::Outcome;
using igac_test::quote;
using igac_test::run_igac;
using igac_test::TempDir;

// cases/NAME.toml with `from` replaced by `to` (which must occur), written to dir/file.
fs::path edited_case(const std::string& name, const std::string& from, const std::string& to, const fs::path& dir,
                     const std::string& file = "case.toml") {
  std::string text = igac_test::read_file(std::string(IGAC_SOURCE_DIR) + "/cases/" + name + ".toml");
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  const fs::path path = dir / file;
  std::ofstream(path) << text;
  return path;
}

nlohmann::json summary(const fs::path& out) { return igac_test::read_summary(out); }

TEST(HostileInput, ShellMetacharactersInNameAndOutRunNothing) {
  TempDir tmp("inject");
  const fs::path c = edited_case("hertz2d", "name = \"hertz2d\"", "name = \"x'; touch PWNED; echo '\"", tmp.path());
  const fs::path out = tmp.path() / "o'; touch PWNED2; echo '";
  const Outcome o = run_igac("run " + quote(c.string()) + " --quiet --out " + quote(out.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "PWNED")) << "the case name was run by a shell";
  EXPECT_FALSE(fs::exists(tmp.path() / "PWNED2")) << "--out was run by a shell";
  EXPECT_TRUE(fs::is_regular_file(out / "summary.json"));
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << "left over: " << e.path();
}

TEST(HostileInput, NameThatIsNotAPlainFileNameIsRefused) {
  for (const std::string bad : {"../../escaped", "", "..", ".", "a/b"}) {
    TempDir tmp("name");
    const fs::path c = edited_case("hertz2d", "name = \"hertz2d\"", "name = \"" + bad + "\"", tmp.path());
    const Outcome o = run_igac("run " + quote(c.string()), tmp.path());
    EXPECT_EQ(o.exit_code, 2) << bad << ": " << o.output;
    EXPECT_NE(o.output.find("[top level] name"), std::string::npos) << o.output;
    EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
    EXPECT_FALSE(fs::exists(tmp.path() / "out")) << bad;
    EXPECT_FALSE(fs::exists(tmp.path().parent_path().parent_path() / "escaped"));
  }
}

TEST(HostileInput, CaseNamedNullConverges) {
  TempDir tmp("null");
  const fs::path c = edited_case("hertz2d", "name = \"hertz2d\"", "name = \"nullcase\"", tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = summary(tmp.path() / "out");
  EXPECT_EQ(j.value("status", ""), "converged");
  // the name is carried through, and the run is hertz2d's (measured: 30
  // active multipliers, contact force = P R to 4e-16)
  EXPECT_EQ(j.value("case", ""), "nullcase");
  EXPECT_EQ(j["contact"].value("active", 0), 30);
  EXPECT_NEAR(j["contact"].value("total_force", 0.0), 0.003, 1e-12 * 0.003);
}

TEST(HostileInput, ZeroLoadGivesZeroDisplacementAndNoNaN) {
  TempDir tmp("zero");
  const fs::path c = edited_case("hertz2d", "value = 0.003", "value = 0.0", tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()) + " --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output.find("nan"), std::string::npos) << o.output;
  const nlohmann::json j = summary(tmp.path() / "out");
  EXPECT_EQ(j.value("status", ""), "converged");
  EXPECT_EQ(j["contact"].value("total_force", 1.0), 0.0);
  EXPECT_FALSE(j["errors"].contains("pressure_l2_rel")) << "a relative error against zero is absent";
  const std::string csv = igac_test::read_file(tmp.path() / "out" / "pressure.csv");
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("inf"), std::string::npos) << csv;
}

TEST(HostileInput, TinyLoadConverges) {
  TempDir tmp("tiny");
  const fs::path c = edited_case("hertz2d", "value = 0.003", "value = 1e-20", tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()) + " --quiet --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 0) << o.output;
  const nlohmann::json j = summary(tmp.path() / "out");
  EXPECT_NEAR(j["contact"].value("total_force", 0.0), 1e-20, 1e-30);
}

TEST(HostileInput, ObstacleNormalPointingAwayIsAnInputError) {
  TempDir tmp("away");
  const fs::path c = edited_case("hertz2d", "normal = [0.0, 1.0]", "normal = [0.0, -1.0]", tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("faces away from the obstacle"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

TEST(HostileInput, ContactFaceThatCannotTouchTheObstacleIsAnInputError) {
  TempDir tmp("top");
  const fs::path c = edited_case("hertz3d", "face = \"curved\"", "face = \"top\"", tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("[contact] face 'top'"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

struct MessageCase {
  std::string name, source, from, to;
  std::vector<std::string> fragments;
};
void PrintTo(const MessageCase& c, std::ostream* os) { *os << c.name; }

class InputMessage : public ::testing::TestWithParam<MessageCase> {};

// Inputs that used to end in a solver's words (a folded map, a knot
// multiplicity, "KINSOL stopped") now name the key or say what is wrong.
TEST_P(InputMessage, NamesTheKeyInOneLine) {
  const MessageCase& m = GetParam();
  TempDir tmp("message");
  const fs::path c = edited_case(m.source, m.from, m.to, tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  for (const auto& f : m.fragments) EXPECT_NE(o.output.find(f), std::string::npos) << f << " in: " << o.output;
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

INSTANTIATE_TEST_SUITE_P(
    HostileInput, InputMessage,
    ::testing::Values(
        MessageCase{"tiny_E", "hertz2d", "E = 1.0", "E = 1e-300", {"[material] E:", "1e-300"}},
        MessageCase{"tiny_radius", "hertz2d", "radius = 1.0", "radius = 1e-300", {"[geometry] radius:", "1e-300"}},
        MessageCase{"tiny_range_fraction", "hertz2d", "range_fraction = 0.1", "range_fraction = 1e-12",
                    {"[mesh.grading] range_fraction", "1e-12"}},
        MessageCase{"unknown_coarse_spans", "hertz2d", "range_fraction = 0.1", "range_fraction = 0.1\ncoarse = \"log\"",
                    {"[mesh.grading] coarse", "\"uniform\" or \"geometric\""}},
        MessageCase{"degree_1_on_arcs", "lame_cylinder", "degree = 2", "degree = 1", {"[mesh] degree:", "at least 2"}},
        MessageCase{"load_pulls_away", "hertz2d_neohookean_pressure", "value = 0.1", "value = -0.1",
                    {"the load pulls the body away from the obstacle"}},
        MessageCase{"not_held_large_deformation", "hertz2d_neohookean_pressure", "faces = [\"left\"]\ncomponent = \"x\"",
                    "faces = [\"left\"]\ncomponent = \"y\"\nvalue = 0.0", {"the body is not held"}},
        MessageCase{"load_pulls_away_small_deformation", "hertz2d", "value = 0.003", "value = -0.003",
                    {"the load pulls the body away from the obstacle"}},
        // bench/hostile_inputs.py: an obstacle 1e300 away ran, printed a
        // displacement of inf and ended in a failed VTU write (exit 1).
        MessageCase{"obstacle_point_1e300", "hertz2d", "point = [0.0, -1.0]", "point = [0.0, 1e300]",
                    {"[contact.obstacle] point:", "1e+300", "larger than 1e100"}},
        MessageCase{"obstacle_radius_1e300", "hertz2d", "type = \"plane\"\npoint = [0.0, -1.0]\nnormal = [0.0, 1.0]",
                    "type = \"sphere\"\ncentre = [0.0, -2.0]\nradius = 1e300",
                    {"[contact.obstacle] radius:", "larger than 1e100"}},
        // a side listed twice doubled its pressure silently, and made a
        // contact face's multipliers twice over: a "singular contact system" (exit 1)
        MessageCase{"pressure_face_twice", "hertz2d", "faces = [\"top\"]", "faces = [\"top\", \"top\"]",
                    {"[pressure] faces top, top:", "listed twice"}},
        MessageCase{"contact_set_lists_a_side_twice", "hertz2d", "face = \"curved\"",
                    "face = \"both\"\n[faces]\nboth = [\"curved\", \"curved\"]", {"[faces] faces curved, curved:", "listed twice"}},
        MessageCase{"same_obstacle_twice", "lame_cylinder", "[reference]",
                    "[[contact]]\nface = \"outer\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [2.0, 0.0]\nnormal = [-1.0, 0.0]\n"
                    "[[contact]]\nface = \"outer\"\n[contact.obstacle]\ntype = \"plane\"\npoint = [2.0, 0.0]\nnormal = [-1.0, 0.0]\n"
                    "[reference]", {"[contact] face: the contact of face 'outer' is given twice"}},
        // an obstacle type with a typo was reported as "normal: unknown key"
        MessageCase{"obstacle_type_typo", "hertz2d", "type = \"plane\"", "type = \"PLANE\"",
                    {"[contact.obstacle] type:", "unknown obstacle 'PLANE'"}},
        // a 3D obstacle in a 2D case was reported as "normal: unknown key"
        MessageCase{"cylinder_in_2d", "hertz2d", "type = \"plane\"", "type = \"cylinder\"",
                    {"[contact.obstacle] type:", "a cylinder obstacle needs a 3D body"}},
        // a name with a line break made the one-line error two lines
        MessageCase{"name_with_line_break", "hertz2d", "name = \"hertz2d\"", "name = \"new\\nline\"",
                    {"[top level] name:", "\"new\\nline\" is not a plain file name"}},
        // issue 35: toml++ reads an integer as a boolean (vtk = 0 was false)
        MessageCase{"integer_as_boolean", "hertz2d", "[reference]", "[output]\nvtk = 0\n[reference]",
                    {"case.toml:51: [output] vtk: must be true or false"}},
        // issue 35: a control character in a unit's name made the SVG plots invalid XML
        MessageCase{"unit_with_control_character", "hertz2d", "[reference]", "[units]\nlength = \"m\\u0007m\"\n[reference]",
                    {"case.toml:51: [units] length: \"m\\x07m\" holds a control character"}},
        // ... and in the name of a set of faces, which titles a plot of several contacts
        MessageCase{"face_set_name_with_control_character", "hertz2d", "face = \"curved\"",
                    "face = \"c\\u0001\"\n[faces]\n\"c\\u0001\" = [\"curved\"]",
                    {"[top level] faces: the name \"c\\x01\" holds a control character"}}),
    [](const ::testing::TestParamInfo<MessageCase>& info) { return info.param.name; });

TEST(HostileInput, SelfContradictingCaseIsWarnedAbout) {
  TempDir tmp("contra");
  const fs::path c = edited_case("hertz2d", "[[pressure]]",
                                 "[[dirichlet]]\nfaces = [\"left\"]\ncomponent = \"x\"\nvalue = 0.01\n\n"
                                 "[[dirichlet]]\nfaces = [\"curved\"]\ncomponent = \"y\"\n\n[[pressure]]",
                                 tmp.path());
  const Outcome o = run_igac("run " + quote(c.string()) + " --no-output", tmp.path());
  EXPECT_NE(o.output.find("igac: warning: " + c.string() + ": [[dirichlet]] face 'left' component x is given two values"),
            std::string::npos) << o.output;
  EXPECT_NE(o.output.find("holds component y of the contact face 'curved'"), std::string::npos) << o.output;
  const Outcome q = run_igac("run " + quote(c.string()) + " --no-output --quiet", tmp.path());
  EXPECT_EQ(q.output.find("warning"), std::string::npos) << "--quiet prints nothing but errors";
}

// A problem whose residual throws a NumericalFailure (an expected one: the
// state cannot be evaluated) on its second call: the exception must not
// cross KINSOL's C frames; the step fails with the reason, the driver cuts
// back and finally ends with a status naming it.  (Other exceptions
// propagate: tests/unit/engine/test_load_stepping.cpp.)
class ThrowingProblem final : public igac::NonlinearProblem {
 public:
  int size() const override { return 1; }
  bool residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) override {
    if (++calls_ >= 2) throw igac::NumericalFailure("material law blew up");
    r.resize(1);
    r[0] = x[0] - t;
    return true;
  }
  bool jacobian(double, const Eigen::VectorXd&, Eigen::SparseMatrix<double>& J) override {
    J.resize(1, 1);
    J.coeffRef(0, 0) = 1;
    J.makeCompressed();
    return true;
  }
  double force_scale(double, const Eigen::VectorXd&) override { return 1; }

 private:
  int calls_ = 0;
};

TEST(HostileInput, ExceptionInsideKinsolCallbackEndsTheRunCleanly) {
  ThrowingProblem problem;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1);
  igac::LoadSteppingOptions opt;
  opt.quiet = true;
  opt.min_increment = 0.2;
  igac::LoadSteppingSummary s;
  ASSERT_NO_THROW(s = igac::run_load_steps(problem, x, opt, {}));
  EXPECT_NE(s.status, "converged");
  EXPECT_NE(s.status.text().find("material law blew up"), std::string::npos) << s.status;
  EXPECT_TRUE(x.allFinite());
}

}  // namespace

namespace {

// bench/hostile_inputs.py: a case file that is a symlink loop ended with the
// library's "filesystem error: status: ..." as a failed run (exit 1), and a
// FIFO was called "no such case file".
TEST(HostileInput, CaseFileThatIsNoRegularFileIsAnInputError) {
  TempDir tmp("case_not_regular");
  fs::create_symlink("loop2.toml", tmp.path() / "loop.toml");
  fs::create_symlink("loop.toml", tmp.path() / "loop2.toml");
  ASSERT_EQ(mkfifo((tmp.path() / "fifo.toml").c_str(), 0600), 0);
  const Outcome loop = run_igac("run loop.toml --out out", tmp.path());
  EXPECT_EQ(loop.exit_code, 2) << loop.output;
  EXPECT_EQ(loop.output.rfind("igac: error: loop.toml: cannot read the case file (", 0), 0u) << loop.output;
  const Outcome fifo = run_igac("run fifo.toml --out out", tmp.path());
  EXPECT_EQ(fifo.exit_code, 2) << fifo.output;
  EXPECT_EQ(fifo.output, "igac: error: fifo.toml: not a regular file (a folder, FIFO or device): a case file must be a "
                         "regular file\n");
  const Outcome none = run_igac("run none.toml --out out", tmp.path());
  EXPECT_EQ(none.output, "igac: error: none.toml: no such case file\n");
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

}  // namespace

namespace {

// bench/hostile_inputs.py: a table header or key of 100000 dotted parts
// overflowed toml++'s stack (SIGSEGV).
TEST(HostileInput, KeyOfManyDottedPartsIsAnInputError) {
  TempDir tmp("dotted");
  std::string header = "[a";
  for (int k = 0; k < 100000; ++k) header += ".a";
  std::ofstream(tmp.path() / "case.toml") << "name = \"x.y\" # a.b.c\n" << header << "]\n";
  const Outcome o = run_igac("run case.toml --out out", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output.substr(0, 300);
  EXPECT_EQ(o.output, "igac: error: case.toml:2: a key of more than 64 dotted parts\n");
  EXPECT_FALSE(fs::exists(tmp.path() / "out"));
}

}  // namespace
