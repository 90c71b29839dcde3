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
//
// Stabilised (since issue 24): the element's dilatation modes of zero mean
// are invisible to Pi_e, so with constants per element only the isochoric
// energy resists them; near a contact point on the O-ring at K/G = 2000 one
// element's J ranged 0.68 ... 1.16 and the contact pressure wiggled 6 % of
// its mean there.  The functional carries a shear-sized penalty on them,
//   + mu_s / 2 int (J - theta)^2 dX,   mu_s = the law's shear modulus at rest,
// so the point pressure is p_q = (Pi_e U'(theta))_q + mu_s (J_q - theta_q) and
// the tangent gains mu_s (B - Bbar)^T W (B - Bbar).  mu_s does not grow with
// K: the modes are held as stiffly as shear holds them, no more, so nothing
// locks (the Lame cylinder's error at nu = 0.49999 stays within 2x of
// nu = 0.3), and with K = mu_s the formulation would be the displacement one.
// Small strain: K Bbar^T W Bbar + mu (B - Bbar)^T W (B - Bbar).
//
// Large deformation (engine/total_lagrangian.hpp) takes theta and p per
// pressure block of 2 x 2 (x 2) elements (engine/pressure_blocks.hpp):
// theta_b = Pi_b J, the mean over the block, p_b = U'(theta_b), the
// stabilisation mu_s (J - Pi_e J) still per element, and the block's
// V_b U''(theta_b) mB_b^T mB_b (mB_b the block's mean of B) in the tangent
// (docs/design.md, "One pressure per 2 x 2 block of elements").  It
// iterates on theta too (the u-p Newton): TotalLagrangianAssembler::assemble
// takes theta_b per block, and contact/finite_strain_problem.hpp carries
// theta_b in Newton's unknowns, condensed in the solve (docs/design.md,
// "The u-p Newton iteration").
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string_view>
#include <vector>

#include "materials/hyperelastic.hpp"

namespace igac {

enum class Formulation { displacement, mixed };

// "displacement" or "mixed"; nullopt for any other name.
std::optional<Formulation> parse_formulation(std::string_view name);
std::string_view formulation_name(Formulation f);

// The degree of the element-local dilatation/pressure space for a
// displacement of degree p (docs/design.md says why).
int pressure_degree(int displacement_degree);

// mu_s of the stabilisation: the shear modulus of `law` at rest, read off
// its isochoric tangent at F = I (dP_xy/dF_xy = mu for an isotropic law), in
// dim = 2 (plane strain) or 3.  0 for a law that declares no split.
double stabilisation_modulus(const HyperelasticLaw& law, int dim);

// The volumetric part of a mixed element tangent: with Bbar = Pi B (B: n_q x
// n_dofs, dJ/du or div N per Gauss point),
//   Ke += Bbar^T diag(JxW U'') Bbar + mu_s (B - Bbar)^T diag(JxW) (B - Bbar).
// Bbar is scratch (resized).  Pi is an L2(Omega_e) projection, so the second
// term is mu_s (B^T W B - Bbar^T W Bbar), which is how it is computed.
void add_volumetric_tangent(const Eigen::MatrixXd& Pi, const std::vector<double>& JxW, const Eigen::VectorXd& d2U,
                            double mu_s, const Eigen::MatrixXd& B, Eigen::MatrixXd& Bbar, Eigen::MatrixXd& Ke);

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
