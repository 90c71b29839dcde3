// SPDX-License-Identifier: BSD-3-Clause
// Weighted gaps between two deformable bodies in small deformation (mortar
// contact: De Lorenzis, Wriggers and Zavarise 2012; the paper's gaps with
// the obstacle replaced by a second body).  The multipliers B_K of degree
// p-2 live on the slave face, as for an obstacle; at each slave quadrature
// point X the master point X' nearest to it (contact/master_surface.hpp, in
// the reference configuration) gives the gap along the master's outward
// normal n, linearised in both bodies' displacements:
//   g_n = (X - X') . n + (u_s(X) - u_m(X')) . n,
//   K_K (Pi g)_K = g0_K + (G u)_K,
//   G_{K,(A,i)} = int B_K N_A n_i  (slave A),  - int B_K N_A(X') n_i  (master A).
// The integration (MortarIntegration below) is segmented by default: each
// slave element cut where its points' master projections cross a master
// element edge (2D: points; 3D: polygons, contact/mortar_cells.hpp), so the
// contact patch test between non-matching meshes (and degrees) is passed to
// round-off; element-based integration passes it to the quadrature error of
// the master's kinks (both measured in tests/unit/contact/test_mortar_gap.cpp).
// The multipliers act on both
// bodies with opposite signs, and the B_K and N_A
// are partitions of unity: the force on the slave is minus the force on the
// master to round-off.
#pragma once

#include "contact/mortar_integration.hpp"

#include <functional>

#include "contact/master_surface.hpp"
#include "contact/weighted_gap.hpp"

namespace igac {

// The master surface seen as a rigid obstacle at its reference position:
// the gap to the nearest master point along the master's outward normal.
// What the contact reports (the initial contact point, the checks that a
// face can touch, the obstacle's description) read for a two-body contact;
// the coupling itself is assemble_mortar_gaps.  Borrows `master`.
class MasterAsObstacle final : public Obstacle {
 public:
  MasterAsObstacle(const MasterSurface& master, std::string face_name) : master_(&master), name_(std::move(face_name)) {}
  ObstacleProbe probe(const Eigen::VectorXd& x, bool with_derivative = false) const override;
  std::string describe() const override;

 private:
  const MasterSurface* master_;
  std::string name_;
};

// How the slave integral is taken.  element: (p+2) Gauss points per slave
// element direction, as for an obstacle; the master's basis has kinks
// inside a slave element where their meshes do not match, so the contact
// patch test is passed to that quadrature error (about 1e-3 at degree 2).
// segmented (the default, `[[contact]] integration`): each slave element
// cut where its points' master projections cross a master element edge,
// the Gauss rule on each piece (2D), a triangle rule on each cell's
// triangles (3D, contact/mortar_cells.hpp): the integrand is smooth on
// every piece and the patch test is passed to round-off.

// One slave quadrature point of the mortar integral: where it is on the
// reference face (X, where the integral is taken) and now (x = X + u(X);
// X without a displacement), its weight (Jacobian of the reference face
// included), the slave's control points (body numbers) with their basis
// values, and the multipliers with theirs.
struct MortarSlavePoint {
  Eigen::VectorXd X, x;
  double JxW = 0;
  std::vector<int> cps;
  Eigen::VectorXd N;
  std::vector<int> K;
  std::vector<double> B;
};

// Every slave quadrature point of the mortar integral, element-based (the
// face's own Gauss points) or segmented (Gauss points on each piece of the
// slave element cut where its points' projections cross a master element
// edge; in 3D on the triangles of each cell).  With u (n_cp x dim, body numbering; null: none) the slave
// face is cut at its displaced position against `master` as it stands (the
// caller has moved it): the integrand is continuous across the cuts, so the
// gaps' derivative may be taken with the cuts held.  `tabulated`: the
// slave's quadrature already tabulated (element-based; null: tabulated
// here), so that a Newton iteration does not tabulate it again.  The one
// loop of the small- and large-deformation mortar gaps.
void for_each_mortar_point(const ContactFace& slave, const MasterSurface& master, MortarIntegration integration,
                           const Eigen::MatrixXd* u, const std::function<void(const MortarSlavePoint&)>& visit,
                           const ContactQuadrature* tabulated = nullptr);

// With friction > 0 also the tangential rows (Coulomb friction between the
// two bodies, contact/small_strain_friction.hpp), in the same loop: the
// weighted tangential displacement of the slave relative to the master
// along the master's tangents t_j at the projection (tangent_basis of its
// normal there),
//   T_{(K,j),(A,i)} = int B_K N_A (t_j)_i  (slave A),  - int B_K N_A(X') (t_j)_i  (master A),
// so that the tangential forces on the two bodies are opposite, as the
// normal ones.  `shift` (empty: none) translates the master body rigidly
// with its supports ([[contact]] master_motion): g0 and t0 lose
// int B_K shift . n and int B_K shift . t_j.
// `u` (n_cp x dim; null: none): at the displaced configuration, each slave
// point X + u(X) projected on `master` as it stands (the caller has moved
// it to u): large-deformation friction's rows of a load step
// (contact/finite_strain_friction.hpp).
WeightedGapOperator assemble_mortar_gaps(const DofMap& dofs, const ContactFace& slave, const MasterSurface& master,
                                         MortarIntegration integration, const ContactLaw& law = {},
                                         const Eigen::VectorXd& shift = {}, const Eigen::MatrixXd* u = nullptr);

// Weighted gaps of the exact gap in the displaced configuration, u per body
// control point (n_cp x dim): each slave point X + u(X) projected on the
// master moved by u (`master` is updated to it).  What G linearises.
Eigen::VectorXd exact_mortar_gaps(const Eigen::MatrixXd& u, const ContactFace& slave, MasterSurface& master,
                                  MortarIntegration integration);

}  // namespace igac
