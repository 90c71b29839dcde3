// SPDX-License-Identifier: BSD-3-Clause
// Case-file texts the tests build their cases from.
#pragma once

#include <fmt/format.h>

#include <string>

namespace igac_test {

// The head of a case of one rectangle [0, lx] x [0, ly] (E = 1, nu = 0.3,
// law `model`), nx x ny elements of degree 2: its supports, loads and
// contacts follow.
inline std::string rectangle_case(double lx, double ly, int nx, int ny, const std::string& model = "linear_elastic") {
  return fmt::format(R"(
[geometry]
shape = "rectangle"
size = [{}, {}]
[mesh]
degree = 2
elements = [{}, {}]
[material]
model = "{}"
E = 1.0
nu = 0.3
)",
                     lx, ly, nx, ny, model);
}

// Rollers for a rectangle_case: its bottom held in y, its left side in x.
inline std::string rollers() {
  return R"(
[[dirichlet]]
faces = ["bottom"]
component = "y"
[[dirichlet]]
faces = ["left"]
component = "x"
)";
}

}  // namespace igac_test
