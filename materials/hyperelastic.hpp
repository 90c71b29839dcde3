// SPDX-License-Identifier: BSD-3-Clause
// Hyperelastic material laws: the interface the total-Lagrangian assembler
// calls at every quadrature point, the adapter that turns a law written once
// as a template on the dimension into that interface, the registry of laws by
// name, and a finite-difference checker of a law's stress and tangent.
//
// Mathematics (Holzapfel, Nonlinear Solid Mechanics, ch. 6; Wriggers,
// Nonlinear Finite Element Methods, ch. 3).  A hyperelastic law is a strain
// energy Psi(F) per unit reference volume; the first Piola-Kirchhoff stress
// is P = dPsi/dF and the tangent (first elasticity tensor) is A = dP/dF,
//   P_iJ = dPsi / dF_iJ,    A_iJkL = dP_iJ / dF_kL = d2Psi / dF_iJ dF_kL,
// so A has the major symmetry A_iJkL = A_kLiJ.  A is stored as a
// (dim*dim) x (dim*dim) matrix with F flattened row by row:
//   A(i*dim + J, k*dim + L) = dP_iJ / dF_kL.
// In 2D a law is plane strain: F = [[F_2x2, 0], [0, 1]], and the 2D
// methods return the in-plane block of the 3D P and A (P_33 is not returned);
// PlaneStressLaw (materials/plane_stress.hpp) makes the plane stress law of any law.
//
// Who owns what: a law owns its constants (lambda, mu) and nothing else; it
// keeps no scratch (callers may share one law between threads).  It reports an
// inadmissible F (det F <= 0 where the law needs J > 0, or anything not
// finite) by returning false and leaving P and A untouched, so a Newton
// driver can cut the load step back instead of carrying NaNs.
//
// Adding a law: see materials/README.md ("Adding a material law").
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>  // determinant and inverse of fixed-size F (closed form)
#include <cmath>
#include <concepts>
#include <limits>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "materials/linear_elastic.hpp"  // MaterialError

namespace igac {

// A parameter a law declares: its case-file key, what it is, and the
// admissible range (open or closed at each end).  Checked, with one-line
// messages naming the key, before the law is made.
struct LawParameter {
  std::string_view key, meaning;
  double lower = -std::numeric_limits<double>::infinity(), upper = std::numeric_limits<double>::infinity();
  bool lower_open = true, upper_open = true;
};

// Invalid or missing material parameter: names the key.
class MaterialParameterError : public MaterialError {
 public:
  MaterialParameterError(std::string key, const std::string& message) : MaterialError(message), key_(std::move(key)) {}
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// The parameters of a law as given by a user: (E, nu) for the laws written in
// Young's modulus and Poisson's ratio, and `values` for a law's own keys
// (C10, C01, bulk_modulus, ...).  lambda() and mu() derive the Lame constants
// of (E, nu) (the same in plane strain and 3D).
struct MaterialParameters {
  double E = std::numeric_limits<double>::quiet_NaN(), nu = std::numeric_limits<double>::quiet_NaN();
  std::map<std::string, double, std::less<>> values;
  // lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
  double lambda() const { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
  double mu() const { return E / (2 * (1 + nu)); }
  // "E", "nu" or a key of `values`; throws MaterialParameterError when absent.
  double value(std::string_view key) const;
  // Throws MaterialError unless E > 0 and -1 < nu < 0.5 (the checks and
  // messages of LinearElastic).
  void validate() const;
};

// The parameters of every law written in (E, nu): derive from it.
struct YoungPoissonParameters {
  static constexpr LawParameter kParameters[] = {
      {"E", "Young's modulus", 0.0, std::numeric_limits<double>::infinity(), true, true},
      {"nu", "Poisson's ratio", -1.0, 0.5, true, true},
  };
  static MaterialParameters small_strain_equivalent(const MaterialParameters& p) { return {p.E, p.nu, {}}; }
};

// Checks every declared parameter of a law: present and in its range.
// Throws MaterialParameterError naming the first key that is not.
void validate_parameters(std::span<const LawParameter> declared, const MaterialParameters& given);

// The volumetric part U(J) of a law's split Psi = W_iso(F) + U(J) and its
// first two derivatives at one J (the mixed formulation, engine/
// volumetric_projection.hpp, evaluates it at the projected dilatation).
struct VolumetricValues {
  double U = 0, dU = 0, d2U = 0;
};

// A second-order tensor (F, P) and a fourth-order tangent in the layout above.
template <int dim>
using DimMatrix = Eigen::Matrix<double, dim, dim>;
template <int dim>
using TangentMatrix = Eigen::Matrix<double, dim * dim, dim * dim>;

class HyperelasticLaw {
 public:
  virtual ~HyperelasticLaw() = default;
  virtual std::string name() const = 0;
  // P = dPsi/dF and, when A is not null, A = dP/dF.  Returns false when F is
  // inadmissible (det F <= 0 for a law that needs J > 0, or not finite, or a
  // result that overflows): P and A are then untouched.
  virtual bool evaluate(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const = 0;
  virtual bool evaluate(const Eigen::Matrix3d& F, Eigen::Matrix3d& P,
                        Eigen::Matrix<double, 9, 9>* A) const = 0;
  // Psi(F); +inf when F is inadmissible.
  virtual double energy(const Eigen::Matrix2d& F) const = 0;
  virtual double energy(const Eigen::Matrix3d& F) const = 0;
  // F_33 of the 2D model at the in-plane F: 1 in plane strain (every law's
  // own 2D methods); the plane stress wrapper (materials/plane_stress.hpp)
  // solves it from P_33 = 0.  NaN when F is inadmissible.
  virtual double out_of_plane_stretch(const Eigen::Matrix2d& F) const {
    return F.allFinite() ? 1.0 : std::numeric_limits<double>::quiet_NaN();
  }

  // The isochoric/volumetric split Psi_split = W_iso(F) + U(J) of a law that
  // declares one (VolumetricSplitLaw below): W_iso depends on F only through
  // Fbar = J^{-1/3} F (3D J, also in plane strain), U is convex with
  // U(1) = U'(1) = 0 and U''(1) = K, the bulk modulus.  The mixed formulation
  // (engine/volumetric_projection.hpp) assembles with the two parts
  // separately; Psi_split linearises at F = I to the law's own (lambda, mu),
  // and for a law written as the split (Mooney-Rivlin) it is the law.
  virtual bool has_volumetric_split() const { return false; }
  // P_iso = dW_iso/dF and A_iso = dP_iso/dF; false when F is inadmissible or
  // the law declares no split (P and A untouched).
  virtual bool evaluate_isochoric(const Eigen::Matrix2d&, Eigen::Matrix2d&, Eigen::Matrix4d*) const { return false; }
  virtual bool evaluate_isochoric(const Eigen::Matrix3d&, Eigen::Matrix3d&, Eigen::Matrix<double, 9, 9>*) const {
    return false;
  }
  virtual double isochoric_energy(const Eigen::Matrix2d&) const { return std::numeric_limits<double>::infinity(); }
  virtual double isochoric_energy(const Eigen::Matrix3d&) const { return std::numeric_limits<double>::infinity(); }
  // U, U', U'' at J; false when J <= 0, not finite, or the law has no split.
  virtual bool volumetric(double J, VolumetricValues& v) const {
    static_cast<void>(J), static_cast<void>(v);
    return false;
  }
};

// What a law written as a template must provide (checked at compile time):
//   static constexpr std::string_view kName;             the registry name
//   static constexpr bool kRequiresPositiveJ;            det F <= 0 inadmissible?
//   static constexpr LawParameter kParameters[];         its case-file keys and ranges
//   static MaterialParameters small_strain_equivalent(p); the (E, nu) it linearises to
//   explicit Law(const MaterialParameters&);             (may throw MaterialParameterError)
// A law in (E, nu) derives from YoungPoissonParameters for the middle two.
//   template <int dim> double energy(const DimMatrix<dim>& F) const;
//   template <int dim> void stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const;
//   template <int dim> void tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const;
// energy/stress/tangent are only called with an admissible F (finite, and
// det F > 0 if kRequiresPositiveJ); the adapter does the checks.
template <class Law>
concept DimensionTemplatedLaw =
    requires(const Law& law, const MaterialParameters& mp, const DimMatrix<2>& F2, DimMatrix<2>& P2,
             TangentMatrix<2>& A2, const DimMatrix<3>& F3, DimMatrix<3>& P3, TangentMatrix<3>& A3) {
      { Law::kName } -> std::convertible_to<std::string_view>;
      { Law::kRequiresPositiveJ } -> std::convertible_to<bool>;
      { std::span<const LawParameter>(Law::kParameters) };
      { Law::small_strain_equivalent(mp) } -> std::same_as<MaterialParameters>;
      Law(mp);
      { law.template energy<2>(F2) } -> std::same_as<double>;
      { law.template energy<3>(F3) } -> std::same_as<double>;
      law.template stress<2>(F2, P2);
      law.template stress<3>(F3, P3);
      law.template tangent<2>(F2, A2);
      law.template tangent<3>(F3, A3);
    };

// A law that also declares its isochoric/volumetric split (optional; the
// adapter exposes it through HyperelasticLaw::evaluate_isochoric/volumetric):
//   template <int dim> double isochoric_energy(const DimMatrix<dim>& F) const;
//   template <int dim> void isochoric_stress(const DimMatrix<dim>& F, DimMatrix<dim>& P) const;
//   template <int dim> void isochoric_tangent(const DimMatrix<dim>& F, TangentMatrix<dim>& A) const;
//   VolumetricValues volumetric(double J) const;     U, U', U'' (J > 0 given)
template <class Law, int dim>
concept HasIsochoricPart = requires(const Law& law, const DimMatrix<dim>& F, DimMatrix<dim>& P, TangentMatrix<dim>& A) {
  { law.template isochoric_energy<dim>(F) } -> std::same_as<double>;
  law.template isochoric_stress<dim>(F, P);
  law.template isochoric_tangent<dim>(F, A);
};
template <class Law>
concept VolumetricSplitLaw = DimensionTemplatedLaw<Law> && HasIsochoricPart<Law, 2> && HasIsochoricPart<Law, 3> &&
                             requires(const Law& law, double J) {
                               { law.volumetric(J) } -> std::same_as<VolumetricValues>;
                             };

// Turns a DimensionTemplatedLaw into a HyperelasticLaw: admissibility checks
// and the no-garbage guarantee live here once, not in every law.
template <DimensionTemplatedLaw Law>
class HyperelasticAdapter final : public HyperelasticLaw {
 public:
  explicit HyperelasticAdapter(const Law& law) : law_(law) {}
  std::string name() const override { return std::string(Law::kName); }
  bool evaluate(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const override {
    return evaluate_dim<2>(F, P, A);
  }
  bool evaluate(const Eigen::Matrix3d& F, Eigen::Matrix3d& P,
                Eigen::Matrix<double, 9, 9>* A) const override {
    return evaluate_dim<3>(F, P, A);
  }
  double energy(const Eigen::Matrix2d& F) const override { return energy_dim<2>(F); }
  double energy(const Eigen::Matrix3d& F) const override { return energy_dim<3>(F); }
  bool has_volumetric_split() const override { return VolumetricSplitLaw<Law>; }
  bool evaluate_isochoric(const Eigen::Matrix2d& F, Eigen::Matrix2d& P, Eigen::Matrix4d* A) const override {
    return evaluate_dim<2, true>(F, P, A);
  }
  bool evaluate_isochoric(const Eigen::Matrix3d& F, Eigen::Matrix3d& P,
                          Eigen::Matrix<double, 9, 9>* A) const override {
    return evaluate_dim<3, true>(F, P, A);
  }
  double isochoric_energy(const Eigen::Matrix2d& F) const override { return energy_dim<2, true>(F); }
  double isochoric_energy(const Eigen::Matrix3d& F) const override { return energy_dim<3, true>(F); }
  bool volumetric(double J, VolumetricValues& v) const override {
    if constexpr (VolumetricSplitLaw<Law>) {
      if (!std::isfinite(J) || !(J > 0)) return false;
      const VolumetricValues local = law_.volumetric(J);
      if (!std::isfinite(local.U) || !std::isfinite(local.dU) || !std::isfinite(local.d2U)) return false;
      v = local;
      return true;
    } else {
      static_cast<void>(J), static_cast<void>(v);
      return false;
    }
  }
  const Law& law() const { return law_; }

 private:
  template <int dim>
  bool admissible(const DimMatrix<dim>& F) const {
    if (!F.allFinite()) return false;
    if constexpr (Law::kRequiresPositiveJ) return F.determinant() > 0;
    return true;
  }
  // isochoric: the split's W_iso instead of the law (false without a split).
  template <int dim, bool isochoric = false>
  bool evaluate_dim(const DimMatrix<dim>& F, DimMatrix<dim>& P, TangentMatrix<dim>* A) const {
    if constexpr (isochoric && !VolumetricSplitLaw<Law>) {
      return false;
    } else {
      if (!admissible<dim>(F)) return false;
      // Into locals first, so an overflow (huge but finite F) leaves P and A
      // untouched; fixed-size, on the stack.
      DimMatrix<dim> P_local;
      if constexpr (isochoric)
        law_.template isochoric_stress<dim>(F, P_local);
      else
        law_.template stress<dim>(F, P_local);
      if (!P_local.allFinite()) return false;
      if (A) {
        TangentMatrix<dim> A_local;
        if constexpr (isochoric)
          law_.template isochoric_tangent<dim>(F, A_local);
        else
          law_.template tangent<dim>(F, A_local);
        if (!A_local.allFinite()) return false;
        *A = A_local;
      }
      P = P_local;
      return true;
    }
  }
  template <int dim, bool isochoric = false>
  double energy_dim(const DimMatrix<dim>& F) const {
    if constexpr (isochoric && !VolumetricSplitLaw<Law>) {
      return std::numeric_limits<double>::infinity();
    } else {
      if (!admissible<dim>(F)) return std::numeric_limits<double>::infinity();
      if constexpr (isochoric)
        return law_.template isochoric_energy<dim>(F);
      else
        return law_.template energy<dim>(F);
    }
  }

  Law law_;
};

// Validates the parameters and wraps Law; the registry's one line per law.
template <DimensionTemplatedLaw Law>
std::unique_ptr<HyperelasticLaw> adapt(const MaterialParameters& parameters) {
  validate_parameters(Law::kParameters, parameters);
  return std::make_unique<HyperelasticAdapter<Law>>(Law(parameters));
}

// The law registered under `name`; throws MaterialError naming the unknown
// law and listing the known ones, or when the parameters are invalid.
std::unique_ptr<HyperelasticLaw> make_law(const std::string& name, const MaterialParameters& parameters);
// Registered names, in registration order.
std::vector<std::string> law_names();
// The parameters the law `name` declares (throws MaterialError if unknown).
std::span<const LawParameter> law_parameters(const std::string& name);
// The linear (E, nu) the law reduces to at small strain with these
// parameters (E and nu filled); the small-strain quantities of a case (the
// Hertz reference, the complementarity scale) use it.
MaterialParameters small_strain_equivalent(const std::string& name, const MaterialParameters& parameters);

// The small-strain material of a law, from the law itself: its first
// elasticity tensor at F = I is the tensor C of linear elasticity
// (Holzapfel, sec. 6.8).  For an isotropic law C_iJkL = lambda d_iJ d_kL +
// mu (d_ik d_JL + d_iL d_Jk), and the small-deformation path assembles with
// these lambda and mu (in `dim` dimensions: 2 is plane strain), so a law is
// written once for both paths.  Throws MaterialError when the law is not
// stress-free at F = I or its C is not isotropic (that path has no
// anisotropic kernel).
LinearElastic small_strain_material(const HyperelasticLaw& law, int dim);

// Gradient checker (after Ceres' GradientChecker): compares the law's P with
// central differences of its energy, and its A with central differences of
// its P, at F.  Errors are max-norm differences relative to the stiffness
// scale max(|A|_max, |P|_max) -- the stress of a unit strain -- so they mean
// the same at F = I (where P = 0) as far from it.  ok when both are at most
// `tolerance`; `report` is a one-line summary naming the worst entries.
// A non-admissible F (or one whose FD stencil leaves the admissible set)
// gives ok = false and infinite errors.
struct TangentCheck {
  double stress_error, tangent_error;
  bool ok;
  std::string report;
};
TangentCheck check_law(const HyperelasticLaw& law, const Eigen::Matrix2d& F, double tolerance);
TangentCheck check_law(const HyperelasticLaw& law, const Eigen::Matrix3d& F, double tolerance);

}  // namespace igac
