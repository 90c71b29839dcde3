// SPDX-License-Identifier: BSD-3-Clause
#include "contact/finite_strain_friction.hpp"

#include "contact/small_strain_friction.hpp"

namespace igac {

FiniteStrainFriction::FiniteStrainFriction(const Body& body, const DofMap& dofs,
                                           const std::vector<FrictionContact>& contacts, const Eigen::VectorXd& weights,
                                           double complementarity_scale)
    : m_(int(weights.size())),
      nt_(dofs.dim() - 1),
      n_(dofs.num_free()),
      dim_(dofs.dim()),
      c_(complementarity_scale),
      contacts_(contacts),
      weights_(weights),
      friction_(Eigen::VectorXd::Zero(weights.size())) {
  // T on every dof (the body's own numbering: prescribed values are part
  // of u), from the small-deformation kernel; t0 of each motion at curve = 1.
  const DofMap every(body, {});
  std::vector<Eigen::Triplet<double>> t;
  for (const FrictionContact& c : contacts_) {
    t0_.push_back(Eigen::VectorXd::Zero(m_ * nt_));
    tangents_.push_back(Eigen::MatrixXd::Zero(dim_, nt_));
    if (!(c.friction > 0)) continue;  // a frictionless contact among frictional ones: lambda_t = 0
    const Eigen::VectorXd shift = c.motion.size() ? c.motion : Eigen::VectorXd::Zero(dim_);
    const WeightedGapOperator op = assemble_weighted_gaps(every, *c.face, *c.obstacle, c.friction, shift);
    const int count = int(op.weights.size());
    friction_.segment(c.offset, count) = op.friction;
    t0_.back().segment(c.offset * nt_, count * nt_) = op.t0;
    tangents_.back() = tangent_basis(c.obstacle->probe(Eigen::VectorXd::Zero(dim_)).normal);
    for (int r = 0; r < op.T.outerSize(); ++r)
      for (RowSparse::InnerIterator it(op.T, r); it; ++it) t.emplace_back(c.offset * nt_ + r, int(it.col()), it.value());
  }
  T_all_.resize(m_ * nt_, every.num_dofs());
  T_all_.setFromTriplets(t.begin(), t.end());
  std::vector<Eigen::Triplet<double>> tf;
  for (int r = 0; r < T_all_.outerSize(); ++r)
    for (RowSparse::InnerIterator it(T_all_, r); it; ++it)
      if (dofs.equation(int(it.col())) >= 0) tf.emplace_back(r, dofs.equation(int(it.col())), it.value());
  T_free_.resize(m_ * nt_, n_);
  T_free_.setFromTriplets(tf.begin(), tf.end());
  tau_prev_ = slip_total_ = Eigen::VectorXd::Zero(m_ * nt_);
  row_weights_.resize(m_ * nt_);
  for (int K = 0; K < m_; ++K) row_weights_.segment(K * nt_, nt_).setConstant(weights_[K]);
}

Eigen::VectorXd FiniteStrainFriction::position(double t, const Eigen::MatrixXd& u) const {
  Eigen::VectorXd uv(u.size());
  for (int a = 0; a < u.rows(); ++a)
    for (int i = 0; i < dim_; ++i) uv[a * dim_ + i] = u(a, i);
  Eigen::VectorXd tau = T_all_ * uv;
  for (size_t k = 0; k < contacts_.size(); ++k)
    if (contacts_[k].motion.size()) tau += (*contacts_[k].curve)(t)*t0_[k];
  return tau;
}

void FiniteStrainFriction::begin_step(double t, const Eigen::MatrixXd& u) {
  const Eigen::VectorXd tau = position(t, u);
  if (started_ && t != t_prev_) slip_total_ += (tau - tau_prev_).cwiseQuotient(row_weights_);
  started_ = true;
  t_prev_ = t;
  tau_prev_ = tau;
}

Eigen::VectorXd FiniteStrainFriction::accumulated_slip(double t, const Eigen::MatrixXd& u) const {
  return slip_total_ + slip(t, u).cwiseQuotient(row_weights_);
}

std::vector<char> FiniteStrainFriction::states(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n,
                                               const Eigen::VectorXd& gamma, const std::vector<char>& normal_active,
                                               const Eigen::VectorXd& lambda_t) const {
  const Eigen::VectorXd s = slip(t, u);
  std::vector<char> out(m_, kOpen);
  for (int K = 0; K < m_; ++K) {
    if (!normal_active[K]) continue;
    if (!(friction_[K] > 0)) {  // frictionless: always sliding, no force
      out[K] = kSlip;
      continue;
    }
    const double w = weights_[K];
    const Eigen::VectorXd xi = lambda_t.segment(K * nt_, nt_) + c_ / w * s.segment(K * nt_, nt_);
    const double b = -friction_[K] * (lambda_n[K] + c_ * gamma[K] / w);
    out[K] = xi.norm() <= b ? kStick : kSlip;
  }
  return out;
}

void FiniteStrainFriction::residual(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n,
                                    const Eigen::VectorXd& gamma, const std::vector<char>& normal_active,
                                    const Eigen::VectorXd& lambda_t, Eigen::Ref<Eigen::VectorXd> r_u,
                                    Eigen::Ref<Eigen::VectorXd> r_t) const {
  r_u += T_free_.transpose() * lambda_t;
  const Eigen::VectorXd s = slip(t, u);
  const std::vector<char> st = states(t, u, lambda_n, gamma, normal_active, lambda_t);
  for (int K = 0; K < m_; ++K) {
    const double w = weights_[K];
    const auto lt = lambda_t.segment(K * nt_, nt_);
    auto r = r_t.segment(K * nt_, nt_);
    if (st[K] == kStick) {
      r = c_ * s.segment(K * nt_, nt_);
    } else if (st[K] == kSlip && friction_[K] > 0) {
      const Eigen::VectorXd xi = lt + c_ / w * s.segment(K * nt_, nt_);
      const double b = -friction_[K] * (lambda_n[K] + c_ * gamma[K] / w);
      r = w * (lt - b / xi.norm() * xi);
    } else {
      r = w * lt;
    }
  }
}

void FiniteStrainFriction::jacobian(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n,
                                    const Eigen::VectorXd& gamma, const std::vector<char>& normal_active,
                                    const Eigen::VectorXd& lambda_t, const RowSparse& G,
                                    std::vector<Eigen::Triplet<double>>& out) const {
  const int first = n_ + m_;  // the first tangential unknown (and row)
  for (int r = 0; r < T_free_.outerSize(); ++r)
    for (RowSparse::InnerIterator it(T_free_, r); it; ++it) out.emplace_back(int(it.col()), first + r, it.value());
  const Eigen::VectorXd s = slip(t, u);
  const std::vector<char> st = states(t, u, lambda_n, gamma, normal_active, lambda_t);
  for (int K = 0; K < m_; ++K) {
    const double w = weights_[K];
    const int row = first + K * nt_;
    if (st[K] == kStick) {
      for (int j = 0; j < nt_; ++j)
        for (RowSparse::InnerIterator it(T_free_, K * nt_ + j); it; ++it)
          out.emplace_back(row + j, int(it.col()), c_ * it.value());
    } else if (st[K] == kSlip && friction_[K] > 0) {
      // r = w Phi(lambda_t, s / w, b), b = -f (lambda_n + c gamma / w)
      const double f = friction_[K];
      const Eigen::VectorXd lt = lambda_t.segment(K * nt_, nt_), sk = s.segment(K * nt_, nt_) / w;
      const double b = -f * (lambda_n[K] + c_ * gamma[K] / w);
      const SlipLinearisation lin = linearise_slip(lt, sk, b, c_);
      for (int i = 0; i < nt_; ++i) {
        for (int j = 0; j < nt_; ++j) {
          out.emplace_back(row + i, row + j, w * lin.d_lambda_t(i, j));
          // d s_K / du = T: w d_s (1 / w) T
          if (lin.d_s(i, j) != 0.0)
            for (RowSparse::InnerIterator it(T_free_, K * nt_ + j); it; ++it)
              out.emplace_back(row + i, int(it.col()), lin.d_s(i, j) * it.value());
        }
        // w d_b db: db = -f dlambda_n - f c / w dgamma
        out.emplace_back(row + i, n_ + K, w * lin.d_b[i] * -f);
        for (RowSparse::InnerIterator it(G, K); it; ++it)
          out.emplace_back(row + i, int(it.col()), lin.d_b[i] * -f * c_ * it.value());
      }
    } else {
      for (int j = 0; j < nt_; ++j) out.emplace_back(row + j, row + j, w);
    }
  }
}

Eigen::VectorXd FiniteStrainFriction::tangential_resultant(int k, const Eigen::VectorXd& lambda_t) const {
  Eigen::VectorXd F = Eigen::VectorXd::Zero(dim_);
  const int first = contacts_[k].offset, past = k + 1 < int(contacts_.size()) ? contacts_[k + 1].offset : m_;
  for (int K = first; K < past; ++K) F -= weights_[K] * (tangents_[k] * lambda_t.segment(K * nt_, nt_));
  return F;
}

}  // namespace igac
