// SPDX-License-Identifier: BSD-3-Clause
#include "contact/weighted_gap.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace igac {

ContactSide::ContactSide(const Body& body, const PatchSide& s, int first)
    : side(s),
      face_patch(body.side_patch(s)),
      face_cps(body.side_control_points(s)),
      space(face_patch),
      first_multiplier(first) {}

ContactFace::ContactFace(const Body& body, const std::vector<PatchSide>& list) : degree(body.degree()) {
  if (list.empty()) throw std::invalid_argument("a contact face needs at least one side");
  int first = 0;
  for (const PatchSide& s : list) {
    sides.emplace_back(body, s, first);
    first += sides.back().space.size();
  }
}

int ContactFace::quadrature_points() const { return gauss_points_for(degree) + 1; }

FaceQuadrature ContactFace::face_quadrature(int points) const {
  std::vector<PatchSide> list;
  std::vector<PatchQuadrature> quads;
  for (const ContactSide& s : sides) {
    list.push_back(s.side);
    quads.push_back(s.quadrature(points));
  }
  return FaceQuadrature(std::move(list), std::move(quads));
}

ContactQuadrature::ContactQuadrature(const ContactFace& cf)
    : cf_(&cf), faces_(cf.face_quadrature(cf.quadrature_points())) {}

void add_gap_coupling(const DofMap& dofs, int K, int a, double w, const Eigen::Ref<const Eigen::VectorXd>& n,
                      GapCouplings& out, Eigen::VectorXd& g0) {
  const int dim = dofs.dim();
  for (int i = 0; i < dim; ++i) {
    const int dof = a * dim + i;
    const double v = w * n[i];
    if (dofs.equation(dof) >= 0) {
      out.free.emplace_back(K, dofs.equation(dof), v);
    } else {
      g0[K] += v * dofs.prescribed_value(dof);
      out.held.emplace_back(K, dof, v);
    }
  }
}

void GapCouplings::build(const DofMap& dofs, int rows, Eigen::SparseMatrix<double, Eigen::RowMajor>& G,
                         Eigen::SparseMatrix<double, Eigen::RowMajor>& G_held) const {
  G.resize(rows, dofs.num_free());
  G.setFromTriplets(free.begin(), free.end());
  G.prune(0.0);
  G_held.resize(rows, dofs.num_dofs());
  G_held.setFromTriplets(held.begin(), held.end());
  G_held.prune(0.0);
}

Eigen::MatrixXd tangent_basis(const Eigen::VectorXd& n) {
  if (n.size() == 2) return Eigen::Vector2d(n[1], -n[0]);
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(n[i]) < std::abs(n[axis])) axis = i;
  const Eigen::Vector3d nn = n, t1 = (Eigen::Vector3d::Unit(axis) - nn[axis] * nn).normalized();
  Eigen::MatrixXd t(3, 2);
  t.col(0) = t1;
  t.col(1) = nn.cross(t1);
  return t;
}

WeightedGapOperator assemble_weighted_gaps(const DofMap& dofs, const ContactFace& cf, const Obstacle& obstacle,
                                           const ContactLaw& law, const Eigen::VectorXd& shift, const Eigen::MatrixXd* u) {
  const int m = cf.num_multipliers(), nt = dofs.dim() - 1;
  WeightedGapOperator op;
  op.weights = Eigen::VectorXd::Zero(m);
  op.g0 = Eigen::VectorXd::Zero(m);
  const bool tangential = law.tangential();
  op.laws.assign(size_t(m), &law.get());
  if (tangential) {
    op.t0 = Eigen::VectorXd::Zero(m * nt);
    op.friction = Eigen::VectorXd::Constant(m, law.get().has_coefficient() ? law.friction : 0.0);
  }
  op.directions = Eigen::MatrixXd::Zero(m, dofs.dim());
  GapCouplings trip, ttrip;
  ContactQuadrature(cf).for_each_point([&](const auto& ev, int q, const std::vector<int>& K,
                                           const std::vector<double>& B) {
    const ObstacleProbe pr = u ? obstacle.probe(ev.displaced(q, *u)) : obstacle.probe(ev.X[q]);
    const Eigen::MatrixXd t = tangential ? tangent_basis(pr.normal) : Eigen::MatrixXd();
    for (size_t k = 0; k < K.size(); ++k) {
      const double bw = B[k] * ev.JxW[q];
      if (bw == 0.0) continue;
      op.weights[K[k]] += bw;
      op.g0[K[k]] += pr.gap * bw;
      op.directions.row(K[k]) += bw * pr.normal.transpose();
      for (int a = 0; a < ev.n_loc; ++a) add_gap_coupling(dofs, K[k], ev.cps[a], bw * ev.N(q, a), pr.normal, trip, op.g0);
      for (int j = 0; j < t.cols(); ++j) {
        const int row = K[k] * nt + j;
        if (shift.size()) op.t0[row] -= bw * shift.dot(t.col(j));
        for (int a = 0; a < ev.n_loc; ++a) add_gap_coupling(dofs, row, ev.cps[a], bw * ev.N(q, a), t.col(j), ttrip, op.t0);
      }
    }
  });
  trip.build(dofs, m, op.G, op.G_held);
  if (tangential) ttrip.build(dofs, m * nt, op.T, op.T_held);
  return op;
}

Eigen::VectorXd exact_weighted_gaps(const Eigen::MatrixXd& u, const ContactFace& cf, const Obstacle& obstacle) {
  const int m = cf.num_multipliers();
  Eigen::VectorXd num = Eigen::VectorXd::Zero(m), den = Eigen::VectorXd::Zero(m);
  ContactQuadrature(cf).for_each_point([&](const auto& ev, int q, const std::vector<int>& K,
                                           const std::vector<double>& B) {
    const double g = obstacle.probe(ev.displaced(q, u)).gap;
    for (size_t k = 0; k < K.size(); ++k) {
      num[K[k]] += g * B[k] * ev.JxW[q];
      den[K[k]] += B[k] * ev.JxW[q];
    }
  });
  return num.cwiseQuotient(den);
}

namespace {
using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor>;
// The matrices `part` of the operators one below the other, op k's rows
// from first[k]; `rows` in all.
RowSparse stacked(const std::vector<WeightedGapOperator>& ops, RowSparse WeightedGapOperator::*part,
                  const std::vector<Eigen::Index>& first, Eigen::Index rows) {
  Eigen::Index cols = 0;
  std::vector<Eigen::Triplet<double>> trip;
  for (size_t k = 0; k < ops.size(); ++k) {
    const RowSparse& A = ops[k].*part;
    cols = std::max(cols, A.cols());
    for (int r = 0; r < A.outerSize(); ++r)
      for (RowSparse::InnerIterator it(A, r); it; ++it) trip.emplace_back(int(first[k] + r), int(it.col()), it.value());
  }
  RowSparse out(rows, cols);
  out.setFromTriplets(trip.begin(), trip.end());
  return out;
}
}  // namespace

WeightedGapOperator stack(const std::vector<WeightedGapOperator>& ops) {
  if (ops.size() == 1) return ops.front();
  WeightedGapOperator out;
  Eigen::Index rows = 0;
  std::vector<Eigen::Index> first;
  for (const auto& op : ops) {
    first.push_back(rows);
    rows += op.G.rows();
  }
  out.weights.resize(rows);
  out.g0.resize(rows);
  for (size_t k = 0; k < ops.size(); ++k) {
    out.weights.segment(first[k], ops[k].G.rows()) = ops[k].weights;
    out.g0.segment(first[k], ops[k].G.rows()) = ops[k].g0;
  }
  out.G = stacked(ops, &WeightedGapOperator::G, first, rows);
  for (const auto& op : ops)
    for (int K = 0; K < op.G.rows(); ++K) out.laws.push_back(&op.law(K));
  out.G_held = stacked(ops, &WeightedGapOperator::G_held, first, rows);
  const Eigen::Index dim = ops.empty() ? 0 : ops.front().directions.cols();
  out.directions = Eigen::MatrixXd::Zero(rows, dim);
  for (size_t k = 0; k < ops.size(); ++k)
    if (ops[k].directions.rows() == ops[k].G.rows() && ops[k].directions.cols() == dim)
      out.directions.middleRows(first[k], ops[k].G.rows()) = ops[k].directions;
  // Every contact gets its tangential rows (zero, f = 0, for a law without
  // them) once one contact's law has them.
  int nt = 0;
  for (const auto& op : ops)
    if (op.G.rows() > 0 && op.T.rows() > 0) nt = int(op.T.rows() / op.G.rows());
  if (nt == 0) return out;
  out.t0 = Eigen::VectorXd::Zero(rows * nt);
  out.friction = Eigen::VectorXd::Zero(rows);
  std::vector<Eigen::Index> first_t;
  for (size_t k = 0; k < ops.size(); ++k) {
    first_t.push_back(first[k] * nt);
    if (ops[k].T.rows() == 0) continue;
    out.t0.segment(first[k] * nt, ops[k].T.rows()) = ops[k].t0;
    out.friction.segment(first[k], ops[k].G.rows()) = ops[k].friction;
  }
  out.T = stacked(ops, &WeightedGapOperator::T, first_t, rows * nt);
  out.T_held = stacked(ops, &WeightedGapOperator::T_held, first_t, rows * nt);
  return out;
}

}  // namespace igac
