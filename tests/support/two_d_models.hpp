// SPDX-License-Identifier: BSD-3-Clause
// Closed forms, shipped cases and checks the whole-run tests of the 2D models share
// (tests/unit/model/test_plane_stress.cpp, test_axisymmetric.cpp).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac_test {

// (l1, l2) of the compressible Neo-Hookean law (E, nu) in uniaxial stress,
// P_11 = T, P_22 = P_33 = 0 with l3 = l2:
//   mu (l1 - 1/l1) + lambda ln J / l1 = T,   mu (l2 - 1/l2) + lambda ln J / l2 = 0,
// J = l1 l2^2, by Newton from (1, 1).
inline Eigen::Vector2d neo_hookean_uniaxial_stretches(double E, double nu, double T) {
  const double mu = E / (2 * (1 + nu)), lambda = E * nu / ((1 + nu) * (1 - 2 * nu));
  Eigen::Vector2d l(1, 1);
  for (int it = 0; it < 50; ++it) {
    const double a = l[0], b = l[1], lnJ = std::log(a * b * b);
    const Eigen::Vector2d r(mu * (a - 1 / a) + lambda * lnJ / a - T, mu * (b - 1 / b) + lambda * lnJ / b);
    Eigen::Matrix2d J;
    J << mu * (1 + 1 / (a * a)) + lambda * (1 - lnJ) / (a * a), 2 * lambda / (a * b),  //
        lambda / (a * b), mu * (1 + 1 / (b * b)) + lambda * (2 - lnJ) / (b * b);
    l -= J.partialPivLu().solve(r);
  }
  return l;
}

// max over the control points of |u_A - G X_A|: how far a run's
// displacement is from the homogeneous field u = G X (one in the spline
// space, so a solve reproduces it up to its own tolerance).
inline double homogeneous_field_error(const igac::Body& body, const Eigen::MatrixXd& u, const Eigen::Matrix2d& G) {
  double error = 0;
  for (int a = 0; a < body.num_control_points(); ++a) {
    const Eigen::Vector2d X = body.points().row(a).transpose();
    error = std::max(error, (u.row(a).transpose() - G * X).norm());
  }
  return error;
}

// The text of cases/NAME.
inline std::string shipped_case(const std::string& name) {
  std::ifstream in(std::string(IGAC_SOURCE_DIR) + "/cases/" + name);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// cases/lame_cylinder.toml as [model] kind = `kind` at --refine 1, 2, 3:
// the relative L2 error against the reference (the kind's closed form)
// falls at the rate p + 1 = 3 and ends below `finest`.
inline void expect_lame_converges_at_the_spline_rate(const std::string& kind, double finest) {
  const std::string text = shipped_case("lame_cylinder.toml") + "\n[model]\nkind = \"" + kind + "\"\n";
  double previous = 0;
  for (int refine : {1, 2, 3}) {
    igac::CaseSpec spec = igac::read_case_text(text, std::string(IGAC_SOURCE_DIR) + "/cases/lame_" + kind + ".toml");
    igac::apply_overrides(spec, std::nullopt, refine);
    const igac::RunResult r = igac::solve_model(igac::build_model(spec), igac::quiet_run());
    ASSERT_TRUE(r.displacement_errors);
    const double e = r.displacement_errors->l2 / r.displacement_errors->ref_l2;
    std::printf("  %s Lame, refine %d: relative L2 error %.3e\n", kind.c_str(), refine, e);
    if (previous > 0) {
      EXPECT_GT(std::log2(previous / e), 2.7) << kind << ": p = 2, L2 rate 3";
    }
    previous = e;
  }
  EXPECT_LT(previous, finest) << kind;
}

// The case `text` (read as `path`; with `when_built`, also built) is
// refused with one line that names `why` and `[model] kind`.
inline void expect_kind_refused(const std::string& text, const std::string& path, const std::string& why,
                                bool when_built = false) {
  try {
    const igac::CaseSpec spec = igac::read_case_text(text, path);
    if (when_built) igac::build_model(spec);
    ADD_FAILURE() << "accepted; expected: " << why;
  } catch (const igac::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(why), std::string::npos) << message;
    EXPECT_NE(message.find("[model] kind"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
  }
}

}  // namespace igac_test
