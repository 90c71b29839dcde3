// SPDX-License-Identifier: BSD-3-Clause
// Splines, mathematics first: the identities that B-spline and NURBS bases
// satisfy exactly (partition of unity, non-negativity, derivatives of the
// basis against central differences), the validation of knot vectors, the
// graded knot vectors of the paper (section 4.1) and their nesting, and the
// exactness of refinement (knot insertion and degree elevation never change
// the geometry nor a field carried with it; Piegl & Tiller ch. 5).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "engine/geometry/shapes.hpp"
#include "engine/spline/knot_vector.hpp"
#include "engine/spline/nurbs_patch.hpp"
#include "engine/spline/refinement.hpp"

namespace {

using igac::Face;
using igac::KnotVector;
using igac::NurbsPatch;
using igac::SplineError;

// Sums of at most (p+1)^3 basis values in [0, 1]: a few ulps each.
constexpr double kRoundoff = 1e-13;
// Central difference step in the parameter (spans are >= ~0.05 long below,
// so u +- h stays inside one span when u keeps 10 h from every knot).
constexpr double kFdStep = 1e-6;
// Central differences err by h^2/6 |f'''| (<~ 1e-12 * 1e5 for the bases
// below, whose third derivatives reach ~(p / span)^3) plus eps/h ~ 1e-10:
// 1e-6 of the derivative's scale leaves a margin of ~100.
constexpr double kFdRelTolerance = 1e-6;
// Refinement is exact in exact arithmetic; the brief asks for agreement to
// 1e-12 (geometry of size ~1), four orders above double round-off, which
// leaves room for the collocation solve of degree elevation.
constexpr double kRefinementExact = 1e-12;
// Knots of two graded vectors built along different paths (subdivision vs
// direct formula): a few ulps of the unit range.
constexpr double kKnotRoundoff = 1e-15;

// A valid open knot vector of degree p on [a, b] with n_el spans of random
// lengths (ratio at most 3) and random interior multiplicities 1..max_mult.
KnotVector random_knot_vector(std::mt19937& rng, int p, int n_el, double a, double b, int max_mult) {
  std::uniform_real_distribution<double> len(1.0, 3.0);
  std::uniform_int_distribution<int> mult(1, std::max(1, max_mult));
  std::vector<double> spans(n_el);
  double total = 0;
  for (double& s : spans) total += (s = len(rng));
  std::vector<double> k(p + 1, a);
  double x = a;
  for (int e = 0; e + 1 < n_el; ++e) {
    x += (b - a) * spans[e] / total;
    k.insert(k.end(), mult(rng), x);
  }
  k.insert(k.end(), p + 1, b);
  return KnotVector(p, k);
}

// A random point of [a, b] at least `gap` away from every knot.
double point_away_from_knots(std::mt19937& rng, const KnotVector& kv, double gap) {
  std::uniform_real_distribution<double> U(kv.first(), kv.last());
  for (;;) {
    const double u = U(rng);
    bool ok = true;
    for (double t : kv.knots()) ok = ok && std::abs(u - t) > gap;
    if (ok) return u;
  }
}

// A NURBS patch with random knots, points and weights (weights in [0.3, 3]).
NurbsPatch random_patch(std::mt19937& rng, int param_dim, int space_dim) {
  std::vector<KnotVector> kv;
  int n = 1;
  for (int d = 0; d < param_dim; ++d) {
    kv.push_back(random_knot_vector(rng, 2 + d % 2, 3, 0.0, 1.0, 2));
    n *= kv.back().num_basis();
  }
  std::uniform_real_distribution<double> coord(-1.0, 1.0), weight(0.3, 3.0);
  Eigen::MatrixXd P(n, space_dim);
  Eigen::VectorXd w(n);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < space_dim; ++c) P(i, c) = coord(rng);
    w[i] = weight(rng);
  }
  return NurbsPatch(kv, P, w);
}

// ---------------------------------------------------------------- B-splines

TEST(SplineBasis, PartitionOfUnityAndNonNegativity) {
  std::mt19937 rng(20240501);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  for (int p = 0; p <= 6; ++p)
    for (int trial = 0; trial < 4; ++trial) {
      const double a = -1.7 + trial, b = a + 0.5 + 2.0 * trial;
      const KnotVector kv = random_knot_vector(rng, p, 2 + 3 * trial, a, b, std::max(p, 1));
      std::vector<std::vector<double>> N;
      for (int q = 0; q < 200; ++q) {
        const double u = q == 0 ? a : q == 1 ? b : a + (b - a) * U01(rng);
        const int s = kv.find_span(u);
        ASSERT_LE(kv[s], u);
        if (u < b) {
          ASSERT_LT(u, kv[s + 1]) << "find_span(" << u << ") = " << s;
        }
        kv.basis_derivatives(s, u, std::min(p, 3), N);
        double sum = 0;
        // Exactly non-negative: A2.2 forms only sums, products and
        // quotients of non-negative numbers.
        for (double v : N[0]) {
          EXPECT_GE(v, 0.0) << "p = " << p << ", u = " << u;
          sum += v;
        }
        EXPECT_NEAR(sum, 1.0, kRoundoff) << "p = " << p << ", u = " << u;
        // Derivatives of a partition of unity sum to zero.
        for (size_t k = 1; k < N.size(); ++k) {
          double dsum = 0, scale = 1;
          for (double v : N[k]) {
            dsum += v;
            scale = std::max(scale, std::abs(v));
          }
          EXPECT_NEAR(dsum, 0.0, kRoundoff * scale) << "derivative " << k << ", p = " << p;
        }
      }
      // Open ends interpolate: N_0(a) = 1 and N_{n-1}(b) = 1.
      kv.basis_derivatives(kv.find_span(a), a, 0, N);
      EXPECT_EQ(kv.find_span(a) - p, 0);
      EXPECT_NEAR(N[0][0], 1.0, kRoundoff);
      kv.basis_derivatives(kv.find_span(b), b, 0, N);
      EXPECT_EQ(kv.find_span(b), kv.num_basis() - 1);
      EXPECT_NEAR(N[0][p], 1.0, kRoundoff);
    }
}

TEST(SplineBasis, DerivativesMatchCentralDifferences) {
  std::mt19937 rng(7);
  for (int p = 1; p <= 5; ++p)
    for (int trial = 0; trial < 3; ++trial) {
      const KnotVector kv = random_knot_vector(rng, p, 4, 0.0, 1.0, 1);
      std::vector<std::vector<double>> N, Np, Nm;
      for (int q = 0; q < 50; ++q) {
        const double u = point_away_from_knots(rng, kv, 10 * kFdStep);
        const int s = kv.find_span(u);
        kv.basis_derivatives(s, u, 2, N);
        kv.basis_derivatives(s, u + kFdStep, 2, Np);
        kv.basis_derivatives(s, u - kFdStep, 2, Nm);
        for (int k = 1; k <= std::min(p, 2); ++k) {
          double scale = 1;
          for (double v : N[k]) scale = std::max(scale, std::abs(v));
          for (int j = 0; j <= p; ++j) {
            const double fd = (Np[k - 1][j] - Nm[k - 1][j]) / (2 * kFdStep);
            EXPECT_NEAR(N[k][j], fd, kFdRelTolerance * scale)
                << "d^" << k << " N_" << j << ", p = " << p << ", u = " << u;
          }
        }
        if (p == 1) {
          EXPECT_EQ(N[2][0], 0.0) << "second derivative of a piecewise linear";
        }
      }
    }
}

TEST(SplineNurbsBasis, PartitionOfUnityNonNegativityAndDerivatives) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  for (int pd = 1; pd <= 3; ++pd) {
    const NurbsPatch patch = random_patch(rng, pd, 3);
    std::vector<int> idx, idx_p, idx_m;
    Eigen::VectorXd R, Rp, Rm;
    Eigen::MatrixXd dR, dRp, dRm;
    for (int q = 0; q < 100; ++q) {
      Eigen::VectorXd xi(pd);
      for (int d = 0; d < pd; ++d) xi[d] = point_away_from_knots(rng, patch.knots(d), 10 * kFdStep);
      patch.rational_basis(xi, idx, R, dR);
      EXPECT_NEAR(R.sum(), 1.0, kRoundoff);
      EXPECT_GE(R.minCoeff(), 0.0);
      const double scale = std::max(1.0, dR.cwiseAbs().maxCoeff());
      for (int d = 0; d < pd; ++d) {
        EXPECT_NEAR(dR.col(d).sum(), 0.0, kRoundoff * scale);
        Eigen::VectorXd h = Eigen::VectorXd::Zero(pd);
        h[d] = kFdStep;
        patch.rational_basis(xi + h, idx_p, Rp, dRp);
        patch.rational_basis(xi - h, idx_m, Rm, dRm);
        ASSERT_EQ(idx_p, idx);
        ASSERT_EQ(idx_m, idx);
        const Eigen::VectorXd fd = (Rp - Rm) / (2 * kFdStep);
        EXPECT_LE((fd - dR.col(d)).cwiseAbs().maxCoeff(), kFdRelTolerance * scale) << "direction " << d;
        // The Jacobian of the map is the same derivative applied to the points.
        const Eigen::VectorXd dX = (patch.point(xi + h) - patch.point(xi - h)) / (2 * kFdStep);
        const Eigen::MatrixXd J = patch.jacobian(xi);
        EXPECT_LE((dX - J.col(d)).norm(), kFdRelTolerance * std::max(1.0, J.norm()));
      }
    }
  }
}

// -------------------------------------------------------- knot validation

// Runs f, expects a SplineError whose message contains every fragment.
template <class F>
void expect_spline_error(F&& f, const std::vector<std::string>& fragments) {
  try {
    f();
    ADD_FAILURE() << "no SplineError thrown";
  } catch (const SplineError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    for (const auto& frag : fragments) EXPECT_NE(msg.find(frag), std::string::npos) << "'" << frag << "' in: " << msg;
  }
}

TEST(SplineKnotValidation, DecreasingKnots) {
  expect_spline_error([] { KnotVector(2, {0, 0, 0, 0.6, 0.4, 1, 1, 1}); }, {"decrease", "position 4", "0.4", "0.6"});
}

TEST(SplineKnotValidation, WrongEndMultiplicity) {
  // too few repetitions of the first knot
  expect_spline_error([] { KnotVector(2, {0, 0, 0.5, 1, 1, 1}); }, {"not open", "3 times"});
  // too few repetitions of the last knot
  expect_spline_error([] { KnotVector(2, {0, 0, 0, 0.5, 1, 1}); }, {"not open", "3 times"});
  // too many repetitions of an end knot
  expect_spline_error([] { KnotVector(1, {0, 0, 0, 1, 1}); }, {"end knot", "more than 2 times"});
}

TEST(SplineKnotValidation, NegativeDegree) {
  expect_spline_error([] { KnotVector(-1, {0, 1}); }, {"degree -1", "negative"});
}

TEST(SplineKnotValidation, TooFewKnots) {
  expect_spline_error([] { KnotVector(3, {0, 0, 0, 1, 1, 1}); }, {"at least 8 knots", "got 6"});
  expect_spline_error([] { KnotVector(1, {}); }, {"at least 4 knots", "got 0"});
}

TEST(SplineKnotValidation, OtherDefects) {
  expect_spline_error([] { KnotVector(1, {0, 0, std::nan(""), 1, 1}); }, {"knot 2", "not finite"});
  expect_spline_error([] { KnotVector(1, {1, 1, 1, 1}); }, {"zero length"});
  expect_spline_error([] { KnotVector(1, {0, 0, 0.5, 0.5, 0.5, 1, 1}); }, {"interior knot 0.5", "multiplicity 3"});
  // valid vectors do not throw, including a C^-1 interior knot (multiplicity p+1)
  EXPECT_NO_THROW(KnotVector(1, {0, 0, 0.5, 0.5, 1, 1}));
  EXPECT_NO_THROW(KnotVector(0, {0, 0.5, 1}));
}

// ------------------------------------------------------------- grading

struct GradedCase {
  int degree, n_elements;
  double span_fraction, range_fraction;
  bool at_start;
};

TEST(SplineGradedKnots, FractionOfSpansInFractionOfRangeAndNesting) {
  // Paper 4.1: 80 % of the spans in the 10 % next to the contact point
  // (hertz2d.toml: 64 elements, toward the start); 3D: 75 %.
  const std::vector<GradedCase> cases{
      {2, 64, 0.8, 0.1, true}, {2, 64, 0.8, 0.1, false}, {3, 20, 0.75, 0.1, true},
      {3, 20, 0.75, 0.1, false}, {2, 10, 0.5, 0.25, true}, {4, 40, 0.8, 0.05, false}};
  for (const auto& c : cases) {
    SCOPED_TRACE(::testing::Message() << "p " << c.degree << ", n " << c.n_elements << ", spans "
                                      << c.span_fraction << ", range " << c.range_fraction
                                      << (c.at_start ? ", at start" : ", at end"));
    const KnotVector kv =
        KnotVector::graded(c.degree, c.n_elements, c.span_fraction, c.range_fraction, c.at_start);
    EXPECT_EQ(kv.degree(), c.degree);
    EXPECT_EQ(kv.num_elements(), c.n_elements);
    EXPECT_EQ(kv.first(), 0.0);
    EXPECT_EQ(kv.last(), 1.0);
    const auto b = kv.breakpoints();
    const double lo = c.at_start ? 0.0 : 1.0 - c.range_fraction;
    const double hi = c.at_start ? c.range_fraction : 1.0;
    int inside = 0;
    for (size_t e = 0; e + 1 < b.size(); ++e)
      if (b[e] >= lo - kKnotRoundoff && b[e + 1] <= hi + kKnotRoundoff) ++inside;
    EXPECT_EQ(inside, std::lround(c.span_fraction * c.n_elements));
    // The graded zone ends exactly at the requested fraction of the range.
    EXPECT_TRUE(std::any_of(b.begin(), b.end(), [&](double x) {
      return std::abs(x - (c.at_start ? hi : lo)) <= kKnotRoundoff;
    }));
    // Each part is uniform.
    const double fine = c.range_fraction / inside, coarse = (1 - c.range_fraction) / (c.n_elements - inside);
    for (size_t e = 0; e + 1 < b.size(); ++e) {
      const bool in = b[e] >= lo - kKnotRoundoff && b[e + 1] <= hi + kKnotRoundoff;
      EXPECT_NEAR(b[e + 1] - b[e], in ? fine : coarse, kKnotRoundoff) << "span " << e;
    }
    // Nesting: halving every span gives the graded vector with twice the
    // elements (what `igac study` relies on).  round(2 x) = 2 round(x) for
    // all the fractions above.
    const KnotVector twice =
        KnotVector::graded(c.degree, 2 * c.n_elements, c.span_fraction, c.range_fraction, c.at_start);
    const KnotVector halved = kv.subdivided(2);
    ASSERT_EQ(halved.size(), twice.size());
    for (int i = 0; i < twice.size(); ++i) EXPECT_NEAR(halved[i], twice[i], kKnotRoundoff) << "knot " << i;
    // and the coarse vector is contained in the fine one
    EXPECT_EQ(kv.knots_missing_from(twice).size(), size_t(c.n_elements));
  }
}

// coarse = "geometric": the fine part as before, then spans that grow by one
// ratio r > 1 from the fine size (the first coarse span is r times a fine
// one) and end exactly at the other end; and uniform again where the fine
// spans are already the larger.
TEST(SplineGradedKnots, GeometricCoarseSpansGrowByOneRatio) {
  for (const bool at_start : {true, false}) {
    SCOPED_TRACE(at_start ? "at start" : "at end");
    const KnotVector kv = KnotVector::graded(2, 16, 0.75, 0.05, at_start, KnotVector::CoarseSpans::geometric);
    EXPECT_EQ(kv.num_elements(), 16);
    auto b = kv.breakpoints();
    std::vector<double> h;
    for (size_t e = 0; e + 1 < b.size(); ++e) h.push_back(b[e + 1] - b[e]);
    if (!at_start) std::reverse(h.begin(), h.end());  // from the graded end
    ASSERT_EQ(h.size(), 16u);
    const double fine = 0.05 / 12;
    for (int e = 0; e < 12; ++e) EXPECT_NEAR(h[e], fine, kKnotRoundoff) << "fine span " << e;
    const double r = h[12] / fine;
    EXPECT_GT(r, 1.5);
    for (int e = 13; e < 16; ++e) EXPECT_NEAR(h[e] / h[e - 1], r, 1e-9) << "coarse span " << e;
    EXPECT_EQ(kv.first(), 0.0);
    EXPECT_EQ(kv.last(), 1.0);
  }
  // 2 fine spans of 0.4 and 8 coarse ones in 0.2: no growth, uniform coarse spans.
  const KnotVector flat = KnotVector::graded(2, 10, 0.2, 0.8, true, KnotVector::CoarseSpans::geometric);
  const auto b = flat.breakpoints();
  for (size_t e = 2; e + 1 < b.size(); ++e) EXPECT_NEAR(b[e + 1] - b[e], 0.2 / 8, kKnotRoundoff);
}

TEST(SplineGradedKnots, RejectsBadFractions) {
  expect_spline_error([] { KnotVector::graded(2, 10, 1.0, 0.1, true); }, {"span fraction", "(0, 1)"});
  expect_spline_error([] { KnotVector::graded(2, 10, 0.8, 0.0, true); }, {"range fraction", "(0, 1)"});
  expect_spline_error([] { KnotVector::graded(2, 1, 0.8, 0.1, true); }, {"at least two elements"});
}

// ------------------------------------------------------ refinement exactness

// Evaluates patch and fields at the given points.
struct Samples {
  std::vector<Eigen::VectorXd> X, F;
  std::vector<Eigen::MatrixXd> J;
};
Samples sample(const NurbsPatch& p, const Eigen::MatrixXd& field, const std::vector<Eigen::VectorXd>& xis) {
  Samples s;
  for (const auto& xi : xis) {
    s.X.push_back(p.point(xi));
    s.J.push_back(p.jacobian(xi));
    s.F.push_back(p.field(field, xi));
  }
  return s;
}

std::vector<Eigen::VectorXd> random_points(std::mt19937& rng, int dim, int n) {
  std::uniform_real_distribution<double> U01(0.0, 1.0);
  std::vector<Eigen::VectorXd> xs;
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd xi(dim);
    for (int d = 0; d < dim; ++d) xi[d] = U01(rng);
    xs.push_back(xi);
  }
  // corners and an edge point too
  xs.push_back(Eigen::VectorXd::Zero(dim));
  xs.push_back(Eigen::VectorXd::Ones(dim));
  Eigen::VectorXd e = Eigen::VectorXd::Constant(dim, 0.5);
  e[0] = 1.0;
  xs.push_back(e);
  return xs;
}

// Compares the samples of a refined patch and field with the originals.
void expect_same(const Samples& before, const NurbsPatch& p, const Eigen::MatrixXd& field,
                 const std::vector<Eigen::VectorXd>& xis, const std::string& what) {
  SCOPED_TRACE(what);
  const Samples after = sample(p, field, xis);
  double e_x = 0, e_f = 0, e_j = 0, s_j = 1;
  for (size_t i = 0; i < xis.size(); ++i) {
    e_x = std::max(e_x, (after.X[i] - before.X[i]).cwiseAbs().maxCoeff());
    e_f = std::max(e_f, (after.F[i] - before.F[i]).cwiseAbs().maxCoeff());
    e_j = std::max(e_j, (after.J[i] - before.J[i]).cwiseAbs().maxCoeff());
    s_j = std::max(s_j, before.J[i].cwiseAbs().maxCoeff());
  }
  EXPECT_LE(e_x, kRefinementExact) << "geometry changed";
  EXPECT_LE(e_f, kRefinementExact) << "field changed";
  // Derivatives: the same exact identity, relative to their size.
  EXPECT_LE(e_j, kRefinementExact * s_j) << "Jacobian changed";
}

// Knot insertion, elevation by 1 and 2, and both mixed, in every direction,
// carrying a random field with the patch.
void check_refinement_exact(const NurbsPatch& patch, std::mt19937& rng) {
  const int pd = patch.param_dim();
  std::uniform_real_distribution<double> coef(-1.0, 1.0);
  Eigen::MatrixXd field(patch.num_control_points(), 3);
  for (int i = 0; i < field.size(); ++i) field.data()[i] = coef(rng);
  const auto xis = random_points(rng, pd, 60);
  const Samples before = sample(patch, field, xis);

  for (int d = 0; d < pd; ++d) {
    // new knots: random, one repeated, one on an existing breakpoint
    const auto b = patch.knots(d).breakpoints();
    std::vector<double> X{0.13, 0.41, 0.41, 0.77, 0.9};
    for (size_t j = 1; j + 1 < b.size(); ++j) X.push_back(b[j]);
    std::sort(X.begin(), X.end());
    const auto h = igac::insert_knots(patch, d, X, {field});
    EXPECT_EQ(h.patch.num_basis(d), patch.num_basis(d) + int(X.size()));
    EXPECT_EQ(h.patch.degree(d), patch.degree(d));
    ASSERT_EQ(h.fields.size(), 1u);
    expect_same(before, h.patch, h.fields[0], xis, "insert knots in direction " + std::to_string(d));

    for (int by = 1; by <= 2; ++by) {
      const auto e = igac::elevate_degree(patch, d, by, {field});
      EXPECT_EQ(e.patch.degree(d), patch.degree(d) + by);
      expect_same(before, e.patch, e.fields[0], xis,
                  "elevate by " + std::to_string(by) + " in direction " + std::to_string(d));
    }
  }
  // Mixed: insert, elevate (interior knots now present), insert again on a
  // knot already present, elevate by 2; every direction.  Multiplicities stay
  // <= p (C^0 at worst; see ElevationAcrossDiscontinuousKnot for p+1).
  igac::RefinedPatch r{patch, {field}};
  for (int d = 0; d < pd; ++d) {
    r = igac::insert_knots(r.patch, d, {0.25, 0.5, 0.6}, r.fields);
    r = igac::elevate_degree(r.patch, d, 1, r.fields);
    r = igac::insert_knots(r.patch, d, {0.1, 0.25, 0.8}, r.fields);
    r = igac::elevate_degree(r.patch, d, 2, r.fields);
  }
  expect_same(before, r.patch, r.fields[0], xis, "insertion and elevation combined");
  // The same through the conveniences that build_model uses.
  NurbsPatch c = igac::elevate_to(patch, patch.degree(0) + 1);
  c = igac::subdivide(c, 3);
  c = igac::refine_to(c, pd - 1, c.knots(pd - 1).subdivided(2));
  // Geometry only (refine_to carries no field).
  const Samples g = sample(c, Eigen::MatrixXd::Zero(c.num_control_points(), 3), xis);
  double e_x = 0;
  for (size_t i = 0; i < xis.size(); ++i) e_x = std::max(e_x, (g.X[i] - before.X[i]).cwiseAbs().maxCoeff());
  EXPECT_LE(e_x, kRefinementExact) << "elevate_to + subdivide + refine_to changed the geometry";
}

TEST(SplineRefinement, QuarterDiscIsUnchangedByRefinement) {
  std::mt19937 rng(3);
  check_refinement_exact(igac::quarter_disc(1.0).patch, rng);
}

TEST(SplineRefinement, RationalBoxIsUnchangedByRefinement) {
  std::mt19937 rng(5);
  // A box made degree 2 with 4 control points per direction, then given
  // random weights and interior points: a genuinely rational 3D patch.
  NurbsPatch p = igac::subdivide(igac::elevate_to(igac::box(1.0, 0.8, 0.6).patch, 2), 2);
  std::uniform_real_distribution<double> weight(0.5, 2.0), shift(-0.05, 0.05);
  Eigen::MatrixXd P = p.points();
  Eigen::VectorXd w = p.weights();
  for (int i = 0; i < p.num_control_points(); ++i) {
    const auto m = p.multi_index(i);
    bool interior = true;
    for (int d = 0; d < 3; ++d) interior = interior && m[d] > 0 && m[d] + 1 < p.num_basis(d);
    if (interior) {
      w[i] = weight(rng);
      for (int c = 0; c < 3; ++c) P(i, c) += shift(rng);
    }
  }
  std::vector<KnotVector> kv = p.all_knots();
  check_refinement_exact(NurbsPatch(kv, P, w), rng);
}

TEST(SplineRefinement, RandomRationalPatchesAreUnchanged) {
  // Random knots with interior multiplicities and weights on every control point.
  std::mt19937 rng(13);
  for (int pd = 1; pd <= 3; ++pd) check_refinement_exact(random_patch(rng, pd, 3), rng);
}

// A knot of multiplicity p+1 (a C^-1 break, which KnotVector accepts) must
// survive degree elevation like any other: the elevated space still contains
// the old one.  Two Greville abscissae of the elevated vector coincide at
// such a knot, so collocation there is singular.
TEST(SplineRefinement, ElevationAcrossDiscontinuousKnot) {
  std::mt19937 rng(17);
  const KnotVector kv(2, {0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1});
  Eigen::MatrixXd P(kv.num_basis(), 2);
  P << 0, 0, 1, 2, 2, 1, 3, 0, 4, -1, 5, 1;  // a jump at u = 0.5
  Eigen::VectorXd w(kv.num_basis());
  w << 1, 0.7, 1.3, 0.9, 2, 1;
  const NurbsPatch curve({kv}, P, w);
  const auto xis = random_points(rng, 1, 40);
  const Eigen::MatrixXd field = Eigen::MatrixXd::Random(kv.num_basis(), 3);
  const Samples before = sample(curve, field, xis);
  for (int by = 1; by <= 2; ++by) {
    igac::RefinedPatch e;
    ASSERT_NO_THROW(e = igac::elevate_degree(curve, 0, by, {field})) << "elevation by " << by;
    expect_same(before, e.patch, e.fields[0], xis, "elevation across a C^-1 knot by " + std::to_string(by));
  }
}

TEST(SplineRefinement, RejectsKnotsOutsideTheRange) {
  const NurbsPatch p = igac::quarter_disc(1.0).patch;
  expect_spline_error([&] { igac::insert_knots(p, 0, {1.5}); }, {"1.5", "not inside"});
  expect_spline_error([&] { igac::insert_knots(p, 0, {0.6, 0.2}); }, {"sorted"});
  expect_spline_error([&] { igac::elevate_degree(p, 1, -1); }, {"negative"});
}

// A NURBS patch refuses weights that are not positive and finite.
TEST(SplinePatchValidation, NonPositiveWeights) {
  const NurbsPatch p = igac::quarter_disc(1.0).patch;
  for (double bad : {-0.5, 0.0, std::nan("")}) {
    Eigen::VectorXd w = p.weights();
    w[4] = bad;
    expect_spline_error([&] { NurbsPatch(p.all_knots(), p.points(), w); }, {"weight", "control point 4", "not positive"});
  }
  expect_spline_error([&] { NurbsPatch(p.all_knots(), p.points().topRows(5), p.weights()); },
                      {"need 9 control points", "got 5 points"});
}

}  // namespace
