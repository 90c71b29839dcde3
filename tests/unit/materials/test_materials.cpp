// SPDX-License-Identifier: BSD-3-Clause
// Hyperelastic material laws (materials/hyperelastic.hpp), mathematics first.
//
// For every registered law, in 2D (plane strain) and 3D:
//  - P against central differences of the energy and A against central
//    differences of P (check_law), at F near the identity and far from it;
//  - P = 0 and Psi = 0 at F = I; A has the major symmetry A_iJkL = A_kLiJ;
//  - A at F = I is the linear elasticity tensor (every law linearises to
//    linear elasticity);
//  - the 2D law is the in-plane block of the 3D law at F = diag(F_2x2, 1);
//  - a non-finite F is refused with P and A untouched.
// For the finite-strain laws: objectivity, P(QF) = Q P(F) and Psi(QF) =
// Psi(F) for random rotations Q.  linear_elastic is deliberately not tested
// for it: eps = sym(F) - I is not invariant under a finite rotation (a rigid
// rotation by theta strains it by ~theta^2/2), which is why it is a
// small-deformation model only.
// Closed forms for uniaxial stretch; det F <= 0 refused by the laws that
// need J > 0; the registry and parameter validation; and the checker itself
// catches a law with a wrong tangent (missing geometric term) and a wrong
// stress.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "materials/hyperelastic.hpp"

namespace igac {
namespace {

// check_law's central differences (h ~ 6e-6 |F|) have truncation error
// ~h^2 |Psi'''| ~ 1e-11 relative and cancellation ~eps |Psi| / (h |A|) ~
// 1e-10 relative on these F (the third derivatives of Neo-Hookean grow like
// J^-3, and J >= 0.25 here).  Measured at most ~2e-9 (see the printed
// maxima); 1e-7 leaves a margin while a real error (a missing term, a
// factor) shows at 1e-3 .. 1 (CatchesMissingGeometricTerm: ~0.1).
constexpr double kFdTolerance = 1e-7;
// Identities that hold exactly up to the rounding of a few dozen flops on
// O(1) .. O(10) entries, relative to the stiffness scale.
constexpr double kRoundOff = 1e-13;
// The brief's bound for "Neo-Hookean linearises to linear elasticity": at
// F = I the tangents agree to rounding (ln 1 = 0, F^{-1} = I exactly).
constexpr double kLinearisation = 1e-10;

// The paper's material (E = 1, nu = 0.3) and a stiff, nearly incompressible
// steel-like one, where lambda / mu = 9 stresses the checker's scaling.
const MaterialParameters kPaperMaterial{1.0, 0.3};
// The law `name` with the small-strain constants of `mp`: (E, nu) itself for
// the laws written in them, its own parameters for the others (Mooney-Rivlin:
// C10 = 0.35 mu, C01 = 0.15 mu, so that 2 (C10 + C01) = mu, and K = lambda + 2 mu / 3).
MaterialParameters own_parameters(const std::string& name, const MaterialParameters& mp) {
  if (name != "mooney_rivlin") return mp;
  return {NAN, NAN, {{"C10", 0.35 * mp.mu()}, {"C01", 0.15 * mp.mu()}, {"bulk_modulus", mp.lambda() + 2 * mp.mu() / 3}}};
}
std::unique_ptr<HyperelasticLaw> make_test_law(const std::string& name, const MaterialParameters& mp) {
  return make_law(name, own_parameters(name, mp));
}
const MaterialParameters kStiffMaterial{210e3, 0.45};

template <int dim>
DimMatrix<dim> random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  if constexpr (dim == 2) {
    const double a = std::uniform_real_distribution<double>(-std::numbers::pi, std::numbers::pi)(rng);
    return Eigen::Rotation2Dd(a).toRotationMatrix();
  } else {
    return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  }
}

// I + amplitude * U(-1, 1) entries, redrawn until det F >= min_det.
template <int dim>
DimMatrix<dim> random_F(std::mt19937& rng, double amplitude, double min_det) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (;;) {
    const DimMatrix<dim> F = DimMatrix<dim>::Identity() + amplitude * DimMatrix<dim>::NullaryExpr([&] { return u(rng); });
    if (F.determinant() >= min_det) return F;
  }
}

// Sample deformation gradients: the identity, near it (1e-2), far from it
// (entries perturbed by 0.6, J >= 0.25, then rotated), a rigid rotation,
// and strong uniaxial stretch / compression.
template <int dim>
std::vector<DimMatrix<dim>> sample_F(unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<DimMatrix<dim>> Fs{DimMatrix<dim>::Identity()};
  for (int s = 0; s < 4; ++s) Fs.push_back(random_F<dim>(rng, 1e-2, 0.5));
  for (int s = 0; s < 6; ++s) Fs.push_back(random_rotation<dim>(rng) * random_F<dim>(rng, 0.6, 0.25));
  Fs.push_back(random_rotation<dim>(rng));
  for (double stretch : {2.5, 0.4}) {
    DimMatrix<dim> F = DimMatrix<dim>::Identity();
    F(0, 0) = stretch;
    Fs.push_back(F);
  }
  return Fs;
}

template <int dim>
double max_abs(const Eigen::Matrix<double, dim, dim>& m) {
  return m.cwiseAbs().maxCoeff();
}

// Measured FD errors across the whole parameterised suite, printed at the end.
struct MeasuredErrors {
  double stress = 0, tangent = 0;
  ~MeasuredErrors() {
    if (stress > 0 || tangent > 0)
      std::cout << "[materials] max relative FD errors over all laws and samples: stress " << stress
                << ", tangent " << tangent << " (tolerance " << kFdTolerance << ")\n";
  }
};
MeasuredErrors measured;

// ---------------------------------------------------------------- every law

class MaterialLaw : public ::testing::TestWithParam<std::string> {};

template <int dim>
void expect_fd_consistent(const std::string& name, unsigned seed) {
  for (const MaterialParameters& mp : {kPaperMaterial, kStiffMaterial}) {
    const auto law = make_test_law(name, mp);
    double worst_stress = 0, worst_tangent = 0;
    for (const DimMatrix<dim>& F : sample_F<dim>(seed)) {
      const TangentCheck c = check_law(*law, F, kFdTolerance);
      EXPECT_TRUE(c.ok) << c.report << "\nF =\n" << F;
      worst_stress = std::max(worst_stress, c.stress_error);
      worst_tangent = std::max(worst_tangent, c.tangent_error);
    }
    std::cout << "[materials] " << name << " " << dim << "D E=" << mp.E << " nu=" << mp.nu
              << ": max stress error " << worst_stress << ", max tangent error " << worst_tangent << "\n";
    measured.stress = std::max(measured.stress, worst_stress);
    measured.tangent = std::max(measured.tangent, worst_tangent);
  }
}

TEST_P(MaterialLaw, StressAndTangentMatchFiniteDifferences2D) { expect_fd_consistent<2>(GetParam(), 11); }
TEST_P(MaterialLaw, StressAndTangentMatchFiniteDifferences3D) { expect_fd_consistent<3>(GetParam(), 13); }

template <int dim>
void expect_zero_at_identity(const HyperelasticLaw& law) {
  const DimMatrix<dim> I = DimMatrix<dim>::Identity();
  DimMatrix<dim> P;
  TangentMatrix<dim> A;
  ASSERT_TRUE(law.evaluate(I, P, &A));
  EXPECT_LE(max_abs<dim>(P), kRoundOff * A.cwiseAbs().maxCoeff()) << P;
  EXPECT_LE(std::abs(law.energy(I)), kRoundOff * A.cwiseAbs().maxCoeff());
}

TEST_P(MaterialLaw, ZeroStressAndEnergyAtIdentity) {
  const auto law = make_test_law(GetParam(), kPaperMaterial);
  expect_zero_at_identity<2>(*law);
  expect_zero_at_identity<3>(*law);
}

template <int dim>
void expect_major_symmetry(const HyperelasticLaw& law) {
  for (const DimMatrix<dim>& F : sample_F<dim>(17)) {
    DimMatrix<dim> P;
    TangentMatrix<dim> A;
    ASSERT_TRUE(law.evaluate(F, P, &A));
    const TangentMatrix<dim> skew = A - A.transpose();
    EXPECT_LE(skew.cwiseAbs().maxCoeff(), kRoundOff * A.cwiseAbs().maxCoeff()) << "F =\n" << F;
  }
}

TEST_P(MaterialLaw, TangentHasMajorSymmetry) {
  const auto law = make_test_law(GetParam(), kStiffMaterial);
  expect_major_symmetry<2>(*law);
  expect_major_symmetry<3>(*law);
}

// A_iJkL(I) = lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk), written out here
// independently of LinearElasticLaw, and compared with linear_elastic too.
template <int dim>
void expect_linearises_to_linear_elasticity(const HyperelasticLaw& law, const MaterialParameters& mp) {
  const DimMatrix<dim> I = DimMatrix<dim>::Identity();
  TangentMatrix<dim> C;
  for (int i = 0; i < dim; ++i)
    for (int J = 0; J < dim; ++J)
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L)
          C(i * dim + J, k * dim + L) = mp.lambda() * I(i, J) * I(k, L) + mp.mu() * (I(i, k) * I(J, L) + I(i, L) * I(J, k));
  DimMatrix<dim> P, P_lin;
  TangentMatrix<dim> A, A_lin;
  ASSERT_TRUE(law.evaluate(I, P, &A));
  ASSERT_TRUE(make_law("linear_elastic", mp)->evaluate(I, P_lin, &A_lin));
  EXPECT_LE((A - C).cwiseAbs().maxCoeff(), kLinearisation * C.cwiseAbs().maxCoeff()) << A << "\nvs\n" << C;
  EXPECT_LE((A - A_lin).cwiseAbs().maxCoeff(), kLinearisation * C.cwiseAbs().maxCoeff());
}

TEST_P(MaterialLaw, LinearisesToLinearElasticityAtIdentity) {
  for (const MaterialParameters& mp : {kPaperMaterial, kStiffMaterial}) {
    const auto law = make_test_law(GetParam(), mp);
    expect_linearises_to_linear_elasticity<2>(*law, mp);
    expect_linearises_to_linear_elasticity<3>(*law, mp);
  }
}

// The small-deformation path takes (lambda, mu) from the law's tangent at
// F = I: for every law it is the (E, nu) the law declares it linearises to.
TEST_P(MaterialLaw, SmallStrainMaterialIsTheLawsOwnElasticityAtIdentity) {
  for (const MaterialParameters& mp : {kPaperMaterial, kStiffMaterial}) {
    const MaterialParameters given = own_parameters(GetParam(), mp);
    const auto law = make_law(GetParam(), given);
    const MaterialParameters lin = small_strain_equivalent(GetParam(), given);
    for (int dim : {2, 3}) {
      const LinearElastic m = small_strain_material(*law, dim);
      EXPECT_NEAR(m.E(), lin.E, 1e-10 * lin.E) << GetParam() << ", " << dim << "D";
      EXPECT_NEAR(m.nu(), lin.nu, 1e-10) << GetParam() << ", " << dim << "D";
    }
  }
}

// Plane strain: the 2D law at F2 is the in-plane block of the 3D law at
// diag(F2, 1) -- energy, P_iJ and A_iJkL for i, J, k, L in {0, 1}.
TEST_P(MaterialLaw, PlaneStrainIsTheInPlaneBlockOf3D) {
  const auto law = make_test_law(GetParam(), kStiffMaterial);
  for (const Eigen::Matrix2d& F2 : sample_F<2>(19)) {
    Eigen::Matrix3d F3 = Eigen::Matrix3d::Identity();
    F3.topLeftCorner<2, 2>() = F2;
    Eigen::Matrix2d P2;
    Eigen::Matrix4d A2;
    Eigen::Matrix3d P3;
    Eigen::Matrix<double, 9, 9> A3;
    ASSERT_TRUE(law->evaluate(F2, P2, &A2));
    ASSERT_TRUE(law->evaluate(F3, P3, &A3));
    const double scale = A3.cwiseAbs().maxCoeff();
    EXPECT_NEAR(law->energy(F2), law->energy(F3), kRoundOff * scale);
    EXPECT_LE((P2 - P3.topLeftCorner<2, 2>()).cwiseAbs().maxCoeff(), kRoundOff * scale);
    for (int i = 0; i < 2; ++i)
      for (int J = 0; J < 2; ++J)
        for (int k = 0; k < 2; ++k)
          for (int L = 0; L < 2; ++L)
            EXPECT_NEAR(A2(i * 2 + J, k * 2 + L), A3(i * 3 + J, k * 3 + L), kRoundOff * scale);
  }
}

template <int dim>
void expect_refused_untouched(const HyperelasticLaw& law, const DimMatrix<dim>& F) {
  DimMatrix<dim> P = DimMatrix<dim>::Constant(42.0);
  TangentMatrix<dim> A = TangentMatrix<dim>::Constant(42.0);
  EXPECT_FALSE(law.evaluate(F, P, &A)) << law.name() << " F =\n" << F;
  EXPECT_FALSE(law.evaluate(F, P, nullptr));
  EXPECT_TRUE((P.array() == 42.0).all()) << "P was written";
  EXPECT_TRUE((A.array() == 42.0).all()) << "A was written";
  EXPECT_EQ(law.energy(F), std::numeric_limits<double>::infinity());
}

TEST_P(MaterialLaw, RefusesNonFiniteF) {
  const auto law = make_test_law(GetParam(), kPaperMaterial);
  for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    Eigen::Matrix2d F2 = Eigen::Matrix2d::Identity();
    F2(0, 1) = bad;
    expect_refused_untouched<2>(*law, F2);
    Eigen::Matrix3d F3 = Eigen::Matrix3d::Identity();
    F3(2, 0) = bad;
    expect_refused_untouched<3>(*law, F3);
  }
}

// evaluate without A (stress only) gives the same P as with it.
TEST_P(MaterialLaw, StressOnlyEvaluationAgrees) {
  const auto law = make_test_law(GetParam(), kPaperMaterial);
  for (const Eigen::Matrix3d& F : sample_F<3>(23)) {
    Eigen::Matrix3d P, P_only;
    Eigen::Matrix<double, 9, 9> A;
    ASSERT_TRUE(law->evaluate(F, P, &A));
    ASSERT_TRUE(law->evaluate(F, P_only, nullptr));
    EXPECT_EQ(P, P_only);
  }
}

INSTANTIATE_TEST_SUITE_P(AllLaws, MaterialLaw, ::testing::ValuesIn(law_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// ----------------------------------------------------- finite-strain laws

// Every registered law but the small-strain one (see the header comment).
std::vector<std::string> finite_strain_law_names() {
  std::vector<std::string> names = law_names();
  std::erase(names, "linear_elastic");
  return names;
}

class MaterialObjectivity : public ::testing::TestWithParam<std::string> {};

template <int dim>
void expect_objective(const HyperelasticLaw& law, unsigned seed) {
  std::mt19937 rng(seed);
  for (const DimMatrix<dim>& F : sample_F<dim>(seed)) {
    for (int r = 0; r < 3; ++r) {
      const DimMatrix<dim> Q = random_rotation<dim>(rng);
      DimMatrix<dim> P, PQ;
      TangentMatrix<dim> A;
      ASSERT_TRUE(law.evaluate(F, P, &A));
      ASSERT_TRUE(law.evaluate(DimMatrix<dim>(Q * F), PQ, nullptr));
      // Relative to the stress of a unit strain (the stiffness scale), a
      // bound that is meaningful at F = I too.
      const double scale = std::max(A.cwiseAbs().maxCoeff(), max_abs<dim>(P));
      EXPECT_LE(max_abs<dim>(PQ - Q * P), kRoundOff * 10 * scale) << "F =\n" << F << "\nQ =\n" << Q;
      EXPECT_NEAR(law.energy(DimMatrix<dim>(Q * F)), law.energy(F), kRoundOff * 10 * scale);
    }
  }
}

// P(QF) = Q P(F), Psi(QF) = Psi(F).  The bound is 10 kRoundOff: Q F adds a
// rotation's rounding to every entry of F before the law sees it.
TEST_P(MaterialObjectivity, RotatingTheDeformationRotatesTheStress) {
  const auto law = make_test_law(GetParam(), kPaperMaterial);
  expect_objective<2>(*law, 29);
  expect_objective<3>(*law, 31);
}

INSTANTIATE_TEST_SUITE_P(FiniteStrainLaws, MaterialObjectivity, ::testing::ValuesIn(finite_strain_law_names()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// ------------------------------------------------ closed forms per law

// Uniaxial stretch F = diag(s, 1, 1), J = s.  Neo-Hookean:
//   Psi = mu/2 (s^2 - 1) - mu ln s + lambda/2 (ln s)^2,
//   P_11 = mu (s - 1/s) + lambda ln s / s,  P_22 = P_33 = lambda ln s.
TEST(MaterialNeoHookean, UniaxialStretchMatchesClosedForm) {
  const MaterialParameters mp = kPaperMaterial;
  const double lambda = mp.lambda(), mu = mp.mu();
  const auto law = make_law("neo_hookean", mp);
  for (double s : {0.5, 0.9, 1.3, 2.0}) {
    const Eigen::Matrix3d F = Eigen::Vector3d(s, 1, 1).asDiagonal();
    Eigen::Matrix3d P;
    ASSERT_TRUE(law->evaluate(F, P, nullptr));
    const double ls = std::log(s);
    EXPECT_NEAR(law->energy(F), mu / 2 * (s * s - 1) - mu * ls + lambda / 2 * ls * ls, kRoundOff);
    EXPECT_NEAR(P(0, 0), mu * (s - 1 / s) + lambda * ls / s, kRoundOff);
    EXPECT_NEAR(P(1, 1), lambda * ls, kRoundOff);
    EXPECT_NEAR(P(2, 2), lambda * ls, kRoundOff);
    EXPECT_NEAR(P(0, 1), 0.0, kRoundOff);
  }
}

// Saint Venant-Kirchhoff, same stretch: E_11 = (s^2 - 1)/2,
//   Psi = (lambda/2 + mu) E_11^2, P_11 = s (lambda + 2 mu) E_11, P_22 = lambda E_11.
TEST(MaterialSaintVenantKirchhoff, UniaxialStretchMatchesClosedForm) {
  const MaterialParameters mp = kPaperMaterial;
  const double lambda = mp.lambda(), mu = mp.mu();
  const auto law = make_law("saint_venant_kirchhoff", mp);
  for (double s : {0.5, 0.9, 1.3, 2.0}) {
    const Eigen::Matrix3d F = Eigen::Vector3d(s, 1, 1).asDiagonal();
    Eigen::Matrix3d P;
    ASSERT_TRUE(law->evaluate(F, P, nullptr));
    const double E11 = (s * s - 1) / 2;
    EXPECT_NEAR(law->energy(F), (lambda / 2 + mu) * E11 * E11, kRoundOff);
    EXPECT_NEAR(P(0, 0), s * (lambda + 2 * mu) * E11, kRoundOff);
    EXPECT_NEAR(P(1, 1), lambda * E11, kRoundOff);
    EXPECT_NEAR(P(2, 2), lambda * E11, kRoundOff);
  }
}

// Simple shear F = I + g e1 (x) e2: eps_12 = g/2, sigma_12 = mu g, tr eps = 0,
// Psi = mu g^2 / 2 -- exact for any g, being linear.
TEST(MaterialLinearElastic, SimpleShearMatchesClosedForm) {
  const MaterialParameters mp = kPaperMaterial;
  const auto law = make_law("linear_elastic", mp);
  for (double g : {0.01, 0.5, 3.0}) {
    Eigen::Matrix2d F = Eigen::Matrix2d::Identity();
    F(0, 1) = g;
    Eigen::Matrix2d P;
    ASSERT_TRUE(law->evaluate(F, P, nullptr));
    EXPECT_NEAR(P(0, 1), mp.mu() * g, kRoundOff);
    EXPECT_NEAR(P(1, 0), mp.mu() * g, kRoundOff);
    EXPECT_NEAR(P(0, 0), 0.0, kRoundOff);
    EXPECT_NEAR(law->energy(F), mp.mu() * g * g / 2, kRoundOff);
  }
}

// The small-strain law has no J > 0 requirement: an inverted F is evaluated.
TEST(MaterialLinearElastic, AcceptsInvertedF) {
  const auto law = make_law("linear_elastic", kPaperMaterial);
  const Eigen::Matrix3d F = Eigen::Vector3d(-1, 1, 1).asDiagonal();
  Eigen::Matrix3d P;
  EXPECT_TRUE(law->evaluate(F, P, nullptr));
  EXPECT_TRUE(std::isfinite(law->energy(F)));
}

// det F <= 0 (a flattened and an inverted element) is refused, P and A untouched.
TEST(MaterialNeoHookean, RefusesNonPositiveDetF) {
  for (const std::string name : {"neo_hookean", "saint_venant_kirchhoff"}) {
    const auto law = make_test_law(name, kPaperMaterial);
    expect_refused_untouched<2>(*law, Eigen::Vector2d(1, 0).asDiagonal().toDenseMatrix());
    expect_refused_untouched<2>(*law, Eigen::Vector2d(-1, 1).asDiagonal().toDenseMatrix());
    expect_refused_untouched<3>(*law, Eigen::Vector3d(1, 1, 0).asDiagonal().toDenseMatrix());
    expect_refused_untouched<3>(*law, Eigen::Vector3d(1, -0.5, 1).asDiagonal().toDenseMatrix());
    Eigen::Matrix3d singular;  // rank 2, entries O(1)
    singular << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    expect_refused_untouched<3>(*law, singular);
  }
}

// ------------------------------------------------------ the checker itself

// Saint Venant-Kirchhoff whose tangent forgets the geometric term d_ik S_JL:
// the classic bug of a material-only stiffness.  Written as a test-only law
// through the public adapter, as a user would add one.
struct SvkWithoutGeometricTerm : YoungPoissonParameters {
  static constexpr std::string_view kName = "svk_without_geometric_term";
  static constexpr bool kRequiresPositiveJ = true;
  explicit SvkWithoutGeometricTerm(const MaterialParameters& mp) : lambda(mp.lambda()), mu(mp.mu()) {}
  template <int dim>
  DimMatrix<dim> green(const DimMatrix<dim>& F) const {
    return 0.5 * (F.transpose() * F - DimMatrix<dim>::Identity());
  }
  template <int dim>
  double energy(const DimMatrix<dim>& F) const {
    const DimMatrix<dim> E = green<dim>(F);
    return 0.5 * lambda * E.trace() * E.trace() + mu * E.squaredNorm();
  }
  template <int dim>
  void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const {
    const DimMatrix<dim> E = green<dim>(F);
    P = F * (lambda * E.trace() * DimMatrix<dim>::Identity() + 2 * mu * E);
  }
  template <int dim>
  void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const {
    const DimMatrix<dim> b = F * F.transpose();
    for (int i = 0; i < dim; ++i)
      for (int J = 0; J < dim; ++J)
        for (int k = 0; k < dim; ++k)
          for (int L = 0; L < dim; ++L)
            A(i * dim + J, k * dim + L) =
                lambda * F(i, J) * F(k, L) + (J == L ? mu * b(i, k) : 0.0) + mu * F(i, L) * F(k, J);
  }
  double lambda, mu;
};

// Neo-Hookean whose stress forgets the volumetric term lambda ln J F^{-T}
// (its tangent is consistent with that wrong stress, so only the stress
// check can catch it).
struct NeoHookeanWithoutVolumetricStress : YoungPoissonParameters {
  static constexpr std::string_view kName = "neo_hookean_without_volumetric_stress";
  static constexpr bool kRequiresPositiveJ = true;
  explicit NeoHookeanWithoutVolumetricStress(const MaterialParameters& mp) : lambda(mp.lambda()), mu(mp.mu()) {}
  template <int dim>
  double energy(const DimMatrix<dim>& F) const {
    const double lnJ = std::log(F.determinant());
    return 0.5 * mu * (F.squaredNorm() - dim) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
  }
  template <int dim>
  void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const {
    P = mu * (F - F.inverse().transpose());
  }
  template <int dim>
  void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const {
    const DimMatrix<dim> Fi = F.inverse();
    for (int i = 0; i < dim; ++i)
      for (int J = 0; J < dim; ++J)
        for (int k = 0; k < dim; ++k)
          for (int L = 0; L < dim; ++L)
            A(i * dim + J, k * dim + L) = (i == k && J == L ? mu : 0.0) + mu * Fi(J, k) * Fi(L, i);
  }
  double lambda, mu;
};

TEST(MaterialTangentCheck, CatchesMissingGeometricTerm) {
  const auto wrong = adapt<SvkWithoutGeometricTerm>(kPaperMaterial);
  const auto right = make_law("saint_venant_kirchhoff", kPaperMaterial);
  std::mt19937 rng(37);
  for (int s = 0; s < 5; ++s) {
    const Eigen::Matrix3d F3 = random_F<3>(rng, 0.3, 0.5);
    const TangentCheck bad = check_law(*wrong, F3, kFdTolerance);
    if (s == 0) std::cout << "[materials] wrong tangent: " << bad.report << "\n";
    EXPECT_FALSE(bad.ok) << bad.report;
    EXPECT_LE(bad.stress_error, kFdTolerance) << bad.report;  // the stress is right
    EXPECT_GT(bad.tangent_error, 1e3 * kFdTolerance) << bad.report;
    EXPECT_NE(bad.report.find("FAILED"), std::string::npos) << bad.report;
    EXPECT_TRUE(check_law(*right, F3, kFdTolerance).ok);
    const Eigen::Matrix2d F2 = random_F<2>(rng, 0.3, 0.5);
    EXPECT_FALSE(check_law(*wrong, F2, kFdTolerance).ok);
  }
  // At F = I the stress, hence the missing term, vanishes: a tangent check
  // only at the identity would pass this bug -- hence the far-from-I samples.
  EXPECT_TRUE(check_law(*wrong, Eigen::Matrix3d::Identity().eval(), kFdTolerance).ok);
}

TEST(MaterialTangentCheck, CatchesWrongStress) {
  const auto wrong = adapt<NeoHookeanWithoutVolumetricStress>(kPaperMaterial);
  std::mt19937 rng(41);
  for (int s = 0; s < 5; ++s) {
    const TangentCheck bad = check_law(*wrong, random_F<3>(rng, 0.3, 0.5), kFdTolerance);
    if (s == 0) std::cout << "[materials] wrong stress: " << bad.report << "\n";
    EXPECT_FALSE(bad.ok) << bad.report;
    EXPECT_GT(bad.stress_error, 1e3 * kFdTolerance) << bad.report;
    EXPECT_LE(bad.tangent_error, kFdTolerance) << bad.report;  // consistent with its own stress
  }
}

TEST(MaterialTangentCheck, InadmissibleFIsNotOk) {
  const auto law = make_law("neo_hookean", kPaperMaterial);
  const TangentCheck c = check_law(*law, Eigen::Vector2d(-1, 1).asDiagonal().toDenseMatrix(), kFdTolerance);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.report.find("inadmissible"), std::string::npos) << c.report;
  // J ~ 1e-7: the difference stencil itself crosses det F = 0.
  const TangentCheck edge = check_law(*law, Eigen::Vector3d(1, 1, 1e-7).asDiagonal().toDenseMatrix(), kFdTolerance);
  EXPECT_FALSE(edge.ok) << edge.report;
}

TEST(MaterialTangentCheck, ReportNamesLawDimensionAndVerdict) {
  const auto law = make_law("neo_hookean", kPaperMaterial);
  const TangentCheck c = check_law(*law, Eigen::Matrix3d::Identity().eval(), kFdTolerance);
  EXPECT_TRUE(c.ok) << c.report;
  EXPECT_EQ(c.report.rfind("neo_hookean (3D): stress error ", 0), 0u) << c.report;
  EXPECT_NE(c.report.find(": ok"), std::string::npos) << c.report;
}

// ---------------------------------------------------- registry, parameters

// A law whose elasticity at F = I is not isotropic (linear elastic plus a
// stiffening of the x direction): the small-deformation path refuses it.
class AnisotropicLaw final : public HyperelasticLaw {
 public:
  std::string name() const override { return "anisotropic"; }
  bool evaluate(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const override {
    return add_fibre<2>(F, P, A);
  }
  bool evaluate(const Eigen::Matrix3d& F, Eigen::Matrix3d& P, Eigen::Matrix<double, 9, 9>* A) const override {
    return add_fibre<3>(F, P, A);
  }
  double energy(const Eigen::Matrix2d&) const override { return 0; }
  double energy(const Eigen::Matrix3d&) const override { return 0; }

 private:
  template <int dim>
  bool add_fibre(const DimMatrix<dim>& F, DimMatrix<dim>& P, TangentMatrix<dim>* A) const {
    if (!base_->evaluate(F, P, A)) return false;
    P(0, 0) += F(0, 0) - 1;
    if (A) (*A)(0, 0) += 1;
    return true;
  }
  std::unique_ptr<HyperelasticLaw> base_ = make_law("linear_elastic", MaterialParameters{1, 0.3});
};

TEST(MaterialSmallStrain, AnisotropicLawIsRefused) {
  const AnisotropicLaw law;
  for (int dim : {2, 3}) {
    try {
      small_strain_material(law, dim);
      ADD_FAILURE() << "accepted in " << dim << "D";
    } catch (const MaterialError& e) {
      EXPECT_NE(std::string(e.what()).find("not isotropic"), std::string::npos) << e.what();
    }
  }
}

TEST(MaterialRegistry, ListsEveryLawAndMakesIt) {
  const std::vector<std::string> expected{"linear_elastic", "neo_hookean", "saint_venant_kirchhoff", "mooney_rivlin"};
  EXPECT_EQ(law_names(), expected);
  for (const std::string& name : law_names()) EXPECT_EQ(make_test_law(name, kPaperMaterial)->name(), name);
}

TEST(MaterialRegistry, UnknownLawThrowsListingTheKnownOnes) {
  try {
    make_law("ogden", kPaperMaterial);
    FAIL() << "no MaterialError";
  } catch (const MaterialError& e) {
    EXPECT_STREQ(e.what(),
                 "unknown material law 'ogden' (known laws: linear_elastic, neo_hookean, "
                 "saint_venant_kirchhoff, mooney_rivlin)");
  }
}

TEST(MaterialParameters, LameConstants) {
  // E = 1, nu = 0.3: lambda = 0.3 / (1.3 * 0.4), mu = 1 / 2.6.
  EXPECT_NEAR(kPaperMaterial.lambda(), 0.3 / 0.52, 1e-15);
  EXPECT_NEAR(kPaperMaterial.mu(), 1 / 2.6, 1e-15);
}

TEST(MaterialParameters, InvalidParametersThrow) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const MaterialParameters bad : {MaterialParameters{1, 0.5}, MaterialParameters{1, 0.7},
                                       MaterialParameters{1, -1}, MaterialParameters{0, 0.3},
                                       MaterialParameters{-2, 0.3}, MaterialParameters{nan, 0.3},
                                       MaterialParameters{1, nan}})
    for (const std::string& name : law_names())
      EXPECT_THROW(make_test_law(name, bad), MaterialError) << name << " E=" << bad.E << " nu=" << bad.nu;
  try {
    make_law("neo_hookean", {1, 0.5});
    FAIL() << "no MaterialError";
  } catch (const MaterialError& e) {
    EXPECT_NE(std::string(e.what()).find("nu = 0.5"), std::string::npos) << e.what();
  }
}

// ------------------------------------------------- the volumetric split

// The isochoric part of a law's split as a law of its own, so check_law
// checks it like any law.
class IsochoricView final : public HyperelasticLaw {
 public:
  explicit IsochoricView(const HyperelasticLaw& law) : law_(law) {}
  std::string name() const override { return law_.name() + " (isochoric)"; }
  bool evaluate(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const override {
    return law_.evaluate_isochoric(F, P, A);
  }
  bool evaluate(const Eigen::Matrix3d& F, Eigen::Matrix3d& P, Eigen::Matrix<double, 9, 9>* A) const override {
    return law_.evaluate_isochoric(F, P, A);
  }
  double energy(const Eigen::Matrix2d& F) const override { return law_.isochoric_energy(F); }
  double energy(const Eigen::Matrix3d& F) const override { return law_.isochoric_energy(F); }

 private:
  const HyperelasticLaw& law_;
};

// Laws with a split (the mixed formulation's seam): the isochoric stress and
// tangent against central differences, U' and U'' likewise, U convex with
// U(1) = U'(1) = 0; the isochoric part is stress-free at F = I and
// insensitive to volume (P_iso : F = 0); and at F = I the split's tangent
// A_iso + U''(1) I (x) I is the law's own elasticity (same lambda, mu).
template <int dim>
void expect_split_consistent(const HyperelasticLaw& law, unsigned seed) {
  const IsochoricView iso(law);
  for (const DimMatrix<dim>& F : sample_F<dim>(seed)) {
    const TangentCheck c = check_law(iso, F, kFdTolerance);
    EXPECT_TRUE(c.ok) << c.report << "\nF =\n" << F;
    DimMatrix<dim> P;
    ASSERT_TRUE(law.evaluate_isochoric(F, P, nullptr));
    // W_iso(s F) = W_iso(F) for a volumetric scaling s (3D: F_33 scales too, so check in 3D only)
    if (dim == 3) EXPECT_NEAR((P.transpose() * F).trace(), 0.0, 1e-10 * std::max(1.0, max_abs<dim>(P)));
  }
  VolumetricValues v1, vp, vm;
  ASSERT_TRUE(law.volumetric(1.0, v1));
  EXPECT_NEAR(v1.U, 0.0, kRoundOff * v1.d2U);
  EXPECT_NEAR(v1.dU, 0.0, kRoundOff * v1.d2U);
  for (double J : {0.3, 0.8, 1.0, 1.2, 2.5}) {
    const double h = 1e-6;
    VolumetricValues v;
    ASSERT_TRUE(law.volumetric(J, v));
    ASSERT_TRUE(law.volumetric(J + h, vp));
    ASSERT_TRUE(law.volumetric(J - h, vm));
    EXPECT_NEAR(v.dU, (vp.U - vm.U) / (2 * h), 1e-7 * v1.d2U) << "J = " << J;
    EXPECT_NEAR(v.d2U, (vp.dU - vm.dU) / (2 * h), 1e-7 * v1.d2U) << "J = " << J;
    EXPECT_GT(v.d2U, 0.0) << "U is convex";
  }
  EXPECT_FALSE(law.volumetric(0.0, v1));
  EXPECT_FALSE(law.volumetric(NAN, v1));
  const DimMatrix<dim> I = DimMatrix<dim>::Identity();
  DimMatrix<dim> P;
  TangentMatrix<dim> A_iso, A;
  ASSERT_TRUE(law.evaluate_isochoric(I, P, &A_iso));
  EXPECT_LE(max_abs<dim>(P), kRoundOff);
  ASSERT_TRUE(law.evaluate(I, P, &A));
  ASSERT_TRUE(law.volumetric(1.0, v1));
  for (int i = 0; i < dim; ++i)
    for (int k = 0; k < dim; ++k) A_iso(i * dim + i, k * dim + k) += v1.d2U;
  EXPECT_LE((A_iso - A).cwiseAbs().maxCoeff(), kLinearisation * A.cwiseAbs().maxCoeff()) << law.name();
}

TEST(MaterialSplit, IsochoricAndVolumetricPartsAreConsistent) {
  for (const std::string name : {"neo_hookean", "mooney_rivlin"})
    for (const MaterialParameters& mp : {kPaperMaterial, kStiffMaterial, MaterialParameters{1.0, 0.49975, {}}}) {
      const auto law = make_test_law(name, mp);
      ASSERT_TRUE(law->has_volumetric_split()) << name;
      expect_split_consistent<2>(*law, 17);
      expect_split_consistent<3>(*law, 19);
    }
}

// Mooney-Rivlin is written as the split: W_iso + U is the law, P and A too.
TEST(MaterialSplit, MooneyRivlinSplitIsTheLaw) {
  const auto law = make_test_law("mooney_rivlin", kStiffMaterial);
  for (const Eigen::Matrix3d& F : sample_F<3>(23)) {
    Eigen::Matrix3d P, P_iso;
    Eigen::Matrix<double, 9, 9> A, A_iso;
    ASSERT_TRUE(law->evaluate(F, P, &A));
    ASSERT_TRUE(law->evaluate_isochoric(F, P_iso, &A_iso));
    VolumetricValues v;
    const double J = F.determinant();
    ASSERT_TRUE(law->volumetric(J, v));
    EXPECT_NEAR(law->isochoric_energy(F) + v.U, law->energy(F), 1e-10 * std::max(1.0, std::abs(law->energy(F))));
    const Eigen::Matrix3d P_vol = v.dU * J * F.inverse().transpose();
    EXPECT_LE((P_iso + P_vol - P).cwiseAbs().maxCoeff(), 1e-10 * std::max(1.0, P.cwiseAbs().maxCoeff()));
  }
}

// A law without a split says so, and its split methods refuse.
TEST(MaterialSplit, LawsWithoutASplitSaySo) {
  for (const std::string name : {"saint_venant_kirchhoff", "linear_elastic"}) {
    const auto law = make_law(name, kPaperMaterial);
    EXPECT_FALSE(law->has_volumetric_split()) << name;
    Eigen::Matrix2d P = Eigen::Matrix2d::Zero();
    EXPECT_FALSE(law->evaluate_isochoric(Eigen::Matrix2d::Identity(), P, nullptr));
    VolumetricValues v;
    EXPECT_FALSE(law->volumetric(1.0, v));
  }
}

}  // namespace
}  // namespace igac
