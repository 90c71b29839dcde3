// SPDX-License-Identifier: BSD-3-Clause
// The mixed formulation of nearly incompressible solids: the volumetric
// quantity projected onto the pressure space (engine/pressure_space.hpp,
// mixed_pressure_space: on a `mixed` patch the B-splines of degree p - 1,
// C^{p-2}, on breakpoints twice coarser; on a `mixed_element` patch one
// constant per element), so the displacement stays the one global field the
// contact solvers see (docs/design.md, "Nearly incompressible solids").
//
// Three-field (Simo-Taylor-Pister) Hu-Washizu functional with the dilatation
// theta and the pressure p in the pressure space (the sub-grid space is
// inf-sup stable, constants per element are not: beta_h ~ h,
// docs/benchmarks.md "Inf-sup"), for a law split as Psi = W_iso(F) + U(J):
//   Pi(u, theta, p) = int W_iso(F) + U(theta) + p (J - theta) dX - work,
// with the pressure mass lumped (row sums m_A = int N_A dX), so that the
// theta and p equations are local to each function N_A:
//   theta_A = Pi_A J = (1/m_A) int N_A J dX,   p_A = U'(theta_A),
// and what is left is the gradient of
//   E(u) = int W_iso(F) dX + sum_A m_A U(Pi_A J) + mu_s/2 int (J - Pi_e J)^2 dX,
// whose point pressure is sum_A N_A p_A + mu_s (J - Pi_e J) and whose
// tangent is, per element, the isochoric and initial-stress parts and the
// stabilisation mu_s (B^T W B - V_e mB_e^T mB_e), and per function the
// rank-one m_A U''(theta_A) mB_A^T mB_A, with B_q = dJ/du at point q
// (J F^{-T} : Grad N), mB_e its element mean and mB_A = (1/m_A) int N_A B dX:
// symmetric, with the pattern widened to the functions' supports
// (coupling_pattern with the space, engine/sparsity.hpp).  In the
// incompressible limit the constraint int N_A (J - 1) dX = 0 is the
// consistent (unlumped) mixed method's: the lumping only changes the
// penalty at finite K.
// Small strain (the linear law) is over the pressure space already
// (engine/pressure_space.hpp, since issue 24): U = K theta^2 / 2, W_iso =
// mu |dev eps|^2 (3D deviator, plane strain included), one dilatation per
// pressure function A with the row-sum (lumped) pressure mass m_A = int N_A
// dX, theta_A = int N_A div u dX / m_A, so the element matrix is the
// displacement one with lambda - K = -2 mu / 3 in place of lambda plus the
// stabilisation mu (B^T W B - V_e mB_e^T mB_e), and each function adds
// K / m_A g_A g_A^T, g_A = int N_A div N dX: the B-bar method of Hughes
// (1980) with the projection of Elguedj et al. (2008) onto the sub-grid
// space, kept local by the lumped mass (assemble_linear_elasticity,
// engine/assembly.hpp).  Constants per element: m_A = V_e, Pi_e.
//
// Stabilised (since issue 24): the dilatation modes of zero element mean
// are invisible to the projection, so with the volumetric energy alone only
// the isochoric energy resists them; near a contact point on the O-ring at
// K/G = 2000 one element's J ranged 0.68 ... 1.16 and the contact pressure
// wiggled 6 % of its mean there.  The functional carries a shear-sized
// penalty on them, element by element,
//   + mu_s / 2 int (J - Pi_e J)^2 dX,   mu_s = the law's shear modulus at rest,
// so the point pressure is p_q = sum_A N_A p_A + mu_s (J_q - (Pi_e J)_q) and the
// tangent gains mu_s (B - Pi_e B)^T W (B - Pi_e B) = mu_s (B^T W B - V_e
// mB_e^T mB_e).  mu_s does not grow with K: the modes are held as stiffly as
// shear holds them, no more, so nothing locks (the Lame cylinder's error at
// nu = 0.49999 stays within 2x of nu = 0.3), and with K = mu_s and constants
// per element the formulation would be the displacement one.
//
// Large deformation iterates on theta too (the u-p Newton, since issue 24):
// TotalLagrangianAssembler::assemble takes the dilatations, p = U'(theta),
// and model/finite_strain_problem.hpp carries them in Newton's unknowns,
// condensed in the solve (docs/design.md, "The u-p Newton iteration").
#pragma once

#include <Eigen/Dense>
#include <optional>
#include <string_view>
#include <vector>

#include "materials/hyperelastic.hpp"

namespace igac {

// mixed: the sub-grid continuous pressure (inf-sup stable); mixed_element:
// one constant per element (not uniformly inf-sup stable; docs/design.md,
// "One pressure per element on request").
enum class Formulation { displacement, mixed, mixed_element };
constexpr bool is_mixed(Formulation f) { return f != Formulation::displacement; }

// "displacement", "mixed" or "mixed_element"; nullopt for any other name.
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
