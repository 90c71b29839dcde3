// SPDX-License-Identifier: BSD-3-Clause
#include "engine/spline/refinement.hpp"

#include <Eigen/SparseLU>
#include <functional>
#include <fmt/format.h>

namespace igac {
namespace {

using LineOp = std::function<Eigen::MatrixXd(const Eigen::MatrixXd&)>;

// Homogeneous coefficients: [w P | w | w u_1 | ...].
Eigen::MatrixXd homogeneous(const NurbsPatch& p, const std::vector<Eigen::MatrixXd>& fields) {
  int cols = p.space_dim() + 1;
  for (const auto& f : fields) {
    if (f.rows() != p.num_control_points())
      throw SplineError("a field to refine needs one row per control point");
    cols += int(f.cols());
  }
  Eigen::MatrixXd H(p.num_control_points(), cols);
  H.leftCols(p.space_dim()) = p.weights().asDiagonal() * p.points();
  H.col(p.space_dim()) = p.weights();
  int c = p.space_dim() + 1;
  for (const auto& f : fields) {
    H.middleCols(c, f.cols()) = p.weights().asDiagonal() * f;
    c += int(f.cols());
  }
  return H;
}

RefinedPatch from_homogeneous(std::vector<KnotVector> knots, const Eigen::MatrixXd& H, int space_dim,
                              const std::vector<Eigen::MatrixXd>& old_fields) {
  const Eigen::VectorXd w = H.col(space_dim);
  const Eigen::VectorXd inv = w.cwiseInverse();
  Eigen::MatrixXd P = inv.asDiagonal() * H.leftCols(space_dim);
  RefinedPatch out{NurbsPatch(std::move(knots), std::move(P), w), {}};
  int c = space_dim + 1;
  for (const auto& f : old_fields) {
    out.fields.push_back(inv.asDiagonal() * H.middleCols(c, f.cols()));
    c += int(f.cols());
  }
  return out;
}

// Applies a 1D coefficient operator along `direction` of a tensor-product
// coefficient array with sizes `n` (one row per coefficient, H.cols() values).
Eigen::MatrixXd apply_along(const Eigen::MatrixXd& H, std::array<int, 3> n, int direction,
                            int n_new, const LineOp& op) {
  const int cols = int(H.cols());
  const int nd = n[direction];
  const int lines = int(H.rows()) / nd;
  // stride of `direction` in the flat numbering, and index of line l's first entry
  int stride = 1;
  for (int d = 0; d < direction; ++d) stride *= n[d];
  auto first_of_line = [&](int l, int len) {
    const int lo = l % stride, hi = l / stride;
    return lo + hi * stride * len;
  };
  Eigen::MatrixXd L(nd, lines * cols);
  for (int l = 0; l < lines; ++l) {
    const int f = first_of_line(l, nd);
    for (int i = 0; i < nd; ++i) L.block(i, l * cols, 1, cols) = H.row(f + i * stride);
  }
  const Eigen::MatrixXd Lnew = op(L);
  Eigen::MatrixXd out(lines * n_new, cols);
  for (int l = 0; l < lines; ++l) {
    const int f = first_of_line(l, n_new);
    for (int i = 0; i < n_new; ++i) out.row(f + i * stride) = Lnew.block(i, l * cols, 1, cols);
  }
  return out;
}

std::array<int, 3> sizes(const NurbsPatch& p) {
  std::array<int, 3> n{1, 1, 1};
  for (int d = 0; d < p.param_dim(); ++d) n[d] = p.num_basis(d);
  return n;
}

// Piegl & Tiller A5.4 on the rows of Pw.
Eigen::MatrixXd refine_rows(const KnotVector& kv, const std::vector<double>& X, const Eigen::MatrixXd& Pw,
                            std::vector<double>& Ubar) {
  const int p = kv.degree();
  const auto& U = kv.knots();
  const int n = kv.num_basis() - 1, m = n + p + 1, r = int(X.size()) - 1;
  const int a = kv.find_span(X.front());
  const int b = kv.find_span(X.back()) + 1;
  Eigen::MatrixXd Qw(n + r + 2, Pw.cols());
  Ubar.assign(m + r + 2, 0.0);
  for (int j = 0; j <= a - p; ++j) Qw.row(j) = Pw.row(j);
  for (int j = b - 1; j <= n; ++j) Qw.row(j + r + 1) = Pw.row(j);
  for (int j = 0; j <= a; ++j) Ubar[j] = U[j];
  for (int j = b + p; j <= m; ++j) Ubar[j + r + 1] = U[j];
  int i = b + p - 1, k = b + p + r;
  for (int j = r; j >= 0; --j) {
    while (X[j] <= U[i] && i > a) {
      Qw.row(k - p - 1) = Pw.row(i - p - 1);
      Ubar[k] = U[i];
      --k;
      --i;
    }
    Qw.row(k - p - 1) = Qw.row(k - p);
    for (int l = 1; l <= p; ++l) {
      const int ind = k - p + l;
      double alfa = Ubar[k + l] - X[j];
      if (alfa == 0.0) {
        Qw.row(ind - 1) = Qw.row(ind);
      } else {
        alfa /= (Ubar[k + l] - U[i - p + l]);
        Qw.row(ind - 1) = alfa * Qw.row(ind - 1) + (1.0 - alfa) * Qw.row(ind);
      }
    }
    Ubar[k] = X[j];
    --k;
  }
  return Qw;
}

// Sparse matrix of the B-spline basis of kv at the points x.
Eigen::SparseMatrix<double> collocation(const KnotVector& kv, const std::vector<double>& x) {
  std::vector<Eigen::Triplet<double>> t;
  std::vector<std::vector<double>> b;
  for (size_t r = 0; r < x.size(); ++r) {
    const int s = kv.find_span(x[r]);
    kv.basis_derivatives(s, x[r], 0, b);
    for (int j = 0; j <= kv.degree(); ++j)
      if (b[0][j] != 0.0) t.emplace_back(int(r), s - kv.degree() + j, b[0][j]);
  }
  Eigen::SparseMatrix<double> A(int(x.size()), kv.num_basis());
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

}  // namespace

RefinedPatch insert_knots(const NurbsPatch& patch, int direction, const std::vector<double>& X,
                          const std::vector<Eigen::MatrixXd>& fields) {
  const KnotVector& kv = patch.knots(direction);
  for (size_t j = 0; j < X.size(); ++j) {
    if (!(X[j] > kv.first() && X[j] < kv.last()))
      throw SplineError(fmt::format("knot {} to insert is not inside ({}, {})", X[j], kv.first(), kv.last()));
    if (j > 0 && X[j] < X[j - 1]) throw SplineError("knots to insert must be sorted");
  }
  auto knots = patch.all_knots();
  if (X.empty()) return {patch, fields};
  std::vector<double> Ubar;
  const Eigen::MatrixXd H = homogeneous(patch, fields);
  const int n_new = kv.num_basis() + int(X.size());
  const Eigen::MatrixXd Hn = apply_along(H, sizes(patch), direction, n_new, [&](const Eigen::MatrixXd& L) {
    return refine_rows(kv, X, L, Ubar);
  });
  knots[direction] = KnotVector(kv.degree(), Ubar);
  return from_homogeneous(std::move(knots), Hn, patch.space_dim(), fields);
}

RefinedPatch elevate_degree(const NurbsPatch& patch, int direction, int by,
                            const std::vector<Eigen::MatrixXd>& fields) {
  if (by < 0) throw SplineError("degree elevation by a negative amount");
  if (by == 0) return {patch, fields};
  const KnotVector& kv = patch.knots(direction);
  const KnotVector up = kv.elevated(by);
  auto g = up.greville();
  // At a knot of full multiplicity (a discontinuity) the last function on
  // its left and the first on its right share a Greville abscissa; move the
  // left one inside its support, which keeps Schoenberg-Whitney.
  for (size_t i = 1; i + 1 < g.size(); ++i)
    if (g[i] == g[i + 1]) g[i] = 0.5 * (g[i - 1] + g[i]);
  const Eigen::SparseMatrix<double> A_old = collocation(kv, g);
  Eigen::SparseMatrix<double> C = collocation(up, g);
  C.makeCompressed();
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(C);
  if (lu.info() != Eigen::Success) throw SplineError("degree elevation: singular collocation matrix");
  const Eigen::MatrixXd Hn = apply_along(homogeneous(patch, fields), sizes(patch), direction, up.num_basis(),
                                         [&](const Eigen::MatrixXd& L) -> Eigen::MatrixXd {
                                           return lu.solve(Eigen::MatrixXd(A_old * L));
                                         });
  auto knots = patch.all_knots();
  knots[direction] = up;
  return from_homogeneous(std::move(knots), Hn, patch.space_dim(), fields);
}

NurbsPatch elevate_to(const NurbsPatch& patch, int degree) {
  NurbsPatch p = patch;
  for (int d = 0; d < p.param_dim(); ++d)
    if (p.degree(d) < degree) p = elevate_degree(p, d, degree - p.degree(d)).patch;
  return p;
}

NurbsPatch subdivide(const NurbsPatch& patch, int parts) {
  NurbsPatch p = patch;
  for (int d = 0; d < p.param_dim(); ++d) p = refine_to(p, d, p.knots(d).subdivided(parts));
  return p;
}

NurbsPatch refine_to(const NurbsPatch& patch, int direction, const KnotVector& finer) {
  return insert_knots(patch, direction, patch.knots(direction).knots_missing_from(finer)).patch;
}

Eigen::SparseMatrix<double> knot_insertion_matrix(const KnotVector& coarse, const KnotVector& fine) {
  if (coarse.degree() != fine.degree())
    throw SplineError(fmt::format("knot insertion between degrees {} and {}", coarse.degree(), fine.degree()));
  const std::vector<double> X = coarse.knots_missing_from(fine);
  const int nc = coarse.num_basis();
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(nc, nc);
  if (!X.empty()) {
    std::vector<double> Ubar;
    T = refine_rows(coarse, X, T, Ubar);
  }
  return T.sparseView();  // the zeros of A5.4 are exact
}

}  // namespace igac
