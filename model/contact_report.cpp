// SPDX-License-Identifier: BSD-3-Clause
#include "model/solve.hpp"

namespace igac {

std::vector<ObstacleReaction> obstacle_reactions(const Model& m, const Eigen::VectorXd& lambda,
                                                const Eigen::VectorXd& weights, const std::vector<char>& active,
                                                const Eigen::VectorXd& lambda_t) {
  std::vector<ObstacleReaction> out;
  int offset = 0;
  const int nt = lambda.size() ? int(lambda_t.size() / lambda.size()) : 0;
  for (const auto& c : m.contacts) {
    ObstacleReaction rr{c.face_name, c.obstacle->describe(), 0.0, 0, {}};
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
