// SPDX-License-Identifier: BSD-3-Clause
#include "model/solve.hpp"

namespace igac {

std::vector<ObstacleReaction> obstacle_reactions(const Model& m, const Eigen::VectorXd& lambda,
                                                const Eigen::VectorXd& weights, const std::vector<char>& active) {
  std::vector<ObstacleReaction> out;
  int offset = 0;
  for (const auto& c : m.contacts) {
    ObstacleReaction rr{c.face_name, c.obstacle->describe(), 0.0, 0};
    for (int K = offset; K < offset + c.face->num_multipliers(); ++K) {
      rr.normal_force -= lambda[K] * weights[K];
      rr.active += active[K] ? 1 : 0;
    }
    rr.normal_force += 0.0;  // no -0
    offset += c.face->num_multipliers();
    out.push_back(rr);
  }
  return out;
}

void report_first_contact(const Model& m, ContactResult& c) {
  const Model::Contact& first = m.contacts.front();
  const int m0 = first.face->num_multipliers();
  std::tie(c.X0, c.normal) = initial_contact_point(*first.face, *first.obstacle);
  c.pressure = std::make_unique<ContactPressure>(
      *first.face, c.solution.lambda.head(m0), c.op.weights.head(m0),
      std::vector<char>(c.solution.active.begin(), c.solution.active.begin() + m0), c.X0, c.normal);
  c.report = c.pressure->report();
}

}  // namespace igac
