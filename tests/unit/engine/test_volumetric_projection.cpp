// SPDX-License-Identifier: BSD-3-Clause
// The stabilised element-constant projection of the mixed formulation
// (engine/volumetric_projection.hpp), against an analytic energy.
//
// One quadratic element on the unit square (cube), u = (x^2 - x, 0 (, 0)):
// eps_xx = 2x - 1, whose element mean is 0, so the projection sees nothing
// of it (Pi_e tr eps = 0) and only the deviatoric energy and the
// stabilisation hold it.  With the 3D deviator (plane strain included),
// |dev eps|^2 = (2/3) eps_xx^2, int (2x - 1)^2 = 1/3:
//   u^T K u = int 2 mu |dev eps|^2 + K (Pi tr eps)^2 + mu ((I - Pi) tr eps)^2
//           = 4 mu / 9 + 0 + mu / 3 = 7 mu / 9
// whatever K (without the stabilisation it would be 4 mu / 9: this mode
// is what let one element of the O-ring at K/G = 2000 change its volume by
// 30 %).  The same number from the small-strain B-bar stiffness and from the
// large-deformation tangent at rest (Mooney-Rivlin, Neo-Hookean), 2D and 3D.
#include <gtest/gtest.h>

#include <cmath>

#include "engine/assembly.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/total_lagrangian.hpp"
#include "engine/volumetric_projection.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {
namespace {

// Sums of a few dozen O(K) terms: round-off relative to the bulk modulus.
constexpr double kRoundoff = 1e-11;

// The Bernstein coefficients of x^2 - x on [0, 1] at degree 2 are 0, -1/2, 0:
// the control point at X has -2 X (1 - X) (X in {0, 1/2, 1}).
Eigen::VectorXd zero_mean_dilatation(const NurbsPatch& patch) {
  const int dim = patch.space_dim();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(patch.num_control_points() * dim);
  for (int a = 0; a < patch.num_control_points(); ++a) {
    const double X = patch.points()(a, 0);
    u[a * dim] = -2 * X * (1 - X);
  }
  return u;
}

NurbsPatch unit_element(int dim) {
  return elevate_to(dim == 2 ? rectangle(1, 1).patch : box(1, 1, 1).patch, 2);
}

TEST(VolumetricProjection, StabilisationHoldsTheModesTheProjectionDoesNotSee) {
  const double mu = 0.96, bulk = 2000 * mu;
  const double expected = 7 * mu / 9;
  for (int dim : {2, 3}) {
    const NurbsPatch patch = unit_element(dim);
    ASSERT_EQ(patch.num_elements(), 1);
    const DofMap dofs(patch, {});
    const Eigen::VectorXd u = zero_mean_dilatation(patch);
    // small strain: E, nu of (K, mu)
    const double E = 9 * bulk * mu / (3 * bulk + mu), nu = (3 * bulk - 2 * mu) / (2 * (3 * bulk + mu));
    const LinearSystem bbar = assemble_linear_elasticity(patch, dofs, LinearElastic{E, nu},
                                                         Eigen::VectorXd::Zero(dim), {}, Formulation::mixed);
    EXPECT_NEAR(u.dot(bbar.K * u), expected, kRoundoff * bulk) << dim << "D, small strain";
    const LinearSystem plain = assemble_linear_elasticity(patch, dofs, LinearElastic{E, nu}, Eigen::VectorXd::Zero(dim));
    EXPECT_GT(u.dot(plain.K * u), 100 * expected) << dim << "D: the displacement formulation sees it with K";
    // large deformation, the tangent at rest
    const MaterialParameters mooney{NAN, NAN, {{"C10", 0.37}, {"C01", 0.11}, {"bulk_modulus", bulk}}};
    const MaterialParameters neo{E, nu, {}};
    for (const auto& [name, parameters] : {std::pair{"mooney_rivlin", mooney}, std::pair{"neo_hookean", neo}}) {
      const auto law = make_law(name, parameters);
      EXPECT_NEAR(stabilisation_modulus(*law, dim), mu, 1e-12 * mu) << name;
      const TotalLagrangianAssembler tl(patch, dofs, *law, Formulation::mixed);
      Eigen::VectorXd f;
      Eigen::SparseMatrix<double> K;
      ASSERT_TRUE(tl.assemble(Eigen::MatrixXd::Zero(patch.num_control_points(), dim), f, &K));
      EXPECT_NEAR(u.dot(K * u), expected, kRoundoff * bulk) << dim << "D, " << name;
    }
  }
}

// A law without a split has no stabilisation modulus.
TEST(VolumetricProjection, NoSplitNoStabilisation) {
  const auto law = make_law("saint_venant_kirchhoff", MaterialParameters{1.0, 0.3, {}});
  EXPECT_EQ(stabilisation_modulus(*law, 2), 0.0);
  EXPECT_EQ(stabilisation_modulus(*law, 3), 0.0);
}

}  // namespace
}  // namespace igac
