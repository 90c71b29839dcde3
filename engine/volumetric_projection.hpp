// SPDX-License-Identifier: BSD-3-Clause
// The mixed formulation of nearly incompressible solids: the volumetric
// quantity projected element by element, so the global unknowns stay the
// displacements (docs/design.md, "Nearly incompressible solids").
//
// Three-field (Simo-Taylor-Pister) Hu-Washizu functional with the dilatation
// theta and the pressure p in the same discontinuous space Q_h (polynomials
// of degree pressure_degree(p) in each parametric direction, per Bezier
// element: constants, the mean dilatation; the .cpp says why), for a law
// split as Psi = W_iso(F) + U(J):
//   Pi(u, theta, p) = int W_iso(F) + U(theta) + p (J - theta) dX - work.
// Its theta and p equations are element-local and are solved in closed form
// (static condensation), with Pi_e the L2(Omega_e) projection onto Q_h
// (weights JxW of the reference configuration):
//   theta = Pi_e J,   p = Pi_e U'(theta),
//   f_(a,i) = int (P_iso + p J F^{-T})_iJ dN_a/dX_J dX,
//   K = int dN A_iso dN + int p dN d(J F^{-T})/dF dN + int Bbar^T U''(theta) Bbar,
// with B_q = dJ/du at point q (J F^{-T} : Grad N) and Bbar = Pi_e B: the
// projected ("B-bar") dilatation.  f is the gradient of
// E(u) = int W_iso(F) + U(Pi_e J) dX, so K is symmetric, has the pattern of
// the displacement formulation, and the contact solvers see no difference.
// Small strain (the linear law): U = K theta^2 / 2, W_iso = mu |dev eps|^2
// (3D deviator, plane strain included), so the element matrix is the
// displacement one with lambda - K = -2 mu / 3 in place of lambda plus
// K Bbar^T W Bbar, B_q = div N: the B-bar method of Hughes (1980) with
// the projection of Elguedj et al. (2008) made element-local.
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string_view>
#include <vector>

namespace igac {

enum class Formulation { displacement, mixed };

// "displacement" or "mixed"; nullopt for any other name.
std::optional<Formulation> parse_formulation(std::string_view name);
std::string_view formulation_name(Formulation f);

// The degree of the element-local dilatation/pressure space for a
// displacement of degree p (docs/design.md says why).
int pressure_degree(int displacement_degree);

// The L2(Omega_e) projection onto Q_k at an element's Gauss points: for
// values f_r at the points, (Pi_e f)_q = sum_r matrix()(q, r) f_r.
// Pi_e = Phi (Phi^T W Phi)^{-1} Phi^T W, Phi the tensor-product monomials
// of degree <= k in each direction of the element's own (centred, scaled)
// parametric coordinates.  Allocates only when the size changes.
class ElementProjection {
 public:
  template <int pd>
  void build(const std::vector<Eigen::Matrix<double, pd, 1>>& xi, const std::vector<double>& JxW, int degree);
  const Eigen::MatrixXd& matrix() const { return pi_; }

 private:
  Eigen::MatrixXd phi_, gram_, pi_;
};

}  // namespace igac
