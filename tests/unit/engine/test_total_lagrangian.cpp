// SPDX-License-Identifier: BSD-3-Clause
// Total-Lagrangian kinematics (engine/total_lagrangian.hpp) and pressure
// loads in large deformation (engine/follower_pressure.hpp), mathematics
// first.
//  - The tangent is the derivative of the internal force: against central
//    differences at a random deformed state, 2D (plane strain) and 3D,
//    Neo-Hookean, p = 2 and 3, curved geometries (quarter disc, sphere octant
//    with its collapsed face) and a distorted box.
//  - Exact identities: f_int = 0 at u = 0 and for a rigid rotation
//    (objectivity of Neo-Hookean); with the linear_elastic law the internal
//    force is exactly K_lin u (K_lin of assemble_linear_elasticity) and the
//    tangent is K_lin, at every u.
//  - An inverted state (det F <= 0) is refused.
//  - Follower pressure: the load stiffness against central differences of
//    f_ext; at u = 0 it is the dead load, and the dead load is the
//    reference load of add_pressure_load; the resultant of the follower load
//    on a rigidly rotated body is the rotated resultant.
//  - Put together: K_int - d f_ext/du is the derivative of f_int - f_ext
//    (and without the load stiffness the same check fails by orders of
//    magnitude), and Newton with it converges quadratically.
#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <cmath>
#include <random>
#include <string>

#include "engine/assembly.hpp"
#include "engine/follower_pressure.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/total_lagrangian.hpp"
#include "materials/hyperelastic.hpp"
#include "materials/plane_stress.hpp"
#include "tests/support/distort.hpp"

namespace igac {
namespace {

// Central differences with step h = kStep (displacements and geometry are
// O(1) here): truncation ~h^2 |f'''| ~ 1e-12 and cancellation
// ~eps |f| / h ~ 1e-10, both relative to the largest tangent entry; measured
// <= ~1e-9.  1e-6 leaves room and still catches any missing term (a missing
// geometric stiffness or load-stiffness term shows at 1e-2 .. 1).
constexpr double kStep = 1e-6;
constexpr double kFiniteDifference = 1e-6;
// Exact identities evaluated in floating point (sums over a few hundred
// Gauss points of O(1) terms), relative to the stiffness scale.
constexpr double kRoundoff = 1e-12;
// The brief's bound for the linear-law tangent against the linear stiffness.
constexpr double kLinearStiffness = 1e-10;

const MaterialParameters kMaterial{1.0, 0.3};

NurbsPatch refined(const NurbsPatch& patch, int degree, int parts) {
  return subdivide(elevate_to(patch, degree), parts);
}

using igac_test::distort_interior;  // tests/support/distort.hpp

// Random free values: a homogeneous stretch G X (large, so the stress and
// with it the geometric stiffness matter; diagonal, so it agrees with the
// symmetry conditions u_i = 0 on X_i = 0 of the test geometries) plus a
// random wiggle.
Eigen::VectorXd random_state(const NurbsPatch& patch, const DofMap& dofs, double wiggle, unsigned seed) {
  const int dim = patch.space_dim();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(dim, dim);
  for (int i = 0; i < dim; ++i) G(i, i) = 0.2 * U(rng);
  Eigen::VectorXd free(dofs.num_free());
  for (int cp = 0; cp < patch.num_control_points(); ++cp)
    for (int i = 0; i < dim; ++i)
      if (const int eq = dofs.equation(cp * dim + i); eq >= 0)
        free[eq] = G.row(i).dot(patch.points().row(cp)) + wiggle * U(rng);
  return free;
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

// max |K - central differences of f(u)| / max |K| over the free dofs.
template <class Force>
double fd_error(const Eigen::MatrixXd& K, const DofMap& dofs, const Eigen::VectorXd& free, Force force) {
  Eigen::MatrixXd Kfd(K.rows(), K.cols());
  for (int j = 0; j < dofs.num_free(); ++j) {
    Eigen::VectorXd up = free, um = free;
    up[j] += kStep;
    um[j] -= kStep;
    Kfd.col(j) = (force(dofs.expand(up)) - force(dofs.expand(um))) / (2 * kStep);
  }
  return max_abs(K - Kfd) / max_abs(K);
}

// The wiggle is a fraction of the control-point spacing, so that
// |Grad u| ~ 0.2 stays admissible (det F > 0) at every Gauss point.
double tangent_fd_error(const NurbsPatch& patch, const DofMap& dofs, double wiggle, unsigned seed,
                        Formulation formulation, const HyperelasticLaw& law) {
  const TotalLagrangianAssembler tl(patch, dofs, law, formulation);
  const Eigen::VectorXd free = random_state(patch, dofs, wiggle, seed);
  Eigen::VectorXd f;
  Eigen::SparseMatrix<double> K;
  if (!tl.assemble(dofs.expand(free), f, &K)) {
    ADD_FAILURE() << "the random state is inadmissible";
    return INFINITY;
  }
  const Eigen::MatrixXd Kd(K);
  EXPECT_LE(max_abs(Kd - Kd.transpose()), kRoundoff * max_abs(Kd)) << "a hyperelastic tangent is symmetric";
  const double err = fd_error(Kd, dofs, free, [&](const Eigen::MatrixXd& u) {
    Eigen::VectorXd fu;
    EXPECT_TRUE(tl.assemble(u, fu, nullptr));
    return fu;
  });
  std::cout << "  TL tangent vs FD (" << formulation_name(formulation) << ", " << patch.space_dim() << "D, p = " << patch.degree(0)
            << ", " << dofs.num_free() << " dofs): " << err << "\n";
  return err;
}
double tangent_fd_error(const NurbsPatch& patch, const DofMap& dofs, double wiggle, unsigned seed,
                        Formulation formulation = Formulation::displacement, const std::string& law_name = "neo_hookean",
                        const MaterialParameters& material = kMaterial) {
  return tangent_fd_error(patch, dofs, wiggle, seed, formulation, *make_law(law_name, material));
}

// Quarter disc held on the left (u_x = 0) with a prescribed, non-zero u_y on
// the top face: rows and columns of prescribed dofs are skipped while their
// values act through u.
DofMap quarter_disc_dofs(const Geometry& g, const NurbsPatch& patch) {
  return DofMap(patch, {{g.faces.at("left"), 0, 0.0}, {g.faces.at("top"), 1, -0.03}});
}

TEST(TotalLagrangian, TangentMatchesFiniteDifferences2D) {
  const Geometry g = quarter_disc(1.0);
  for (int p : {2, 3}) {
    const NurbsPatch patch = refined(g.patch, p, 3);
    EXPECT_LE(tangent_fd_error(patch, quarter_disc_dofs(g, patch), 0.02, 7 + p), kFiniteDifference) << "p = " << p;
  }
}

// Plane stress (materials/plane_stress.hpp): the condensed tangent of each
// law assembles into the tangent of the assembled force.
TEST(TotalLagrangian, PlaneStressTangentMatchesFiniteDifferences) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 3);
  for (const std::string& name : {"neo_hookean", "saint_venant_kirchhoff"}) {
    const PlaneStressLaw law(std::shared_ptr<const HyperelasticLaw>(make_law(name, kMaterial)));
    EXPECT_LE(tangent_fd_error(patch, quarter_disc_dofs(g, patch), 0.02, 11, Formulation::displacement, law),
              kFiniteDifference) << name;
  }
}

// Axisymmetric (a revolved patch, engine/spline/nurbs_patch.hpp): F_33 =
// 1 + u_r / r joins F, and the tangent of the assembled force is still its
// derivative, displacement and mixed (the hoop stretch in J), p = 2 and 3.
TEST(TotalLagrangian, AxisymmetricTangentMatchesFiniteDifferences) {
  const MaterialParameters rubber{1.0, 0.49975, {}};  // K / mu = 2000
  const Geometry g = quarter_disc(1.0);  // the left face (x = 0) is the axis: u_r = 0 there
  for (int p : {2, 3}) {
    NurbsPatch patch = refined(g.patch, p, 3);
    patch.set_revolved(true);
    EXPECT_LE(tangent_fd_error(patch, quarter_disc_dofs(g, patch), 0.02, 30 + p), kFiniteDifference) << "p = " << p;
    EXPECT_LE(tangent_fd_error(patch, quarter_disc_dofs(g, patch), 0.02, 40 + p, Formulation::mixed, "neo_hookean", rubber),
              kFiniteDifference)
        << "mixed, p = " << p;
  }
}

TEST(TotalLagrangian, TangentMatchesFiniteDifferences3D) {
  {  // p = 2, curved, with the collapsed face whose control points share dofs
    const Geometry g = sphere_octant(1.0);
    const NurbsPatch patch = refined(g.patch, 2, 2);
    const DofMap dofs(patch, {{g.faces.at("left"), 0, 0.0}, {g.faces.at("back"), 1, 0.0}});
    EXPECT_LE(tangent_fd_error(patch, dofs, 0.02, 5), kFiniteDifference) << "sphere octant, p = 2";
  }
  {  // p = 3, distorted box
    const Geometry g = box(1.0, 0.8, 0.6);
    const NurbsPatch patch = distort_interior(refined(g.patch, 3, 2), 0.03, 3);
    const DofMap dofs(patch, {{g.faces.at("bottom"), 2, 0.02}});
    EXPECT_LE(tangent_fd_error(patch, dofs, 0.005, 6), kFiniteDifference) << "box, p = 3";
  }
}

// The mixed formulation (engine/volumetric_projection.hpp): its condensed
// tangent is the derivative of its internal force too (the projected
// dilatation's block term V_b U'' mB_b^T mB_b and the pressure's geometric term
// included), for both laws with a split, nearly incompressible (K/mu = 2000,
// where a missing term of U'' size would show at once), 2D and 3D, p = 2, 3,
// on pressure blocks of 2 x 2 (x 2) elements and of 3 x 3 (x 3).
TEST(TotalLagrangian, MixedTangentMatchesFiniteDifferences) {
  const MaterialParameters rubber{1.0, 0.49975, {}};  // K / mu = 2000
  const MaterialParameters mooney{NAN, NAN, {{"C10", 0.3}, {"C01", 0.05}, {"bulk_modulus", 1400.0}}};
  const Geometry g = quarter_disc(1.0);
  for (int p : {2, 3}) {
    const NurbsPatch patch = refined(g.patch, p, 3);
    EXPECT_LE(tangent_fd_error(patch, quarter_disc_dofs(g, patch), 0.02, 7 + p, Formulation::mixed, "neo_hookean", rubber),
              kFiniteDifference)
        << "neo_hookean, p = " << p;
    EXPECT_LE(tangent_fd_error(patch, quarter_disc_dofs(g, patch), 0.02, 9 + p, Formulation::mixed, "mooney_rivlin", mooney),
              kFiniteDifference)
        << "mooney_rivlin, p = " << p;
  }
  const Geometry b = box(1.0, 0.8, 0.6);
  for (int parts : {2, 3}) {  // one pressure block of 2 x 2 x 2 elements; of 3 x 3 x 3 (the leftover joins it)
    const NurbsPatch patch = distort_interior(refined(b.patch, 2, parts), 0.03, 3);
    const DofMap dofs(patch, {{b.faces.at("bottom"), 2, 0.02}});
    EXPECT_LE(tangent_fd_error(patch, dofs, 0.005, 6, Formulation::mixed, "neo_hookean", rubber), kFiniteDifference)
        << "box, p = 2, " << parts << " elements per direction";
  }
}

// A law without a split cannot run mixed: said at construction.
TEST(TotalLagrangian, MixedNeedsALawWithASplit) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 1);
  const DofMap dofs = quarter_disc_dofs(g, patch);
  const auto law = make_law("saint_venant_kirchhoff", kMaterial);
  EXPECT_THROW(TotalLagrangianAssembler(patch, dofs, *law, Formulation::mixed), std::invalid_argument);
}

// With the linear law's small-strain split (U = K theta^2/2), the mixed
// tangent at u = 0 is the B-bar stiffness of assemble_linear_elasticity:
// the two paths project the same way, for the sub-grid continuous pressure
// (`mixed`, 3 x 3 elements: one pressure span of 3 elements per direction)
// and for constants per element (`mixed_element`).
TEST(TotalLagrangian, MixedTangentAtRestIsTheBbarStiffness) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 3);
  const DofMap dofs(patch, {{g.faces.at("left"), 0, 0.0}});
  const MaterialParameters mooney{NAN, NAN, {{"C10", 0.5}, {"C01", 0.0}, {"bulk_modulus", 300.0}}};
  const auto law = make_law("mooney_rivlin", mooney);
  const LinearElastic lin = small_strain_material(*law, 2);
  const LinearSystem plain = assemble_linear_elasticity(patch, dofs, lin, Eigen::VectorXd::Zero(2));
  const Eigen::MatrixXd Kp(plain.K);
  for (const Formulation formulation : {Formulation::mixed, Formulation::mixed_element}) {
    const TotalLagrangianAssembler tl(patch, dofs, *law, formulation);
    Eigen::VectorXd f;
    Eigen::SparseMatrix<double> K;
    ASSERT_TRUE(tl.assemble(dofs.expand(Eigen::VectorXd::Zero(dofs.num_free())), f, &K));
    const LinearSystem bbar =
        assemble_linear_elasticity(patch, dofs, {lin}, Eigen::VectorXd::Zero(2), {}, {formulation});
    const Eigen::MatrixXd Kd(K), Kb(bbar.K);
    ASSERT_EQ(Kd.rows(), Kb.rows());
    EXPECT_LE(max_abs(Kd - Kb), kRoundoff * 1e2 * max_abs(Kb)) << formulation_name(formulation);
    EXPECT_GT(max_abs(Kd - Kp), 1e-3 * max_abs(Kp)) << "B-bar differs from the plain stiffness";
  }
}

// f_int = 0 at u = 0 and under u = (Q - I) X: NURBS reproduce affine fields
// with their control-point values as coefficients, so F = Q at every point,
// and P(Q) = Q P(I) = 0 for an objective law.
template <int dim>
void expect_stress_free(const NurbsPatch& patch, const Eigen::Matrix<double, dim, dim>& Q) {
  const auto law = make_law("neo_hookean", kMaterial);
  const DofMap dofs(patch, {});
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  Eigen::VectorXd f;
  Eigen::SparseMatrix<double> K;
  ASSERT_TRUE(tl.assemble(Eigen::MatrixXd::Zero(patch.num_control_points(), dim), f, &K));
  const double scale = max_abs(Eigen::MatrixXd(K));  // force of a unit displacement
  EXPECT_LE(f.cwiseAbs().maxCoeff(), kRoundoff * scale) << "u = 0";
  const Eigen::MatrixXd u = patch.points() * (Q - Eigen::Matrix<double, dim, dim>::Identity()).transpose();
  ASSERT_TRUE(tl.assemble(u, f, nullptr));
  EXPECT_LE(f.cwiseAbs().maxCoeff(), kRoundoff * scale) << "rigid rotation";
}

TEST(TotalLagrangian, NoForceAtRestOrUnderRigidRotation) {
  const double t = 0.7;
  Eigen::Matrix2d Q2;
  Q2 << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  expect_stress_free<2>(refined(quarter_disc(1.0).patch, 3, 3), Q2);
  const Eigen::Matrix3d Q3 =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  expect_stress_free<3>(refined(sphere_octant(1.0).patch, 2, 2), Q3);
}

// linear_elastic as a law of F: P = C : sym(F - I) is linear in u, so the TL
// machinery must give the linear assembler's system exactly: tangent K_lin at
// every u, and f_int = K_lin u_free - f_lin (f_lin = -K_fp g, the lift of the
// prescribed values g).
template <int dim>
void expect_linear_law_is_linear_elasticity(const NurbsPatch& patch, const DofMap& dofs) {
  const auto law = make_law("linear_elastic", kMaterial);
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  const LinearSystem lin =
      assemble_linear_elasticity(patch, dofs, LinearElastic(kMaterial.E, kMaterial.nu), Eigen::VectorXd());
  const Eigen::MatrixXd Klin(lin.K);
  const double scale = max_abs(Klin);
  Eigen::VectorXd f;
  Eigen::SparseMatrix<double> K;
  // u = 0 but for the prescribed values
  ASSERT_TRUE(tl.assemble(dofs.expand(Eigen::VectorXd::Zero(dofs.num_free())), f, &K));
  EXPECT_LE(max_abs(Eigen::MatrixXd(K) - Klin), kLinearStiffness * scale);
  EXPECT_LE((f + lin.f).cwiseAbs().maxCoeff(), kRoundoff * scale);
  const Eigen::VectorXd free = random_state(patch, dofs, 0.02, 11);
  ASSERT_TRUE(tl.assemble(dofs.expand(free), f, &K));
  EXPECT_LE(max_abs(Eigen::MatrixXd(K) - Klin), kLinearStiffness * scale);
  EXPECT_LE((f - (lin.K * free - lin.f)).cwiseAbs().maxCoeff(), kRoundoff * scale);
}

TEST(TotalLagrangian, LinearLawReproducesLinearElasticity) {
  const Geometry disc = quarter_disc(1.0);
  const NurbsPatch p2 = refined(disc.patch, 2, 4);
  expect_linear_law_is_linear_elasticity<2>(p2, quarter_disc_dofs(disc, p2));
  NurbsPatch revolved = p2;  // axisymmetric: the hoop terms of both assemblers
  revolved.set_revolved(true);
  expect_linear_law_is_linear_elasticity<2>(revolved, quarter_disc_dofs(disc, revolved));
  const Geometry oct = sphere_octant(1.0);
  const NurbsPatch p3 = refined(oct.patch, 2, 2);
  expect_linear_law_is_linear_elasticity<3>(
      p3, DofMap(p3, {{oct.faces.at("left"), 0, 0.0}, {oct.faces.at("top"), 2, -0.01}}));
}

TEST(TotalLagrangian, TangentKeepsItsPattern) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 3);
  const DofMap dofs = quarter_disc_dofs(g, patch);
  const auto law = make_law("neo_hookean", kMaterial);
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  Eigen::VectorXd f;
  Eigen::SparseMatrix<double> K;
  for (unsigned seed : {1u, 2u}) {
    ASSERT_TRUE(tl.assemble(dofs.expand(random_state(patch, dofs, 0.02, seed)), f, &K));
    const double* values = K.valuePtr();
    ASSERT_TRUE(tl.assemble(dofs.expand(random_state(patch, dofs, 0.02, seed + 10)), f, &K));
    EXPECT_EQ(values, K.valuePtr()) << "a K with the pattern is filled in place";
    ASSERT_EQ(K.nonZeros(), tl.pattern().nonZeros());
    EXPECT_TRUE(std::equal(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros(), tl.pattern().innerIndexPtr()));
    EXPECT_TRUE(std::equal(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1, tl.pattern().outerIndexPtr()));
  }
  // The pattern is exactly the linear assembler's (same couplings).
  const LinearSystem lin =
      assemble_linear_elasticity(patch, dofs, LinearElastic(kMaterial.E, kMaterial.nu), Eigen::VectorXd());
  ASSERT_EQ(lin.K.nonZeros(), tl.pattern().nonZeros());
  EXPECT_TRUE(std::equal(lin.K.innerIndexPtr(), lin.K.innerIndexPtr() + lin.K.nonZeros(), tl.pattern().innerIndexPtr()));
}

// A reflection x -> -x inverts every element (det F = -1): refused by the
// assembler even for a law that accepts any F (linear_elastic).
TEST(TotalLagrangian, InvertedStateIsRefused) {
  for (const char* name : {"neo_hookean", "linear_elastic"}) {
    const auto law = make_law(name, kMaterial);
    for (const NurbsPatch& patch : {refined(quarter_disc(1.0).patch, 2, 2), refined(box(1, 1, 1).patch, 2, 2)}) {
      const DofMap dofs(patch, {});
      const TotalLagrangianAssembler tl(patch, dofs, *law);
      Eigen::MatrixXd u = Eigen::MatrixXd::Zero(patch.num_control_points(), patch.space_dim());
      u.col(0) = -2.0 * patch.points().col(0);
      Eigen::VectorXd f;
      Eigen::SparseMatrix<double> K;
      EXPECT_FALSE(tl.assemble(u, f, &K)) << name << ", " << patch.space_dim() << "D";
      EXPECT_FALSE(tl.assemble(u, f, nullptr)) << name << ", " << patch.space_dim() << "D";
      u.col(0) = -0.5 * patch.points().col(0);  // compressed to half: admissible
      EXPECT_TRUE(tl.assemble(u, f, &K)) << name << ", " << patch.space_dim() << "D";
    }
  }
}

TEST(TotalLagrangian, WrongShapeThrows) {
  const NurbsPatch patch = refined(quarter_disc(1.0).patch, 2, 1);
  const DofMap dofs(patch, {});
  const auto law = make_law("neo_hookean", kMaterial);
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  Eigen::VectorXd f;
  EXPECT_THROW(tl.assemble(Eigen::MatrixXd::Zero(3, 2), f, nullptr), std::invalid_argument);
  EXPECT_THROW(TotalLagrangianAssembler(refined(box(1, 1, 1).patch, 2, 1), dofs, *law), std::invalid_argument);
}

// ----- pressure loads -----

double follower_fd_error(const NurbsPatch& patch, const DofMap& dofs, const std::vector<PatchSide>& faces,
                         const Eigen::VectorXd& free) {
  const double P = 0.3;
  const auto law = make_law("neo_hookean", kMaterial);
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  Eigen::SparseMatrix<double> K = tl.pattern();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs.num_free());
  add_follower_pressure(patch, dofs, faces, P, dofs.expand(free), f, &K);  // K = -d f_ext / du
  const double err = fd_error(-Eigen::MatrixXd(K), dofs, free, [&](const Eigen::MatrixXd& u) {
    Eigen::VectorXd fu = Eigen::VectorXd::Zero(dofs.num_free());
    add_follower_pressure(patch, dofs, faces, P, u, fu, nullptr);
    return fu;
  });
  std::cout << "  load stiffness vs FD (" << patch.space_dim() << "D, p = " << patch.degree(0) << "): " << err
            << "\n";
  return err;
}

TEST(FollowerPressure, LoadStiffnessMatchesFiniteDifferences) {
  {
    const Geometry g = quarter_disc(1.0);
    for (int p : {2, 3}) {
      const NurbsPatch patch = refined(g.patch, p, 3);
      const DofMap dofs = quarter_disc_dofs(g, patch);
      EXPECT_LE(follower_fd_error(patch, dofs, g.faces.at("curved"), random_state(patch, dofs, 0.05, 21)),
                kFiniteDifference);
      const DofMap held(patch, {{g.faces.at("left"), 0, 0.0}});
      EXPECT_LE(follower_fd_error(patch, held, g.faces.at("top"), random_state(patch, held, 0.05, 22)),
                kFiniteDifference);
    }
  }
  {
    const Geometry g = box(1.0, 0.8, 0.6);
    const NurbsPatch patch = distort_interior(refined(g.patch, 2, 2), 0.03, 4);
    const DofMap dofs(patch, {{g.faces.at("bottom"), 2, 0.0}});
    EXPECT_LE(follower_fd_error(patch, dofs, g.faces.at("top"), random_state(patch, dofs, 0.05, 23)),
              kFiniteDifference);
    // every orientation (s and face direction) at once
    std::vector<PatchSide> all;
    for (int d = 0; d < 3; ++d)
      for (bool e : {false, true}) all.push_back(Face{d, e});
    const DofMap none(patch, {});
    EXPECT_LE(follower_fd_error(patch, none, all, random_state(patch, none, 0.05, 24)), kFiniteDifference);
  }
  {  // axisymmetric: the area of the swept surface carries 2 pi r at the current radius
    const Geometry g = quarter_disc(1.0);
    NurbsPatch patch = refined(g.patch, 2, 3);
    patch.set_revolved(true);
    const DofMap dofs = quarter_disc_dofs(g, patch);
    EXPECT_LE(follower_fd_error(patch, dofs, g.faces.at("curved"), random_state(patch, dofs, 0.05, 25)),
              kFiniteDifference);
  }
}

// The residual tangent K_int - d f_ext/du against central differences of
// f_int - f_ext, and the check's power: leaving out the load stiffness (as a
// dead-load tangent would) must fail it by orders of magnitude.
TEST(FollowerPressure, ResidualTangentCheckCatchesMissingLoadStiffness) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 3);
  const DofMap dofs(patch, {{g.faces.at("left"), 0, 0.0}, {g.faces.at("curved"), 1, 0.0}});
  const auto law = make_law("neo_hookean", kMaterial);
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  const Eigen::VectorXd free = random_state(patch, dofs, 0.02, 31);
  const double P = 0.2;
  auto residual = [&](const Eigen::MatrixXd& u) {
    Eigen::VectorXd f, fe = Eigen::VectorXd::Zero(dofs.num_free());
    EXPECT_TRUE(tl.assemble(u, f, nullptr));
    add_follower_pressure(patch, dofs, g.faces.at("top"), P, u, fe, nullptr);
    return Eigen::VectorXd(f - fe);
  };
  Eigen::VectorXd f, fe = Eigen::VectorXd::Zero(dofs.num_free());
  Eigen::SparseMatrix<double> K;
  ASSERT_TRUE(tl.assemble(dofs.expand(free), f, &K));
  const Eigen::MatrixXd K_int(K);
  add_follower_pressure(patch, dofs, g.faces.at("top"), P, dofs.expand(free), fe, &K);
  const double full = fd_error(Eigen::MatrixXd(K), dofs, free, residual);
  const double without = fd_error(K_int, dofs, free, residual);
  std::cout << "  residual tangent vs FD: " << full << ", without load stiffness: " << without << "\n";
  EXPECT_LE(full, kFiniteDifference);
  EXPECT_GE(without, 1e3 * kFiniteDifference);
}

// -P int N_A n dGamma from the face's unit normals and dGamma = |n dA| w
// (ElementData of its PatchQuadrature), independently of the area vector
// that the pressure loads integrate.
Eigen::VectorXd normal_times_area_load(const NurbsPatch& patch, const DofMap& dofs, const PatchSide& side, double P) {
  const int dim = patch.space_dim();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs.num_free());
  const PatchQuadrature quad = face_quadrature(patch, side, gauss_points_for(Body(patch).degree()));
  ElementData ed;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, false);
    for (int q = 0; q < ed.JxW.size(); ++q)
      for (size_t a = 0; a < ed.cps.size(); ++a)
        for (int i = 0; i < dim; ++i)
          if (const int eq = dofs.equation(ed.cps[a] * dim + i); eq >= 0)
            f[eq] -= P * ed.normal(q, i) * ed.N(q, a) * ed.JxW[q];
  }
  return f;
}

// Dead load (= add_pressure_load) = -P int N n dGamma on every face of each
// shape (all orientations), and the follower load at u = 0 equals it.
TEST(FollowerPressure, DeadLoadIsTheReferenceLoad) {
  for (const Geometry& g : {quarter_disc(1.0), box(1.0, 0.8, 0.6), sphere_octant(1.0)}) {
    const NurbsPatch patch = refined(g.patch, 2, 2);
    const int dim = patch.space_dim();
    const DofMap dofs(patch, {{{Face{0, false}}, 0, 0.0}});
    for (int d = 0; d < dim; ++d)
      for (bool e : {false, true}) {
        const std::vector<PatchSide> faces{Face{d, e}};
        Eigen::VectorXd f_ref = Eigen::VectorXd::Zero(dofs.num_free()), f_dead = f_ref, f_fol = f_ref;
        f_ref = normal_times_area_load(patch, dofs, faces.front(), 0.7);
        add_dead_pressure(patch, dofs, faces, 0.7, f_dead);
        add_follower_pressure(patch, dofs, faces, 0.7, Eigen::MatrixXd::Zero(patch.num_control_points(), dim), f_fol,
                              nullptr);
        const double scale = std::max(f_ref.cwiseAbs().maxCoeff(), 1e-300);
        EXPECT_LE((f_dead - f_ref).cwiseAbs().maxCoeff(), kRoundoff * scale) << dim << "D face " << d << e;
        EXPECT_LE((f_fol - f_ref).cwiseAbs().maxCoeff(), kRoundoff * scale) << dim << "D face " << d << e;
      }
  }
}

// Resultant sum_A f_A = -P int n da: on a rigidly rotated (and translated)
// body it is Q times the reference resultant; the dead load does not turn.
template <int dim>
void expect_resultant_rotates(const Geometry& g, const std::vector<PatchSide>& faces,
                              const Eigen::Matrix<double, dim, dim>& Q) {
  const NurbsPatch patch = refined(g.patch, 2, 3);
  const DofMap dofs(patch, {});  // all free: f_ext's rows are the control points' forces
  const int n_cp = patch.num_control_points();
  std::vector<int> component(dofs.num_free());  // coincident control points share equations
  for (int dof = 0; dof < dofs.num_dofs(); ++dof)
    if (dofs.equation(dof) >= 0) component[dofs.equation(dof)] = dof % dim;
  auto resultant = [&](const Eigen::VectorXd& f) {
    Eigen::Matrix<double, dim, 1> r = Eigen::Matrix<double, dim, 1>::Zero();
    for (int eq = 0; eq < dofs.num_free(); ++eq) r[component[eq]] += f[eq];
    return r;
  };
  Eigen::VectorXd f0 = Eigen::VectorXd::Zero(dofs.num_free()), f1 = f0;
  add_follower_pressure(patch, dofs, faces, 1.3, Eigen::MatrixXd::Zero(n_cp, dim), f0, nullptr);
  Eigen::MatrixXd u = patch.points() * (Q - Eigen::Matrix<double, dim, dim>::Identity()).transpose();
  u.rowwise() += Eigen::Matrix<double, 1, dim>::Constant(0.4);
  add_follower_pressure(patch, dofs, faces, 1.3, u, f1, nullptr);
  const Eigen::Matrix<double, dim, 1> r0 = resultant(f0), r1 = resultant(f1);
  EXPECT_GT(r0.norm(), 0.1);
  EXPECT_LE((r1 - Q * r0).norm(), kRoundoff * r0.norm()) << "reference " << r0.transpose() << ", rotated "
                                                          << r1.transpose();
}

TEST(FollowerPressure, ResultantRotatesWithTheBody) {
  const double t = 0.9;
  Eigen::Matrix2d Q2;
  Q2 << std::cos(t), -std::sin(t), std::sin(t), std::cos(t);
  const Geometry disc = quarter_disc(1.0);
  expect_resultant_rotates<2>(disc, disc.faces.at("top"), Q2);
  expect_resultant_rotates<2>(disc, disc.faces.at("curved"), Q2);
  const Eigen::Matrix3d Q3 = Eigen::AngleAxisd(0.8, Eigen::Vector3d(2.0, 1.0, -1.0).normalized()).toRotationMatrix();
  const Geometry oct = sphere_octant(1.0);
  expect_resultant_rotates<3>(oct, oct.faces.at("top"), Q3);
  expect_resultant_rotates<3>(oct, {Face{1, false}}, Q3);  // the spherical face
}

// Newton on the quarter disc under a follower pressure P = 0.1 (the paper's
// large-deformation load) held by a fixed bottom arc instead of contact:
// with the exact tangent K_int - d f_ext / du the residual falls
// quadratically, log r_{k+1} / log r_k >= 1.8 once r < 1e-2 (relative).
TEST(FollowerPressure, NewtonConvergesQuadratically) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 4);
  const DofMap dofs(patch, {{g.faces.at("left"), 0, 0.0}, {g.faces.at("curved"), 0, 0.0},
                            {g.faces.at("curved"), 1, 0.0}});
  const auto law = make_law("neo_hookean", kMaterial);
  const TotalLagrangianAssembler tl(patch, dofs, *law);
  Eigen::VectorXd free = Eigen::VectorXd::Zero(dofs.num_free()), f, fe;
  Eigen::SparseMatrix<double> K;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  std::vector<double> r;
  double r0 = 0;
  for (int it = 0; it < 12; ++it) {
    const Eigen::MatrixXd u = dofs.expand(free);
    ASSERT_TRUE(tl.assemble(u, f, &K));
    fe = Eigen::VectorXd::Zero(dofs.num_free());
    add_follower_pressure(patch, dofs, g.faces.at("top"), 0.1, u, fe, &K);
    const Eigen::VectorXd res = f - fe;
    if (it == 0) r0 = res.norm();
    r.push_back(res.norm() / r0);
    if (r.back() < 1e-13) break;
    if (it == 0) lu.analyzePattern(K);
    lu.factorize(K);
    ASSERT_EQ(lu.info(), Eigen::Success);
    free -= lu.solve(res);
  }
  for (size_t k = 0; k < r.size(); ++k) std::cout << "  Newton " << k << ": " << r[k] << "\n";
  ASSERT_LT(r.back(), 1e-12) << "no convergence";
  int checked = 0;
  for (size_t k = 1; k + 1 < r.size(); ++k)
    if (r[k] < 1e-2 && r[k + 1] > 1e-13) {
      EXPECT_GE(std::log(r[k + 1]) / std::log(r[k]), 1.8) << "iteration " << k;
      ++checked;
    }
  EXPECT_GE(checked, 1);
}

// A distributed run's shares (set_element_range): any cut of the elements
// gives f_int and K whose sums over the blocks are the whole body's, to
// round-off of the order of the additions changed; a mixed patch refuses.
TEST(TotalLagrangian, ElementRangesSumToTheWholeBody) {
  const Geometry g = quarter_disc(1.0);
  const NurbsPatch patch = refined(g.patch, 2, 4);
  const DofMap dofs = quarter_disc_dofs(g, patch);
  const auto law = make_law("neo_hookean", kMaterial);
  const TotalLagrangianAssembler whole(patch, dofs, *law);
  const Eigen::MatrixXd u = dofs.expand(random_state(patch, dofs, 0.01, 3));
  Eigen::VectorXd f;
  Eigen::SparseMatrix<double> K;
  ASSERT_TRUE(whole.assemble(u, f, &K));
  const int n_el = whole.num_elements();
  for (const int cut : {1, n_el / 3, n_el - 1}) {
    Eigen::VectorXd f_sum = Eigen::VectorXd::Zero(f.size());
    Eigen::SparseMatrix<double> K_sum(K.rows(), K.cols());
    for (const ElementRange range : {ElementRange{0, cut}, ElementRange{cut, -1}}) {
      TotalLagrangianAssembler share(patch, dofs, *law);
      share.set_element_range(range);
      Eigen::VectorXd f_share;
      Eigen::SparseMatrix<double> K_share;
      ASSERT_TRUE(share.assemble(u, f_share, &K_share));
      EXPECT_EQ(K_share.nonZeros(), K.nonZeros()) << "each share keeps the whole pattern";
      f_sum += f_share;
      K_sum += K_share;
    }
    EXPECT_LE((f_sum - f).cwiseAbs().maxCoeff(), kRoundoff * f.cwiseAbs().maxCoeff()) << "cut " << cut;
    EXPECT_LE(max_abs(Eigen::MatrixXd(K_sum - K)), kRoundoff * max_abs(Eigen::MatrixXd(K))) << "cut " << cut;
  }
  TotalLagrangianAssembler mixed(patch, dofs, *law, Formulation::mixed);
  EXPECT_THROW(mixed.set_element_range({0, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace igac

