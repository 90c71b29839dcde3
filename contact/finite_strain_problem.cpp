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
  modes_ = free_rigid_modes(*s_.body, *s_.dofs);
  weights_ = Eigen::VectorXd::Zero(m_);
  if (m_ > 0) {
    // tabulated once: every residual and Jacobian walks the same face points
    for (const auto& c : s_.contacts) {
      face_quadratures_.emplace_back();
      for (const ContactSide& side : c.face->sides)
        face_quadratures_.back().push_back(side.quadrature(c.face->quadrature_points()));
    }
    // K_K on the reference faces: the small-deformation operator's weights
    for (size_t k = 0; k < s_.contacts.size(); ++k)
      weights_.segment(offsets_[k], offsets_[k + 1] - offsets_[k]) =
          assemble_weighted_gaps(*s_.dofs, *s_.contacts[k].face, *s_.contacts[k].obstacle).weights;
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

bool FiniteStrainProblem::block_jacobian(double t, const Eigen::VectorXd& x, BlockJacobian& J) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int, f_ext = Eigen::VectorXd::Zero(n_);
  if (J.K.rows() != n_ || J.K.nonZeros() != tl_->pattern().nonZeros()) J.K = tl_->pattern();  // then filled in place
  if (!tl_->assemble(u, f_int, &J.K)) return false;
  J.B.resize(m_, n_);
  J.s = Eigen::VectorXd::Zero(m_);
  J.d = Eigen::VectorXd::Zero(m_);
  J.rigid_modes = modes_.modes;
  J.pinned = modes_.pinned;
  if (m_ > 0) {
    const Eigen::VectorXd lambda = x.tail(m_);
    ContactEval ce;
    evaluate_contact(t, u, lambda, true, ce);
    const auto active = decide_active(ce.gamma, lambda);
    J.B.setFromTriplets(ce.G.begin(), ce.G.end());
    for (int K = 0; K < m_; ++K) {
      if (active[K]) J.s[K] = s_.complementarity_scale;
      else J.d[K] = weights_[K];
    }
    for (const auto& c : ce.curvature) J.K.coeffRef(c.row(), c.col()) += c.value();  // face couplings: in the pattern
  }
  // The follower load stiffness is the only unsymmetric part: the solver
  // factorises K without it (symmetric, and K R = 0 for the translations
  // that contact holds) and lets GMRES add it.
  const bool follower = s_.follower_pressure && !s_.pressures.empty();
  if (follower) {
    if (J.K_factor.nonZeros() != J.K.nonZeros()) J.K_factor = J.K;
    else std::copy(J.K.valuePtr(), J.K.valuePtr() + J.K.nonZeros(), J.K_factor.valuePtr());
    for (const auto& p : s_.pressures) add_follower_pressure(*s_.body, *s_.dofs, p.faces, t * p.value, u, f_ext, &J.K);
  } else {
    J.K_factor.resize(0, 0);
  }
  return true;
}

bool FiniteStrainProblem::jacobian(double t, const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& J) {
  if (!block_jacobian(t, x, blocks_)) return false;
  J = assemble_full(blocks_);
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
