// SPDX-License-Identifier: BSD-3-Clause
// Built-in shapes behind a registry (engine/geometry/shapes.hpp, one file per
// shape in engine/geometry/shapes/): every shape is listed once, makes the
// same geometry as its function, and a case gives it exactly its own keys.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "engine/geometry/shapes.hpp"
#include "tests/support/igac_process.hpp"

namespace igac {
namespace {

TEST(ShapeRegistry, ListsEveryShapeOnceWithItsDimension) {
  std::vector<std::string> names;
  for (const ShapeType* t : shape_types()) names.emplace_back(t->name);
  EXPECT_EQ(names, (std::vector<std::string>{"quarter_disc", "sphere_octant", "quarter_annulus", "rectangle", "box"}));
  EXPECT_EQ(find_shape_type("box")->dim, 3);
  EXPECT_EQ(find_shape_type("sphere_octant")->dim, 3);
  EXPECT_EQ(find_shape_type("rectangle")->dim, 2);
  EXPECT_TRUE(find_shape_type("quarter_annulus")->curved);
  EXPECT_FALSE(find_shape_type("rectangle")->curved);
  EXPECT_EQ(find_shape_type("hexagon"), nullptr);
}

TEST(ShapeRegistry, MakesTheSameGeometryAsTheShapeFunction) {
  const Geometry a = find_shape_type("quarter_annulus")->make({{"inner_radius", {1.0}}, {"outer_radius", {2.5}}});
  const Geometry b = quarter_annulus(1.0, 2.5);
  EXPECT_EQ(a.patch.points(), b.patch.points());
  EXPECT_EQ(a.patch.weights(), b.patch.weights());
  EXPECT_EQ(a.faces.size(), b.faces.size());
}

TEST(ShapeRegistry, AKeyOfAnotherShapeIsRefused) {
  igac_test::TempDir tmp("shape");
  std::ofstream(tmp.path() / "c.toml") << "name = \"c\"\n[geometry]\nshape = \"rectangle\"\nsize = [1, 1]\nradius = 2\n"
                                          "[mesh]\ndegree = 2\nelements = [2, 2]\n[material]\nE = 1\nnu = 0.3\n";
  const auto o = igac_test::run_igac("run c.toml", tmp.path());
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("c.toml:5: [geometry] radius: unknown key (expected one of: file, mirror, rotate, scale, shape, size, translate)"),
            std::string::npos) << o.output;
}

}  // namespace
}  // namespace igac
