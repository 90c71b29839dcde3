// SPDX-License-Identifier: BSD-3-Clause
// A planar patch stored with geoDim 3 and z = 0 (as G+Smo's planar/unitdisk
// and unitsquare are) reads as the same 2D body; a z that is not 0 is
// refused naming the control point.  Both were refused as "geoDim 3
// differs from the parametric dimension 2".
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/case_file.hpp"
#include "io/gismo_xml.hpp"

namespace {

// cases/quarter_disc.xml with every control point given a third coordinate.
std::string in_3d(double z_of_point_4) {
  std::ifstream in(std::string(IGAC_SOURCE_DIR) + "/cases/quarter_disc.xml");
  std::stringstream all;
  all << in.rdbuf();
  std::string text = all.str();
  const auto a = text.find("<coefs geoDim=\"2\">\n"), b = text.find("</coefs>");
  std::istringstream rows(text.substr(a + 19, b - a - 19));
  std::string out, line;
  for (int i = 0; std::getline(rows, line); ++i)
    out += line + " " + (i == 4 ? std::to_string(z_of_point_4) : "0") + "\n";
  return text.substr(0, a) + "<coefs geoDim=\"3\">\n" + out + text.substr(b);
}

std::string write(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(GismoPlanar, PlanarPatchStoredIn3DReadsAsThe2DBody) {
  const igac::MultiPatch flat = igac::read_gismo_xml(std::string(IGAC_SOURCE_DIR) + "/cases/quarter_disc.xml");
  const igac::MultiPatch stored = igac::read_gismo_xml(write("igac_planar_in_3d.xml", in_3d(0.0)));
  ASSERT_EQ(stored.patches.size(), 1u);
  EXPECT_EQ(stored.patches[0].space_dim(), 2);
  EXPECT_EQ(stored.patches[0].points(), flat.patches[0].points());
  EXPECT_EQ(stored.patches[0].weights(), flat.patches[0].weights());
}

TEST(GismoPlanar, NonzeroZIsRefusedNamingThePoint) {
  const std::string path = write("igac_planar_z.xml", in_3d(0.25));
  try {
    igac::read_gismo_xml(path);
    FAIL() << "a patch with z = 0.25 was read";
  } catch (const igac::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("control point 4 has z = 0.25"), std::string::npos) << e.what();
  }
}

}  // namespace
