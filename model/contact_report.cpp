// SPDX-License-Identifier: BSD-3-Clause
#include "model/solve.hpp"

#include <algorithm>
#include <optional>

namespace igac {

std::vector<ObstacleReaction> obstacle_reactions(const Model& m, const Eigen::VectorXd& lambda,
                                                const Eigen::VectorXd& weights, const std::vector<char>& active,
                                                const Eigen::VectorXd& lambda_t) {
  std::vector<ObstacleReaction> out;
  int offset = 0;
  const int nt = lambda.size() ? int(lambda_t.size() / lambda.size()) : 0;
  for (const auto& c : m.contacts) {
    ObstacleReaction rr{.face = c.face_name, .obstacle = c.obstacle->describe()};
    if (nt > 0) rr.tangential_force = Eigen::VectorXd::Zero(nt);
    for (int K = offset; K < offset + c.face->num_multipliers(); ++K) {
      rr.normal_force -= lambda[K] * weights[K];
      rr.active += active[K] ? 1 : 0;
      if (nt > 0) rr.tangential_force -= lambda_t.segment(K * nt, nt) * weights[K];
    }
    rr.normal_force += 0.0;  // no -0
    offset += c.face->num_multipliers();
    out.push_back(rr);
  }
  return out;
}

void add_extrusions(const Model& m, const Eigen::MatrixXd& u, double t, std::vector<ObstacleReaction>& reactions) {
  for (size_t i = 0; i < m.contacts.size() && i < reactions.size(); ++i) {
    const Model::Contact& c = m.contacts[i];
    if (c.master) continue;
    // Where the obstacle stands at t: large deformation moves the reference
    // one by curve(t) motion; small deformation holds it where the whole
    // motion puts it (model/build_model.cpp), so a curve below 1 draws it back.
    Eigen::VectorXd shift = Eigen::VectorXd::Zero(m.body.space_dim());
    if (c.motion.size() > 0) shift = (c.curve(t) - (m.spec.finite_strain() ? 0.0 : 1.0)) * c.motion;
    const TranslatedObstacle obstacle(*c.obstacle, shift);
    // An obstacle without an edge has no reach anywhere: sample nothing.
    if (!obstacle.reach_past_edge(Eigen::VectorXd::Zero(m.body.space_dim()))) continue;
    std::optional<double> reach;
    for (const ContactSide& side : c.face->sides) {
      Eigen::MatrixXd uf(side.face_cps.size(), m.body.space_dim());
      for (size_t a = 0; a < side.face_cps.size(); ++a) uf.row(Eigen::Index(a)) = u.row(side.face_cps[a]);
      // Each face element at a grid of p + 2 points a direction, its ends
      // included (a tongue's tip may lie on one).
      const NurbsPatch& f = side.face_patch;
      std::vector<std::vector<double>> along(size_t(f.param_dim()));
      for (int d = 0; d < f.param_dim(); ++d) {
        const std::vector<double> breaks = f.knots(d).breakpoints();
        const int n = f.degree(d) + 1;
        for (size_t e = 0; e + 1 < breaks.size(); ++e)
          for (int k = 0; k < n; ++k) along[size_t(d)].push_back(breaks[e] + (breaks[e + 1] - breaks[e]) * k / n);
        along[size_t(d)].push_back(breaks.back());
      }
      Eigen::VectorXd xi(f.param_dim());
      const size_t n0 = along[0].size(), n1 = f.param_dim() > 1 ? along[1].size() : 1;
      for (size_t i0 = 0; i0 < n0; ++i0)
        for (size_t i1 = 0; i1 < n1; ++i1) {
          xi[0] = along[0][i0];
          if (f.param_dim() > 1) xi[1] = along[1][i1];
          const Eigen::VectorXd x = f.point(xi) + f.field(uf, xi);
          if (const std::optional<double> r = obstacle.reach_past_edge(x)) reach = std::max(reach.value_or(0.0), *r);
        }
    }
    reactions[i].extrusion = reach;
  }
}

std::vector<ContactResult> report_contacts(const Model& m, const ContactSolve& s) {
  std::vector<ContactResult> out;
  int offset = 0;
  for (const auto& c : m.contacts) {
    ContactResult& cr = out.emplace_back();
    const int n = c.face->num_multipliers();
    cr.face = c.face_name;
    cr.first_multiplier = offset;
    cr.num_multipliers = n;
    std::tie(cr.X0, cr.normal) = initial_contact_point(*c.face, *c.obstacle);
    const auto active = s.solution.active.begin() + offset;
    cr.pressure = std::make_unique<ContactPressure>(*c.face, s.solution.lambda.segment(offset, n),
                                                    s.op.weights.segment(offset, n),
                                                    std::vector<char>(active, active + n), cr.X0, cr.normal);
    cr.report = cr.pressure->report();
    cr.has_half_width = !touches_over_an_extent(*c.face, *c.obstacle);
    for (int K = offset; K < offset + n; ++K)
      if (s.solution.active[K]) cr.contact_area += s.op.weights[K];
    // The normal force on the face, -sum_K lambda_K int B_K n: against a
    // curved partner the resultant, what balances the loads (the integral
    // of p, sum_K -lambda_K K_K, exceeds it).
    if (s.op.directions.rows() == s.solution.lambda.size())
      cr.resultant = -(s.op.directions.middleRows(offset, n).transpose() * s.solution.lambda.segment(offset, n));
    offset += n;
  }
  return out;
}

}  // namespace igac
