// SPDX-License-Identifier: BSD-3-Clause
#include "contact/mortar_gap.hpp"

#include <stdexcept>
#include <string>

namespace igac {

ObstacleProbe MasterAsObstacle::probe(const Eigen::VectorXd& x, bool with_derivative) const {
  if (with_derivative)
    throw std::logic_error("a master surface has no normal derivative here: two-body contact is small-deformation");
  const std::optional<MasterPoint> mp = master_->project(x);
  if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
  ObstacleProbe out;
  out.gap = mp->gap;
  out.normal = mp->normal;
  return out;
}

std::string MasterAsObstacle::describe() const { return "the deformable face '" + name_ + "'"; }

WeightedGapOperator assemble_mortar_gaps(const DofMap& dofs, const ContactFace& slave, const MasterSurface& master) {
  const int m = slave.num_multipliers();
  WeightedGapOperator op;
  op.weights = Eigen::VectorXd::Zero(m);
  op.g0 = Eigen::VectorXd::Zero(m);
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<int> master_local;
  Eigen::VectorXd master_values;
  Eigen::MatrixXd master_derivs;
  ContactQuadrature(slave).for_each_point([&](const auto& ev, int q, const std::vector<int>& K,
                                              const std::vector<double>& B) {
    const Eigen::VectorXd X = ev.X[q];
    const std::optional<MasterPoint> mp = master.project(X);
    if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
    master.side_patch(mp->side).rational_basis(mp->xi, master_local, master_values, master_derivs);
    const std::vector<int>& master_cps = master.side_control_points(mp->side);
    for (size_t k = 0; k < K.size(); ++k) {
      const double bw = B[k] * ev.JxW[q];
      if (bw == 0.0) continue;
      op.weights[K[k]] += bw;
      op.g0[K[k]] += mp->gap * bw;
      for (int a = 0; a < ev.n_loc; ++a) add_gap_coupling(dofs, K[k], ev.cps[a], bw * ev.N(q, a), mp->normal, trip, op.g0);
      for (size_t a = 0; a < master_local.size(); ++a)
        add_gap_coupling(dofs, K[k], master_cps[master_local[a]], -bw * master_values[a], mp->normal, trip, op.g0);
    }
  });
  op.G.resize(m, dofs.num_free());
  op.G.setFromTriplets(trip.begin(), trip.end());
  op.G.prune(0.0);
  return op;
}

Eigen::VectorXd exact_mortar_gaps(const Eigen::MatrixXd& u, const ContactFace& slave, MasterSurface& master) {
  master.update(u);
  const int m = slave.num_multipliers();
  Eigen::VectorXd num = Eigen::VectorXd::Zero(m), den = Eigen::VectorXd::Zero(m);
  ContactQuadrature(slave).for_each_point([&](const auto& ev, int q, const std::vector<int>& K,
                                              const std::vector<double>& B) {
    const std::optional<MasterPoint> mp = master.project(ev.displaced(q, u));
    if (!mp) throw std::invalid_argument("a contact's master surface has no elements");
    for (size_t k = 0; k < K.size(); ++k) {
      num[K[k]] += mp->gap * B[k] * ev.JxW[q];
      den[K[k]] += B[k] * ev.JxW[q];
    }
  });
  return num.cwiseQuotient(den);
}

}  // namespace igac
