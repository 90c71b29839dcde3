// SPDX-License-Identifier: BSD-3-Clause
#include "model/held_motions.hpp"

#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contact/friction_state.hpp"

namespace igac {

namespace {
// The motion on the fixed dofs is zero (what a mode of the free unknowns is).
Eigen::MatrixXd motion_of(const Model& m, const Eigen::VectorXd& free) {
  const int dim = m.body.space_dim();
  Eigen::MatrixXd u = Eigen::MatrixXd::Zero(m.body.num_control_points(), dim);
  for (int d = 0; d < m.dofs->num_dofs(); ++d)
    if (const int eq = m.dofs->equation(d); eq >= 0) u(d / dim, d % dim) = free[eq];
  return u;
}

// Three digits; a coordinate below 1e-6 of `size` (round-off of a centre on
// an axis) is 0.
std::string point(const Eigen::VectorXd& x, double size) {
  std::vector<std::string> parts;
  for (int i = 0; i < x.size(); ++i) parts.push_back(fmt::format("{:.3g}", std::abs(x[i]) < 1e-6 * size ? 0.0 : x[i]));
  return fmt::format("({})", fmt::join(parts, ", "));
}

// A fit whose residual keeps more than this share of the motion's squared
// norm is a deformation, not a rigid motion (a wedge hinged on a tiny face:
// 1e-9; a slender cantilever's bending, which a rotation fits to 1.4e-2:
// a deformation); a centre of rotation farther than kFarCentre body sizes
// away is a translation.
constexpr double kRigidShare = 1e-3;
constexpr double kFarCentre = 10.0;
}  // namespace

std::string describe_motion(const Body& body, const Eigen::MatrixXd& u) {
  const int dim = body.space_dim(), nr = dim == 2 ? 1 : 3;
  // The part (patches joined) the motion moves most.
  const std::vector<int> part = body.parts();
  std::vector<double> amount(body.num_patches(), 0.0);
  for (int k = 0; k < body.num_patches(); ++k)
    for (int a : body.body_cps(k)) amount[part[k]] += u.row(a).squaredNorm();
  const int moved = int(std::max_element(amount.begin(), amount.end()) - amount.begin());
  std::vector<char> in(body.num_control_points(), 0);
  for (int k = 0; k < body.num_patches(); ++k)
    if (part[k] == moved)
      for (int a : body.body_cps(k)) in[a] = 1;
  const Eigen::MatrixXd& X = body.points();
  Eigen::VectorXd x0 = Eigen::VectorXd::Zero(dim);
  int n = 0;
  for (int a = 0; a < int(in.size()); ++a)
    if (in[a]) x0 += X.row(a).transpose(), ++n;
  x0 /= std::max(n, 1);
  double size = 0, total = 0;
  int largest = -1;
  for (int a = 0; a < int(in.size()); ++a)
    if (in[a]) {
      size = std::max(size, (X.row(a).transpose() - x0).norm());
      total += u.row(a).squaredNorm();
      if (largest < 0 || u.row(a).squaredNorm() > u.row(largest).squaredNorm()) largest = a;
    }
  // Least squares u_a ~ t + w x r_a (2D: w (-r_y, r_x)), r_a = x_a - x0,
  // by the normal equations (dim + nr unknowns).
  const int nu = dim + nr;
  Eigen::MatrixXd AtA = Eigen::MatrixXd::Zero(nu, nu);
  Eigen::VectorXd Atb = Eigen::VectorXd::Zero(nu);
  const auto rows = [&](const Eigen::VectorXd& r) {
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(dim, nu);
    A.leftCols(dim).setIdentity();
    if (dim == 2) {
      A(0, 2) = -r[1];
      A(1, 2) = r[0];
    } else {  // w x r
      A(0, 4) = r[2], A(0, 5) = -r[1];
      A(1, 3) = -r[2], A(1, 5) = r[0];
      A(2, 3) = r[1], A(2, 4) = -r[0];
    }
    return A;
  };
  for (int a = 0; a < int(in.size()); ++a)
    if (in[a]) {
      const Eigen::MatrixXd A = rows(X.row(a).transpose() - x0);
      AtA += A.transpose() * A;
      Atb += A.transpose() * u.row(a).transpose();
    }
  const Eigen::VectorXd c = AtA.ldlt().solve(Atb);
  double residual = 0;
  for (int a = 0; a < int(in.size()); ++a)
    if (in[a]) residual += (u.row(a).transpose() - rows(X.row(a).transpose() - x0) * c).squaredNorm();
  if (!(total > 0) || residual > kRigidShare * total)
    return fmt::format("a deformation largest at {}", point(X.row(std::max(largest, 0)).transpose(), size));
  const Eigen::VectorXd t = c.head(dim), w = c.tail(nr);
  if (dim == 2) {
    const double theta = w[0];
    Eigen::VectorXd centre(2);
    if (theta != 0) centre << x0[0] - t[1] / theta, x0[1] + t[0] / theta;
    if (theta != 0 && (centre - x0).norm() <= kFarCentre * size) return fmt::format("a rotation about {}", point(centre, size));
  } else if (w.norm() > 0) {
    const Eigen::Vector3d w3 = w, t3 = t;
    const Eigen::VectorXd centre = x0 + Eigen::VectorXd(w3.cross(t3) / w3.squaredNorm());
    if ((centre - x0).norm() <= kFarCentre * size)
      return fmt::format("a rotation about the axis {} through {}", point(w / w.norm(), 1.0), point(centre, size));
  }
  return fmt::format("a translation along {}", point(t / t.norm(), 1.0));
}

std::optional<std::string> stiffness_warning(const Model& m, const Eigen::SparseMatrix<double>& K,
                                             const std::vector<int>& pinned, const SparseCholesky& chol) {
  const Eigen::VectorXd d = chol.pivots();
  const Eigen::VectorXd diag = K.diagonal();
  std::vector<char> skip(size_t(K.rows()), 0);
  for (int p : pinned) skip[p] = 1;
  int worst = -1;
  double ratio = 0;
  for (int i = 0; i < int(K.rows()); ++i)
    if (!skip[i] && diag[i] > 0 && d[i] > 0 && diag[i] / d[i] > ratio) ratio = diag[i] / d[i], worst = i;
  if (!(ratio > kMaxPivotRatio)) return std::nullopt;
  // K^-1 e_i: the load on that unknown, answered mostly by the motion K
  // barely holds.
  Eigen::VectorXd e = Eigen::VectorXd::Zero(K.rows());
  e[worst] = 1;
  Eigen::VectorXd v = chol.solve(e);
  for (int p : pinned) v[p] = 0;
  const int dim = m.body.space_dim();
  int dof = 0;
  while (m.dofs->equation(dof) != worst) ++dof;
  return fmt::format("{}: the stiffness is nearly singular: {} is barely held (with every other unknown eliminated, "
                     "control point {} along {} keeps 1/{:.2g} of its own stiffness, beyond {:g}): a small load along "
                     "it moves the body far; if the body should not move so, hold it with a [[dirichlet]] condition, "
                     "or look for a thin neck or a face that barely holds the body",
                     m.spec.path, describe_motion(m.body, motion_of(m, v)), dof / dim, "xyz"[dof % dim], ratio,
                     kMaxPivotRatio);
}

std::optional<std::string> contact_hold_warning(const Model& m, const WeightedGapOperator& op,
                                                const ContactSolution& s, const RigidModes& modes) {
  const int k = int(modes.modes.cols()), mult = int(s.active.size());
  if (k == 0 || mult == 0 || int(op.G.rows()) != mult) return std::nullopt;
  const Eigen::MatrixXd GR = op.G * modes.modes;
  const bool stick = !s.friction_state.empty() && op.T.rows() > 0;
  const Eigen::MatrixXd TR = stick ? Eigen::MatrixXd(op.T * modes.modes) : Eigen::MatrixXd();
  const int nt = stick ? int(op.T.rows()) / mult : 0;
  std::vector<Eigen::RowVectorXd> rows;
  for (int K = 0; K < mult; ++K) {
    if (!s.active[K]) continue;
    rows.push_back(GR.row(K));
    if (stick && s.friction_state[K] == kStick)
      for (int j = 0; j < nt; ++j) rows.push_back(TR.row(K * nt + j));
  }
  if (int(rows.size()) < k) return std::nullopt;  // not held at all: the solve's status says so
  Eigen::MatrixXd B(Eigen::Index(rows.size()), k);
  for (size_t i = 0; i < rows.size(); ++i) B.row(Eigen::Index(i)) = rows[i];
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  const double bound = 1 / std::sqrt(kMaxPivotRatio);
  if (!(sigma[0] > 0) || sigma[k - 1] >= bound * sigma[0]) return std::nullopt;
  const Eigen::VectorXd motion = modes.modes * svd.matrixV().col(k - 1);
  return fmt::format("{}: the contact barely holds {}: the active multipliers resist it {:.2g} times less than the "
                     "rigid motion they hold best (beyond sqrt({:g})): a load along it takes large contact forces or "
                     "moves the body far; if the body should not move so, hold it with a [[dirichlet]] condition",
                     m.spec.path, describe_motion(m.body, motion_of(m, motion)), sigma[0] / sigma[k - 1],
                     kMaxPivotRatio);
}

}  // namespace igac
