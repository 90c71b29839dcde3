// SPDX-License-Identifier: BSD-3-Clause
// Knot vectors and univariate B-spline bases (Piegl & Tiller, The NURBS Book,
// ch. 2: A2.1 FindSpan, A2.3 DersBasisFuns).
//
// A KnotVector owns a non-decreasing sequence of knots with open ends (first
// and last knot repeated degree+1 times) on any range [a, b].  Construction
// validates; every function below assumes a valid vector.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace igac {

// Error in user-supplied spline data; the message names what is wrong.
class SplineError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class KnotVector {
 public:
  KnotVector() = default;
  // Throws SplineError naming the reason when the knots are not a valid
  // open knot vector of this degree (degree < 1 is allowed only as 0 for
  // multiplier spaces; decreasing knots; wrong end multiplicity; interior
  // multiplicity above degree+1... see validate()).
  KnotVector(int degree, std::vector<double> knots);

  // n_elements equal spans on [0, 1], open ends.
  static KnotVector uniform(int degree, int n_elements);
  // n_elements spans of which round(span_fraction * n_elements) share the
  // range_fraction of [0, 1] next to the end `at_start ? 0 : 1`, uniformly
  // (paper, section 4.1: 80 % of the spans in 10 % of the range).  The other
  // spans are uniform too (CoarseSpans::uniform, the paper's: the span size
  // jumps by a factor of 10-60 where the fine range ends), or grow
  // geometrically from the fine span size to fill the rest (geometric: one
  // ratio r > 1, the first coarse span r times a fine one; uniform when the
  // fine size is already the larger).
  enum class CoarseSpans { uniform, geometric };
  static KnotVector graded(int degree, int n_elements, double span_fraction,
                           double range_fraction, bool at_start, CoarseSpans coarse = CoarseSpans::uniform);

  int degree() const { return degree_; }
  const std::vector<double>& knots() const { return knots_; }
  int size() const { return static_cast<int>(knots_.size()); }
  double operator[](int i) const { return knots_[i]; }
  double first() const { return knots_.front(); }
  double last() const { return knots_.back(); }

  int num_basis() const { return size() - degree_ - 1; }
  // Distinct knots (breakpoints) and their multiplicities.
  std::vector<double> breakpoints() const;
  std::vector<int> multiplicities() const;
  int num_elements() const { return static_cast<int>(breakpoints().size()) - 1; }
  // Index of the knot span [t_s, t_{s+1}) holding u (last span for u = last).
  int find_span(double u) const;
  // Span index of element e (0-based over nonzero spans).
  std::vector<int> element_spans() const;

  // Values and derivatives up to n_derivs of the degree+1 basis functions
  // nonzero on span s at u: out[k][j] = d^k/du^k N_{s-degree+j}(u).
  void basis_derivatives(int span, double u, int n_derivs,
                         std::vector<std::vector<double>>& out) const;

  // Values only of the degree+1 basis functions nonzero on span s at u:
  // out[j] = N_{s-degree+j}(u) (Piegl & Tiller A2.2; allocates nothing).
  void basis_values(int span, double u, double* out) const;

  // Greville abscissae (knot averages), one per basis function.
  std::vector<double> greville() const;

  // Knot vector with every breakpoint's multiplicity raised by `by`
  // (degree raised by `by`): the space of degree elevation.
  KnotVector elevated(int by) const;
  // Knot vector with each span split into `parts` equal parts.
  KnotVector subdivided(int parts) const;
  // The knots to insert into *this to obtain `finer` (must contain *this).
  std::vector<double> knots_missing_from(const KnotVector& finer) const;
  // This knot vector with every knot of `kept` added (at least its
  // multiplicity there), for refining a patch whose knots are `kept`: a
  // breakpoint of this one within 1e-10 of the range from one of `kept`'s
  // takes `kept`'s value (a file's knot written with 12 digits is the mesh's
  // breakpoint, not a second one beside it), so `kept` is contained exactly
  // and kept.knots_missing_from(result) succeeds.  Same degree and range.
  KnotVector united_with(const KnotVector& kept) const;

 private:
  void validate() const;
  int degree_ = 0;
  std::vector<double> knots_;
};

}  // namespace igac
