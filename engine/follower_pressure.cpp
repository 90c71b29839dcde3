#include "engine/follower_pressure.hpp"

#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <stdexcept>

#include "engine/quadrature.hpp"
#include "engine/spline/rational_basis.hpp"

namespace igac {

namespace {

// Orientation factor sigma of the outward area vector, written with the face
// tangents t_0 (, t_1) in their parametric order (as face_area_vector):
//   2D: a = sigma (t_0[1], -t_0[0]),  3D: a = sigma t_0 x t_1.
double orientation(const Face& f, int dim) {
  const double s = f.at_end ? 1.0 : -1.0;
  if (dim == 2) return f.direction == 0 ? s : -s;
  return f.direction == 1 ? -s : s;
}

template <int dim>
Eigen::Matrix<double, dim, 1> area_vector(double sigma, const Eigen::Matrix<double, dim, dim - 1>& T) {
  if constexpr (dim == 2)
    return sigma * Eigen::Vector2d(T(1, 0), -T(0, 0));
  else
    return sigma * T.col(0).cross(T.col(1));
}

// d a / d u_(B,k) for a basis function with parametric derivatives dR
// (one per face direction): a is linear in each tangent, and
// d t_a / d u_(B,k) = dR_a e_k.
template <int dim>
Eigen::Matrix<double, dim, 1> area_derivative(double sigma, const Eigen::Matrix<double, dim, dim - 1>& T,
                                              const double* dR, int k) {
  Eigen::Matrix<double, dim, 1> ek = Eigen::Matrix<double, dim, 1>::Unit(k);
  if constexpr (dim == 2)
    return sigma * dR[0] * Eigen::Vector2d(ek[1], -ek[0]);
  else
    return sigma * (dR[0] * ek.cross(T.col(1)) + dR[1] * T.col(0).cross(ek));
}

// Pressure p on one face: f_ext -= p int N_A a dxi, with a the area vector
// of the current face (u given) or of the reference face (u null); when K is
// given, K += p int N_A da/du dxi (= -d f_ext / du).
template <int dim>
void face_pressure(const Body& body, const DofMap& dofs, const PatchSide& side, double p,
                   const Eigen::MatrixXd* u, Eigen::VectorXd& f, Eigen::SparseMatrix<double>* K) {
  constexpr int pd = dim - 1;
  const NurbsPatch fp = body.side_patch(side);
  const std::vector<int> parent = body.side_control_points(side);
  const GaussRule rule = gauss_legendre(gauss_points_for(body.degree()));
  const int nq1 = int(rule.points.size());
  const double sigma = orientation(side.face, dim);
  std::array<UnivariateTable, 2> t;
  std::array<int, 2> np{1, 1}, n_el{1, 1}, nq{1, 1};
  for (int d = 0; d < pd; ++d) {
    t[d] = tabulate(fp.knots(d), rule);
    np[d] = t[d].degree + 1;
    n_el[d] = int(t[d].span.size());
    nq[d] = nq1;
  }
  const int nl = np[0] * np[1], n_pts = nq[0] * nq[1];

  std::vector<int> eq(nl * dim);
  Eigen::VectorXd wt(nl), R(nl), dRv(nl * pd);
  Eigen::Matrix<double, Eigen::Dynamic, pd> dR(nl, pd);
  Eigen::Matrix<double, Eigen::Dynamic, dim> x(nl, dim);  // current (or reference) control points
  Eigen::Matrix<double, dim, pd> T;
  std::vector<Eigen::Matrix<double, dim, 1>> da(nl * dim);
  const int* outer = K ? K->outerIndexPtr() : nullptr;
  const int* inner = K ? K->innerIndexPtr() : nullptr;

  for (int e1 = 0; e1 < n_el[1]; ++e1)
    for (int e0 = 0; e0 < n_el[0]; ++e0) {
      const std::array<int, 2> ei{e0, e1};
      for (int a = 0; a < nl; ++a) {
        const std::array<int, 2> loc{a % np[0], a / np[0]};
        std::array<int, 3> gi{0, 0, 0};
        for (int d = 0; d < pd; ++d) gi[d] = t[d].span[ei[d]] - t[d].degree + loc[d];
        const int own = fp.index(gi), cp = parent[own];
        wt[a] = fp.weights()[own];
        x.row(a) = fp.points().row(own);
        if (u) x.row(a) += u->row(cp);
        for (int i = 0; i < dim; ++i) eq[a * dim + i] = dofs.equation(cp * dim + i);
      }
      for (int q = 0; q < n_pts; ++q) {
        const std::array<int, 2> qi{q % nq[0], q / nq[0]};
        std::array<int, 2> row{0, 0};
        double wq = 1;
        for (int d = 0; d < pd; ++d) {
          row[d] = ei[d] * nq[d] + qi[d];
          wq *= t[d].weight[row[d]];
        }
        // rational basis and its parametric derivatives
        std::array<const double*, pd> Nd, dNd;
        for (int d = 0; d < pd; ++d) {
          Nd[d] = t[d].value.data() + size_t(row[d]) * np[d];
          dNd[d] = t[d].deriv.data() + size_t(row[d]) * np[d];
        }
        rational_basis_values<pd>(np.data(), Nd.data(), dNd.data(), wt.data(), R.data(), dRv.data());
        for (int a = 0; a < nl; ++a)
          for (int d = 0; d < pd; ++d) dR(a, d) = dRv[a * pd + d];
        T.noalias() = x.transpose() * dR;
        const Eigen::Matrix<double, dim, 1> area = area_vector<dim>(sigma, T);
        const double pw = p * wq;
        for (int a = 0; a < nl; ++a)
          for (int i = 0; i < dim; ++i)
            if (eq[a * dim + i] >= 0) f[eq[a * dim + i]] -= pw * R[a] * area[i];
        if (!K) continue;
        for (int b = 0; b < nl; ++b) {
          const double dRb[2] = {dR(b, 0), pd > 1 ? dR(b, pd - 1) : 0.0};
          for (int k = 0; k < dim; ++k) da[b * dim + k] = area_derivative<dim>(sigma, T, dRb, k);
        }
        for (int c = 0; c < nl * dim; ++c) {
          if (eq[c] < 0) continue;
          const int* first = inner + outer[eq[c]];
          const int* past = inner + outer[eq[c] + 1];
          for (int a = 0; a < nl; ++a)
            for (int i = 0; i < dim; ++i) {
              const int r = eq[a * dim + i];
              if (r < 0) continue;
              const int* pos = std::lower_bound(first, past, r);
              if (pos == past || *pos != r)
                throw std::logic_error(fmt::format(
                    "follower pressure: the tangent has no entry ({}, {}); pass a matrix with the "
                    "total-Lagrangian pattern",
                    r, eq[c]));
              K->valuePtr()[pos - inner] += pw * R[a] * da[c][i];
            }
        }
      }
    }
}

void check_shapes(const Body& body, const DofMap& dofs, const Eigen::VectorXd& f) {
  const int dim = body.space_dim();
  if ((dim != 2 && dim != 3) || body.param_dim() != dim)
    throw std::invalid_argument("a pressure load needs a 2D or 3D volume body");
  if (dofs.dim() != dim || dofs.num_dofs() != body.num_control_points() * dim)
    throw std::invalid_argument("the dof map does not belong to the body of the pressure load");
  if (f.size() != dofs.num_free())
    throw std::invalid_argument(
        fmt::format("pressure load: force vector has {} entries for {} free dofs", f.size(), dofs.num_free()));
}

}  // namespace

void add_follower_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                           const Eigen::MatrixXd& u, Eigen::VectorXd& f_ext, Eigen::SparseMatrix<double>* K) {
  check_shapes(body, dofs, f_ext);
  const int dim = body.space_dim();
  if (u.rows() != body.num_control_points() || u.cols() != dim)
    throw std::invalid_argument(fmt::format("follower pressure: displacement is {} x {}, the body needs {} x {}",
                                            u.rows(), u.cols(), body.num_control_points(), dim));
  if (K) {
    if (K->rows() != dofs.num_free() || K->cols() != dofs.num_free())
      throw std::invalid_argument("follower pressure: the tangent is not free x free");
    if (!K->isCompressed()) K->makeCompressed();
  }
  for (const PatchSide& face : faces) {
    if (dim == 2)
      face_pressure<2>(body, dofs, face, p, &u, f_ext, K);
    else
      face_pressure<3>(body, dofs, face, p, &u, f_ext, K);
  }
}

void add_dead_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                       Eigen::VectorXd& f_ext) {
  check_shapes(body, dofs, f_ext);
  for (const PatchSide& face : faces) {
    if (body.space_dim() == 2)
      face_pressure<2>(body, dofs, face, p, nullptr, f_ext, nullptr);
    else
      face_pressure<3>(body, dofs, face, p, nullptr, f_ext, nullptr);
  }
}

}  // namespace igac
