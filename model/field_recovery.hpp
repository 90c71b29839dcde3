// SPDX-License-Identifier: BSD-3-Clause
// Fields recovered for output, on the Bezier elements ParaView draws
// (io/vtk_output writes them; what is exact is said there): the stress by
// an element-local L2 projection onto each element's rational Bezier basis,
// and on the contact part the pressure -lambda_h likewise, with per-element
// means of the pressure and the weighted gap.  Runs only when output is
// written.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "contact/small_strain_contact.hpp"
#include "contact/weighted_gap.hpp"
#include "engine/spline/bezier_extraction.hpp"
#include "model/model.hpp"

namespace igac {


// Cauchy stress (3 x 3) from the displacement gradient grad u = du/dX
// (3 x 3; the third row and column zero in plane strain).
using StressLaw = std::function<Eigen::Matrix3d(const Eigen::Matrix3d& grad_u)>;
// sigma(grad u) of a law: its P in small strain (the linear law's P is the
// small-strain sigma), P F^T / J in large deformation.  NaN where F is inadmissible.
StressLaw cauchy_stress(std::shared_ptr<const HyperelasticLaw> law, bool small_strain);
// The linear_elastic law's sigma from its Lame constants.
StressLaw linear_elastic_stress(double lambda, double mu);

// The component order of a symmetric tensor's 6 columns (XX YY ZZ XY YZ
// XZ, ParaView's), and the tensor of such a row.
inline constexpr int kVoigt[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
Eigen::Matrix3d symmetric_tensor(const Eigen::Ref<const Eigen::RowVectorXd>& six);

struct RecoveredStress {
  Eigen::MatrixXd stress;       // num_points x 6: XX YY ZZ XY YZ XZ
  Eigen::VectorXd von_mises;    // num_points
  Eigen::VectorXd magnitude;    // num_points, Frobenius norm
  Eigen::MatrixXd principal;    // num_points x 3: sigma_1 >= sigma_2 >= sigma_3
  Eigen::MatrixXd strain;       // num_points x 6, tensor components: eps, or E with green_lagrange
};
// Element-local L2 projection (see above) of the stress tensor for a mesh
// whose field 0 is the displacement; rows follow the mesh's elements, then
// local points.  The scalars are not projected themselves (the projection of
// a nonnegative function has coefficients below zero next to steep
// gradients, -0.052 in the O-ring): each Bezier coefficient of von Mises and
// of |sigma| is the scalar of the tensor's coefficient there.  So they are
// >= 0 and so is what ParaView draws (a rational Bezier basis is >= 0); they
// are exact at element corners (where a Bezier element interpolates its
// corner coefficient) and for a stress in the elements' span, e.g. constant;
// and since both scalars are convex functions of sigma (seminorms), the
// drawn scalar sum_i R_i s(c_i) is never below s(sum_i R_i c_i), the scalar of
// the drawn tensor.  The principal stresses likewise: the eigenvalues of
// each coefficient (exact at corners and for a stress in the span; sigma_1
// is convex, so its drawn value is never below the drawn tensor's).  The
// strain is projected as the stress: eps = sym grad u, or with
// `green_lagrange` (large deformation) E = (F^T F - I) / 2 (plane strain:
// the zz component 0).
RecoveredStress recover_stress(const BezierMesh& mesh, const StressLaw& law, bool green_lagrange = false);
// von Mises, |sigma| and the principal stresses of s.stress, coefficient by
// coefficient (as recover_stress computes them).
void fill_stress_scalars(RecoveredStress& s);

double von_mises(const Eigen::Matrix3d& sigma);

// The stress law of a model's output: the case's law (sigma = P in small
// strain, P F^T / J in large deformation).
StressLaw model_stress_law(const Model& model);
// The Bezier elements of patches first_patch ... first_patch + num_patches - 1
// of the body (num_patches < 0: to the last), one patch after another,
// with the displacement u (one row per body control point) as field 0;
// patches of a lower degree than the body's (bodies of different degrees)
// elevated to it, geometry and field exactly.
// `patch_of`, when given, receives each element's patch.
BezierMesh body_bezier_mesh(const Body& body, const Eigen::MatrixXd& u, int first_patch = 0, int num_patches = -1,
                            std::vector<int>* patch_of = nullptr);

// J = det F and the hydrostatic pressure -tr(sigma)/3, projected onto each
// element's Bezier basis like the stress (rows as recover_stress), for
// `mesh` = body_bezier_mesh(model.body, u) (every patch: std::invalid_argument
// for another number of elements).  On a patch in a mixed formulation the
// pressure is the formulation's own over its pressure space
// (mixed_pressure_space, engine/pressure_space.hpp), not the pointwise law's,
// whose J oscillates at the scale the projection removes:
//   theta_A = (1/m_A) int N_A J dX  (small strain: tr eps),  m_A = int N_A dX,
//   p(x) = -sum_A N_A(x) U'(theta_A)  (small strain: U' = K theta_A),
// so continuous across elements for "mixed" (degree p - 1, C^{p-2}) and one
// constant per element for "mixed_element".  The per-element stabilisation
// mu_s (J - Pi_e J) of the stress is not part of this field.  theta_A is
// integrated with this recovery's own Gauss rule.
struct RecoveredVolume {
  Eigen::VectorXd jacobian, pressure;  // num_points each
};
// `element_pressures` (RunResult's, the incompressible limit): U' of each
// pressure function, which the law's U' at theta = 1 is not (one per
// element is read per element, as a run numbered them before the pressure
// space); any other non-zero length: std::invalid_argument.
RecoveredVolume recover_volume(const BezierMesh& mesh, const Model& model, const Eigen::VectorXd& element_pressures = {});

// The ParaView body fields in one pass over the elements (the law evaluated
// once per Gauss point): recover_volume's J and pressure, and recover_stress's
// stress and strain with each patch's own law (its body's).  On a patch in a
// mixed formulation the stress's volumetric part is the formulation's
// pressure (the volume's), not the pointwise law's U'(J): every stress field
// of a mixed run, and its principal stresses and magnitude, agree with the
// hydrostatic_pressure field (von Mises, which has no volumetric part, is
// the law's).
struct RecoveredFields {
  RecoveredStress stress;
  RecoveredVolume volume;
};
RecoveredFields recover_body_fields(const BezierMesh& mesh, const Model& model, const Eigen::VectorXd& element_pressures = {});

// Where contact k's partner stands when the body has the displacement u
// (n_cp x dim, every body's control points) at load factor (or time) t: the
// signed normal gap of a point of space to it, positive outside, and its
// outward unit normal there.  A rigid obstacle where the step puts it (large
// deformation: its reference position moved by curve(t) motion; small
// deformation: where its whole motion puts it, moved back by (curve(t) - 1)
// motion); a second body's face moved by u.  Owns what it needs (a moved
// copy of the master surface).
using ContactPartner = std::function<ObstacleProbe(const Eigen::VectorXd& x)>;
ContactPartner contact_partner(const Model& model, size_t k, const Eigen::MatrixXd& u, double t);

struct ContactPartFields {
  Eigen::VectorXd point_pressure;          // per Bezier point: the projection of -lambda_h
  Eigen::MatrixXd point_traction;          // per Bezier point (x dim): the projection of p_h n
  Eigen::VectorXd point_gap;               // per Bezier point: the projection of g_n(X + u)
  std::vector<double> cell_pressure;       // per element: mean of -lambda_h over the reference face
  std::vector<double> cell_weighted_gap;   // per element: mean of sum_K (Pi g)_K B_K
  std::vector<double> cell_gap;            // per element: mean of g_n(X + u)
  std::vector<char> cell_active;           // a multiplier whose support meets the element is active (char: threads write it)
};
// `side_of[e]`: the contact side element e of `mesh` lies on; field 0 of
// `mesh` the displacement.  The traction p_h n on the body: n the partner's
// outward unit normal at the deformed point X + u.  The normal gap, a
// length: the signed distance g_n(X + u) to the partner (docs/design.md,
// "Gap and sign convention"), an obstacle or a second body's face alike.
ContactPartFields recover_contact_fields(const BezierMesh& mesh, const std::vector<const ContactSide*>& side_of,
                                         const ContactSolution& sol, const ContactPartner& partner);

}  // namespace igac
