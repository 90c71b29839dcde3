// Gauss-Legendre quadrature on [0, 1] (points by Newton iteration on the
// Legendre polynomial, Golub & Welsch give the same to round-off).  n points
// integrate polynomials of degree 2n-1 exactly; igac uses p+1 per direction.
#pragma once

#include <vector>

namespace igac {

struct GaussRule {
  std::vector<double> points;   // in (0, 1)
  std::vector<double> weights;  // sum to 1
};

GaussRule gauss_legendre(int n);

}  // namespace igac
