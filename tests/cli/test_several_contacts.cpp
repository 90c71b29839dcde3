// SPDX-License-Identifier: BSD-3-Clause
// A case with several contacts reports every one of them (issue 21,
// "Several contacts"): cases/oring_two_plates.toml, the O-ring squeezed
// between a fixed plate (face "lower") and a moving one ("upper"), writes
// pressure_lower.* and pressure_upper.* (no pressure.csv), a ParaView
// contact part and multiplier part per contact, a summary.json "contacts"
// entry per contact whose forces are the obstacles' reactions, and a
// console block per contact.  A case with one contact keeps its files and
// keys.  And the labels say only what the case has ("Labels"): the part
// modelled follows its symmetry planes, and a face that starts flat on the
// obstacle reports its contact area rather than a half width.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include <vtkDataArray.h>
#include <vtkPointData.h>

#include "tests/support/igac_process.hpp"
#include "tests/support/vtu_file.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using igac_test::quote;
using igac_test::read_file;
using igac_test::run_igac;
using igac_test::TempDir;

const std::string kCases = std::string(IGAC_SOURCE_DIR) + "/cases/";
const std::string kData = std::string(IGAC_SOURCE_DIR) + "/tests/data/";

// One run of oring_two_plates (about 1 s) shared by the tests below.
class TwoPlates : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() / ("igac_test_two_plates_" + std::to_string(getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const auto o = run_igac("run " + quote(kCases + "oring_two_plates.toml") + " --out out", *dir_);
    exit_code_ = o.exit_code;
    console_ = new std::string(o.output);
    summary_ = new json(json::parse(read_file(*dir_ / "out" / "summary.json"), nullptr, false));
  }
  static void TearDownTestSuite() {
    std::error_code ec;
    fs::remove_all(*dir_, ec);
    delete dir_;
    delete console_;
    delete summary_;
  }
  void SetUp() override {
    ASSERT_EQ(exit_code_, 0) << *console_;
    ASSERT_FALSE(summary_->is_discarded());
  }
  static fs::path out() { return *dir_ / "out"; }
  static const json& summary() { return *summary_; }
  static const std::string& console() { return *console_; }

 private:
  static inline fs::path* dir_ = nullptr;
  static inline std::string* console_ = nullptr;
  static inline json* summary_ = nullptr;
  static inline int exit_code_ = -1;
};

TEST_F(TwoPlates, EveryContactHasItsPressureFiles) {
  EXPECT_FALSE(fs::exists(out() / "pressure.csv")) << "with several contacts no file stands for one of them";
  EXPECT_FALSE(fs::exists(out() / "pressure.svg"));
  for (const char* face : {"lower", "upper"}) {
    const fs::path csv = out() / (std::string("pressure_") + face + ".csv");
    ASSERT_TRUE(fs::exists(csv)) << csv;
    EXPECT_TRUE(fs::exists(out() / (std::string("pressure_") + face + ".svg")));
    const auto rows = igac_test::csv_rows(csv);
    ASSERT_GT(rows.size(), 2u);
    EXPECT_EQ(rows[0][0], "kind");
    // the largest multiplier pressure is the contact's max_pressure
    double peak = 0;
    for (size_t i = 1; i < rows.size(); ++i)
      if (rows[i][0] == "multiplier") peak = std::max(peak, std::stod(rows[i][2]));
    for (const auto& c : summary()["contacts"]) {
      if (c["face"] != face) continue;
      EXPECT_NEAR(peak, c["max_pressure"].get<double>(), 1e-9 * peak) << face;
    }
  }
  // the manifest lists them: a later run may replace the folder
  const std::string manifest = read_file(out() / ".igac-manifest");
  EXPECT_NE(manifest.find("pressure_lower.csv\n"), std::string::npos) << manifest;
  EXPECT_NE(manifest.find("pressure_upper.svg\n"), std::string::npos) << manifest;
}

TEST_F(TwoPlates, SummaryHasOneEntryPerContactWhoseForcesAreTheReactions) {
  const json& s = summary();
  ASSERT_TRUE(s.contains("contacts")) << s.dump(1);
  const json& contacts = s["contacts"];
  const json& obstacles = s["obstacles"];
  ASSERT_EQ(contacts.size(), 2u);
  ASSERT_EQ(obstacles.size(), 2u);
  const char* faces[] = {"lower", "upper"};
  for (size_t i = 0; i < 2; ++i) {
    const json& c = contacts[i];
    EXPECT_EQ(c["face"], faces[i]);
    EXPECT_EQ(c["obstacle"], obstacles[i]["obstacle"]);
    EXPECT_EQ(c["pressure_csv"], std::string("pressure_") + faces[i] + ".csv");
    EXPECT_EQ(c["active"], obstacles[i]["active"]);
    EXPECT_GT(c["active"].get<int>(), 0);
    for (const char* key : {"half_width", "half_width_reference", "max_pressure", "max_pressure_cauchy"})
      EXPECT_GT(c[key].get<double>(), 0) << faces[i] << " " << key;
    EXPECT_NEAR(c["total_force"].get<double>(), obstacles[i]["normal_force"].get<double>(),
                1e-12 * obstacles[i]["normal_force"].get<double>());
  }
  // Nothing but the two plates holds the ring vertically: their forces balance.
  const double f0 = contacts[0]["total_force"], f1 = contacts[1]["total_force"];
  EXPECT_GT(f0, 0);
  EXPECT_NEAR(f0 / f1, 1.0, 1e-8);
  // "contact" keeps what belongs to the run, no one contact's numbers
  const json& run = s["contact"];
  EXPECT_FALSE(run.contains("total_force")) << run.dump();
  EXPECT_FALSE(run.contains("half_width")) << run.dump();
  EXPECT_EQ(run["applied_force"], 0.0);  // driven by the plate's motion
}

TEST_F(TwoPlates, ParaViewHasAContactPartPerContact) {
  const int last = int(summary()["load_steps"].size());  // step 0 is the undeformed body
  ASSERT_GE(last, 1);
  const std::string pvd = read_file(out() / "solution.pvd");
  int multipliers = 0;
  for (size_t i = 0; i < 2; ++i) {
    const std::string face = i == 0 ? "lower" : "upper";
    for (const std::string& part : {"contact_face_" + face, "multipliers_" + face})
      EXPECT_NE(pvd.find("name=\"" + part + "\""), std::string::npos) << part << "\n" << pvd;
    char step[16];
    std::snprintf(step, sizeof step, "%04d", last);
    const fs::path contact = out() / ("contact_" + face + "_" + step + ".vtu");
    const fs::path mult = out() / ("multipliers_" + face + "_" + step + ".vtu");
    ASSERT_TRUE(fs::exists(contact)) << contact;
    ASSERT_TRUE(fs::exists(mult)) << mult;
    EXPECT_GT(igac_test::read_vtu(contact.string())->GetNumberOfCells(), 0);
    // each part holds its own contact's multipliers: its peak is that contact's
    const auto g = igac_test::read_vtu(mult.string());
    multipliers += int(g->GetNumberOfPoints());
    vtkDataArray* p = g->GetPointData()->GetArray("pressure");
    ASSERT_NE(p, nullptr);
    double peak = 0;
    for (vtkIdType k = 0; k < p->GetNumberOfTuples(); ++k) peak = std::max(peak, p->GetTuple1(k));
    const double expected = summary()["contacts"][i]["max_pressure"];
    EXPECT_NEAR(peak, expected, 1e-12 * expected) << face;
  }
  EXPECT_EQ(multipliers, summary()["multipliers"].get<int>());
  EXPECT_FALSE(fs::exists(out() / "contact_0001.vtu"));
}

// The load curve has each plate's force: they balance at every step, and
// the last is the contacts' total_force.
TEST_F(TwoPlates, LoadCurveHasAForceColumnPerContact) {
  const auto rows = igac_test::csv_rows(out() / "load_curve.csv");
  ASSERT_GT(rows.size(), 1u);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"load_factor", "contact_force_lower", "contact_force_upper",
                                               "face_displacement", "obstacle_displacement", "reaction_axis_x",
                                               "reaction_axis_y"}));
  for (size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), 7u);
    EXPECT_NEAR(std::stod(rows[i][1]) / std::stod(rows[i][2]), 1.0, 1e-8) << "row " << i;
  }
  for (size_t k = 0; k < 2; ++k) {
    const double last = std::stod(rows.back()[1 + k]), force = summary()["contacts"][k]["total_force"];
    EXPECT_NEAR(last, force, 1e-9 * force);
  }
}

TEST_F(TwoPlates, ConsolePrintsABlockPerContact) {
  const std::string& c = console();
  const size_t lower = c.find("contact       face 'lower'"), upper = c.find("contact       face 'upper'");
  ASSERT_NE(lower, std::string::npos) << c;
  ASSERT_NE(upper, std::string::npos) << c;
  EXPECT_LT(lower, upper);
  // each block has its half width, peak and force
  for (const std::string& block : {c.substr(lower, upper - lower), c.substr(upper)}) {
    EXPECT_NE(block.find("half width"), std::string::npos) << block;
    EXPECT_NE(block.find("max pressure"), std::string::npos) << block;
    EXPECT_NE(block.find("total force"), std::string::npos) << block;
  }
}

TEST_F(TwoPlates, ModelPartIsTheHalfItModels) {
  // one symmetry plane (x = 0): half the cross-section, not a quarter
  EXPECT_EQ(summary()["contact"]["model_part"], "half (forces per unit thickness of the modelled half)");
}

// One contact: pressure.csv, contact_0001.vtu (step 0 is the undeformed body alone) and the "contact" report as
// before, no "contacts".
TEST(OneContact, KeepsItsFilesAndKeys) {
  TempDir tmp("one_contact");
  const auto o = run_igac("run " + quote(kCases + "hertz2d.toml") + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const fs::path out = tmp.path() / "out";
  for (const char* f : {"pressure.csv", "pressure.svg", "contact_0001.vtu", "multipliers_0001.vtu"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  const json s = json::parse(read_file(out / "summary.json"));
  EXPECT_FALSE(s.contains("contacts"));
  EXPECT_TRUE(s["contact"].contains("half_width"));
  EXPECT_EQ(s["contact"]["model_part"], "quarter (forces per unit thickness of the modelled quarter)");
  const std::string pvd = read_file(out / "solution.pvd");
  EXPECT_NE(pvd.find("name=\"contact_face\" file=\"contact_0001.vtu\""), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("name=\"multipliers\" file=\"multipliers_0001.vtu\""), std::string::npos) << pvd;
  EXPECT_NE(o.output.find("  half width    "), std::string::npos) << o.output;
}

// A block lying flat on a plane touches over its whole face from the start:
// no half width (no point the zone grows from); its contact area instead.
TEST(Labels, FlatContactReportsItsAreaNotAHalfWidth) {
  TempDir tmp("flat");
  const auto o = run_igac("run " + quote(kData + "contact_flat_block.toml") + " --out out", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const json c = json::parse(read_file(tmp.path() / "out" / "summary.json"))["contact"];
  EXPECT_FALSE(c.contains("half_width")) << c.dump();
  ASSERT_TRUE(c.contains("contact_area")) << c.dump();
  EXPECT_NEAR(c["contact_area"].get<double>(), 1.0, 1e-12);  // the whole bottom face, width 1, is pressed
  EXPECT_EQ(o.output.find("half width"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("contact area  1 "), std::string::npos) << o.output;
  // u_x = 0 on x = 0 is its one plane of symmetry
  EXPECT_EQ(c["model_part"], "half (forces per unit thickness of the modelled half)");
}

// The indented block is the whole block, glued to its base: no symmetry to
// name.  Its ball makes a round contact: a half width.
TEST(Labels, BodyWithoutSymmetryHasNoModelPart) {
  TempDir tmp("no_symmetry");
  const auto o = run_igac("run " + quote(kCases + "indented_block.toml") + " --out out --quiet", tmp.path());
  ASSERT_EQ(o.exit_code, 0) << o.output;
  const json c = json::parse(read_file(tmp.path() / "out" / "summary.json"))["contact"];
  EXPECT_FALSE(c.contains("model_part")) << c.dump();
  EXPECT_TRUE(c.contains("half_width")) << c.dump();
  EXPECT_FALSE(c.contains("contact_area")) << c.dump();
}

}  // namespace
