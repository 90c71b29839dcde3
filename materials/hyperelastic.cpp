#include "materials/hyperelastic.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "materials/linear_elastic_law.hpp"
#include "materials/neo_hookean.hpp"
#include "materials/saint_venant_kirchhoff.hpp"

namespace igac {

// One place for the checks and messages: the small-strain material's constructor.
void MaterialParameters::validate() const { static_cast<void>(LinearElastic(E, nu)); }

namespace {

struct LawEntry {
  std::string_view name;
  std::unique_ptr<HyperelasticLaw> (*make)(const MaterialParameters&);
};

template <DimensionTemplatedLaw Law>
constexpr LawEntry entry() {
  return {Law::kName, &adapt<Law>};
}

// The registry: one line per law.
constexpr LawEntry kLaws[] = {
    entry<LinearElasticLaw>(),
    entry<NeoHookean>(),
    entry<SaintVenantKirchhoff>(),
};

}  // namespace

std::vector<std::string> law_names() {
  std::vector<std::string> names;
  for (const LawEntry& law : kLaws) names.emplace_back(law.name);
  return names;
}

std::unique_ptr<HyperelasticLaw> make_law(const std::string& name, const MaterialParameters& parameters) {
  for (const LawEntry& law : kLaws)
    if (law.name == name) return law.make(parameters);
  throw MaterialError(fmt::format("unknown material law '{}' (known laws: {})", name,
                                  fmt::join(law_names(), ", ")));
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

}  // namespace igac
