// SPDX-License-Identifier: BSD-3-Clause
#include "contact/small_strain_friction.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <set>
#include <stdexcept>

#include "contact/active_schur.hpp"
#include "engine/bordered_spd.hpp"
#include "engine/free_cores.hpp"

namespace igac {

struct SmallStrainFriction::Impl {
  int n = 0, m = 0, nt = 0, k = 0;
  double cn = 1;
  Eigen::VectorXd ct;  // c_t per multiplier (tangential_scales)
  int max_iterations = 100;
  double touch_tolerance = 1e-9;  // a gap (length) this small is touching (ContactSolverOptions::initial_gap_tolerance)
  const RigidModes& modes;
  SparseCholesky& chol;
  RowSparse Gs, Gsp;    // [G; T], and without the pinned columns
  Eigen::VectorXd fp, Gvf, Rf;
  Eigen::MatrixXd GR;   // [G; T] R
  ContactSolution counters;  // the Schur columns computed over all steps
  std::unique_ptr<ActiveSchur> schur;
  // History: the weighted tangential position T u + t0 where the last step
  // ended, the accumulated slip, and the state and slip direction of each
  // multiplier (the next step starts from them).
  Eigen::VectorXd tau_prev, slip_total;
  std::vector<char> state;
  Eigen::MatrixXd dir;  // m x nt
  Eigen::VectorXd alpha;  // b / |xi| where the slip direction was last taken (3D: the linearised slip law)
  Eigen::VectorXd g_start;  // the weighted gaps where the run starts: a tie holds them

  // A linear backend (engine/linear_backend.hpp) instead of the Schur
  // complement on CHOLMOD's factor: each iteration's sparse saddle system
  // solved whole (PETSc's, on one or more processes).  K and f unpinned.
  LinearBackend* backend = nullptr;
  Eigen::SparseMatrix<double> K;
  Eigen::VectorXd f;
  Eigen::VectorXd u_last;  // the backend's last solution's displacements

  Impl(const RigidModes& md, SparseCholesky& c) : modes(md), chol(c) {}
  int trow(int K, int j) const { return m + K * nt + j; }
};

SmallStrainFriction::~SmallStrainFriction() = default;

namespace {
// Iterative refinement of an iteration's dense system on the factors of an
// earlier one (same states): at most this many steps, each contracting the
// residual ten times, until its max-norm is at most kRefinedBackwardError
// (|A| |x| + |r|), within ten times the backward error a partial-pivoting LU
// leaves on these systems (1.5e-15 on bench/flat_punch_friction.toml, where
// each step contracts by 0.07: ten steps, a tenth of an LU's flops).
constexpr int kMaxRefinements = 15;
constexpr double kRefinedBackwardError = 1e-14;
// The state a closed multiplier starts from: stuck where its law has
// tangential rows; a frictionless one (beside frictional ones) slides from
// the start, its tangential rows being zero (a stick unknown there has no
// column: the system was singular at the first iteration).
char closed_state(const InterfaceLaw& law) { return law.tangential() ? kStick : kSlip; }
}  // namespace

double slip_compliance(double alpha, double ct) {
  const double a = std::clamp(alpha, kMinAlpha, 1.0);
  return (1 - a) / (a * ct);
}

Eigen::VectorXd per_multiplier_scales(double cn, double mesh_size, const Eigen::VectorXd& weights, int dim,
                                      double factor) {
  Eigen::VectorXd ct = Eigen::VectorXd::Constant(weights.size(), cn);
  if (mesh_size > 0)
    for (int K = 0; K < weights.size(); ++K)
      if (weights[K] > 0) ct[K] = factor * cn * mesh_size / std::pow(weights[K], 1.0 / (dim - 1));
  return ct;
}

Eigen::VectorXd tangential_scales(double cn, double mesh_size, const Eigen::VectorXd& weights, int dim) {
  if (dim == 3) return per_multiplier_scales(cn, mesh_size, weights, dim, 1.0);
  return Eigen::VectorXd::Constant(weights.size(), cn);
}

SlipLinearisation linearise_slip(const Eigen::VectorXd& lambda_t, const Eigen::VectorXd& s, double b, double ct) {
  const Eigen::VectorXd xi = lambda_t + ct * s;
  const double norm = xi.norm();
  SlipLinearisation out;
  out.v = xi / norm;
  const double alpha = b / norm;
  const Eigen::MatrixXd P = Eigen::MatrixXd::Identity(xi.size(), xi.size()) - out.v * out.v.transpose();
  out.d_lambda_t = Eigen::MatrixXd::Identity(xi.size(), xi.size()) - alpha * P;
  out.d_s = -alpha * ct * P;
  out.d_b = -out.v;
  return out;
}

SmallStrainFriction::SmallStrainFriction(const Eigen::SparseMatrix<double>& K, const Eigen::VectorXd& f,
                                         const WeightedGapOperator& op, const RigidModes& modes, SparseCholesky& chol,
                                         const ContactSolverOptions& opt, LinearBackend* backend)
    : impl_(std::make_unique<Impl>(modes, chol)) {
  Impl& s = *impl_;
  s.backend = backend;
  s.n = int(K.rows());
  s.m = int(op.weights.size());
  s.nt = s.m ? int(op.T.rows() / s.m) : 0;
  s.k = int(modes.modes.cols());
  s.cn = opt.complementarity_scale;
  s.ct = tangential_scales(s.cn, opt.mesh_size, op.weights, s.nt + 1);
  s.max_iterations = std::max(opt.max_iterations, 100);
  s.touch_tolerance = opt.initial_gap_tolerance;
  s.Gs.resize(s.m * (1 + s.nt), s.n);
  {
    std::vector<Eigen::Triplet<double>> t;
    for (int r = 0; r < op.G.outerSize(); ++r)
      for (RowSparse::InnerIterator it(op.G, r); it; ++it) t.emplace_back(r, int(it.col()), it.value());
    for (int r = 0; r < op.T.outerSize(); ++r)
      for (RowSparse::InnerIterator it(op.T, r); it; ++it) t.emplace_back(s.m + r, int(it.col()), it.value());
    s.Gs.setFromTriplets(t.begin(), t.end());
  }
  std::vector<char> pinned(s.n, 0);
  for (int p : modes.pinned) pinned[p] = 1;
  std::vector<int> face_eqs;
  {
    std::vector<char> on_face(s.n, 0);
    for (int r = 0; r < s.Gs.outerSize(); ++r)
      for (RowSparse::InnerIterator it(s.Gs, r); it; ++it) on_face[it.col()] = !pinned[it.col()];
    for (int i = 0; i < s.n; ++i)
      if (on_face[i]) face_eqs.push_back(i);
  }
  if (backend) {
    s.K = K;
    s.f = f;
    s.fp = f;
    for (int p : modes.pinned) s.fp[p] = 0.0;
  } else {
    const Eigen::SparseMatrix<double> Kp = pin_equations(K, modes.pinned);
    chol.analyze(Kp, opt.face_last ? face_eqs : std::vector<int>{});
    chol.factorize(Kp);
    s.Gsp = s.Gs;
    for (int r = 0; r < s.Gsp.outerSize(); ++r)
      for (RowSparse::InnerIterator it(s.Gsp, r); it; ++it)
        if (pinned[it.col()]) it.valueRef() = 0.0;
    s.Gsp.prune(0.0);
    s.fp = f;
    for (int p : modes.pinned) s.fp[p] = 0.0;
    s.schur = std::make_unique<ActiveSchur>(chol, s.Gsp, s.fp, s.counters);
    s.Gvf = s.schur->G_solve_f();
  }
  s.GR = s.Gs * modes.modes;
  s.Rf = modes.modes.transpose() * f;
  s.tau_prev = Eigen::VectorXd::Zero(s.m * s.nt);  // u = 0, the obstacle where the first step has it
  s.slip_total = Eigen::VectorXd::Zero(s.m * s.nt);
  const std::vector<char> active = initial_active_set(op, s.k, opt);
  s.state.assign(s.m, kOpen);
  // (a tie is closed from the start, and holds the gap it starts with)
  for (int i = 0; i < s.m; ++i)
    s.state[i] = active[i] || op.law(i).bilateral() ? closed_state(op.law(i)) : char(kOpen);
  s.g_start = op.g0;
  s.dir = Eigen::MatrixXd::Zero(s.m, s.nt);
  if (s.nt > 0) s.dir.col(0).setOnes();
  s.alpha = Eigen::VectorXd::Ones(s.m);
}

void SmallStrainFriction::set_load(const Eigen::VectorXd& f) {
  Impl& s = *impl_;
  s.fp = f;
  for (int p : s.modes.pinned) s.fp[p] = 0.0;
  s.Rf = s.modes.modes.transpose() * f;
  if (s.backend) {
    s.f = f;
    return;
  }
  s.Gvf = s.Gsp * Eigen::VectorXd(s.chol.solve(s.fp));  // G K^-1 f (the pinned K), as ActiveSchur::G_solve_f
  s.Rf = s.modes.modes.transpose() * f;
}

void SmallStrainFriction::start_from(const WeightedGapOperator& op0) {
  impl_->tau_prev = op0.t0;
  impl_->g_start = op0.g0;
}

FrictionHistory SmallStrainFriction::history() const {
  const Impl& s = *impl_;
  FrictionHistory h;
  h.position = s.tau_prev;
  h.slip = s.slip_total;
  h.state = s.state;
  h.direction = Eigen::VectorXd(s.m * s.nt);
  for (int K = 0; K < s.m; ++K)
    for (int j = 0; j < s.nt; ++j) h.direction[K * s.nt + j] = s.dir(K, j);
  h.alpha = s.alpha;
  if (s.schur) h.schur_batches = s.schur->batches();
  return h;
}

void SmallStrainFriction::restore(const FrictionHistory& h) {
  Impl& s = *impl_;
  if (h.position.size() != s.m * s.nt || h.slip.size() != s.m * s.nt || int(h.state.size()) != s.m ||
      h.direction.size() != s.m * s.nt || h.alpha.size() != s.m)
    throw std::invalid_argument("SmallStrainFriction::restore: a history of another contact");
  if (s.schur && !s.schur->batches().empty()) throw std::logic_error("SmallStrainFriction::restore: after a step");
  s.tau_prev = h.position;
  s.slip_total = h.slip;
  s.state = h.state;
  for (int K = 0; K < s.m; ++K)
    for (int j = 0; j < s.nt; ++j) s.dir(K, j) = h.direction[K * s.nt + j];
  s.alpha = h.alpha;
  for (const std::vector<int>& batch : h.schur_batches) {
    for (int K : batch)
      if (K < 0 || K >= s.m * (1 + s.nt)) throw std::invalid_argument("SmallStrainFriction::restore: a column beyond the rows");
    if (s.schur) s.schur->S_active(batch);
  }
}

namespace {
constexpr int kCycleRestarts = 4;
}  // namespace

ContactSolution SmallStrainFriction::step(const WeightedGapOperator& op) {
  Impl& s = *impl_;
  const int m = s.m, nt = s.nt, k = s.k, rows_all = m * (1 + nt);
  const Eigen::VectorXd& fr = op.friction;
  ContactSolution sol;
  Eigen::VectorXd r0(rows_all);
  r0.head(m) = op.g0;
  for (int K = 0; K < m; ++K)
    if (op.law(K).bilateral()) r0[K] -= s.g_start[K];  // a tie: g - g_0 = 0
  r0.tail(m * nt) = op.t0 - s.tau_prev;
  // One free rigid motion that the load drives off the contact: friction
  // needs a normal force, and no multiplier can push against this load.
  if (k == 1 && !op.bilateral() && load_pulls_off(s.GR.col(0).head(m), s.Rf[0], s.fp.norm())) {
    sol.status = pulled_off_status();
    sol.u = Eigen::VectorXd::Zero(s.n);
    sol.lambda = Eigen::VectorXd::Zero(m);
    sol.lambda_t = Eigen::VectorXd::Zero(m * nt);
    sol.active.assign(m, 0);
    sol.weighted_gap = op.g0.cwiseQuotient(op.weights);
    return sol;
  }

  // Nothing to apply (no load, no gap closed beyond touching, no tangential
  // offset; the first of a moving obstacle's steps often): the solution is
  // u = 0 and lambda = 0, and the states stay.  An iteration would decide them
  // on tractions at round-off, and the next step would start from there
  // (docs/benchmarks.md, "Friction in 3D").
  if (s.fp.isZero(0.0)) {
    bool at_rest = true;
    for (int K = 0; K < m && at_rest; ++K) {
      const double g = r0[K] / op.weights[K];
      at_rest = op.law(K).bilateral() ? std::abs(g) <= s.touch_tolerance : g >= -s.touch_tolerance;
      for (int l = 0; l < nt && at_rest; ++l) at_rest = std::abs(r0[s.trow(K, l)] / op.weights[K]) <= s.touch_tolerance;
    }
    if (at_rest) {
      sol.converged = true;
      sol.status = "converged";
      sol.u = Eigen::VectorXd::Zero(s.n);
      sol.lambda = Eigen::VectorXd::Zero(m);
      sol.lambda_t = Eigen::VectorXd::Zero(m * nt);
      sol.active.assign(m, 0);
      for (int K = 0; K < m; ++K) sol.active[K] = s.state[K] != kOpen;
      sol.weighted_gap = op.g0.cwiseQuotient(op.weights);
      s.tau_prev = op.t0;
      sol.slip = s.slip_total;
      sol.friction_state = s.state;
      sol.schur_columns = s.counters.schur_columns;
      sol.reach_rows = s.counters.reach_rows;
      return sol;
    }
  }

  // The unknowns of an iteration, each a combination of the stacked rows
  // [G; T]: its force direction H_j and its constraint row C_j (below).
  struct Unknown {
    std::vector<std::pair<int, double>> H, C;
    double diagonal = 0;  // + diagonal * x_j in its own constraint row
  };
  // The iteration's system on CHOLMOD's factor: the dense Schur complement of
  // the unknowns' columns, bordered by the rigid amplitudes c.  Gives lam (the
  // stacked multipliers), c and Gu = [G; T] u; false when singular.
  // A and the dense solver live across iterations: the last ones keep the
  // active set and only turn slip directions, and their matrices of the
  // same size reuse the memory (no fresh pages for 3000 x 3000 doubles).
  // Such an iteration's A differs from the factorised one only in the
  // sliding rows' directions (by the last turn, 1e-2 .. 1e-10): it is
  // solved by iterative refinement on the old factors, each step a product
  // with A instead of an LU, until the residual is at the round-off a
  // fresh LU leaves; a refinement that does not get there factorises.
  Eigen::MatrixXd A;
  BorderedLuSolver dense;
  std::vector<char> factored_states;  // the states `dense` was factorised for (empty: none)
  const auto refine_on_old_factors = [&](const Eigen::MatrixXd& Bc, const Eigen::MatrixXd& Bh,
                                         const Eigen::VectorXd& r, Eigen::VectorXd& x, Eigen::VectorXd& c) {
    dense.solve(r, s.Rf, x, c);
    const double scale_A = A.cwiseAbs().maxCoeff();
    double last = std::numeric_limits<double>::infinity();
    for (int step = 0; step < kMaxRefinements; ++step) {
      // residual of [A -Bc; -Bh^T 0] [x; c] = [r; -Rf]
      const Eigen::VectorXd rho_x = r - A * x + Bc * c, rho_c = Bh.transpose() * x - s.Rf;
      const double size = rho_x.cwiseAbs().maxCoeff() + (rho_c.size() ? rho_c.cwiseAbs().maxCoeff() : 0.0);
      const double bound = kRefinedBackwardError * (scale_A * x.cwiseAbs().maxCoeff() + r.cwiseAbs().maxCoeff());
      if (size <= bound) return true;
      if (!(size < 0.1 * last)) return false;  // not contracting: the old factors are too far
      last = size;
      Eigen::VectorXd dx, dc;
      dense.solve(rho_x, -rho_c, dx, dc);
      x += dx;
      c += dc;
    }
    return false;
  };
  const auto solve_schur = [&](const std::vector<Unknown>& unknowns, const std::vector<int>& cols,
                               const Eigen::VectorXd& r0, Eigen::VectorXd& lam, Eigen::VectorXd& c_out,
                               Eigen::VectorXd& Gu) -> bool {
  s.schur->prepare(cols);
  const int nc = int(unknowns.size());
  // [A -Bc; -Bh^T 0] [x; c] = [r; -R^T f]: A_ij = C_i . S H_j (+ D_jj), the rows of Bc and Bh
  // C_i . G R and H_j . G R.  C_i and H_j have one to three rows each, so A
  // is filled entry by entry from S, with no copy of S_AA.
  Eigen::MatrixXd Bc = Eigen::MatrixXd::Zero(nc, k), Bh = Eigen::MatrixXd::Zero(nc, k);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(nc);
  for (int i = 0; i < nc; ++i) {
    for (const auto& [row, a] : unknowns[i].C) {
      Bc.row(i) += a * s.GR.row(row);
      r[i] += a * (r0[row] + s.Gvf[row]);
    }
    for (const auto& [q, b] : unknowns[i].H) Bh.row(i) += b * s.GR.row(q);
  }
  A.resize(nc, nc);
  const ActiveSchur& schur = *s.schur;
#pragma omp parallel for schedule(dynamic, 64) num_threads(nc >= 256 ? free_cores() : 1)
  for (int j = 0; j < nc; ++j)
    for (int i = 0; i < nc; ++i) {
      double v = 0;
      for (const auto& [p, a] : unknowns[i].C) {
        double Sh = 0;  // (S H_j)_p
        for (const auto& [q, b] : unknowns[j].H) Sh += schur.S(p, q) * b;
        v += a * Sh;
      }
      A(i, j) = v + (i == j ? unknowns[j].diagonal : 0.0);
    }
  Eigen::VectorXd x;
  const bool refined = factored_states == s.state && refine_on_old_factors(Bc, Bh, r, x, c_out);
  if (!refined) {
    factored_states.clear();
    if (!dense.compute(A, Bc, Bh)) return false;
    factored_states = s.state;
    dense.solve(r, s.Rf, x, c_out);
  }
  lam.setZero();
  for (int j = 0; j < nc; ++j)
    for (const auto& [q, b] : unknowns[j].H) lam[q] += b * x[j];
  Gu = s.Gvf + s.GR * c_out - s.schur->G_solve_Gt(cols, lam);
  return true;
  };
  // The same system whole and sparse, by the linear backend:
  //   [ K    H^T ] [u]   [ f      ]
  //   [ C G  -D  ] [x] = [ -C r0  ]
  // (C G: each unknown's constraint row of [G; T], D its diagonal); K is not
  // pinned, the constraints hold the rigid motions (else it is singular).
  const auto solve_sparse = [&](const std::vector<Unknown>& unknowns, const Eigen::VectorXd& r0, Eigen::VectorXd& lam,
                                Eigen::VectorXd& Gu, std::string& why) -> bool {
    const int n = s.n, nc = int(unknowns.size());
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(s.K.nonZeros() + 4 * nc * 8);
    for (int col = 0; col < s.K.outerSize(); ++col)
      for (Eigen::SparseMatrix<double>::InnerIterator it(s.K, col); it; ++it) t.emplace_back(it.row(), it.col(), it.value());
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + nc);
    rhs.head(n) = s.f;
    for (int j = 0; j < nc; ++j) {
      for (const auto& [q, b] : unknowns[j].H)
        for (RowSparse::InnerIterator it(s.Gs, q); it; ++it) t.emplace_back(int(it.col()), n + j, b * it.value());
      for (const auto& [r, a] : unknowns[j].C) {
        for (RowSparse::InnerIterator it(s.Gs, r); it; ++it) t.emplace_back(n + j, int(it.col()), a * it.value());
        rhs[n + j] -= a * r0[r];
      }
      t.emplace_back(n + j, n + j, -unknowns[j].diagonal);
    }
    BlockJacobian J;
    J.K.resize(n + nc, n + nc);
    J.K.setFromTriplets(t.begin(), t.end());
    J.general = true;
    J.B.resize(0, n + nc);
    Eigen::VectorXd x;
    if (!s.backend->setup(J) || !s.backend->solve(rhs, x, 0)) {
      if (!s.backend->why().empty() && s.backend->why().find("singular") == std::string::npos) why = s.backend->why();
      return false;
    }
    lam.setZero();
    for (int j = 0; j < nc; ++j)
      for (const auto& [q, b] : unknowns[j].H) lam[q] += b * x[n + j];
    s.u_last = x.head(n);
    Gu = s.Gs * s.u_last;
    return true;
  };

  std::set<std::vector<char>> seen;
  // The tangential scale c_t of xi = lambda_t + c_t s (the normal one's
  // unless the iteration cycles, below).
  double ct_factor = 1;
  int restarts = 0;
  Eigen::VectorXd lam = Eigen::VectorXd::Zero(rows_all), c = Eigen::VectorXd::Zero(k), Gu(rows_all);
  Eigen::VectorXd gap(m), slip(m * nt);
  for (int it = 0; it < s.max_iterations; ++it) {
    // The unknowns, each a combination of the stacked rows [G; T]: its force
    // direction H_j and its constraint row C_j (the same but for a slip
    // multiplier's normal unknown, whose force is G_K - f v . T_K).  In 3D a
    // slip multiplier also has the tangential unknown across its slip
    // direction, w = v rotated in the tangent plane, with the linearised
    // slip law (docs/design.md, "Friction"): w . s_K = beta_K w . lambda_t,K.
    // Schur columns: every row of an active multiplier.
    std::vector<Unknown> unknowns;
    std::vector<int> cols;
    for (int K = 0; K < m; ++K)
      if (s.state[K] != kOpen) {
        Unknown u;
        u.C = {{K, 1.0}};
        u.H = u.C;
        if (s.state[K] == kSlip)
          for (int l = 0; l < nt; ++l) u.H.emplace_back(s.trow(K, l), -fr[K] * s.dir(K, l));
        unknowns.push_back(std::move(u));
        cols.push_back(K);
      }
    for (int K = 0; K < m; ++K)
      if (s.state[K] != kOpen)
        for (int j = 0; j < nt; ++j) {
          cols.push_back(s.trow(K, j));
          if (s.state[K] == kStick) unknowns.push_back({{{s.trow(K, j), 1.0}}, {{s.trow(K, j), 1.0}}});
        }
    if (nt == 2)
      for (int K = 0; K < m; ++K)
        if (s.state[K] == kSlip && fr[K] > 0) {
          const double w0 = -s.dir(K, 1), w1 = s.dir(K, 0);
          Unknown u;
          u.C = {{s.trow(K, 0), w0}, {s.trow(K, 1), w1}};
          u.H = u.C;
          u.diagonal = op.weights[K] * slip_compliance(s.alpha[K], ct_factor * s.ct[K]);
          unknowns.push_back(std::move(u));
        }
    sol.active_set_sizes.push_back(int(unknowns.size()));
    const bool solved = s.backend ? solve_sparse(unknowns, r0, lam, Gu, sol.status)
                                  : solve_schur(unknowns, cols, r0, lam, c, Gu);
    if (!solved) {
      // Friction's reason only where a frictional multiplier slides: stuck
      // ones hold the motion along the obstacle.
      bool sliding = false;
      for (int K = 0; K < m; ++K) sliding = sliding || (s.state[K] == kSlip && fr[K] > 0);
      if (sol.status.empty())
        sol.status = std::string("singular contact system: the active multipliers do not hold the body's rigid motions") +
                     (sliding ? " (with friction: a load along the obstacle above f times the normal force slides the "
                                "body away)"
                              : "");
      break;
    }
    gap = (op.g0 + Gu.head(m)).cwiseQuotient(op.weights);
    for (int K = 0; K < m; ++K)
      for (int l = 0; l < nt; ++l) slip[K * nt + l] = (Gu[s.trow(K, l)] + r0[s.trow(K, l)]) / op.weights[K];
    // The next states.
    const Eigen::VectorXd lam_n = lam.head(m), lam_t = lam.tail(m * nt);
    std::vector<char> active(m);
    for (int K = 0; K < m; ++K) active[K] = s.state[K] != kOpen;
    int forced = 0;
    // (a tie is closed whatever its sign: the rigid motions' extension of
    // next_active_set would count its pulling multipliers as forced)
    std::vector<char> next_active = next_active_set(lam_n, gap, active, op.bilateral() ? 0 : k, s.cn, &forced);
    const double scale = std::max({lam.cwiseAbs().maxCoeff(), s.cn * gap.cwiseAbs().maxCoeff(),
                                   nt ? s.cn * slip.cwiseAbs().maxCoeff() : 0.0});
    const double tol = 1e-12 * scale;
    std::vector<char> next(m, kOpen);
    Eigen::MatrixXd next_dir = s.dir;
    Eigen::VectorXd next_alpha = s.alpha;
    bool directions_settled = true, turned_back = false;
    for (int K = 0; K < m; ++K) {
      const InterfaceLaw& law = op.law(K);
      // (a unilateral law's rule, with the rigid motions' extension, is next_active_set's)
      if (law.bilateral()) next_active[K] = law.closed(lam_n[K] + s.cn * gap[K], true, tol);
      if (!next_active[K]) continue;
      if (!law.tangential()) {  // a frictionless contact among frictional ones: always sliding, no force
        next[K] = kSlip;
        continue;
      }
      const Eigen::VectorXd xi = lam_t.segment(K * nt, nt) + ct_factor * s.ct[K] * slip.segment(K * nt, nt);
      const double b = std::max(0.0, -fr[K] * (lam_n[K] + s.cn * gap[K]));
      const double norm = xi.norm();
      next[K] = law.tangential_state(norm, b, FrictionState(s.state[K]), tol);
      if (next[K] == kSlip && norm > tol) {
        next_dir.row(K) = (xi / norm).transpose();
        next_alpha[K] = b / norm;
        if ((next_dir.row(K) - s.dir.row(K)).norm() > 1e-10 && s.state[K] == kSlip) directions_settled = false;
        if (nt == 2 && s.state[K] == kSlip && next_dir.row(K).dot(s.dir.row(K)) < 0) turned_back = true;
      }
    }
    sol.weighted_gap = gap;
    if (next == s.state && directions_settled) {
      sol.converged = forced == 0;
      sol.status = forced == 0 ? "converged" : pulled_off_status(forced);
      break;
    }
    // A repeated state (with the signs of a 2D slip) is a cycle; so is, in
    // 3D, a slip direction turned back (more than 90 degrees in one
    // iteration): the same overshoot, whose directions never repeat exactly.
    std::vector<char> key = s.state;
    if (nt == 1)
      for (int K = 0; K < m; ++K) key[K] += s.state[K] == kSlip && s.dir(K, 0) < 0 ? 1 : 0;
    const bool keyed = nt == 1 || directions_settled;
    const bool repeated = keyed && seen.count(key);
    if ((repeated || turned_back) && restarts < kCycleRestarts) {
      // A cycle (seen when a step reverses the slip: slip one way, then
      // the other, never stick, c_t s overshooting the cone): the
      // iteration starts again from every closed multiplier stuck, the
      // elastic predictor of a return mapping, and after the first time
      // with c_t 10 times smaller (the solution does not depend on c_t).
      // Runs that do not cycle never come here: their iterations are as before.
      if (restarts++ > 0) ct_factor *= 0.1;
      seen.clear();
      for (int K = 0; K < m; ++K)
        if (next[K] != kOpen) next[K] = closed_state(op.law(K));
      s.state = next;
      continue;
    }
    if (repeated) {
      sol.status = fmt::format("active set cycling after {} iterations", it + 1);
      break;
    }
    if (keyed) seen.insert(key);
    s.state = next;
    s.dir = next_dir;
    s.alpha = next_alpha;
  }
  if (!sol.converged && sol.status.empty())
    sol.status = fmt::format("active set not settled in {} iterations", s.max_iterations);

  if (s.backend) {
    sol.u = s.u_last.size() == s.n ? s.u_last : Eigen::VectorXd::Zero(s.n);
  } else {
    Eigen::VectorXd u = s.chol.solve(Eigen::VectorXd(s.fp - s.Gsp.transpose() * lam));
    if (k > 0) u += s.modes.modes * c;
    sol.u = u;
  }
  sol.lambda = lam.head(m);
  sol.lambda_t = lam.tail(m * nt);
  sol.active.assign(m, 0);
  for (int K = 0; K < m; ++K) sol.active[K] = s.state[K] != kOpen;
  if (sol.converged) {
    s.tau_prev = Gu.tail(m * nt) + op.t0;
    s.slip_total += slip;
  }
  sol.slip = s.slip_total;
  sol.friction_state = s.state;
  sol.schur_columns = s.counters.schur_columns;
  sol.reach_rows = s.counters.reach_rows;
  return sol;
}

}  // namespace igac
