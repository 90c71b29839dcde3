#include "contact/finite_strain_problem.hpp"

#include <optional>

#include <algorithm>
#include <fmt/format.h>

#include "engine/follower_pressure.hpp"

namespace igac {
FiniteStrainProblem::FiniteStrainProblem(FiniteStrainSetup setup) : s_(std::move(setup)) {
  n_ = s_.dofs->num_free();
  offsets_.assign(1, 0);
  for (const auto& c : s_.contacts) offsets_.push_back(offsets_.back() + c.face->num_multipliers());
  m_ = offsets_.back();
  tl_ = std::make_unique<TotalLagrangianAssembler>(*s_.body, *s_.dofs, *s_.law);
  const Eigen::SparseMatrix<double>& P = tl_->pattern();
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(P.nonZeros() + 4 * size_t(m_) * 64);
  for (int c = 0; c < P.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(P, c); it; ++it) trip.emplace_back(it.row(), it.col(), 0.0);
  weights_ = Eigen::VectorXd::Zero(m_);
  if (m_ > 0) {
    // tabulated once: every residual and Jacobian walks the same face points
    for (const auto& c : s_.contacts) {
      face_quadratures_.emplace_back();
      for (const ContactSide& side : c.face->sides)
        face_quadratures_.back().push_back(side.quadrature(c.face->quadrature_points()));
    }
    ContactEval ce;
    evaluate_contact(0.0, Eigen::MatrixXd::Zero(s_.body->num_control_points(), s_.body->space_dim()),
                     Eigen::VectorXd::Zero(m_), false, ce);
    for (const auto& g : ce.G) {
      trip.emplace_back(g.col(), n_ + g.row(), 0.0);
      trip.emplace_back(n_ + g.row(), g.col(), 0.0);
    }
    for (int K = 0; K < m_; ++K) trip.emplace_back(n_ + K, n_ + K, 0.0);
    // K_K on the reference faces: the small-deformation operator's weights
    for (size_t k = 0; k < s_.contacts.size(); ++k)
      weights_.segment(offsets_[k], offsets_[k + 1] - offsets_[k]) =
          assemble_weighted_gaps(*s_.dofs, *s_.contacts[k].face, *s_.contacts[k].obstacle).weights;
  }
  J_.resize(n_ + m_, n_ + m_);
  J_.setFromTriplets(trip.begin(), trip.end());
  J_.makeCompressed();
  // where each K_T value sits in J_
  kt_to_j_.resize(P.nonZeros());
  for (int c = 0; c < P.outerSize(); ++c) {
    const int* first = J_.innerIndexPtr() + J_.outerIndexPtr()[c];
    const int* past = J_.innerIndexPtr() + J_.outerIndexPtr()[c + 1];
    for (int k = P.outerIndexPtr()[c]; k < P.outerIndexPtr()[c + 1]; ++k)
      kt_to_j_[k] = int(std::lower_bound(first, past, P.innerIndexPtr()[k]) - J_.innerIndexPtr());
  }
}

Eigen::MatrixXd FiniteStrainProblem::displacement(double t, const Eigen::VectorXd& x) const {
  const DofMap& d = *s_.dofs;
  const int dim = d.dim();
  Eigen::MatrixXd u(d.num_dofs() / dim, dim);
  for (int i = 0; i < d.num_dofs(); ++i)
    u(i / dim, i % dim) = d.equation(i) >= 0 ? x[d.equation(i)] : t * d.prescribed_value(i);
  return u;
}

void FiniteStrainProblem::evaluate_contact(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda,
                                           bool tangent, ContactEval& out) const {
  const int dim = s_.body->space_dim();
  const DofMap& dofs = *s_.dofs;
  out.gamma = Eigen::VectorXd::Zero(m_);
  out.G.clear();
  out.curvature.clear();
  ElementData ed;
  std::vector<int> kidx;
  std::vector<double> kval;
  for (size_t c = 0; c < s_.contacts.size(); ++c) {
    const auto& contact = s_.contacts[c];
    const int offset = offsets_[c];
    // A moving obstacle stands at its reference position moved by t * motion.
    std::optional<TranslatedObstacle> moved;
    if (contact.motion.size() > 0) moved.emplace(*contact.obstacle, t * contact.motion);
    const Obstacle& obstacle = moved ? static_cast<const Obstacle&>(*moved) : *contact.obstacle;
    for (size_t si = 0; si < contact.face->sides.size(); ++si) {
    const ContactSide& side = contact.face->sides[si];
    const int side_offset = offset + side.first_multiplier;
    const PatchQuadrature& quad = face_quadratures_[c][si];
    for (int e = 0; e < quad.num_elements(); ++e) {
      quad.evaluate(e, ed, false);
      for (int q = 0; q < ed.JxW.size(); ++q) {
        Eigen::VectorXd x = ed.X.row(q).transpose();
        for (size_t a = 0; a < ed.cps.size(); ++a) x += ed.N(q, a) * u.row(ed.cps[a]).transpose();
        const ObstacleProbe pr = obstacle.probe(x, tangent);
        side.space.basis(ed.xi.row(q).transpose(), kidx, kval);
        double lambda_B = 0;  // sum_K lambda_K B_K at the point
        for (size_t k = 0; k < kidx.size(); ++k) {
          const int K = side_offset + kidx[k];
          const double bw = kval[k] * ed.JxW[q];
          out.gamma[K] += pr.gap * bw;
          lambda_B += lambda[K] * bw;
          for (size_t a = 0; a < ed.cps.size(); ++a)
            for (int i = 0; i < dim; ++i) {
              const int eq = dofs.equation(ed.cps[a] * dim + i);
              if (eq >= 0) out.G.emplace_back(K, eq, bw * ed.N(q, a) * pr.normal[i]);
            }
        }
        if (tangent && lambda_B != 0.0 && pr.normal_derivative.squaredNorm() > 0)
          for (size_t a = 0; a < ed.cps.size(); ++a)
            for (size_t b = 0; b < ed.cps.size(); ++b)
              for (int i = 0; i < dim; ++i)
                for (int j = 0; j < dim; ++j) {
                  const int r = dofs.equation(ed.cps[a] * dim + i), cc = dofs.equation(ed.cps[b] * dim + j);
                  if (r >= 0 && cc >= 0)
                    out.curvature.emplace_back(r, cc, lambda_B * ed.N(q, a) * ed.N(q, b) * pr.normal_derivative(i, j));
                }
      }
    }
    }
  }
}

std::vector<char> FiniteStrainProblem::decide_active(const Eigen::VectorXd& gamma, const Eigen::VectorXd& lambda) const {
  std::vector<char> active(m_);
  for (int K = 0; K < m_; ++K) active[K] = weights_[K] * lambda[K] + s_.complementarity_scale * gamma[K] < 0;
  return active;
}

bool FiniteStrainProblem::residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int;
  if (!tl_->assemble(u, f_int, nullptr)) return false;
  Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(n_);
  for (const auto& p : s_.pressures) {
    if (s_.follower_pressure) add_follower_pressure(*s_.body, *s_.dofs, p.faces, t * p.value, u, f_ext, nullptr);
    else add_dead_pressure(*s_.body, *s_.dofs, p.faces, t * p.value, f_ext);
  }
  r.resize(n_ + m_);
  r.head(n_) = f_int - f_ext;
  if (m_ > 0) {
    const Eigen::VectorXd lambda = x.tail(m_);
    ContactEval ce;
    evaluate_contact(t, u, lambda, false, ce);
    for (const auto& g : ce.G) r[g.col()] += lambda[g.row()] * g.value();
    last_active_ = decide_active(ce.gamma, lambda);
    for (int K = 0; K < m_; ++K)
      r[n_ + K] = last_active_[K] ? s_.complementarity_scale * ce.gamma[K] : weights_[K] * lambda[K];
  }
  return true;
}

bool FiniteStrainProblem::jacobian(double t, const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& J) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int, f_ext = Eigen::VectorXd::Zero(n_);
  Eigen::SparseMatrix<double>& K = tangent_;
  if (K.nonZeros() == 0) K = tl_->pattern();  // filled in place from the second call on
  if (!tl_->assemble(u, f_int, &K)) return false;
  if (s_.follower_pressure)
    for (const auto& p : s_.pressures) add_follower_pressure(*s_.body, *s_.dofs, p.faces, t * p.value, u, f_ext, &K);
  std::fill(J_.valuePtr(), J_.valuePtr() + J_.nonZeros(), 0.0);
  for (int k = 0; k < K.nonZeros(); ++k) J_.valuePtr()[kt_to_j_[k]] = K.valuePtr()[k];
  if (m_ > 0) {
    const Eigen::VectorXd lambda = x.tail(m_);
    ContactEval ce;
    evaluate_contact(t, u, lambda, true, ce);
    const auto active = decide_active(ce.gamma, lambda);
    for (const auto& g : ce.G) {
      J_.coeffRef(g.col(), n_ + g.row()) += g.value();
      if (active[g.row()]) J_.coeffRef(n_ + g.row(), g.col()) += s_.complementarity_scale * g.value();
    }
    for (int Kk = 0; Kk < m_; ++Kk)
      if (!active[Kk]) J_.coeffRef(n_ + Kk, n_ + Kk) = weights_[Kk];
    for (const auto& c : ce.curvature) J_.coeffRef(c.row(), c.col()) += c.value();
  }
  J = J_;
  return true;
}

int FiniteStrainProblem::active_set_size(const Eigen::VectorXd& x) const {
  const auto a = active_set(x);
  return int(std::count(a.begin(), a.end(), 1));
}

std::vector<char> FiniteStrainProblem::active_set(const Eigen::VectorXd&) const { return last_active_; }

double FiniteStrainProblem::force_scale(double t, const Eigen::VectorXd& x) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int, f_ext = Eigen::VectorXd::Zero(n_);
  double scale = 0;
  if (tl_->assemble(u, f_int, nullptr)) scale = f_int.cwiseAbs().maxCoeff();
  for (const auto& p : s_.pressures) add_dead_pressure(*s_.body, *s_.dofs, p.faces, t * p.value, f_ext);
  if (n_ > 0) scale = std::max(scale, f_ext.cwiseAbs().maxCoeff());
  return scale > 0 ? scale : 1.0;
}

Eigen::VectorXd FiniteStrainProblem::weighted_gaps(double t, const Eigen::VectorXd& x) const {
  if (m_ == 0) return {};
  ContactEval ce;
  evaluate_contact(t, displacement(t, x), x.tail(m_), false, ce);
  return ce.gamma.cwiseQuotient(weights_);
}

void FiniteStrainProblem::activate_nearest(Eigen::VectorXd& x, int count) const {
  if (m_ == 0 || count <= 0) return;
  const Eigen::VectorXd g = weighted_gaps(0.0, x);
  std::vector<int> order(m_);
  for (int K = 0; K < m_; ++K) order[K] = K;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return g[a] < g[b]; });
  for (int i = 0; i < std::min(count, m_); ++i) {
    const int K = order[i];
    // just enough below zero for K_K lambda_K + c gamma_K < 0
    x[n_ + K] = -2.0 * s_.complementarity_scale * std::max(g[K], 0.0) - 1e-12 * s_.complementarity_scale;
  }
}

}  // namespace igac
