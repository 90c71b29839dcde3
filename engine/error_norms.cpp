// SPDX-License-Identifier: BSD-3-Clause
#include "engine/error_norms.hpp"

#include <cmath>
#include <stdexcept>

#include "engine/discretisation.hpp"
#include "engine/free_cores.hpp"

namespace igac {
namespace {

// Integrates |v - v_h|^2 and |grad(v - v_h)|^2 over the elements of `mesh`,
// where `other(patch, xi, X, v, grad)` gives the comparison field.
using Other = std::function<void(int patch, const Eigen::VectorXd& xi, const Eigen::VectorXd& X, Eigen::VectorXd& v,
                                 Eigen::MatrixXd& grad)>;

ErrorNorms integrate(const Body& mesh, const Eigen::MatrixXd& u, int points, const Other& other,
                     bool mesh_field_is_reference) {
  const BodyQuadrature quad(mesh, points);
  const int dim = mesh.space_dim();
  double e0 = 0, e1 = 0, r0 = 0, r1 = 0;
#pragma omp parallel reduction(+ : e0, e1, r0, r1) num_threads(free_cores())
  {
    ElementData ed;
    Eigen::VectorXd v;
    Eigen::MatrixXd gv;
#pragma omp for schedule(dynamic, 16)
    for (int e = 0; e < quad.num_elements(); ++e) {
      quad.evaluate(e, ed, true);
      for (int q = 0; q < ed.JxW.size(); ++q) {
        Eigen::VectorXd uh = Eigen::VectorXd::Zero(dim);
        Eigen::MatrixXd guh = Eigen::MatrixXd::Zero(dim, dim);
        for (size_t a = 0; a < ed.cps.size(); ++a) {
          uh += ed.N(q, a) * u.row(ed.cps[a]).transpose();
          guh += u.row(ed.cps[a]).transpose() * ed.dN[q].row(a);
        }
        const Eigen::VectorXd xi = ed.xi.row(q).transpose();
        const Eigen::VectorXd X = ed.X.row(q).transpose();
        other(quad.patch_of(e), xi, X, v, gv);
        const double w = ed.JxW[q];
        e0 += (v - uh).squaredNorm() * w;
        e1 += (gv - guh).squaredNorm() * w;
        if (mesh_field_is_reference) {
          r0 += uh.squaredNorm() * w;
          r1 += guh.squaredNorm() * w;
        } else {
          r0 += v.squaredNorm() * w;
          r1 += gv.squaredNorm() * w;
        }
      }
    }
  }
  return {std::sqrt(e0), std::sqrt(e1), std::sqrt(r0), std::sqrt(r1)};
}

}  // namespace

ErrorNorms errors_against_exact(const Body& body, const Eigen::MatrixXd& u, const ExactDisplacement& exact,
                                int points) {
  return integrate(body, u, points,
                   [&](int, const Eigen::VectorXd&, const Eigen::VectorXd& X, Eigen::VectorXd& v, Eigen::MatrixXd& g) {
                     exact(X, v, g);
                   },
                   false);
}

ErrorNorms errors_against_reference(const Body& coarse, const Eigen::MatrixXd& u_coarse,
                                    const Body& fine, const Eigen::MatrixXd& u_fine, int points) {
  if (coarse.num_patches() != fine.num_patches())
    throw std::invalid_argument("errors against a reference: the meshes have different patches");
  std::vector<Eigen::MatrixXd> coarse_u;  // per patch
  for (int k = 0; k < coarse.num_patches(); ++k) coarse_u.push_back(coarse.patch_field(k, u_coarse));
  return integrate(fine, u_fine, points,
                   [&](int k, const Eigen::VectorXd& xi, const Eigen::VectorXd&, Eigen::VectorXd& v,
                       Eigen::MatrixXd& g) {
                     Eigen::MatrixXd dv;
                     v = coarse.patch(k).field(coarse_u[k], xi, &dv);
                     const Eigen::MatrixXd J = coarse.patch(k).jacobian(xi);
                     g = dv * J.inverse();
                   },
                   true);
}

}  // namespace igac
