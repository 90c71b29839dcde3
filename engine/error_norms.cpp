#include "engine/error_norms.hpp"

#include <cmath>

#include "engine/discretisation.hpp"

namespace igac {
namespace {

// Integrates |v - v_h|^2 and |grad(v - v_h)|^2 over the elements of `mesh`,
// where `other(xi, X, J, v, grad)` gives the comparison field.
using Other = std::function<void(const Eigen::VectorXd& xi, const Eigen::VectorXd& X, const Eigen::MatrixXd& J,
                                 Eigen::VectorXd& v, Eigen::MatrixXd& grad)>;

ErrorNorms integrate(const NurbsPatch& mesh, const Eigen::MatrixXd& u, int points, const Other& other,
                     bool mesh_field_is_reference) {
  const PatchQuadrature quad(mesh, points);
  const int dim = mesh.space_dim();
  double e0 = 0, e1 = 0, r0 = 0, r1 = 0;
#pragma omp parallel reduction(+ : e0, e1, r0, r1)
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
        // J is needed only by reference comparisons: rebuild it from dN
        const Eigen::VectorXd xi = ed.xi.row(q).transpose();
        const Eigen::VectorXd X = ed.X.row(q).transpose();
        other(xi, X, Eigen::MatrixXd(), v, gv);
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

ErrorNorms errors_against_exact(const NurbsPatch& patch, const Eigen::MatrixXd& u, const ExactDisplacement& exact,
                                int points) {
  return integrate(patch, u, points,
                   [&](const Eigen::VectorXd&, const Eigen::VectorXd& X, const Eigen::MatrixXd&, Eigen::VectorXd& v,
                       Eigen::MatrixXd& g) { exact(X, v, g); },
                   false);
}

ErrorNorms errors_against_reference(const NurbsPatch& coarse, const Eigen::MatrixXd& u_coarse,
                                    const NurbsPatch& fine, const Eigen::MatrixXd& u_fine, int points) {
  return integrate(fine, u_fine, points,
                   [&](const Eigen::VectorXd& xi, const Eigen::VectorXd&, const Eigen::MatrixXd&, Eigen::VectorXd& v,
                       Eigen::MatrixXd& g) {
                     Eigen::MatrixXd dv;
                     v = coarse.field(u_coarse, xi, &dv);
                     const Eigen::MatrixXd J = coarse.jacobian(xi);
                     g = dv * J.inverse();
                   },
                   true);
}

}  // namespace igac
