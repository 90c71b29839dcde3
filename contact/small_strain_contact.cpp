// SPDX-License-Identifier: BSD-3-Clause
#include "contact/small_strain_contact.hpp"

#include <algorithm>

#include "engine/bordered_spd.hpp"
#include "engine/stopwatch.hpp"
#include <memory>
#include <fmt/format.h>
#include <set>

namespace igac {
namespace {
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// What the active-set iterations need of K^-1: S_AA, G K^-1 f, and
// G K^-1 G_A^T lambda_A for every multiplier.  Columns Y_K = L^-1 P G_K^T of
// the multipliers that become active are computed on the reach of the
// contact zone, each once; gaps come from a backward solve on the reach of
// the face (with the face ordered last, both are the trailing block).
class ActiveSchur {
 public:
  ActiveSchur(const SparseCholesky& chol, const RowSparse& Gp, const Eigen::VectorXd& fp, ContactSolution& sol)
      : chol_(chol), Gp_(Gp), sol_(sol), slot_(Gp.rows(), -1) {
    face_ = chol.reach(equations_of(all_multipliers()));
    sol.reach_rows = int(face_.rows.size());
    face_local_.assign(chol.size(), -1);
    for (size_t i = 0; i < face_.rows.size(); ++i) face_local_[face_.rows[i]] = int(i);
    const Eigen::VectorXd yf = chol.forward_full(fp);
    yf_face_.resize(Eigen::Index(face_.rows.size()));
    for (size_t i = 0; i < face_.rows.size(); ++i) yf_face_[i] = yf[face_.rows[i]];
  }
  Eigen::VectorXd G_solve_f() const { return G_times_backward(yf_face_); }
  // Makes the columns of A available; returns S_AA.
  Eigen::MatrixXd S_active(const std::vector<int>& A) {
    std::vector<int> fresh;
    for (int K : A)
      if (slot_[K] < 0) fresh.push_back(K);
    if (!fresh.empty()) add_columns(fresh);
    std::vector<int> s(A.size());
    for (size_t i = 0; i < A.size(); ++i) s[i] = slot_[A[i]];
    return S_(s, s);
  }
  // G K^-1 G_A^T lambda_A for all multipliers (lambda zero outside A).
  Eigen::VectorXd G_solve_Gt(const std::vector<int>& A, const Eigen::VectorXd& lambda) const {
    Eigen::VectorXd y = Eigen::VectorXd::Zero(yf_face_.size());
    Eigen::VectorXd ly = Eigen::VectorXd::Zero(Y_.cols());
    for (int K : A) ly[slot_[K]] = lambda[K];
    const Eigen::VectorXd yl = Y_ * ly;
    for (size_t i = 0; i < zone_.rows.size(); ++i) y[face_local_[zone_.rows[i]]] = yl[i];
    return G_times_backward(y);
  }

 private:
  std::vector<int> all_multipliers() const {
    std::vector<int> all(Gp_.rows());
    for (int K = 0; K < int(all.size()); ++K) all[K] = K;
    return all;
  }
  std::vector<int> equations_of(const std::vector<int>& multipliers) const {
    std::vector<int> eqs;
    for (int K : multipliers)
      for (RowSparse::InnerIterator it(Gp_, K); it; ++it) eqs.push_back(it.col());
    return eqs;
  }
  // G P^T x for x = L^-T y on the face's reach (G reads x there only).
  Eigen::VectorXd G_times_backward(const Eigen::VectorXd& y) const {
    const Eigen::VectorXd x = chol_.backward(face_, y);
    Eigen::VectorXd out = Eigen::VectorXd::Zero(Gp_.rows());
    for (int K = 0; K < Gp_.rows(); ++K)
      for (RowSparse::InnerIterator it(Gp_, K); it; ++it)
        out[K] += it.value() * x[face_local_[chol_.position(it.col())]];
    return out;
  }
  // One blocked forward pass for the new columns on the grown zone reach.
  void add_columns(const std::vector<int>& fresh) {
    std::vector<int> all = ever_;
    all.insert(all.end(), fresh.begin(), fresh.end());
    SparseCholesky::Reach zone = chol_.reach(equations_of(all));
    // the old columns, laid out on the new rows (zero on the rows added)
    Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(Eigen::Index(zone.rows.size()), Eigen::Index(all.size()));
    {
      std::vector<int> at(chol_.size(), -1);
      for (size_t i = 0; i < zone.rows.size(); ++i) at[zone.rows[i]] = int(i);
      for (size_t i = 0; i < zone_.rows.size(); ++i) Y.row(at[zone_.rows[i]]).head(Y_.cols()) = Y_.row(i);
    }
    Eigen::SparseMatrix<double> C(Gp_.cols(), Eigen::Index(fresh.size()));
    {
      std::vector<Eigen::Triplet<double>> t;
      for (size_t j = 0; j < fresh.size(); ++j)
        for (RowSparse::InnerIterator it(Gp_, fresh[j]); it; ++it) t.emplace_back(it.col(), int(j), it.value());
      C.setFromTriplets(t.begin(), t.end());
    }
    Y.rightCols(Eigen::Index(fresh.size())) = chol_.forward(zone, C);
    const Eigen::Index old = Y_.cols(), total = Eigen::Index(all.size());
    Eigen::MatrixXd S(total, total);
    S.topLeftCorner(old, old) = S_;
    S.rightCols(total - old).noalias() = Y.transpose() * Y.rightCols(total - old);
    S.bottomLeftCorner(total - old, old) = S.topRightCorner(old, total - old).transpose();
    for (size_t j = 0; j < fresh.size(); ++j) slot_[fresh[j]] = int(old + j);
    S_ = std::move(S);
    Y_ = std::move(Y);
    zone_ = std::move(zone);
    ever_ = std::move(all);
    sol_.schur_columns += int(fresh.size());
  }

  const SparseCholesky& chol_;
  const RowSparse& Gp_;
  ContactSolution& sol_;
  SparseCholesky::Reach face_;    // reach of every contact-face equation
  std::vector<int> face_local_;   // factor position -> row in face_ (-1: outside)
  Eigen::VectorXd yf_face_;       // L^-1 P f_p on face_
  SparseCholesky::Reach zone_;    // reach of the multipliers with a column
  std::vector<int> ever_;         // those multipliers, in column order
  std::vector<int> slot_;         // multiplier -> column (-1: none yet)
  Eigen::MatrixXd Y_;             // zone_.rows x ever_
  Eigen::MatrixXd S_;             // ever_ x ever_
};
}  // namespace

std::vector<char> initial_active_set(const WeightedGapOperator& op, int k, const ContactSolverOptions& opt) {
  const int m = int(op.weights.size());
  std::vector<char> active(m, 0);
  const Eigen::VectorXd gap0 = op.g0.cwiseQuotient(op.weights);
  const bool given = int(opt.initial_active.size()) == m;
  for (int K_ = 0; K_ < m; ++K_) active[K_] = given ? opt.initial_active[K_] : gap0[K_] <= opt.initial_gap_tolerance;
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

bool settle_active_set(const std::vector<char>& next, std::vector<char>& active, std::set<std::vector<char>>& seen,
                       int iteration, ContactSolution& sol, const ContactSolverOptions& opt) {
  if (opt.on_iteration) {
    int changed = 0;
    for (size_t K = 0; K < next.size(); ++K) changed += next[K] != active[K];
    opt.on_iteration(iteration, sol.active_set_sizes.empty() ? 0 : sol.active_set_sizes.back(), changed,
                     sol.linear_iterations.size() == sol.active_set_sizes.size() ? sol.linear_iterations.back() : -1);
  }
  if (next == active) {
    sol.converged = true;
    sol.status = "converged";
    return true;
  }
  seen.insert(active);
  if (seen.count(next)) {
    sol.status = fmt::format("active set cycling after {} iterations", iteration + 1);
    return true;
  }
  active = next;
  return false;
}

ContactSolution solve_small_strain_contact(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f,
                                           const WeightedGapOperator& op, const RigidModes& modes,
                                           SparseCholesky& chol, const ContactSolverOptions& opt) {
  ContactSolution sol;
  const int n = int(K.rows()), m = int(op.weights.size()), k = int(modes.modes.cols());
  std::vector<char> pinned(n, 0);
  for (int p : modes.pinned) pinned[p] = 1;
  std::vector<int> face_eqs;  // the equations G touches
  {
    std::vector<char> on_face(n, 0);
    for (int r = 0; r < op.G.outerSize(); ++r)
      for (RowSparse::InnerIterator it(op.G, r); it; ++it) on_face[it.col()] = !pinned[it.col()];
    for (int i = 0; i < n; ++i)
      if (on_face[i]) face_eqs.push_back(i);
  }
  Stopwatch clock;
  const Eigen::SparseMatrix<double> Kp = pin_equations(K, modes.pinned);
  chol.analyze(Kp, opt.face_last ? face_eqs : std::vector<int>{});
  chol.factorize(Kp);
  sol.factorize_s = clock.seconds();

  // G with the pinned columns removed (they carry no unknown of K_p).
  RowSparse Gp = op.G;
  for (int r = 0; r < Gp.outerSize(); ++r)
    for (RowSparse::InnerIterator it(Gp, r); it; ++it)
      if (pinned[it.col()]) it.valueRef() = 0.0;
  Gp.prune(0.0);
  Eigen::VectorXd fp = f;
  for (int p : modes.pinned) fp[p] = 0.0;

  clock.restart();
  ActiveSchur schur(chol, Gp, fp, sol);
  const Eigen::VectorXd Gvf = schur.G_solve_f();
  const Eigen::MatrixXd GR = op.G * modes.modes;  // m x k
  const Eigen::VectorXd Rf = modes.modes.transpose() * f;
  sol.schur_s += clock.seconds();

  // Initial active set: closed initial gaps; a body not held otherwise
  // starts with the multipliers nearest to the obstacle.
  std::vector<char> active = initial_active_set(op, k, opt);
  const Eigen::VectorXd gap0 = op.g0.cwiseQuotient(op.weights);

  std::set<std::vector<char>> seen;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(m), c = Eigen::VectorXd::Zero(k), Gu(m);
  const Stopwatch iterations_clock;
  double schur_in_loop = 0;
  for (int it = 0; it < opt.max_iterations; ++it) {
    std::vector<int> A;
    for (int K_ = 0; K_ < m; ++K_)
      if (active[K_]) A.push_back(K_);
    sol.active_set_sizes.push_back(int(A.size()));
    Stopwatch schur_clock;
    const Eigen::MatrixXd S_AA = schur.S_active(A);
    schur_in_loop += schur_clock.seconds();
    const int na = int(A.size());
    // [S_AA -G_A R; -R^T G_A^T 0] [lambda_A; c] = [g0_A + G_A K^-1 f; -R^T f]
    Eigen::VectorXd r1(na);
    Eigen::MatrixXd GRa(na, k);
    for (int i = 0; i < na; ++i) {
      GRa.row(i) = GR.row(A[i]);
      r1[i] = op.g0[A[i]] + Gvf[A[i]];
    }
    BorderedSpdSolver dense;
    if (!dense.compute(S_AA, GRa)) {
      sol.status = "singular contact system: the active multipliers do not hold the body's rigid motions";
      sol.u = Eigen::VectorXd::Zero(n);
      sol.lambda = Eigen::VectorXd::Zero(m);
      sol.active = active;
      sol.weighted_gap = gap0;
      return sol;
    }
    Eigen::VectorXd x;
    dense.solve(r1, Rf, x, c);
    lambda.setZero();
    for (int i = 0; i < na; ++i) lambda[A[i]] = x[i];
    // G u = G v_f - G K^-1 G_A^T lambda_A + G R c
    schur_clock.restart();
    Gu = Gvf + GR * c - schur.G_solve_Gt(A, lambda);
    schur_in_loop += schur_clock.seconds();
    const Eigen::VectorXd gap = (op.g0 + Gu).cwiseQuotient(op.weights);
    const std::vector<char> next = next_active_set(lambda, gap, active, k, opt.complementarity_scale);
    sol.weighted_gap = gap;
    if (settle_active_set(next, active, seen, it, sol, opt)) break;
  }
  sol.schur_s += schur_in_loop;
  sol.iterations_s = iterations_clock.seconds() - schur_in_loop;
  if (!sol.converged && sol.status.empty())
    sol.status = fmt::format("active set not settled in {} iterations", opt.max_iterations);

  // Final displacement: one more solve with the converged multipliers.
  clock.restart();
  Eigen::VectorXd rhs = fp - Gp.transpose() * lambda;
  sol.u = chol.solve(rhs);
  if (k > 0) sol.u += modes.modes * c;
  sol.iterations_s += clock.seconds();
  sol.lambda = lambda;
  sol.active = active;
  return sol;
}

}  // namespace igac
