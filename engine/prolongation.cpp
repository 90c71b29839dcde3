// SPDX-License-Identifier: BSD-3-Clause
#include "engine/prolongation.hpp"

#include <fmt/format.h>

#include "engine/spline/refinement.hpp"

namespace igac {

Eigen::SparseMatrix<double, Eigen::RowMajor> prolongation(const Body& coarse, const DofMap& cd, const Body& fine,
                                                          const DofMap& fd) {
  if (coarse.num_patches() != fine.num_patches() || coarse.param_dim() != fine.param_dim() || cd.dim() != fd.dim())
    throw SplineError(fmt::format("prolongation between different bodies ({} and {} patches)", coarse.num_patches(),
                                  fine.num_patches()));
  const int dim = fd.dim(), pd = fine.param_dim();
  std::vector<Eigen::Triplet<double>> t;
  std::vector<char> done(fd.num_free(), 0);  // rows given (a point on an interface is in two patches)
  std::vector<std::pair<int, double>> row;   // coarse point (patch numbering), coefficient
  for (int k = 0; k < fine.num_patches(); ++k) {
    const NurbsPatch &pc = coarse.patch(k), &pf = fine.patch(k);
    std::array<Eigen::SparseMatrix<double, Eigen::RowMajor>, 3> T;
    for (int d = 0; d < 3; ++d) {
      if (d < pd) {
        T[d] = knot_insertion_matrix(pc.knots(d), pf.knots(d));
      } else {
        T[d].resize(1, 1);
        T[d].insert(0, 0) = 1.0;
      }
    }
    const std::vector<int>& bc = coarse.body_cps(k);
    const std::vector<int>& bf = fine.body_cps(k);
    for (int i = 0; i < pf.num_control_points(); ++i) {
      const std::array<int, 3> f = pf.multi_index(i);
      row.clear();
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator a(T[0], f[0]); a; ++a)
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator b(T[1], f[1]); b; ++b)
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator c(T[2], f[2]); c; ++c) {
            const int j = pc.index({int(a.col()), int(b.col()), int(c.col())});
            row.emplace_back(j, pc.weights()[j] / pf.weights()[i] * a.value() * b.value() * c.value());
          }
      for (int comp = 0; comp < dim; ++comp) {
        // A fine equation may stand for several dofs (coincident points
        // held together): its row once.  Coarse dofs sharing an equation
        // add up in its column (setFromTriplets sums them).
        const int r = fd.equation(bf[i] * dim + comp);
        if (r < 0 || done[r]) continue;
        done[r] = 1;
        for (const auto& [j, v] : row)
          if (const int col = cd.equation(bc[j] * dim + comp); col >= 0) t.emplace_back(r, col, v);
      }
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> P(fd.num_free(), cd.num_free());
  P.setFromTriplets(t.begin(), t.end());
  return P;
}

}  // namespace igac
