#include "contact/small_strain_contact.hpp"

#include <algorithm>
#include <chrono>
#include <fmt/format.h>
#include <set>

namespace igac {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
}  // namespace

std::vector<char> initial_active_set(const WeightedGapOperator& op, int k, const ContactSolverOptions& opt) {
  const int m = int(op.weights.size());
  std::vector<char> active(m, 0);
  const Eigen::VectorXd gap0 = op.g0.cwiseQuotient(op.weights);
  for (int K_ = 0; K_ < m; ++K_) active[K_] = gap0[K_] <= opt.initial_gap_tolerance;
  if (k > 0 && std::count(active.begin(), active.end(), 1) < k && m > 0) {
    std::vector<int> order(m);
    for (int i = 0; i < m; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return gap0[a] < gap0[b]; });
    for (int i = 0; i < std::min(k, m); ++i) active[order[i]] = 1;
  }
  return active;
}

std::vector<char> next_active_set(const Eigen::VectorXd& lambda, const Eigen::VectorXd& gap,
                                  const std::vector<char>& active, int k, double cn) {
  const int m = int(lambda.size());
  // Round-off guard: where |lambda_K + c_n g_K| is below round-off of the
  // larger of the two terms, the multiplier keeps its state (at zero load
  // both vanish and nothing changes).
  const double scale = m ? std::max(lambda.cwiseAbs().maxCoeff(), cn * gap.cwiseAbs().maxCoeff()) : 0.0;
  const double tol = 1e-12 * scale;
  std::vector<char> next(m, 0);
  for (int K_ = 0; K_ < m; ++K_) {
    const double v = lambda[K_] + cn * gap[K_];
    next[K_] = std::abs(v) <= tol ? active[K_] : v < 0;
  }
  if (k > 0 && std::count(next.begin(), next.end(), 1) < k) {
    // A body held only by contact needs k active multipliers: keep the
    // ones nearest to activation.
    std::vector<int> order(m);
    for (int i = 0; i < m; ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return lambda[a] + cn * gap[a] < lambda[b] + cn * gap[b]; });
    for (int i = 0; i < std::min(k, m); ++i) next[order[i]] = 1;
  }
  return next;
}

ContactSolution solve_small_strain_contact(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f,
                                           const WeightedGapOperator& op, const RigidModes& modes,
                                           SparseCholesky& chol, const ContactSolverOptions& opt) {
  ContactSolution sol;
  const int n = int(K.rows()), m = int(op.weights.size()), k = int(modes.modes.cols());
  // Contact-face equations (those G touches) are ordered last, so that the
  // factor's trailing block gives S = G K^-1 G^T for all multipliers at once.
  std::vector<char> pinned(n, 0);
  for (int p : modes.pinned) pinned[p] = 1;
  std::vector<int> face_eqs;
  {
    std::vector<char> on_face(n, 0);
    for (int r = 0; r < op.G.outerSize(); ++r)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(op.G, r); it; ++it)
        on_face[it.col()] = !pinned[it.col()];
    for (int i = 0; i < n; ++i)
      if (on_face[i]) face_eqs.push_back(i);
  }
  auto t0 = Clock::now();
  const Eigen::SparseMatrix<double> Kp = pin_equations(K, modes.pinned);
  chol.analyze(Kp, face_eqs);
  chol.factorize(Kp);
  sol.factorize_s = since(t0);

  // G with the pinned columns removed (they carry no unknown of K_p).
  Eigen::SparseMatrix<double, Eigen::RowMajor> Gp = op.G;
  for (int r = 0; r < Gp.outerSize(); ++r)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Gp, r); it; ++it)
      if (pinned[it.col()]) it.valueRef() = 0.0;
  Gp.prune(0.0);
  Eigen::VectorXd fp = f;
  for (int p : modes.pinned) fp[p] = 0.0;

  t0 = Clock::now();
  const Eigen::VectorXd vf = chol.solve(fp);
  const Eigen::VectorXd Gvf = op.G * vf;
  const Eigen::MatrixXd GR = op.G * modes.modes;  // m x k
  const Eigen::VectorXd Rf = modes.modes.transpose() * f;
  Eigen::MatrixXd S(m, m);  // columns valid where have_column
  std::vector<char> have_column(m, 0);
  // The trailing block is the face (plus what the ordering could not keep
  // apart); when it stays small, S comes whole from it.
  const int face_block_limit = 4 * int(face_eqs.size()) + 4000;
  if (opt.schur_from_factor && chol.trailing_size() <= face_block_limit) {
    const Eigen::SparseMatrix<double> Gt = Eigen::SparseMatrix<double>(Gp.transpose());
    const Eigen::MatrixXd Y = chol.half_solve_trailing(Gt);
    S.noalias() = Y.transpose() * Y;
    std::fill(have_column.begin(), have_column.end(), 1);
  }
  // Otherwise columns come from sparse solves, only for multipliers that
  // become active, each computed once.
  auto ensure_columns = [&](const std::vector<int>& want) {
    std::vector<int> missing;
    for (int K_ : want)
      if (!have_column[K_]) missing.push_back(K_);
    if (missing.empty()) return;
    Eigen::MatrixXd B = Eigen::MatrixXd::Zero(n, missing.size());
    for (size_t j = 0; j < missing.size(); ++j)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(Gp, missing[j]); it; ++it)
        B(it.col(), j) = it.value();
    const Eigen::MatrixXd Z = chol.solve(B);
    const Eigen::MatrixXd SZ = Gp * Z;
    for (size_t j = 0; j < missing.size(); ++j) {
      S.col(missing[j]) = SZ.col(j);
      have_column[missing[j]] = 1;
    }
    sol.schur_columns += int(missing.size());
  };
  sol.schur_s += since(t0);

  // Initial active set: closed initial gaps; a body not held otherwise
  // starts with the multipliers nearest to the obstacle.
  std::vector<char> active = initial_active_set(op, k, opt);
  const Eigen::VectorXd gap0 = op.g0.cwiseQuotient(op.weights);

  std::set<std::vector<char>> seen;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m), c = Eigen::VectorXd::Zero(k), Gu(m);
  const auto t_iter = Clock::now();
  for (int it = 0; it < opt.max_iterations; ++it) {
    seen.insert(active);
    std::vector<int> A;
    for (int K_ = 0; K_ < m; ++K_)
      if (active[K_]) A.push_back(K_);
    sol.active_set_sizes.push_back(int(A.size()));
    auto ts = Clock::now();
    ensure_columns(A);
    sol.schur_s += since(ts);
    const int na = int(A.size());
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(na + k, na + k);
    Eigen::VectorXd rhs(na + k);
    for (int i = 0; i < na; ++i) {
      for (int j = 0; j < na; ++j) M(i, j) = S(A[i], A[j]);
      for (int j = 0; j < k; ++j) M(i, na + j) = M(na + j, i) = -GR(A[i], j);
      rhs[i] = op.g0[A[i]] + Gvf[A[i]];
    }
    rhs.tail(k) = -Rf;
    Eigen::VectorXd x;
    if (na + k > 0) {
      Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
      if (lu.rank() < na + k) {
        sol.status = "singular contact system: the active multipliers do not hold the body's rigid motions";
        sol.u = Eigen::VectorXd::Zero(n);
        sol.lambda = Eigen::VectorXd::Zero(m);
        sol.active = active;
        sol.weighted_gap = gap0;
        return sol;
      }
      x = lu.solve(rhs);
    }
    lambda.setZero();
    for (int i = 0; i < na; ++i) lambda[A[i]] = x[i];
    c = x.tail(k);
    // G u = G v_f - S(:, A) lambda_A + G R c
    Gu = Gvf + GR * c;
    for (int i = 0; i < na; ++i) Gu -= S.col(A[i]) * lambda[A[i]];
    const Eigen::VectorXd gap = (op.g0 + Gu).cwiseQuotient(op.weights);
    const std::vector<char> next = next_active_set(lambda, gap, active, k, opt.complementarity_scale);
    sol.weighted_gap = gap;
    if (next == active) {
      sol.converged = true;
      sol.status = "converged";
      break;
    }
    if (seen.count(next)) {
      sol.status = fmt::format("active set cycling after {} iterations", it + 1);
      break;
    }
    active = next;
  }
  sol.iterations_s = since(t_iter);
  if (!sol.converged && sol.status.empty())
    sol.status = fmt::format("active set not settled in {} iterations", opt.max_iterations);

  // Final displacement: one more solve with the converged multipliers.
  t0 = Clock::now();
  Eigen::VectorXd rhs = fp - Gp.transpose() * lambda;
  sol.u = chol.solve(rhs);
  if (k > 0) sol.u += modes.modes * c;
  sol.iterations_s += since(t0);
  sol.lambda = lambda;
  sol.active = active;
  return sol;
}

}  // namespace igac
