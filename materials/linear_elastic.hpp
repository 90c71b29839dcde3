// SPDX-License-Identifier: BSD-3-Clause
// Isotropic linear elasticity (small strain): sigma = lambda tr(eps) I + 2 mu eps,
// with lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).  In 2D the
// model is plane strain (eps_zz = 0), which keeps these same lambda and mu.
// Knows nothing of splines: the assembler asks it for lambda and mu only.
#pragma once

#include <stdexcept>
#include <string>

namespace igac {

// Invalid material data; the message names the parameter and the reason.
class MaterialError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class LinearElastic {
 public:
  // Throws MaterialError unless E > 0 and -1 < nu < 0.5.
  LinearElastic(double youngs_modulus, double poisson_ratio);
  double E() const { return E_; }
  double nu() const { return nu_; }
  double lambda() const { return E_ * nu_ / ((1 + nu_) * (1 - 2 * nu_)); }
  double mu() const { return E_ / (2 * (1 + nu_)); }

 private:
  double E_, nu_;
};

}  // namespace igac
