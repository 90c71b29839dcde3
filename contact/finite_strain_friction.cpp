// SPDX-License-Identifier: BSD-3-Clause
#include "contact/finite_strain_friction.hpp"

#include <algorithm>
#include <stdexcept>

#include "contact/small_strain_friction.hpp"

namespace igac {

Eigen::VectorXd finite_strain_tangential_scales(double cn, double mesh_size, const Eigen::VectorXd& weights, int dim) {
  if (dim == 3) return tangential_scales(cn, mesh_size, weights, dim);
  return per_multiplier_scales(cn, mesh_size, weights, dim, kTangentialScale2D);
}

FiniteStrainFriction::FiniteStrainFriction(const Body& body, const DofMap& dofs,
                                           const std::vector<FrictionContact>& contacts, const Eigen::VectorXd& weights,
                                           double complementarity_scale, const Eigen::VectorXd& tangential_scale)
    : m_(int(weights.size())),
      nt_(dofs.dim() - 1),
      n_(dofs.num_free()),
      dim_(dofs.dim()),
      c_(complementarity_scale),
      ct_(tangential_scale),
      contacts_(contacts),
      body_(&body),
      dofs_(&dofs),
      every_(body, {}),
      weights_(weights),
      friction_(Eigen::VectorXd::Zero(weights.size())) {
  for (const FrictionContact& c : contacts_) {
    masters_.push_back(c.master ? std::make_unique<MasterSurface>(*c.master) : nullptr);
    if (c.law.get().has_coefficient()) friction_.segment(c.offset, c.face->num_multipliers()).setConstant(c.law.friction);
  }
  laws_.assign(size_t(m_), nullptr);
  for (const FrictionContact& c : contacts_)
    std::fill_n(laws_.begin() + c.offset, c.face->num_multipliers(), &c.law.get());
  on_obstacle_.assign(m_, 0);
  for (const FrictionContact& c : contacts_)
    if (!c.master) std::fill_n(on_obstacle_.begin() + c.offset, c.face->num_multipliers(), char(1));
  row_weights_.resize(m_ * nt_);
  for (int K = 0; K < m_; ++K) row_weights_.segment(K * nt_, nt_).setConstant(weights_[K]);
  tau_prev_ = slip_total_ = Eigen::VectorXd::Zero(m_ * nt_);
  assemble_rows(0.0, Eigen::MatrixXd::Zero(every_.num_dofs() / dim_, dim_));
}

void FiniteStrainFriction::assemble_rows(double t, const Eigen::MatrixXd& u) {
  // T on every dof (the body's own numbering: prescribed values are part
  // of u), from the small-deformation kernels at the configuration u; t0
  // of each obstacle's motion at curve = 1.
  std::vector<Eigen::Triplet<double>> trip;
  t0_.clear();
  row_tangent_ = Eigen::MatrixXd::Zero(m_ * nt_, dim_);
  for (size_t k = 0; k < contacts_.size(); ++k) {
    const FrictionContact& c = contacts_[k];
    t0_.push_back(Eigen::VectorXd::Zero(m_ * nt_));
    if (!c.law.tangential()) continue;  // a frictionless contact among frictional ones: lambda_t = 0
    WeightedGapOperator op;
    if (masters_[k]) {
      masters_[k]->update(u);
      op = assemble_mortar_gaps(every_, *c.face, *masters_[k], c.integration, c.law, {}, &u);
    } else {
      const Eigen::VectorXd motion = c.motion.size() ? c.motion : Eigen::VectorXd::Zero(dim_);
      const TranslatedObstacle where(*c.obstacle, (*c.curve)(t) * motion);  // as the step starts
      op = assemble_weighted_gaps(every_, *c.face, where, c.law, motion, &u);
    }
    const int count = int(op.weights.size());
    t0_.back().segment(c.offset * nt_, count * nt_) = op.t0;
    // the slave face's control points: int B_K t_j from its columns (partition of unity)
    std::vector<char> on_face(every_.num_dofs() / dim_, 0);
    for (const ContactSide& side : c.face->sides)
      for (int cp : side.face_cps) on_face[cp] = 1;
    for (int r = 0; r < op.T.outerSize(); ++r)
      for (RowSparse::InnerIterator it(op.T, r); it; ++it) {
        trip.emplace_back(c.offset * nt_ + r, int(it.col()), it.value());
        if (on_face[it.col() / dim_]) row_tangent_(c.offset * nt_ + r, it.col() % dim_) += it.value();
      }
  }
  T_all_.resize(m_ * nt_, every_.num_dofs());
  T_all_.setFromTriplets(trip.begin(), trip.end());
  std::vector<Eigen::Triplet<double>> tf;
  for (int r = 0; r < T_all_.outerSize(); ++r)
    for (RowSparse::InnerIterator it(T_all_, r); it; ++it)
      if (dofs_->equation(int(it.col())) >= 0) tf.emplace_back(r, dofs_->equation(int(it.col())), it.value());
  T_free_.resize(m_ * nt_, n_);
  T_free_.setFromTriplets(tf.begin(), tf.end());
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
  if (started_ && t != t_prev_) slip_total_ += slip(t, u).cwiseQuotient(row_weights_);  // the last step's (its T)
  assemble_rows(t, u);
  started_ = true;
  t_prev_ = t;
  tau_prev_ = position(t, u);
}

FrictionHistory FiniteStrainFriction::history() const {
  FrictionHistory h;
  h.slip = slip_total_;
  h.from = t_prev_;
  return h;
}

void FiniteStrainFriction::restore(const FrictionHistory& h, const Eigen::MatrixXd& u_from) {
  if (h.slip.size() != m_ * nt_) throw std::invalid_argument("FiniteStrainFriction::restore: a history of another contact");
  // as begin_step(h.from, u_from) left it: the rows there, the slip up to there
  assemble_rows(h.from, u_from);
  started_ = true;
  t_prev_ = h.from;
  tau_prev_ = position(h.from, u_from);
  slip_total_ = h.slip;
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
    const InterfaceLaw& law = *laws_[size_t(K)];
    if (!law.tangential()) {  // frictionless: always sliding, no force
      out[K] = kSlip;
      continue;
    }
    const double w = weights_[K];
    const Eigen::VectorXd xi = lambda_t.segment(K * nt_, nt_) + ct_[K] / w * s.segment(K * nt_, nt_);
    const double b = -friction_[K] * (lambda_n[K] + c_ * gamma[K] / w);
    out[K] = law.tangential_state(xi.norm(), b, kOpen, 0);
    // Closed but carrying no normal force yet (lambda_n = 0: the predictor
    // of a multiplier that was open): nothing holds it, it slips.  Between
    // two bodies the rule cost iterations (docs/benchmarks.md): not there;
    // nor for a tie, which holds without a normal force.
    if (lambda_n[K] == 0.0 && on_obstacle_[K] && xi.norm() > 0 && !law.bilateral()) out[K] = kSlip;
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
      const Eigen::VectorXd xi = lt + ct_[K] / w * s.segment(K * nt_, nt_);
      const double b = -friction_[K] * (lambda_n[K] + c_ * gamma[K] / w);
      r = w * (lt - b / xi.norm() * xi);
    } else {
      r = w * lt;
    }
  }
}

void FiniteStrainFriction::constraint_rows(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda_n,
                                           const Eigen::VectorXd& gamma, const std::vector<char>& normal_active,
                                           const Eigen::VectorXd& lambda_t, TangentialRows& out) const {
  const int first = m_;  // the first tangential row among the constraints
  out.s = Eigen::VectorXd::Zero(m_ * nt_);
  out.d = Eigen::VectorXd::Zero(m_ * nt_);
  out.mixed_B.clear();
  out.mixed_lambda.clear();
  const Eigen::VectorXd s = slip(t, u);
  const std::vector<char> st = states(t, u, lambda_n, gamma, normal_active, lambda_t);
  for (int K = 0; K < m_; ++K) {
    const double w = weights_[K];
    const int row = K * nt_;  // among the tangential rows
    if (st[K] == kStick) {
      out.s.segment(row, nt_).setConstant(c_);  // c s_K: c T_K du
    } else if (st[K] == kSlip && friction_[K] > 0) {
      // r = w Phi(lambda_t, s / w, b), b = -f (lambda_n + c gamma / w)
      const double f = friction_[K];
      const Eigen::VectorXd lt = lambda_t.segment(row, nt_), sk = s.segment(row, nt_) / w;
      const double b = -f * (lambda_n[K] + c_ * gamma[K] / w);
      const SlipLinearisation lin = linearise_slip(lt, sk, b, ct_[K]);
      for (int i = 0; i < nt_; ++i) {
        for (int j = 0; j < nt_; ++j) {
          out.mixed_lambda.emplace_back(first + row + i, first + row + j, w * lin.d_lambda_t(i, j));
          // d s_K / du = T: w d_s (1 / w) T
          if (lin.d_s(i, j) != 0.0) out.mixed_B.emplace_back(first + row + i, first + row + j, lin.d_s(i, j));
        }
        // w d_b db: db = -f dlambda_n - f c / w dgamma, dgamma = G_K du
        out.mixed_lambda.emplace_back(first + row + i, K, w * lin.d_b[i] * -f);
        out.mixed_B.emplace_back(first + row + i, K, lin.d_b[i] * -f * c_);
      }
    } else {
      out.d.segment(row, nt_).setConstant(w);
    }
  }
}

Eigen::VectorXd FiniteStrainFriction::tangential_resultant(int k, const Eigen::VectorXd& lambda_t) const {
  const int first = contacts_[k].offset, past = k + 1 < int(contacts_.size()) ? contacts_[k + 1].offset : m_;
  return -(row_tangent_.middleRows(first * nt_, (past - first) * nt_).transpose() *
           lambda_t.segment(first * nt_, (past - first) * nt_));
}

}  // namespace igac
