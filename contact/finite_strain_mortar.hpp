// SPDX-License-Identifier: BSD-3-Clause
// Mortar contact between two deformable bodies in large deformation: the
// weighted gaps at the CURRENT position and their consistent linearisation
// (Wriggers, Computational Contact Mechanics, 2nd ed., sec. 4.3 and 6.4;
// De Lorenzis, Temizer, Wriggers and Zavarise 2011).
//
// Slave point X of the reference slave face (where the integral is taken,
// as for a rigid obstacle), now at x_s = X + u_s(X); its closest point on the
// current master surface x_m(xi), tangents a_a = x_m,a, outward unit normal
// n, gap g = (x_s - x_m) . n, so that x_s - x_m = g n and a_a . n = 0:
//   gamma_K = int B_K g dGamma_0,
//   delta g = (delta x_s - delta x_m) . n            (delta x_m at fixed xi),
// with, for a variation d of every control point (D = d x_s - d x_m, the
// master tangents' variation d a_a = sum_B N_B,a d u_B, the metric
// m_ab = a_a . a_b, the curvature b_ab = n . x_m,ab and A = m - g b):
//   P_a = a_a . D,   W_a = n . d a_a,
//   Delta delta g = -(W^T A^-1 P + P^T A^-1 W) - g W^T A^-1 W - P^T m^-1 b A^-1 P,
// the exact second derivative of g (symmetric: m^-1 b A^-1 = (m b^-1 m -
// g m)^-1).  It follows from the projection's own linearisation,
// A Delta xi = P(Delta) + g W(Delta), and Delta n = -a^a (n . Delta a_a +
// b_ab Delta xi^b).  The slave-slave and master-master blocks of
// lambda int B_K Delta delta g lie in the stiffness pattern (the control
// points of one face element share a volume element); the slave-master
// blocks do not, and go to a separate matrix that GMRES applies
// (BlockJacobian::K_coupling, engine/saddle_solver.hpp).
//
// The integration is MortarIntegration (contact/mortar_gap.hpp): element-based,
// or segmented at the current position (the cuts move with the bodies; the
// integrand is continuous across them, so the derivative is taken with the
// cuts held).
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "contact/mortar_gap.hpp"

namespace igac {

// What one contact adds to the large-deformation problem at displacement u.
struct FiniteStrainMortarTerms {
  Eigen::VectorXd* gamma = nullptr;                      // += int B_K g, rows offset + K
  std::vector<Eigen::Triplet<double>>* G = nullptr;      // (offset + K, free eq, d gamma_K / d u); null: not asked
  Eigen::VectorXd* force = nullptr;                      // += G^T lambda (free equations), without G; null: not asked
  Eigen::SparseMatrix<double>* K = nullptr;              // += the in-pattern curvature blocks (null: none)
  std::vector<Eigen::Triplet<double>>* K_coupling = nullptr;  // the slave-master blocks (free x free)
  // += the force on the slave face, -int lambda n dGamma_0 (minus the force on the master); null: not asked
  Eigen::VectorXd* resultant = nullptr;
};

// The slave points of one contact's mortar integral with their master
// projections, kept for the last displacement asked about: the residual,
// the Jacobian and the resultants of one Newton state share one cut and
// one search (in 3D most of a two-body run's time).  Compared exactly: any
// other u recomputes.
class MortarPointCache {
 public:
  struct Point {
    MortarSlavePoint slave;
    MasterPoint master;
  };
  // The points at u; `master` already moved to u (recomputed when u differs
  // from the last call's).
  const std::vector<Point>& at(const ContactFace& slave, const MasterSurface& master, MortarIntegration integration,
                               const Eigen::MatrixXd& u, const ContactQuadrature& tabulated);

 private:
  Eigen::MatrixXd u_;
  bool valid_ = false;
  std::vector<Point> points_;
};

// Adds contact (slave, master) at displacement u (n_cp x dim, prescribed
// values included) to `out`: `master` is moved to u first.  lambda: the
// multipliers of this contact (the face's numbering), weighting the
// curvature terms; its rows start at `offset`.  `tabulated`: the slave's
// quadrature, tabulated once by the caller (element-based integration);
// `points`: this contact's cache.
void add_finite_strain_mortar(const DofMap& dofs, const ContactFace& slave, MasterSurface& master,
                              MortarIntegration integration, const Eigen::MatrixXd& u, const Eigen::VectorXd& lambda,
                              int offset, const FiniteStrainMortarTerms& out, const ContactQuadrature& tabulated,
                              MortarPointCache& points);

}  // namespace igac
