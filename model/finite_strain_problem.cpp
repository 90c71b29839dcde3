// SPDX-License-Identifier: BSD-3-Clause
#include "model/finite_strain_problem.hpp"

#include "engine/assembly.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include "contact/small_strain_friction.hpp"
#include "engine/follower_pressure.hpp"
#include "engine/numerical_failure.hpp"
#include "engine/sparsity.hpp"

namespace igac {
FiniteStrainProblem::FiniteStrainProblem(FiniteStrainSetup setup) : s_(std::move(setup)) {
  n_ = s_.dofs->num_free();
  offsets_.assign(1, 0);
  for (const auto& c : s_.contacts) offsets_.push_back(offsets_.back() + c.face->num_multipliers());
  m_ = offsets_.back();
  if (s_.patch_laws.empty()) s_.patch_laws.assign(1, s_.law);
  if (s_.patch_formulations.empty()) s_.patch_formulations.assign(1, s_.formulation);
  tl_ = std::make_unique<TotalLagrangianAssembler>(*s_.body, *s_.dofs, s_.patch_laws, s_.patch_formulations);
  if (s_.share.distributed()) {
    if (tl_->has_mixed()) s_.share = {};  // (its pressure terms: whole on every process)
    else tl_->set_element_range(s_.share.elements);
  }
  if (s_.follower_pressure && !s_.pressures.empty()) {
    std::vector<PatchSide> loaded;
    for (const auto& p : s_.pressures) loaded.insert(loaded.end(), p.faces.begin(), p.faces.end());
    load_stiffness_ = follower_pressure_pattern(*s_.body, *s_.dofs, loaded);
  }
  wet_.resize(s_.pressures.size());
  for (size_t i = 0; i < s_.pressures.size(); ++i)  // before any contact: wherever the fluid reaches
    if (s_.pressures[i].fluid) wet_[i] = s_.pressures[i].fluid->wet(s_.pressures[i].fluid->none());
  if (s_.incompressibility_tolerance > 0) tl_->make_incompressible(s_.incompressibility_tolerance);
  modes_ = free_rigid_modes(*s_.body, *s_.dofs);
  if (s_.body_force.size() > 0 && s_.body_force.norm() > 0)
    body_force_load_ = body_force_load(*s_.body, *s_.dofs, s_.body_force);
  weights_ = Eigen::VectorXd::Zero(m_);
  if (m_ > 0) {
    // tabulated once: every residual and Jacobian walks the same face points
    for (const auto& c : s_.contacts) contact_quadratures_.emplace_back(*c.face);
    // the equations a contact row may touch (BlockJacobian::constraint_equations)
    std::vector<int> cps;
    for (const auto& c : s_.contacts) {
      for (const ContactSide& side : c.face->sides) cps.insert(cps.end(), side.face_cps.begin(), side.face_cps.end());
      for (int s = 0; c.master && s < c.master->num_sides(); ++s)
        cps.insert(cps.end(), c.master->side_control_points(s).begin(), c.master->side_control_points(s).end());
    }
    std::sort(cps.begin(), cps.end());
    cps.erase(std::unique(cps.begin(), cps.end()), cps.end());
    for (int a : cps)
      for (int i = 0; i < s_.dofs->dim(); ++i)
        if (const int eq = s_.dofs->equation(a * s_.dofs->dim() + i); eq >= 0) contact_equations_.push_back(eq);
    mortar_points_.resize(s_.contacts.size());
    // K_K on the reference faces: the small-deformation operator's weights
    for (size_t k = 0; k < s_.contacts.size(); ++k) {
      const auto& c = s_.contacts[k];
      masters_.push_back(c.master ? std::make_unique<MasterSurface>(*c.master) : nullptr);
      weights_.segment(offsets_[k], offsets_[k + 1] - offsets_[k]) =
          c.master ? assemble_mortar_gaps(*s_.dofs, *c.face, *c.master, c.integration).weights
                   : assemble_weighted_gaps(*s_.dofs, *c.face, *c.obstacle).weights;
    }
  }
  laws_.assign(size_t(m_), nullptr);
  for (size_t k = 0; k < s_.contacts.size(); ++k)
    std::fill(laws_.begin() + offsets_[k], laws_.begin() + offsets_[k + 1], &s_.contacts[k].law.get());
  // A tie holds the weighted gaps the run starts with (g - g_0 = 0): g_0 of
  // the reference configuration, taken off every gap evaluate_contact gives.
  if (std::any_of(laws_.begin(), laws_.end(), [](const InterfaceLaw* l) { return l->bilateral(); })) {
    ContactEval start;
    evaluate_contact(0.0, Eigen::MatrixXd::Zero(s_.dofs->num_dofs() / s_.dofs->dim(), s_.dofs->dim()),
                     Eigen::VectorXd(), nullptr, start, ContactTerms::gaps);
    gamma_start_ = Eigen::VectorXd::Zero(m_);
    for (int K = 0; K < m_; ++K)
      if (laws_[size_t(K)]->bilateral()) gamma_start_[K] = start.gamma[K];
  }
  // An interference fit: the overlap the reference configuration has,
  // max(0, -g_0), offsets the gaps by (1 - min(t, 1)) times it
  // (evaluate_contact), so the run starts clear and fits by the load's end.
  if (std::any_of(s_.contacts.begin(), s_.contacts.end(), [](const auto& c) { return c.interference; })) {
    ContactEval start;
    evaluate_contact(0.0, Eigen::MatrixXd::Zero(s_.dofs->num_dofs() / s_.dofs->dim(), s_.dofs->dim()),
                     Eigen::VectorXd(), nullptr, start, ContactTerms::gaps);
    Eigen::VectorXd overlap = Eigen::VectorXd::Zero(m_);
    for (size_t k = 0; k < s_.contacts.size(); ++k)
      if (s_.contacts[k].interference)
        for (int K = offsets_[k]; K < offsets_[k + 1]; ++K) overlap[K] = std::max(0.0, -start.gamma[K]);
    overlap_ = std::move(overlap);
  }
  if (std::any_of(s_.contacts.begin(), s_.contacts.end(), [](const auto& c) { return c.law.tangential(); })) {
    std::vector<FrictionContact> fc;
    for (size_t k = 0; k < s_.contacts.size(); ++k) {
      const auto& c = s_.contacts[k];
      fc.push_back({c.face, c.obstacle, c.master, c.integration, c.motion, &c.curve, c.law, offsets_[k]});
    }
    friction_ = std::make_unique<FiniteStrainFriction>(
        *s_.body, *s_.dofs, fc, weights_, s_.complementarity_scale,
        finite_strain_tangential_scales(s_.complementarity_scale, s_.mesh_size, weights_, s_.dofs->dim()));
    mt_ = friction_->rows();
  }
  weights_of_rows_.resize(0);
  if (tl_->has_mixed()) {  // the u-p Newton: the pressure functions' dilatation rows, scaled at rest
    nz_ = tl_->num_pressures();
    const int dim = s_.dofs->dim();
    TotalLagrangianAssembler::LocalDilatation rest;
    Eigen::VectorXd f;
    const Eigen::VectorXd z = Eigen::VectorXd::Zero(nz_);
    if (!tl_->assemble(Eigen::MatrixXd::Zero(s_.dofs->num_dofs() / dim, dim), f, nullptr, &z, &rest))
      throw std::logic_error("the mixed formulation refuses the reference state");
    local_scale_ = Eigen::VectorXd::Ones(nz_);
    weights_of_rows_ = Eigen::VectorXd::Ones(size());
    for (int e = 0; e < nz_; ++e) {  // e: a pressure function
      if (!(rest.shear[e] > 0) || !(rest.volume[e] > 0)) continue;  // a displacement patch's: z_e stays 0
      local_scale_[e] = rest.shear[e] * std::pow(rest.volume[e], double(dim - 1) / dim);
      weights_of_rows_[n_ + m_ + mt_ + e] = rest.stiffness[e] / (rest.volume[e] * rest.shear[e]);  // U''(1) / mu_s
    }
  }
}

Eigen::VectorXd FiniteStrainProblem::local_residual(const TotalLagrangianAssembler::LocalDilatation& local,
                                                    const Eigen::VectorXd& z) const {
  return local_scale_.cwiseProduct(local.projected - z);
}

void FiniteStrainProblem::add_dead_loads(double t, Eigen::VectorXd& f_ext) const {
  for (const TractionLoad& l : s_.tractions)
    add_dead_traction(*s_.body, *s_.dofs, l.faces, l.curve(t) * l.value, f_ext);
  if (body_force_load_.size() == f_ext.size()) f_ext += s_.body_force_curve(t) * body_force_load_;
}

Eigen::MatrixXd FiniteStrainProblem::displacement(double t, const Eigen::VectorXd& x) const {
  const DofMap& d = *s_.dofs;
  const int dim = d.dim();
  Eigen::MatrixXd u(d.num_dofs() / dim, dim);
  for (int i = 0; i < d.num_dofs(); ++i)
    u(i / dim, i % dim) = d.equation(i) >= 0 ? x[d.equation(i)] : (s_.prescribed_curves.empty() ? t : (*s_.prescribed_curves[i])(t)) * d.prescribed_value(i);
  return u;
}

void FiniteStrainProblem::evaluate_contact(double t, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda,
                                           Eigen::SparseMatrix<double>* K, ContactEval& out, ContactTerms terms,
                                           std::vector<Eigen::Triplet<double>>* K_coupling,
                                           const DofMap* numbering) const {
  const DofMap& dofs = numbering ? *numbering : *s_.dofs;
  const bool coupling = terms != ContactTerms::gaps, linearised = terms == ContactTerms::linearised;
  out.gamma = Eigen::VectorXd::Zero(m_);
  out.G.clear();
  out.force = Eigen::VectorXd::Zero(terms == ContactTerms::forces ? dofs.num_free() : 0);
  out.resultants.assign(s_.contacts.size(), Eigen::VectorXd::Zero(dofs.dim()));
  std::vector<int> eq;
  Eigen::MatrixXd Kc;
  for (size_t c = 0; c < s_.contacts.size(); ++c) {
    const auto& contact = s_.contacts[c];
    const int offset = offsets_[c];
    if (masters_[c]) {
      const int count = offsets_[c + 1] - offset;
      add_finite_strain_mortar(dofs, *contact.face, *masters_[c], contact.integration, u,
                               lambda.size() ? Eigen::VectorXd(lambda.segment(offset, count))
                                             : Eigen::VectorXd::Zero(count),
                               offset, {&out.gamma, linearised ? &out.G : nullptr, coupling && !linearised ? &out.force : nullptr,
                                        K, K_coupling, coupling ? &out.resultants[c] : nullptr},
                               contact_quadratures_[c], mortar_points_[c]);
      continue;
    }
    // A moving obstacle stands at its reference position moved by t * motion.
    std::optional<TranslatedObstacle> moved;
    if (contact.motion.size() > 0) moved.emplace(*contact.obstacle, contact.curve(t) * contact.motion);
    const Obstacle& obstacle = moved ? static_cast<const Obstacle&>(*moved) : *contact.obstacle;
    contact_quadratures_[c].for_each_point([&](const auto& v, int q, const std::vector<int>& Ks,
                                               const std::vector<double>& B) {
      constexpr int dim = std::remove_cvref_t<decltype(v)>::space_dim;
      const ObstacleProbe pr = obstacle.probe(v.displaced(q, u), K != nullptr);
      if (!coupling) {  // the gaps alone
        for (size_t k = 0; k < Ks.size(); ++k) out.gamma[offset + Ks[k]] += pr.gap * (B[k] * v.JxW[q]);  // as below, to the bit
        return;
      }
      dofs.element_equations(v.cps, eq);
      double lambda_B = 0;  // sum_K lambda_K B_K at the point
      for (size_t k = 0; k < Ks.size(); ++k) {
        const int row = offset + Ks[k];
        const double bw = B[k] * v.JxW[q];
        out.gamma[row] += pr.gap * bw;
        lambda_B += lambda[row] * bw;
        if (!linearised) continue;
        for (int a = 0; a < v.n_loc; ++a)
          for (int i = 0; i < dim; ++i)
            if (eq[a * dim + i] >= 0) out.G.emplace_back(row, eq[a * dim + i], bw * v.N(q, a) * pr.normal[i]);
      }
      out.resultants[c] -= lambda_B * pr.normal;
      if (!linearised)  // the force alone: lambda_B N_a n
        for (int a = 0; a < v.n_loc; ++a)
          for (int i = 0; i < dim; ++i)
            if (eq[a * dim + i] >= 0) out.force[eq[a * dim + i]] += lambda_B * v.N(q, a) * pr.normal[i];
      // the obstacle's curvature: lambda_B N_a N_b dn/dx, into K by the one scatter
      if (!K || lambda_B == 0.0 || !(pr.normal_derivative.squaredNorm() > 0)) return;
      const int nd = v.n_loc * dim;
      Kc.resize(nd, nd);
      for (int b = 0; b < v.n_loc; ++b)
        for (int j = 0; j < dim; ++j)
          for (int a = 0; a < v.n_loc; ++a)
            for (int i = 0; i < dim; ++i)
              Kc(a * dim + i, b * dim + j) = lambda_B * v.N(q, a) * v.N(q, b) * pr.normal_derivative(i, j);
      scatter_element_matrix(*K, K->valuePtr(), eq, Kc);
    });
  }
  if (gamma_start_.size()) out.gamma -= gamma_start_;  // a tie's gap counts from where it started
  if (overlap_.size()) out.gamma += (1.0 - std::clamp(t, 0.0, 1.0)) * overlap_;  // a fit not yet whole
}

bool FiniteStrainProblem::elasticity(const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K,
                                     const Eigen::VectorXd* z, TotalLagrangianAssembler::LocalDilatation* local) const {
  if (!s_.share.distributed()) return tl_->assemble(u, f_int, K, z, local);
  bool ok = false;
  try {
    ok = tl_->assemble(u, f_int, K, z, local);
  } catch (const NumericalFailure&) {
    ok = false;  // (inadmissible: as false, and said to every process)
  }
  if (!s_.share.everywhere(ok)) return false;
  s_.share.sum(f_int.data(), int(f_int.size()));
  if (K) s_.share.sum(K->valuePtr(), int(K->nonZeros()));
  return true;
}

std::vector<char> FiniteStrainProblem::decide_active(const Eigen::VectorXd& gamma, const Eigen::VectorXd& lambda) const {
  std::vector<char> active(m_);
  for (int K = 0; K < m_; ++K)
    active[K] = laws_[size_t(K)]->closed(weights_[K] * lambda[K] + s_.complementarity_scale * gamma[K], false, 0);
  return active;
}

bool FiniteStrainProblem::residual(double t, const Eigen::VectorXd& x, Eigen::VectorXd& r) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int;
  TotalLagrangianAssembler::LocalDilatation local;
  const Eigen::VectorXd z = x.tail(nz_);
  if (!elasticity(u, f_int, nullptr, nz_ ? &z : nullptr, nz_ ? &local : nullptr)) return false;
  Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(n_);
  for (size_t i = 0; i < s_.pressures.size(); ++i) {
    const PressureLoad& p = s_.pressures[i];
    if (s_.follower_pressure)
      add_follower_pressure(*s_.body, *s_.dofs, p.faces, p.curve(t) * p.value, u, f_ext, nullptr, wet(i));
    else
      add_dead_pressure(*s_.body, *s_.dofs, p.faces, p.curve(t) * p.value, f_ext, wet(i));
  }
  add_dead_loads(t, f_ext);
  r.resize(size());
  r.head(n_) = f_int - f_ext;
  if (nz_ > 0) r.tail(nz_) = local_residual(local, z);
  if (m_ > 0) {
    const Eigen::VectorXd lambda = normal_multipliers(x);
    ContactEval ce;
    evaluate_contact(t, u, lambda, nullptr, ce, ContactTerms::forces);
    r.head(n_) += ce.force;
    const std::vector<char> active = decide_active(ce.gamma, lambda);  // of (t, x), as active_set
    last_t_ = t;
    last_x_ = x;
    last_gamma_ = ce.gamma;
    for (int K = 0; K < m_; ++K)
      r[n_ + K] = active[K] ? s_.complementarity_scale * ce.gamma[K] : weights_[K] * lambda[K];
    if (friction_) friction_->residual(t, u, lambda, ce.gamma, active, tangential(x), r.head(n_), r.segment(n_ + m_, mt_));
  }
  return true;
}

bool FiniteStrainProblem::block_jacobian(double t, const Eigen::VectorXd& x, BlockJacobian& J) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int, f_ext = Eigen::VectorXd::Zero(n_);
  if (J.K.rows() != n_ || J.K.nonZeros() != tl_->pattern().nonZeros()) J.K = tl_->pattern();  // then filled in place
  TotalLagrangianAssembler::LocalDilatation local;
  const Eigen::VectorXd z = x.tail(nz_);
  if (!elasticity(u, f_int, &J.K, nz_ ? &z : nullptr, nz_ ? &local : nullptr)) return false;
  J.local = {};  // (set below)
  J.B.resize(m_, n_);
  J.s = Eigen::VectorXd::Zero(m_);
  J.d = Eigen::VectorXd::Zero(m_);
  J.rigid_modes = modes_.modes;
  J.pinned = modes_.pinned;
  J.constraint_equations = contact_equations_;
  J.general = false;
  J.K_coupling.resize(n_, n_);  // (empty)
  std::vector<char> active;
  Eigen::VectorXd gamma;
  if (m_ > 0) {
    const Eigen::VectorXd lambda = normal_multipliers(x);
    ContactEval& ce = jacobian_contact_;  // (reused: millions of triplets in 3D, their memory kept)
    std::vector<Eigen::Triplet<double>>& coupling = jacobian_coupling_;
    coupling.clear();
    // adds the curvature terms to K (one face's couplings: in the pattern; two bodies': beside it)
    evaluate_contact(t, u, lambda, &J.K, ce, ContactTerms::linearised, &coupling);
    active = decide_active(ce.gamma, lambda);
    gamma = ce.gamma;
    if (!friction_) at_jacobian_ = {ce.gamma, lambda, active, {active}};  // (relinearise_active_set)
    J.B.setFromTriplets(ce.G.begin(), ce.G.end());
    J.K_coupling.setFromTriplets(coupling.begin(), coupling.end());
    for (int K = 0; K < m_; ++K) {
      if (active[K]) J.s[K] = s_.complementarity_scale;
      else J.d[K] = weights_[K];
    }
  }
  // The follower load stiffness is the only unsymmetric part: it goes
  // beside K (K_coupling), which a solver factorises without it (symmetric,
  // and K R = 0 for the translations that contact holds), and GMRES adds it.
  const bool loaded = std::any_of(s_.pressures.begin(), s_.pressures.end(),
                                  [&](const PressureLoad& p) { return p.curve(t) * p.value != 0; });
  if (load_stiffness_.size() > 0 && loaded) {
    std::fill(load_stiffness_.valuePtr(), load_stiffness_.valuePtr() + load_stiffness_.nonZeros(), 0.0);
    for (size_t i = 0; i < s_.pressures.size(); ++i) {
      const PressureLoad& p = s_.pressures[i];
      add_follower_pressure(*s_.body, *s_.dofs, p.faces, p.curve(t) * p.value, u, f_ext, &load_stiffness_, wet(i));
    }
    if (J.K_coupling.nonZeros() > 0) J.K_coupling = Eigen::SparseMatrix<double>(J.K_coupling + load_stiffness_);
    else J.K_coupling = load_stiffness_;
  }
  J.mixed_B.resize(0, 0);
  J.mixed_lambda.resize(0, 0);
  if (friction_) {  // the tangential rows below the normal ones; the slip rows tie lambda_t to lambda_n and gamma
    FiniteStrainFriction::TangentialRows& rows = jacobian_tangential_;
    friction_->constraint_rows(t, u, normal_multipliers(x), gamma, active, tangential(x), rows);
    using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
    const RowSparse& T = friction_->slip_rows();
    const int all = m_ + mt_;
    std::vector<Eigen::Triplet<double>> b;
    b.reserve(J.B.nonZeros() + T.nonZeros());
    for (int r = 0; r < J.B.outerSize(); ++r)
      for (RowSparse::InnerIterator it(J.B, r); it; ++it) b.emplace_back(r, int(it.col()), it.value());
    for (int r = 0; r < T.outerSize(); ++r)
      for (RowSparse::InnerIterator it(T, r); it; ++it) b.emplace_back(m_ + r, int(it.col()), it.value());
    J.B.resize(all, n_);
    J.B.setFromTriplets(b.begin(), b.end());
    J.s.conservativeResize(all);
    J.d.conservativeResize(all);
    J.s.tail(mt_) = rows.s;
    J.d.tail(mt_) = rows.d;
    J.mixed_B.resize(all, all);
    J.mixed_B.setFromTriplets(rows.mixed_B.begin(), rows.mixed_B.end());
    J.mixed_lambda.resize(all, all);
    J.mixed_lambda.setFromTriplets(rows.mixed_lambda.begin(), rows.mixed_lambda.end());
  }
  if (nz_ > 0) {  // the dilatations, condensed by the solver (BlockJacobian::local)
    J.local.C = local.mean_B;
    J.local.g = local.stiffness;
    J.local.h = local_scale_;
  }
  return true;
}

bool FiniteStrainProblem::relinearise_active_set(const Eigen::VectorXd& dx, BlockJacobian& J, Eigen::VectorXd& rhs) {
  JacobianPoint& p = at_jacobian_;
  if (m_ == 0 || friction_ || p.active.size() != size_t(m_) || dx.size() != size()) return false;
  const Eigen::VectorXd gamma = p.gamma + J.B * dx.head(n_);
  const Eigen::VectorXd lambda = p.lambda + normal_multipliers(dx);
  std::vector<char> active = decide_active(gamma, lambda);
  if (active == p.active) return false;
  if (std::find(p.visited.begin(), p.visited.end(), active) != p.visited.end()) return false;  // a cycle
  p.visited.push_back(active);
  // the rows of R(x) (residual) and of J (block_jacobian) under the new set
  for (int K = 0; K < m_; ++K) {
    J.s[K] = active[K] ? s_.complementarity_scale : 0.0;
    J.d[K] = active[K] ? 0.0 : weights_[K];
    rhs[n_ + K] = -(active[K] ? s_.complementarity_scale * p.gamma[K] : weights_[K] * p.lambda[K]);
  }
  p.active = std::move(active);
  return true;
}

bool FiniteStrainProblem::jacobian(double t, const Eigen::VectorXd& x, Eigen::SparseMatrix<double>& J) {
  if (!block_jacobian(t, x, blocks_)) return false;
  J = assemble_full(blocks_);
  return true;
}

int FiniteStrainProblem::active_set_size(double t, const Eigen::VectorXd& x) const {
  if (m_ == 0) return 0;
  const std::vector<char> a = decide_active(gaps_at(t, x), normal_multipliers(x));
  return int(std::count(a.begin(), a.end(), 1));
}

Eigen::VectorXd FiniteStrainProblem::gaps_at(double t, const Eigen::VectorXd& x) const {
  if (t == last_t_ && x.size() == last_x_.size() && x == last_x_) return last_gamma_;  // the same bits
  ContactEval ce;
  evaluate_contact(t, displacement(t, x), normal_multipliers(x), nullptr, ce, ContactTerms::gaps);
  return ce.gamma;
}

std::vector<char> FiniteStrainProblem::active_set(double t, const Eigen::VectorXd& x) const {
  if (m_ == 0) return {};
  std::vector<char> set = decide_active(gaps_at(t, x), normal_multipliers(x));
  if (friction_) {  // then each multiplier's FrictionState (open, stick, slip)
    const std::vector<char> states = friction_states(t, x);
    set.insert(set.end(), states.begin(), states.end());
  }
  return set;
}

std::vector<char> FiniteStrainProblem::friction_states(double t, const Eigen::VectorXd& x) const {
  if (!friction_) return {};
  const Eigen::VectorXd gamma = gaps_at(t, x), lambda = normal_multipliers(x);
  return friction_->states(t, displacement(t, x), lambda, gamma, decide_active(gamma, lambda), tangential(x));
}

Eigen::VectorXd FiniteStrainProblem::accumulated_slip(double t, const Eigen::VectorXd& x) const {
  return friction_ ? friction_->accumulated_slip(t, displacement(t, x)) : Eigen::VectorXd();
}

void FiniteStrainProblem::begin_step(double t, const Eigen::VectorXd& x) {
  if (friction_) friction_->begin_step(t, displacement(t, x));
  update_wet_elements(x);
}

bool FiniteStrainProblem::augment(double t, const Eigen::VectorXd& x) {
  const bool multipliers = tl_->augment(displacement(t, x));
  const bool fluid = update_wet_elements(x);
  unsettled_ = multipliers && fluid ? "the incompressibility constraint is not met and the fluid's wet faces still change"
               : multipliers        ? "the incompressibility constraint is not met"
                                    : "the fluid's wet faces still change with the contact front";
  return multipliers || fluid;
}

bool FiniteStrainProblem::update_wet_elements(const Eigen::VectorXd& x) {
  bool changed = false;
  for (size_t i = 0; i < s_.pressures.size(); ++i) {
    const FluidFront* front = s_.pressures[i].fluid.get();
    if (!front) continue;
    FaceElementFlags pressed = front->none();
    for (size_t k = 0; k < s_.contacts.size(); ++k)
      mark_pressed(*front, *s_.contacts[k].face, x.segment(n_ + offsets_[k], offsets_[k + 1] - offsets_[k]), pressed);
    FaceElementFlags wet = front->wet(pressed);
    if (wet != wet_[i]) changed = true;
    wet_[i] = std::move(wet);
  }
  return changed;
}

FiniteStrainProblem::History FiniteStrainProblem::history() const {
  History h;
  if (friction_) h.friction = friction_->history();
  if (tl_->incompressible()) h.pressure_multipliers = tl_->incompressibility()->accepted;
  return h;
}

void FiniteStrainProblem::restore(const History& h, const Eigen::VectorXd& x_from) {
  if (bool(friction_) == h.friction.empty() || tl_->incompressible() != (h.pressure_multipliers.size() > 0))
    throw std::invalid_argument("FiniteStrainProblem::restore: the history of another problem");
  if (friction_) friction_->restore(h.friction, displacement(h.friction.from, x_from));
  if (tl_->incompressible()) tl_->restore_multipliers(h.pressure_multipliers);
  update_wet_elements(x_from);
}

double FiniteStrainProblem::force_scale(double t, const Eigen::VectorXd& x) {
  const Eigen::MatrixXd u = displacement(t, x);
  Eigen::VectorXd f_int, f_ext = Eigen::VectorXd::Zero(n_);
  double scale = 0;
  if (elasticity(u, f_int, nullptr)) scale = f_int.cwiseAbs().maxCoeff();
  for (size_t i = 0; i < s_.pressures.size(); ++i) {
    const PressureLoad& p = s_.pressures[i];
    add_dead_pressure(*s_.body, *s_.dofs, p.faces, p.curve(t) * p.value, f_ext, wet(i));
  }
  add_dead_loads(t, f_ext);
  if (n_ > 0) scale = std::max(scale, f_ext.cwiseAbs().maxCoeff());
  // At rest with no load the forces are zero, or round-off (the mixed
  // formulation's isochoric stress at F = I is 1e-17, not 0): no scale then.
  return scale > 1e-12 * s_.complementarity_scale ? scale : 1.0;
}

Eigen::VectorXd FiniteStrainProblem::weighted_gaps(double t, const Eigen::VectorXd& x) const {
  if (m_ == 0) return {};
  return gaps_at(t, x).cwiseQuotient(weights_);
}

std::vector<Eigen::VectorXd> FiniteStrainProblem::contact_resultants(double t, const Eigen::VectorXd& x) const {
  if (m_ == 0) return {};
  ContactEval ce;
  evaluate_contact(t, displacement(t, x), normal_multipliers(x), nullptr, ce, ContactTerms::forces);
  if (friction_)
    for (size_t k = 0; k < ce.resultants.size(); ++k) ce.resultants[k] += friction_->tangential_resultant(int(k), tangential(x));
  return ce.resultants;
}

Eigen::VectorXd FiniteStrainProblem::contact_forces_on_every_dof(double t, const Eigen::VectorXd& x) const {
  const DofMap every(*s_.body, {});
  Eigen::VectorXd f = Eigen::VectorXd::Zero(every.num_free()), out = Eigen::VectorXd::Zero(every.num_dofs());
  if (m_ == 0) return out;
  const Eigen::VectorXd lambda = normal_multipliers(x);
  ContactEval ce;
  evaluate_contact(t, displacement(t, x), lambda, nullptr, ce, ContactTerms::forces, nullptr, &every);
  f += ce.force;
  if (friction_) f += friction_->forces_on_every_dof(tangential(x));  // (numbered as `every`, the friction's every_)
  // The dofs of a collapsed point share one equation: each holds its force.
  for (int i = 0; i < every.num_dofs(); ++i) out[i] = f[every.equation(i)];
  return out;
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
