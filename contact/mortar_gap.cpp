// SPDX-License-Identifier: BSD-3-Clause
#include "contact/mortar_gap.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <stdexcept>

#include <string>

#include "contact/mortar_cells.hpp"
#include "engine/quadrature.hpp"

namespace igac {

ObstacleProbe MasterAsObstacle::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  if (with_derivative)
    // (the reports and checks read the gap only; the large-deformation
    // coupling linearises the master itself: contact/finite_strain_mortar)
    throw std::logic_error("MasterAsObstacle::probe: no derivative: a master seen as an obstacle serves the reports only");
  const std::optional<MasterPoint> mp = master_->project(x);
  if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
  ObstacleProbe out;
  out.gap = mp->gap;
  out.normal = mp->normal;
  return out;
}

std::string MasterAsObstacle::describe() const { return "the deformable face '" + name_ + "'"; }

namespace {

// The slave side's element [a, b] (2D: a curve) cut where the master
// point nearest to it crosses a master element edge, so that the master's
// basis is smooth on every piece.  The projected master parameter is
// monotone along the slave curve; each crossing of a master breakpoint is
// found by the Illinois (regula falsi) iteration on it; a change of master
// side by bisection.
std::vector<double> segment_cuts(const ContactSide& side, const Eigen::MatrixXd* u_side, const MasterSurface& master,
                                 double a, double b) {
  constexpr double kParameterTolerance = 1e-13;
  auto project = [&](double t) {
    const Eigen::VectorXd xi = Eigen::VectorXd::Constant(1, t);
    Eigen::VectorXd x = side.face_patch.point(xi);
    if (u_side) x += side.face_patch.field(*u_side, xi);
    const std::optional<MasterPoint> mp = master.project(x);
    if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
    return *mp;
  };
  std::vector<double> cuts{a, b};
  std::vector<std::pair<double, double>> todo{{a, b}};
  while (!todo.empty()) {
    const auto [t0, t1] = todo.back();
    todo.pop_back();
    const MasterPoint p0 = project(t0), p1 = project(t1);
    if (p0.side == p1.side && p0.element == p1.element) continue;
    if (t1 - t0 < kParameterTolerance * (b - a)) continue;
    if (p0.side != p1.side) {  // two master sides: halve until each piece has one
      const double tm = 0.5 * (t0 + t1);
      cuts.push_back(tm);
      todo.push_back({t0, tm});
      todo.push_back({tm, t1});
      continue;
    }
    // One master side: every breakpoint strictly between the two master
    // parameters is a cut.
    const double x0 = p0.xi[0], x1 = p1.xi[0];
    for (double beta : master.side_patch(p0.side).knots(0).breakpoints()) {
      if (!(beta > std::min(x0, x1) && beta < std::max(x0, x1))) continue;
      double lo = t0, hi = t1, f_lo = x0 - beta, f_hi = x1 - beta, t = 0.5 * (t0 + t1);
      int side_kept = 0;
      for (int it = 0; it < 100 && hi - lo > kParameterTolerance * (b - a); ++it) {
        t = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
        const double f = project(t).xi[0] - beta;
        if (f == 0.0) break;
        if ((f < 0) == (f_lo < 0)) {
          lo = t, f_lo = f;
          if (side_kept == -1) f_hi *= 0.5;  // Illinois: the stale end's value halved
          side_kept = -1;
        } else {
          hi = t, f_hi = f;
          if (side_kept == 1) f_lo *= 0.5;
          side_kept = 1;
        }
      }
      cuts.push_back(t);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end(), [&](double x, double y) { return y - x < kParameterTolerance * (b - a); }),
             cuts.end());
  cuts.back() = b;
  return cuts;
}

}  // namespace

void for_each_mortar_point(const ContactFace& slave, const MasterSurface& master, MortarIntegration integration,
                           const Eigen::MatrixXd* u, const std::function<void(const MortarSlavePoint&)>& visit,
                           const ContactQuadrature* tabulated) {
  MortarSlavePoint sp;
  const auto displace = [&] {
    sp.x = sp.X;
    if (u)
      for (size_t a = 0; a < sp.cps.size(); ++a) sp.x += sp.N[Eigen::Index(a)] * u->row(sp.cps[a]).transpose();
  };
  if (integration == MortarIntegration::element) {
    std::optional<ContactQuadrature> own;
    if (!tabulated) own.emplace(slave);
    (tabulated ? *tabulated : *own).for_each_point([&](const auto& ev, int q, const std::vector<int>& K,
                                                const std::vector<double>& B) {
      sp.X = ev.X[q];
      sp.JxW = ev.JxW[q];
      sp.cps.assign(ev.cps.begin(), ev.cps.begin() + ev.n_loc);
      sp.N.resize(ev.n_loc);
      for (int a = 0; a < ev.n_loc; ++a) sp.N[a] = ev.N(q, a);
      sp.K = K;
      sp.B = B;
      displace();
      visit(sp);
    });
    return;
  }
  // Segmented: the points of each side's cut elements, at parameters xi
  // with weights w (parameter measure; times the reference face's
  // Jacobian here).
  std::vector<int> local;
  Eigen::VectorXd values;
  Eigen::MatrixXd derivs, tangents;
  const auto emit = [&](const ContactSide& side, const Eigen::VectorXd& xi, double w) {
    side.face_patch.rational_basis(xi, local, values, derivs);
    sp.X = Eigen::VectorXd::Zero(side.face_patch.space_dim());
    tangents = Eigen::MatrixXd::Zero(side.face_patch.space_dim(), side.face_patch.param_dim());
    sp.cps.resize(local.size());
    for (size_t a = 0; a < local.size(); ++a) {
      sp.X += values[Eigen::Index(a)] * side.face_patch.points().row(local[a]).transpose();
      tangents += side.face_patch.points().row(local[a]).transpose() * derivs.row(Eigen::Index(a));
      sp.cps[a] = side.face_cps[local[a]];
    }
    sp.N = values;
    sp.JxW = w * std::sqrt((tangents.transpose() * tangents).determinant()) * side.face_patch.ring_length(sp.X);
    side.space.basis(xi, sp.K, sp.B);
    for (int& K : sp.K) K += side.first_multiplier;
    displace();
    visit(sp);
  };
  const GaussRule rule = gauss_legendre(slave.quadrature_points());
  Eigen::MatrixXd u_side;
  std::vector<Eigen::VectorXd> points;
  std::vector<double> weights;
  for (const ContactSide& side : slave.sides) {
    if (u) {
      u_side.resize(Eigen::Index(side.face_cps.size()), u->cols());
      for (size_t a = 0; a < side.face_cps.size(); ++a) u_side.row(Eigen::Index(a)) = u->row(side.face_cps[a]);
    }
    if (side.face_patch.param_dim() == 2) {  // 3D: cells of the slave elements (contact/mortar_cells.hpp)
      segmented_side_rule(side, u ? &u_side : nullptr, master, slave.quadrature_points(), points, weights);
      for (size_t q = 0; q < points.size(); ++q) emit(side, points[q], weights[q]);
      continue;
    }
    const std::vector<double> breaks = side.face_patch.knots(0).breakpoints();
    for (size_t e = 0; e + 1 < breaks.size(); ++e) {
      const std::vector<double> cuts = segment_cuts(side, u ? &u_side : nullptr, master, breaks[e], breaks[e + 1]);
      for (size_t c = 0; c + 1 < cuts.size(); ++c)
        for (size_t q = 0; q < rule.points.size(); ++q)
          emit(side, Eigen::VectorXd::Constant(1, cuts[c] + rule.points[q] * (cuts[c + 1] - cuts[c])),
               rule.weights[q] * (cuts[c + 1] - cuts[c]));
    }
  }
}

WeightedGapOperator assemble_mortar_gaps(const DofMap& dofs, const ContactFace& slave, const MasterSurface& master,
                                         MortarIntegration integration, const ContactLaw& law, const Eigen::VectorXd& shift,
                                         const Eigen::MatrixXd* u) {
  const int m = slave.num_multipliers(), nt = dofs.dim() - 1;
  WeightedGapOperator op;
  op.weights = Eigen::VectorXd::Zero(m);
  op.g0 = Eigen::VectorXd::Zero(m);
  const bool tangential = law.tangential();
  op.laws.assign(size_t(m), &law.get());
  if (tangential) {
    op.t0 = Eigen::VectorXd::Zero(m * nt);
    op.friction = Eigen::VectorXd::Constant(m, law.get().has_coefficient() ? law.friction : 0.0);
  }
  op.directions = Eigen::MatrixXd::Zero(m, dofs.dim());
  GapCouplings trip, ttrip;
  std::vector<int> master_local;
  Eigen::VectorXd master_values;
  Eigen::MatrixXd master_derivs;
  for_each_mortar_point(slave, master, integration, u, [&](const MortarSlavePoint& sp) {
    const std::optional<MasterPoint> mp = master.project(u ? sp.x : sp.X);
    if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
    master.side_patch(mp->side).rational_basis(mp->xi, master_local, master_values, master_derivs);
    const std::vector<int>& master_cps = master.side_control_points(mp->side);
    const Eigen::MatrixXd t = tangential ? tangent_basis(mp->normal) : Eigen::MatrixXd();
    const double gap = shift.size() ? mp->gap - shift.dot(mp->normal) : mp->gap;
    for (size_t k = 0; k < sp.K.size(); ++k) {
      const double bw = sp.B[k] * sp.JxW;
      if (bw == 0.0) continue;
      op.weights[sp.K[k]] += bw;
      op.g0[sp.K[k]] += gap * bw;
      op.directions.row(sp.K[k]) += bw * mp->normal.transpose();
      for (size_t a = 0; a < sp.cps.size(); ++a)
        add_gap_coupling(dofs, sp.K[k], sp.cps[a], bw * sp.N[Eigen::Index(a)], mp->normal, trip, op.g0);
      for (size_t a = 0; a < master_local.size(); ++a)
        add_gap_coupling(dofs, sp.K[k], master_cps[master_local[a]], -bw * master_values[Eigen::Index(a)], mp->normal,
                         trip, op.g0);
      for (int j = 0; j < t.cols(); ++j) {  // friction: the same couplings along the master's tangents
        const int row = sp.K[k] * nt + j;
        if (shift.size()) op.t0[row] -= bw * shift.dot(t.col(j));
        for (size_t a = 0; a < sp.cps.size(); ++a)
          add_gap_coupling(dofs, row, sp.cps[a], bw * sp.N[Eigen::Index(a)], t.col(j), ttrip, op.t0);
        for (size_t a = 0; a < master_local.size(); ++a)
          add_gap_coupling(dofs, row, master_cps[master_local[a]], -bw * master_values[Eigen::Index(a)], t.col(j),
                           ttrip, op.t0);
      }
    }
  });
  trip.build(dofs, m, op.G, op.G_held);
  if (tangential) ttrip.build(dofs, m * nt, op.T, op.T_held);
  return op;
}

Eigen::VectorXd exact_mortar_gaps(const Eigen::MatrixXd& u, const ContactFace& slave, MasterSurface& master,
                                  MortarIntegration integration) {
  // The slave points at the reference position (where the integral is
  // taken), each moved by u; the master moved by u.
  master.update(Eigen::MatrixXd::Zero(u.rows(), u.cols()));  // the cuts of the reference surface
  const int m = slave.num_multipliers();
  Eigen::VectorXd num = Eigen::VectorXd::Zero(m), den = Eigen::VectorXd::Zero(m);
  std::vector<MortarSlavePoint> points;
  for_each_mortar_point(slave, master, integration, nullptr, [&](const MortarSlavePoint& sp) {
    points.push_back(sp);
    for (size_t a = 0; a < sp.cps.size(); ++a) points.back().x += sp.N[Eigen::Index(a)] * u.row(sp.cps[a]).transpose();
  });
  master.update(u);
  for (const MortarSlavePoint& sp : points) {
    const std::optional<MasterPoint> mp = master.project(sp.x);
    if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
    for (size_t k = 0; k < sp.K.size(); ++k) {
      num[sp.K[k]] += mp->gap * sp.B[k] * sp.JxW;
      den[sp.K[k]] += sp.B[k] * sp.JxW;
    }
  }
  return num.cwiseQuotient(den);
}

}  // namespace igac
