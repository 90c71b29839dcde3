// SPDX-License-Identifier: BSD-3-Clause
#include "contact/coarse_start.hpp"

#include <stdexcept>

namespace igac {

Eigen::VectorXd prolongated_multipliers(const std::vector<const ContactFace*>& coarse_faces,
                                        const std::vector<const ContactFace*>& fine_faces,
                                        const Eigen::VectorXd& coarse_lambda) {
  if (coarse_faces.size() != fine_faces.size())
    throw std::invalid_argument("prolongated_multipliers: the coarse and fine meshes have different contact faces");
  int coarse_total = 0, fine_total = 0;
  for (size_t c = 0; c < fine_faces.size(); ++c) {
    if (coarse_faces[c]->sides.size() != fine_faces[c]->sides.size())
      throw std::invalid_argument("prolongated_multipliers: the coarse and fine contact faces differ");
    coarse_total += coarse_faces[c]->num_multipliers();
    fine_total += fine_faces[c]->num_multipliers();
  }
  if (coarse_lambda.size() != coarse_total)
    throw std::invalid_argument("prolongated_multipliers: the multipliers do not belong to the coarse faces");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(fine_total);
  std::vector<int> idx;
  std::vector<double> val;
  int coarse_first = 0, fine_first = 0;
  for (size_t c = 0; c < fine_faces.size(); ++c) {
    const ContactFace &cf = *coarse_faces[c], &ff = *fine_faces[c];
    for (size_t side = 0; side < ff.sides.size(); ++side) {
      const ContactSide &cs = cf.sides[side], &fs = ff.sides[side];
      for (int K = 0; K < fs.space.size(); ++K) {
        cs.space.basis(fs.space.anchor(K), idx, val);
        double l = 0;
        for (size_t j = 0; j < idx.size(); ++j) l += coarse_lambda[coarse_first + cs.first_multiplier + idx[j]] * val[j];
        out[fine_first + fs.first_multiplier + K] = l;
      }
    }
    coarse_first += cf.num_multipliers();
    fine_first += ff.num_multipliers();
  }
  return out;
}

ActiveSetStart start_from_coarse(const std::vector<const ContactFace*>& coarse_faces,
                                 const std::vector<const ContactFace*>& fine_faces,
                                 const Eigen::SparseMatrix<double, Eigen::RowMajor>& P, const ContactSolution& coarse,
                                 const WeightedGapOperator& fine_op, int k, double cn) {
  if (P.cols() != coarse.u.size() || P.rows() != fine_op.G.cols())
    throw std::invalid_argument("start_from_coarse: the prolongation does not fit the coarse and fine meshes");
  ActiveSetStart s;
  s.u = P * coarse.u;
  s.lambda = prolongated_multipliers(coarse_faces, fine_faces, coarse.lambda);
  const int m = int(fine_op.weights.size());
  if (s.lambda.size() != m) throw std::invalid_argument("start_from_coarse: the fine faces do not fit the weighted gaps");
  const Eigen::VectorXd gap = (fine_op.g0 + fine_op.G * s.u).cwiseQuotient(fine_op.weights);
  s.active = next_active_set(s.lambda, gap, std::vector<char>(m, 0), k, cn);
  for (int K = 0; K < m; ++K)
    if (!s.active[K]) s.lambda[K] = 0.0;
  return s;
}

}  // namespace igac
