// SPDX-License-Identifier: BSD-3-Clause
#include "materials/hyperelastic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "materials/linear_elastic_law.hpp"
#include "materials/mooney_rivlin.hpp"
#include "materials/neo_hookean.hpp"
#include "materials/saint_venant_kirchhoff.hpp"

namespace igac {

// One place for the checks and messages: the small-strain material's constructor.
void MaterialParameters::validate() const { static_cast<void>(LinearElastic(E, nu)); }

double MaterialParameters::value(std::string_view key) const {
  if (key == "E") return E;
  if (key == "nu") return nu;
  const auto it = values.find(key);
  if (it == values.end())
    throw MaterialParameterError(std::string(key), fmt::format("{} is missing", key));
  return it->second;
}

void validate_parameters(std::span<const LawParameter> declared, const MaterialParameters& given) {
  for (const LawParameter& p : declared) {
    const double v = given.value(p.key);
    const bool above = p.lower_open ? v > p.lower : v >= p.lower;
    const bool below = p.upper_open ? v < p.upper : v <= p.upper;
    if (above && below && std::isfinite(v)) continue;
    const std::string key(p.key);
    if (p.lower == 0 && std::isinf(p.upper))
      throw MaterialParameterError(key, fmt::format("{} = {} must be {} ({})", key, v,
                                                    p.lower_open ? "positive" : "non-negative", p.meaning));
    throw MaterialParameterError(key, fmt::format("{} = {} must lie in {}{}, {}{} ({})", key, v, p.lower_open ? '(' : '[',
                                                  p.lower, p.upper, p.upper_open ? ')' : ']', p.meaning));
  }
}

namespace {

struct LawEntry {
  std::string_view name;
  std::unique_ptr<HyperelasticLaw> (*make)(const MaterialParameters&);
  std::span<const LawParameter> parameters;
  MaterialParameters (*small_strain)(const MaterialParameters&);
};

template <DimensionTemplatedLaw Law>
constexpr LawEntry entry() {
  return {Law::kName, &adapt<Law>, Law::kParameters, &Law::small_strain_equivalent};
}

// The registry: one line per law.
constexpr LawEntry kLaws[] = {
    entry<LinearElasticLaw>(),
    entry<NeoHookean>(),
    entry<SaintVenantKirchhoff>(),
    entry<MooneyRivlin>(),
};

}  // namespace

std::vector<std::string> law_names() {
  std::vector<std::string> names;
  for (const LawEntry& law : kLaws) names.emplace_back(law.name);
  return names;
}

namespace {
const LawEntry& find_law(const std::string& name) {
  for (const LawEntry& law : kLaws)
    if (law.name == name) return law;
  throw MaterialError(fmt::format("unknown material law '{}' (known laws: {})", name,
                                  fmt::join(law_names(), ", ")));
}
}  // namespace

std::unique_ptr<HyperelasticLaw> make_law(const std::string& name, const MaterialParameters& parameters) {
  return find_law(name).make(parameters);
}

std::span<const LawParameter> law_parameters(const std::string& name) { return find_law(name).parameters; }

MaterialParameters small_strain_equivalent(const std::string& name, const MaterialParameters& parameters) {
  const LawEntry& law = find_law(name);
  validate_parameters(law.parameters, parameters);
  return law.small_strain(parameters);
}

namespace {

// Central differences: truncation ~ h^2 |third derivative| / 6, cancellation
// ~ eps |value| / h; h = eps^(1/3) (~6e-6) balances the two, scaled with F
// so that a stretched F is perturbed by the same relative amount.
double fd_step(double F_scale) { return std::cbrt(std::numeric_limits<double>::epsilon()) * std::max(1.0, F_scale); }

// Index of the largest |entry| of a matrix, as (row, col).
template <class M>
std::pair<int, int> argmax_abs(const M& m) {
  Eigen::Index r = 0, c = 0;
  m.cwiseAbs().maxCoeff(&r, &c);
  return {static_cast<int>(r), static_cast<int>(c)};
}

template <int dim>
TangentCheck check_law_dim(const HyperelasticLaw& law, const DimMatrix<dim>& F, double tolerance) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const std::string what = fmt::format("{} ({}D)", law.name(), dim);
  DimMatrix<dim> P;
  TangentMatrix<dim> A;
  if (!law.evaluate(F, P, &A))
    return {kInf, kInf, false, fmt::format("{}: F is inadmissible (det F = {:.3g}), nothing to check", what,
                                           F.determinant())};

  const double h = fd_step(F.cwiseAbs().maxCoeff());
  DimMatrix<dim> P_fd;
  TangentMatrix<dim> A_fd;
  for (int k = 0; k < dim; ++k)
    for (int L = 0; L < dim; ++L) {
      DimMatrix<dim> Fp = F, Fm = F;
      Fp(k, L) += h;
      Fm(k, L) -= h;
      DimMatrix<dim> Pp, Pm;
      const double Wp = law.energy(Fp), Wm = law.energy(Fm);
      if (!std::isfinite(Wp) || !std::isfinite(Wm) || !law.evaluate(Fp, Pp, nullptr) ||
          !law.evaluate(Fm, Pm, nullptr))
        return {kInf, kInf, false,
                fmt::format("{}: the difference stencil (h = {:.2g}) leaves the admissible set at F({},{})", what,
                            h, k, L)};
      P_fd(k, L) = (Wp - Wm) / (2 * h);
      for (int i = 0; i < dim; ++i)
        for (int J = 0; J < dim; ++J) A_fd(i * dim + J, k * dim + L) = (Pp(i, J) - Pm(i, J)) / (2 * h);
    }

  // Stiffness scale; the floor only matters for a law with no stiffness.
  const double A_scale = std::max({A.cwiseAbs().maxCoeff(), A_fd.cwiseAbs().maxCoeff(),
                                   std::numeric_limits<double>::min()});
  const double P_scale = std::max({A_scale, P.cwiseAbs().maxCoeff(), P_fd.cwiseAbs().maxCoeff()});
  const DimMatrix<dim> dP = P - P_fd;
  const TangentMatrix<dim> dA = A - A_fd;
  const auto [pi, pj] = argmax_abs(dP);
  const auto [ai, aj] = argmax_abs(dA);
  TangentCheck c;
  c.stress_error = dP.cwiseAbs().maxCoeff() / P_scale;
  c.tangent_error = dA.cwiseAbs().maxCoeff() / A_scale;
  c.ok = c.stress_error <= tolerance && c.tangent_error <= tolerance;
  c.report = fmt::format(
      "{}: stress error {:.2e} at P({},{}) [law {:.6g}, fd {:.6g}], tangent error {:.2e} at "
      "dP({},{})/dF({},{}) [law {:.6g}, fd {:.6g}]; tolerance {:.1e}: {}",
      what, c.stress_error, pi, pj, P(pi, pj), P_fd(pi, pj), c.tangent_error, ai / dim, ai % dim, aj / dim, aj % dim,
      A(ai, aj), A_fd(ai, aj), tolerance, c.ok ? "ok" : "FAILED");
  return c;
}

}  // namespace

TangentCheck check_law(const HyperelasticLaw& law, const Eigen::Matrix2d& F, double tolerance) {
  return check_law_dim<2>(law, F, tolerance);
}
TangentCheck check_law(const HyperelasticLaw& law, const Eigen::Matrix3d& F, double tolerance) {
  return check_law_dim<3>(law, F, tolerance);
}

namespace {

template <int dim>
LinearElastic small_strain_material_dim(const HyperelasticLaw& law) {
  const DimMatrix<dim> I = DimMatrix<dim>::Identity();
  DimMatrix<dim> P;
  TangentMatrix<dim> A;
  if (!law.evaluate(I, P, &A)) throw MaterialError(law.name() + ": the law cannot be evaluated at F = I");
  const double lambda = A(0, dim + 1), mu = A(1, 1);  // A_0011 and A_0101
  const double scale = std::max(A.cwiseAbs().maxCoeff(), 1e-300);
  if (P.cwiseAbs().maxCoeff() > 1e-10 * scale)
    throw MaterialError(law.name() + ": the reference configuration is not stress-free (P(I) != 0)");
  double worst = 0;
  for (int i = 0; i < dim; ++i)
    for (int J = 0; J < dim; ++J)
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L) {
          const double c = lambda * (i == J) * (k == L) + mu * ((i == k) * (J == L) + (i == L) * (J == k));
          worst = std::max(worst, std::abs(A(i * dim + J, k * dim + L) - c));
        }
  if (worst > 1e-8 * scale)
    throw MaterialError(law.name() + ": its elasticity at F = I is not isotropic; the small-deformation path "
                                     "assembles isotropic laws only");
  // E and nu of (lambda, mu): E = mu (3 lambda + 2 mu) / (lambda + mu), nu = lambda / (2 (lambda + mu)).
  return LinearElastic(mu * (3 * lambda + 2 * mu) / (lambda + mu), lambda / (2 * (lambda + mu)));
}

}  // namespace

LinearElastic small_strain_material(const HyperelasticLaw& law, int dim) {
  return dim == 2 ? small_strain_material_dim<2>(law) : small_strain_material_dim<3>(law);
}

}  // namespace igac
