// SPDX-License-Identifier: BSD-3-Clause
#include "engine/saddle_solver.hpp"

#include <Eigen/SVD>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "engine/bordered_spd.hpp"
#include "engine/cholesky.hpp"
#include "engine/dense_kernels.hpp"
#include "engine/condition_estimate.hpp"
#include "engine/stopwatch.hpp"

namespace igac {
namespace {
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// GMRES on the preconditioned operator: restarted after kRestart vectors, at
// most kMaxIterations in all (the fallback takes over beyond).
constexpr int kRestart = 30;
constexpr int kMaxIterations = 90;
// Normwise backward error |J x - b| / (|J| |x| + |b|) (infinity norms) a
// solve must reach: well below what Newton needs (its relative residual
// tolerance is 1e-9), well above what a direct solve reaches (~1e-16).
constexpr double kBackwardError = 1e-13;
}  // namespace

struct SaddleSolver::Impl {
  const BlockJacobian* J = nullptr;
  int n = 0, m = 0, k = 0;  // k: the rigid modes the active rows hold (hold_rigid_modes)
  // the symmetric part, in K's pattern, and where K's transpose entries sit
  Eigen::SparseMatrix<double> Ks;
  std::vector<int> transpose_of;
  bool symmetric_pattern = false;
  std::unique_ptr<SparseCholesky> chol_owner = std::make_unique<SparseCholesky>();
  SparseCholesky& chol() const { return *chol_owner; }
  std::vector<char> pinned;
  // per setup
  bool fallback = false;
  bool factorised = false;  // K_s's factor is that of the last setup (its Schur part may be redone)
  double norm_J = 0;  // infinity norm
  std::vector<int> active, inactive;
  SparseCholesky::Reach reach;
  Eigen::MatrixXd Y;   // L^-1 P B_A^T on reach.rows
  Eigen::MatrixXd BR;  // B_A R_h
  // R_h: the combinations of the rigid modes R the active rows hold
  // (hold_rigid_modes): J's own R when they hold all of it, else
  // reduced_modes
  const Eigen::MatrixXd* held_modes = nullptr;
  Eigen::MatrixXd reduced_modes;
  BorderedSpdSolver M;
  // Rows that combine (BlockJacobian::mixed_B, mixed_lambda; friction's slip
  // rows): C_A = (diag(s) + M_B)_A B is not B_A, so the Schur complement
  // C_A K_s^-1 B_A^T - (diag(d) + M_l)_AA is not symmetric.  Y then holds
  // the columns of every B row a closed row reads (`reads`, the closed ones
  // among them, by the order of their first row), mixed_rows C_A's
  // coefficients on them, and the bordered system is solved by LU.
  bool mixed = false;
  std::vector<int> reads;        // the B rows whose columns Y holds (a superset of `active`)
  std::vector<int> active_in_Y;  // per active multiplier: its column of Y
  RowSparse mixed_rows;          // na x reads.size()
  BorderedLuSolver M_lu;
  Eigen::UmfPackLU<Eigen::SparseMatrix<double>> lu;
  Eigen::SparseMatrix<double> full;

  Impl() {
    // J has a symmetric pattern: order A + A^T by nested dissection, as for
    // a Cholesky factor, not UMFPACK's column ordering of A^T A.
    lu.umfpackControl()(UMFPACK_STRATEGY) = UMFPACK_STRATEGY_SYMMETRIC;
    lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  }

  void analyse_pattern(const Eigen::SparseMatrix<double>& K) {
    Ks = K;
    Ks.makeCompressed();
    transpose_of.assign(Ks.nonZeros(), -1);
    symmetric_pattern = Ks.rows() == Ks.cols();
    for (int c = 0; c < Ks.outerSize() && symmetric_pattern; ++c)
      for (int p = Ks.outerIndexPtr()[c]; p < Ks.outerIndexPtr()[c + 1]; ++p) {
        const int r = Ks.innerIndexPtr()[p];
        const int* first = Ks.innerIndexPtr() + Ks.outerIndexPtr()[r];
        const int* past = Ks.innerIndexPtr() + Ks.outerIndexPtr()[r + 1];
        const int* hit = std::lower_bound(first, past, c);
        if (hit == past || *hit != c) {
          symmetric_pattern = false;
          break;
        }
        transpose_of[p] = int(hit - Ks.innerIndexPtr());
      }
  }

  Eigen::VectorXd apply_J(const Eigen::VectorXd& x) const {
    Eigen::VectorXd y(n + m);
    y.head(n).noalias() = J->K * x.head(n);
    if (J->K_coupling.nonZeros() > 0) y.head(n).noalias() += J->K_coupling * x.head(n);
    if (m > 0) {
      y.head(n).noalias() += J->B.transpose() * x.tail(m);
      const Eigen::VectorXd Bu = J->B * x.head(n);
      y.tail(m) = J->s.cwiseProduct(Bu) + J->d.cwiseProduct(x.tail(m));
      if (J->mixed_B.rows() > 0) y.tail(m).noalias() += J->mixed_B * Bu;
      if (J->mixed_lambda.rows() > 0) y.tail(m).noalias() += J->mixed_lambda * x.tail(m);
    }
    return y;
  }

  // x = P^-1 b for P = J with K replaced by K_s (exact when K_s R = 0).
  // With rows that combine (`mixed`) the closed rows read
  //   C_A du + E_AA dl_A = b_A - E_AI dl_I,  E = diag(d) + M_l,
  // du = K_s^-1 (f - B_A^T dl_A) + R c, f = b_u - B_I^T dl_I, and
  //   [ C_A K_s^-1 B_A^T - E_AA   -C_A R ] [dl_A]   [ C_A K_s^-1 f - b_A + E_AI dl_I ]
  //   [ -R^T B_A^T                  0    ] [ c  ] = [ -R^T f                         ];
  // without, each active row is divided by its s_k: C_A = B_A, E = 0.
  void precondition(const Eigen::VectorXd& b, Eigen::VectorXd& x) const {
    x.setZero(n + m);
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m);
    for (int K : inactive) lambda[K] = b[n + K] / J->d[K];
    Eigen::VectorXd f = b.head(n);
    if (m > 0) f.noalias() -= J->B.transpose() * lambda;
    Eigen::VectorXd fp = f;
    for (int p : J->pinned) fp[p] = 0;
    Eigen::VectorXd y = chol().forward_full(fp);
    const int na = int(active.size());
    Eigen::VectorXd yr(Eigen::Index(reach.rows.size()));
    for (size_t i = 0; i < reach.rows.size(); ++i) yr[i] = y[reach.rows[i]];
    const Eigen::VectorXd q = k > 0 ? Eigen::VectorXd(held_modes->transpose() * f) : Eigen::VectorXd();
    Eigen::VectorXd lambda_A, c, in_Y;
    if (!mixed) {
      Eigen::VectorXd r = Y.transpose() * yr;
      for (int i = 0; i < na; ++i) r[i] -= b[n + active[i]] / J->s[active[i]];
      M.solve(r, q, lambda_A, c);
      in_Y = lambda_A;
    } else {
      Eigen::VectorXd r = mixed_rows * (Y.transpose() * yr);
      for (int i = 0; i < na; ++i) {
        r[i] -= b[n + active[i]];
        if (J->mixed_lambda.rows() > 0)
          for (RowSparse::InnerIterator it(J->mixed_lambda, active[i]); it; ++it) r[i] += it.value() * lambda[it.col()];
      }
      M_lu.solve(r, q, lambda_A, c);
      in_Y = Eigen::VectorXd::Zero(Eigen::Index(reads.size()));
      for (int i = 0; i < na; ++i) in_Y[active_in_Y[i]] = lambda_A[i];
    }
    if (na > 0) {
      yr.noalias() = Y * in_Y;
      for (size_t i = 0; i < reach.rows.size(); ++i) y[reach.rows[i]] -= yr[i];
    }
    x.head(n) = chol().backward_full(y);
    if (k > 0) x.head(n).noalias() += *held_modes * c;
    for (int i = 0; i < na; ++i) lambda[active[i]] = lambda_A[i];
    x.tail(m) = lambda;
  }

  double backward_error(const Eigen::VectorXd& r, const Eigen::VectorXd& x, const Eigen::VectorXd& b) const {
    const double den = norm_J * x.cwiseAbs().maxCoeff() + b.cwiseAbs().maxCoeff();
    return den > 0 ? r.cwiseAbs().maxCoeff() / den : 0.0;
  }

  // Right-preconditioned restarted GMRES from x; true when the backward
  // error reaches kBackwardError.
  bool gmres(const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance, int& iterations) const {
    const double b_norm = b.cwiseAbs().maxCoeff();
    auto done = [&](const Eigen::VectorXd& r) {
      return backward_error(r, x, b) <= kBackwardError || r.cwiseAbs().maxCoeff() <= tolerance * b_norm;
    };
    const int N = n + m;
    Eigen::VectorXd r = b - apply_J(x);
    Eigen::MatrixXd V(N, kRestart + 1), Z(N, kRestart), H(kRestart + 1, kRestart);
    Eigen::VectorXd g(kRestart + 1), cs(kRestart), sn(kRestart), z, w;
    while (iterations < kMaxIterations) {
      if (done(r)) return true;
      // the 2-norm the Arnoldi process sees, for either criterion
      const double target = std::max(kBackwardError * (norm_J * x.cwiseAbs().maxCoeff() + b_norm), tolerance * b_norm);
      const double beta = r.norm();
      V.col(0) = r / beta;
      H.setZero();
      g.setZero();
      g[0] = beta;
      int j = 0;
      while (j < kRestart && iterations < kMaxIterations) {
        precondition(V.col(j), z);
        Z.col(j) = z;
        w = apply_J(z);
        for (int i = 0; i <= j; ++i) {  // modified Gram-Schmidt
          H(i, j) = V.col(i).dot(w);
          w -= H(i, j) * V.col(i);
        }
        const double h_next = w.norm();  // 0: the Krylov space holds the solution (happy breakdown)
        H(j + 1, j) = h_next;
        if (h_next > 0) V.col(j + 1) = w / h_next;
        for (int i = 0; i < j; ++i) {  // earlier rotations
          const double a = H(i, j), c = H(i + 1, j);
          H(i, j) = cs[i] * a + sn[i] * c;
          H(i + 1, j) = -sn[i] * a + cs[i] * c;
        }
        const double rho = std::hypot(H(j, j), H(j + 1, j));
        cs[j] = rho > 0 ? H(j, j) / rho : 1.0;
        sn[j] = rho > 0 ? H(j + 1, j) / rho : 0.0;
        H(j, j) = rho;
        H(j + 1, j) = 0;
        g[j + 1] = -sn[j] * g[j];
        g[j] *= cs[j];
        ++j;
        ++iterations;
        if (std::abs(g[j]) <= target || h_next == 0) break;
      }
      const Eigen::VectorXd yk = H.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g.head(j));
      x.noalias() += Z.leftCols(j) * yk;
      r = b - apply_J(x);
    }
    return done(r);
  }

  // Y = L^-1 P B_rows^T on the reach of B's rows `rows` (the pinned
  // equations left out), its columns, and so `rows`, reordered by their
  // first row: both the solve and the Gram matrix skip the zeros above it.
  // Returns each column's first row.
  std::vector<int> columns_of_rows(const BlockJacobian& Jac, std::vector<int>& rows) {
    const int nr = int(rows.size());
    std::vector<Eigen::Triplet<double>> t;
    std::vector<int> eqs;
    for (int i = 0; i < nr; ++i)
      for (RowSparse::InnerIterator it(Jac.B, rows[i]); it; ++it)
        if (!pinned[it.col()] && it.value() != 0.0) {
          t.emplace_back(it.col(), i, it.value());
          eqs.push_back(it.col());
        }
    Eigen::SparseMatrix<double> C(n, nr);
    C.setFromTriplets(t.begin(), t.end());
    reach = chol().reach(eqs);
    SparseCholesky::ColumnsByStart columns = chol().forward_by_start(reach, C);
    Y = std::move(columns.Y);
    const std::vector<int> by_row = rows;
    for (int i = 0; i < nr; ++i) rows[i] = by_row[columns.order[i]];
    return std::move(columns.start);
  }

  // held_modes and BR from the rigid modes R and the active rows: the
  // combinations of R along which some active row's gap changes (the right
  // singular vectors of B_A R with a singular value above round-off of the
  // rows' size).  A motion no active row holds (a ring between two
  // frictionless planes sliding along them) is absent from J's range too:
  // its amplitude is left at 0, the pinned equations' values, instead of
  // letting an LU of the singular J pick one (an arbitrary drift, and a
  // full factorisation every iteration).
  void hold_rigid_modes(const BlockJacobian& Jac) {
    const int na = int(active.size()), all = int(Jac.rigid_modes.cols());
    Eigen::MatrixXd BR_all(na, all);
    double row_scale = 0;
    for (int i = 0; i < na; ++i) {
      BR_all.row(i) = Jac.B.row(active[i]) * Jac.rigid_modes;
      row_scale = std::max(row_scale, Jac.B.row(active[i]).norm());
    }
    if (na == 0 || all == 0) {
      BR.resize(na, 0);
      k = 0;
      return;
    }
    constexpr double kHeldTolerance = 1e-12;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(BR_all, Eigen::ComputeFullV);
    int held = 0;
    while (held < int(svd.singularValues().size()) && svd.singularValues()[held] > kHeldTolerance * row_scale) ++held;
    if (held == all) {
      held_modes = &Jac.rigid_modes;
      BR = std::move(BR_all);
    } else {
      reduced_modes = Jac.rigid_modes * svd.matrixV().leftCols(held);
      held_modes = &reduced_modes;
      BR = BR_all * svd.matrixV().leftCols(held);
    }
    k = held;
  }

  // K_s is the preconditioner's, not J's.  Where it is indefinite (a soft
  // mode made negative by stress, e.g. in a Neo-Hookean sphere octant
  // pressed on another body, or a mixed tangent deep in a rubber squeeze)
  // the factor is that of K_s + D, D diagonal and nonzero only at
  // equations whose pivot was not positive: each failure adds |K_s,ii| at
  // CHOLMOD's first such equation i (again if it fails there again) and
  // factorises anew.  D is of low rank, so GMRES, which multiplies by J
  // itself, absorbs it in a few more iterations.  The next setup starts
  // from this one's D (the soft modes stay where they were).  False when
  // D would need more than kMaxShifts entries: then the LU of J.
  static constexpr int kMaxShifts = 8;
  std::map<int, int> shifts;  // equation -> how many times |K_s,ii| is added
  bool factorize_shifted() {
    const int n_eq = int(Ks.outerSize());
    std::vector<int> diagonal(n_eq, -1);  // where K_s's diagonal entries sit
    for (int c = 0; c < n_eq; ++c)
      for (int p = Ks.outerIndexPtr()[c]; p < Ks.outerIndexPtr()[c + 1]; ++p)
        if (Ks.innerIndexPtr()[p] == c) diagonal[c] = p;
    double largest = 0;
    for (int c = 0; c < n_eq; ++c)
      if (diagonal[c] >= 0) largest = std::max(largest, std::abs(Ks.valuePtr()[diagonal[c]]));
    std::map<int, double> kept;  // K_s's own values where D is not zero
    const auto shift = [&](int eq, int times) {
      double& v = Ks.valuePtr()[diagonal[eq]];
      if (!kept.count(eq)) kept[eq] = v;
      const double own = kept[eq];
      v = own + times * (own != 0 ? std::abs(own) : largest);
    };
    for (auto it = shifts.begin(); it != shifts.end();)  // (a pattern of another size: none kept)
      it = it->first < n_eq && diagonal[it->first] >= 0 ? std::next(it) : shifts.erase(it);
    for (const auto& [eq, times] : shifts) shift(eq, times);
    bool positive = false;
    for (int attempt = 0; attempt <= 2 * kMaxShifts; ++attempt) {
      try {
        chol().factorize(Ks);
        positive = true;
      } catch (const std::runtime_error&) {
      }
      const int eq = positive ? -1 : chol().indefinite_at();
      if (positive || eq < 0 || diagonal[eq] < 0 || int(shifts.size()) + (shifts.count(eq) ? 0 : 1) > kMaxShifts) break;
      shift(eq, ++shifts[eq]);
    }
    for (const auto& [eq, v] : kept) Ks.valuePtr()[diagonal[eq]] = v;  // K_s as it was
    if (!positive) shifts.clear();
    return positive;
  }

  bool factor_full(std::string& why) {
    full = assemble_condensed(*J);
    lu.compute(full);
    if (lu.info() != Eigen::Success) {
      why = "singular Newton matrix";
      return false;
    }
    fallback = true;
    return true;
  }
};

namespace {
// |J|_inf, the scale of the solves' backward error
double infinity_norm(const BlockJacobian& J) {
  const int n = int(J.K.rows()), m = int(J.B.rows());
  Eigen::VectorXd rows = Eigen::VectorXd::Zero(n + m);
  for (int c = 0; c < J.K.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(J.K, c); it; ++it) rows[it.row()] += std::abs(it.value());
  for (int c = 0; c < J.K_coupling.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(J.K_coupling, c); it; ++it)
      rows[it.row()] += std::abs(it.value());
  for (int k = 0; k < m; ++k)
    for (RowSparse::InnerIterator it(J.B, k); it; ++it) {
      rows[it.col()] += std::abs(it.value());
      rows[n + k] += std::abs(J.s[k] * it.value());
    }
  if (m > 0) rows.tail(m) += J.d.cwiseAbs();
  if (J.has_mixed_rows()) {  // (|M_B| |B| bounds the rows' sums from above: a scale)
    Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(m);
    for (int k = 0; k < m; ++k)
      for (RowSparse::InnerIterator it(J.B, k); it; ++it) row_sums[k] += std::abs(it.value());
    for (const RowSparse* M : {&J.mixed_B, &J.mixed_lambda})
      for (int k = 0; k < M->outerSize(); ++k)
        for (RowSparse::InnerIterator it(*M, k); it; ++it)
          rows[n + k] += std::abs(it.value()) * (M == &J.mixed_B ? row_sums[it.col()] : 1.0);
  }
  return rows.size() ? rows.maxCoeff() : 0.0;
}
}  // namespace

SaddleSolver::SaddleSolver() : impl_(std::make_unique<Impl>()) {}
SaddleSolver::~SaddleSolver() = default;

bool SaddleSolver::setup(const BlockJacobian& J) {
  auto& I = *impl_;
  why_.clear();
  ++stats_.setups;
  I.J = &J;
  I.n = int(J.K.rows());
  I.m = int(J.B.rows());
  I.k = int(J.rigid_modes.cols());
  I.fallback = false;
  I.factorised = false;
  I.norm_J = infinity_norm(J);
  const Stopwatch factorize_clock;
  const bool same_pattern =
      J.K.isCompressed() && I.Ks.rows() == J.K.rows() && I.Ks.nonZeros() == J.K.nonZeros() &&
      std::equal(J.K.outerIndexPtr(), J.K.outerIndexPtr() + J.K.outerSize() + 1, I.Ks.outerIndexPtr()) &&
      std::equal(J.K.innerIndexPtr(), J.K.innerIndexPtr() + J.K.nonZeros(), I.Ks.innerIndexPtr());
  if (!same_pattern) {
    I.analyse_pattern(J.K);
    I.chol_owner = std::make_unique<SparseCholesky>();
  }
  if (J.general || !I.symmetric_pattern || !J.K.isCompressed()) {
    const bool ok = I.factor_full(why_);
    stats_.factorize_s += factorize_clock.seconds();
    stats_.fallbacks += ok;
    return ok;
  }
  // K_s values, rigid motions pinned
  const double* kv = J.K.valuePtr();
  double* sv = I.Ks.valuePtr();
  for (int p = 0; p < int(I.Ks.nonZeros()); ++p) sv[p] = 0.5 * (kv[p] + kv[I.transpose_of[p]]);
  I.pinned.assign(I.n, 0);
  for (int p : J.pinned) I.pinned[p] = 1;
  if (!J.pinned.empty())
    for (int c = 0; c < I.Ks.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(I.Ks, c); it; ++it)
        if (I.pinned[it.row()] || I.pinned[it.col()]) it.valueRef() = it.row() == it.col() ? 1.0 : 0.0;
  bool analysed = true;
  try {
    if (!I.chol().analyzed()) {
      std::vector<int> last;  // the equations B touches (may touch: constraint_equations), ordered last
      std::vector<char> touched(I.n, 0);
      for (int k = 0; k < I.m && J.constraint_equations.empty(); ++k)
        for (RowSparse::InnerIterator it(J.B, k); it; ++it)
          if (it.value() != 0.0 && !I.pinned[it.col()]) touched[it.col()] = 1;
      for (int eq : J.constraint_equations)
        if (!I.pinned[eq]) touched[eq] = 1;
      for (int i = 0; i < I.n; ++i)
        if (touched[i]) last.push_back(i);
      I.chol().analyze(I.Ks, last);
    }
  } catch (const std::runtime_error&) {
    analysed = false;
  }
  if (!analysed || !I.factorize_shifted()) {  // indefinite beyond kMaxShifts local shifts: this iteration by LU
    const bool ok = I.factor_full(why_);
    stats_.factorize_s += factorize_clock.seconds();
    stats_.fallbacks += ok;
    return ok;
  }
  stats_.shifted += !I.shifts.empty();
  stats_.factorize_s += factorize_clock.seconds();
  I.factorised = true;
  return schur_of_active_rows(J);
}

bool SaddleSolver::update_constraint_rows(const BlockJacobian& J) {
  auto& I = *impl_;
  if (I.fallback || !I.factorised || I.J != &J) return setup(J);
  why_.clear();
  I.norm_J = infinity_norm(J);
  return schur_of_active_rows(J);
}

// The Schur complement of the active multipliers, K_s factorised.
bool SaddleSolver::schur_of_active_rows(const BlockJacobian& J) {
  auto& I = *impl_;
  const Stopwatch schur_clock;
  I.active.clear();
  I.inactive.clear();
  for (int k = 0; k < I.m; ++k) {
    if (J.closed_row(k)) I.active.push_back(k);
    else I.inactive.push_back(k);
  }
  I.mixed = J.has_mixed_rows();
  if (I.mixed) {
    const bool ok = schur_of_mixed_rows(J);
    stats_.schur_s += schur_clock.seconds();
    return ok;
  }
  const std::vector<int> start = I.columns_of_rows(J, I.active);
  I.hold_rigid_modes(J);
  const Eigen::MatrixXd S = dense::gram(I.Y, start);  // Y^T Y on OpenBLAS (engine/dense_kernels.hpp)
  if (!I.M.compute(S, I.BR)) {  // dependent constraints: let LU on J decide
    const bool ok = I.factor_full(why_);
    stats_.schur_s += schur_clock.seconds();
    stats_.fallbacks += ok;
    return ok;
  }
  stats_.schur_s += schur_clock.seconds();
  return true;
}

// The same with rows that combine (Impl::precondition): Y holds the
// columns of every B row a closed row reads, S = C_A K_s^-1 B_A^T - E_AA is
// a product with the Gram matrix of Y, and the bordered system an LU.
bool SaddleSolver::schur_of_mixed_rows(const BlockJacobian& J) {
  auto& I = *impl_;
  std::vector<int> where(I.m, -1);  // a B row's place in `reads`
  I.reads = I.active;
  for (int k : I.reads) where[k] = 0;
  if (J.mixed_B.rows() > 0)
    for (int k : I.active)
      for (RowSparse::InnerIterator it(J.mixed_B, k); it; ++it)
        if (where[it.col()] < 0) {
          where[it.col()] = 0;
          I.reads.push_back(int(it.col()));
        }
  const int nr = int(I.reads.size()), na = int(I.active.size());
  const std::vector<int> start = I.columns_of_rows(J, I.reads);
  for (int i = 0; i < nr; ++i) where[I.reads[i]] = i;
  // the closed rows in Y's order, each with its column of Y
  std::vector<char> closed(I.m, 0);
  for (int k : I.active) closed[k] = 1;
  I.active.clear();
  I.active_in_Y.clear();
  for (int i = 0; i < nr; ++i)
    if (closed[I.reads[i]]) {
      I.active.push_back(I.reads[i]);
      I.active_in_Y.push_back(i);
    }
  // C_A's coefficients on the rows Y holds, and E_AA
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < na; ++i) {
    const int k = I.active[i];
    if (J.s[k] != 0.0) t.emplace_back(i, where[k], J.s[k]);
    if (J.mixed_B.rows() > 0)
      for (RowSparse::InnerIterator it(J.mixed_B, k); it; ++it) t.emplace_back(i, where[it.col()], it.value());
  }
  I.mixed_rows.resize(na, nr);
  I.mixed_rows.setFromTriplets(t.begin(), t.end());
  I.hold_rigid_modes(J);
  const Eigen::MatrixXd gram = dense::gram(I.Y, start);  // Y^T Y (engine/dense_kernels.hpp)
  Eigen::MatrixXd S(na, na);
  if (nr == na) {  // (the usual case: every row a closed row reads is closed)
    S.noalias() = I.mixed_rows * gram;
  } else {
    Eigen::MatrixXd gram_active(nr, na);
    for (int i = 0; i < na; ++i) gram_active.col(i) = gram.col(I.active_in_Y[i]);
    S.noalias() = I.mixed_rows * gram_active;
  }
  std::vector<int> in_active(I.m, -1);
  for (int i = 0; i < na; ++i) in_active[I.active[i]] = i;
  for (int i = 0; i < na; ++i) {
    const int k = I.active[i];
    S(i, i) -= J.d[k];
    if (J.mixed_lambda.rows() > 0)
      for (RowSparse::InnerIterator it(J.mixed_lambda, k); it; ++it)
        if (in_active[it.col()] >= 0) S(i, in_active[it.col()]) -= it.value();
  }
  // the borders: B_A R_h (the balance) and C_A R_h (the rows)
  Eigen::MatrixXd read_R(nr, I.k);
  for (int i = 0; i < nr && I.k > 0; ++i) read_R.row(i) = J.B.row(I.reads[i]) * *I.held_modes;
  const Eigen::MatrixXd rows_R = I.mixed_rows * read_R;
  if (!I.M_lu.compute(S, rows_R, I.BR)) {  // dependent constraints: let LU on J decide
    const bool ok = I.factor_full(why_);
    stats_.fallbacks += ok;
    return ok;
  }
  return true;
}

LinearBackendReport SaddleSolver::report() const {
  return {.type = "direct", .method = "CHOLMOD + Schur complement on the active set", .iterations = {}, .ranks = 1,
          .peak_resident_all_ranks_gib = 0};
}

double SaddleSolver::condition_estimate() const {
  const auto& I = *impl_;
  if (I.fallback) {
    // Eigen's UMFPACK wrapper solves with J only: J^-1 stands in for J^-T in
    // the climb's gradient steps.  Every value the climb takes is still some
    // ||J^-1 x||_1 with ||x||_1 = 1, a lower bound; J is symmetric but for
    // the follower load and friction's slip rows.
    const VectorSolve solve = [&I](const Eigen::VectorXd& b) -> Eigen::VectorXd { return I.lu.solve(b); };
    return norm1(I.full) * inverse_norm1_estimate(int(I.full.rows()), solve, solve);
  }
  if (!I.chol_owner || !I.chol().analyzed()) return 0;
  if (!I.shifts.empty() && I.J) {
    // The factor is of K_s shifted, no matrix of the problem: kappa_1 of J
    // itself, J^-1 by the preconditioned GMRES of solve() (the same lower
    // bound as the LU's above).
    const Eigen::SparseMatrix<double> full = assemble_condensed(*I.J);
    const VectorSolve solve = [&I](const Eigen::VectorXd& b) -> Eigen::VectorXd {
      Eigen::VectorXd x;
      I.precondition(b, x);
      int iterations = 0;
      I.gmres(b, x, 0.0, iterations);
      return x;
    };
    return norm1(full) * inverse_norm1_estimate(int(full.rows()), solve, solve);
  }
  return I.chol().condition_estimate();
}

bool SaddleSolver::solve(const Eigen::VectorXd& b_whole, Eigen::VectorXd& x, double tolerance) {
  auto& I = *impl_;
  const Stopwatch clock;
  ++stats_.solves;
  bool ok = true;
  const CondensedRhs rhs = condense_rhs(*I.J, b_whole);  // (BlockJacobian::local)
  const Eigen::VectorXd& b = rhs.b;
  if (I.fallback) {
    x = I.lu.solve(b);
  } else {
    I.precondition(b, x);
    int iterations = 0;
    ok = I.gmres(b, x, tolerance, iterations);
    stats_.krylov_iterations += iterations;
    if (!ok && I.factor_full(why_)) {  // GMRES stalled: this iteration by LU
      ++stats_.fallbacks;
      x = I.lu.solve(b);
      ok = true;
    }
  }
  if (ok) recover_local(*I.J, rhs, x);
  stats_.solve_s += clock.seconds();
  if (!ok || !x.allFinite()) {
    if (why_.empty()) why_ = "singular Newton matrix";
    return false;
  }
  return true;
}

}  // namespace igac
