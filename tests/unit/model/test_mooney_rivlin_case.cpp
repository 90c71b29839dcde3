// SPDX-License-Identifier: BSD-3-Clause
// A law with parameters of its own, end to end: the case file passes C10,
// C01 and bulk_modulus to the Mooney-Rivlin law (materials/mooney_rivlin.hpp),
// the law declares and checks them, and at a small load the rubber presses
// like the linear solid it linearises to (mu = 2 (C10 + C01), K).
#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

const std::string kSource = IGAC_SOURCE_DIR;

// hertz2d with its [material] table replaced by `material` (TOML lines).
std::filesystem::path hertz_with_material(const std::string& material, const std::filesystem::path& dir) {
  std::string s = igac_test::read_file(kSource + "/cases/hertz2d.toml");
  const auto a = s.find("[material]"), b = s.find("[[dirichlet]]");
  s.replace(a, b - a, "[material]\n" + material + "\n\n[loading]\nsteps = 2\npressure = \"dead\"\n\n");
  const auto path = dir / "rubber.toml";
  std::ofstream(path) << s;
  return path;
}

// E = 1, nu = 0.3: mu = 1/2.6, K = E / (3 (1 - 2 nu)) = 1/1.2.
constexpr double kMu = 1 / 2.6, kBulk = 1 / 1.2;

TEST(MooneyRivlinCase, SmallLoadReproducesTheLinearHertzSolution) {
  igac_test::TempDir tmp("mr");
  const auto path = hertz_with_material(
      fmt::format("model = \"mooney_rivlin\"\nC10 = {:.17g}\nC01 = {:.17g}\nbulk_modulus = {:.17g}", 0.3 * kMu,
                  0.2 * kMu, kBulk),
      tmp.path());
  const CaseSpec spec = read_case(path.string());
  EXPECT_NEAR(spec.E, 1.0, 1e-14) << "the small-strain equivalent of (C10, C01, K)";
  EXPECT_NEAR(spec.nu, 0.3, 1e-14);
  Model rubber = build_model(spec), linear = build_model(read_case(kSource + "/cases/hertz2d.toml"));
  const RunResult rr = solve_model(rubber, quiet_run()), rl = solve_model(linear);
  ASSERT_EQ(rr.status, "converged");
  EXPECT_NEAR(rr.contacts.front().report.max_pressure / rl.contacts.front().report.max_pressure, 1.0, 0.01);
  EXPECT_NEAR(rr.contacts.front().report.half_width / rl.contacts.front().report.half_width, 1.0, 0.01);
  EXPECT_NEAR(rr.contacts.front().report.total_force / rr.applied_force, 1.0, 1e-7);
}

struct BadRubber {
  std::string name, material;
  std::vector<std::string> fragments;
};
void PrintTo(const BadRubber& b, std::ostream* os) { *os << b.name; }
class MooneyRivlinBadInput : public ::testing::TestWithParam<BadRubber> {};

TEST_P(MooneyRivlinBadInput, OneLineNamingTheKey) {
  igac_test::TempDir tmp("mrbad");
  const auto path = hertz_with_material(GetParam().material, tmp.path());
  const auto o = igac_test::run_igac("run " + igac_test::quote(path.string()), tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1) << o.output;
  for (const auto& f : GetParam().fragments) EXPECT_NE(o.output.find(f), std::string::npos) << f << " in " << o.output;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out"));
}

INSTANTIATE_TEST_SUITE_P(
    MooneyRivlin, MooneyRivlinBadInput,
    ::testing::Values(
        BadRubber{"shear_modulus_not_positive", "model = \"mooney_rivlin\"\nC10 = 0.1\nC01 = -0.2\nbulk_modulus = 1",
                  {"[material] C10:", "C10 + C01 = -0.1 must be positive"}},
        BadRubber{"bulk_modulus_zero", "model = \"mooney_rivlin\"\nC10 = 0.1\nC01 = 0.0\nbulk_modulus = 0",
                  {"[material] bulk_modulus:", "must be positive"}},
        BadRubber{"missing_key", "model = \"mooney_rivlin\"\nC10 = 0.1\nbulk_modulus = 1", {"[material] C01: missing"}},
        BadRubber{"E_is_not_its_key", "model = \"mooney_rivlin\"\nC10 = 0.1\nC01 = 0.0\nbulk_modulus = 1\nE = 1",
                  {"[material] E: unknown key", "C01", "C10", "bulk_modulus"}},
        BadRubber{"unknown_model", "model = \"ogden\"\nE = 1\nnu = 0.3", {"[material] model:", "mooney_rivlin"}}),
    [](const ::testing::TestParamInfo<BadRubber>& info) { return info.param.name; });

}  // namespace
}  // namespace igac
