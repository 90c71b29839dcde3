// SPDX-License-Identifier: BSD-3-Clause
#include "contact/small_strain_contact.hpp"

#include <algorithm>

#include "contact/active_schur.hpp"
#include "engine/bordered_spd.hpp"
#include "engine/stopwatch.hpp"
#include <memory>
#include <fmt/format.h>
#include <set>

namespace igac {

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
                                  const std::vector<char>& active, int k, double cn, int* forced) {
  const int m = int(lambda.size());
  // Round-off guard: where |lambda_K + c_n g_K| is below round-off of the
  // larger of the two terms, the multiplier keeps its state (at zero load
  // both vanish and nothing changes).
  const double scale = m ? std::max(lambda.cwiseAbs().maxCoeff(), cn * gap.cwiseAbs().maxCoeff()) : 0.0;
  const double tol = 1e-12 * scale;
  std::vector<char> next(m, 0);
  for (int K_ = 0; K_ < m; ++K_) {
    next[K_] = unilateral_closed(lambda[K_] + cn * gap[K_], active[K_], tol);
  }
  if (forced) *forced = 0;
  if (k > 0 && std::count(next.begin(), next.end(), 1) < k) {
    // A body held only by contact needs k active multipliers: keep the
    // ones nearest to activation.
    std::vector<int> order(m);
    for (int i = 0; i < m; ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return lambda[a] + cn * gap[a] < lambda[b] + cn * gap[b]; });
    for (int i = 0; i < std::min(k, m); ++i) {
      const int K = order[i];
      if (forced && !next[K] && lambda[K] + cn * gap[K] > tol) ++*forced;
      next[K] = 1;
    }
  }
  return next;
}

bool load_pulls_off(const Eigen::VectorXd& Gr, double push, double f_scale) {
  const double scale = Gr.size() ? Gr.cwiseAbs().maxCoeff() : 0.0;
  if (!(std::abs(push) > 1e-12 * f_scale) || scale == 0) return false;
  const Eigen::VectorXd opening = (push > 0 ? 1.0 : -1.0) * Gr;  // the gaps' change along the load's motion
  return opening.minCoeff() >= -1e-12 * scale && opening.maxCoeff() > 1e-12 * scale;
}

std::string pulled_off_status(int forced, const std::string& note) {
  return fmt::format("the load pulls the body off the contact, and nothing else holds it ({}{}{})",
                     forced > 0 ? fmt::format("{} multiplier(s) would have to pull to hold its free rigid motion(s)",
                                              forced)
                                : "its free rigid motion, along the load, opens every gap",
                     note.empty() ? "" : "; ", note);
}

bool settle_active_set(const std::vector<char>& next, std::vector<char>& active, std::set<std::vector<char>>& seen,
                       int iteration, ContactSolution& sol, const ContactSolverOptions& opt, int forced) {
  if (opt.on_iteration) {
    int changed = 0;
    for (size_t K = 0; K < next.size(); ++K) changed += next[K] != active[K];
    opt.on_iteration(iteration, sol.active_set_sizes.empty() ? 0 : sol.active_set_sizes.back(), changed,
                     sol.linear_iterations.size() == sol.active_set_sizes.size() ? sol.linear_iterations.back() : -1);
  }
  if (next == active && forced > 0) {
    sol.status = pulled_off_status(forced);
    return true;
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
  // One free rigid motion that the load drives off the contact: no
  // solution (the iteration would keep a multiplier pulling, or cycle).
  if (k == 1 && load_pulls_off(GR.col(0), Rf[0], f.norm())) {
    sol.status = pulled_off_status();
    sol.u = Eigen::VectorXd::Zero(n);
    sol.lambda = Eigen::VectorXd::Zero(m);
    sol.active.assign(m, 0);
    sol.weighted_gap = gap0;
    return sol;
  }

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
    int forced = 0;
    const std::vector<char> next = next_active_set(lambda, gap, active, k, opt.complementarity_scale, &forced);
    sol.weighted_gap = gap;
    if (settle_active_set(next, active, seen, it, sol, opt, forced)) break;
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
