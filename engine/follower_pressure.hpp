// SPDX-License-Identifier: BSD-3-Clause
// Pressure loads on faces of a body in large deformation: a follower load
// that acts on the deformed face (default) and a dead load on the reference
// face (option).  Wriggers, Nonlinear FEM, sec. 4.2.5; Holzapfel sec. 8.4.
//
// A pressure p acts on the deformed face with the traction -p n (n the
// current outward normal).  Nanson's formula n da = J F^{-T} N dA moves it to
// the reference face; on the face's own parametrisation xi with the current
// position x(xi) = X(xi) + u(xi) it is simply
//   n da = s (x_,1 x x_,2) dxi      (3D),   n da = s rot(x_,1) dxi   (2D),
// the outward area vector of face_area_vector (nurbs_patch.hpp) evaluated
// with the current tangents x_,a = sum_B dN_B/dxi_a (X_B + u_B).  Hence
//   f_ext_(A,i) = -p int N_A (n da)_i,
// which depends on u through the tangents only: linearly in 2D, bilinearly in
// 3D.  Its exact derivative (the load stiffness)
//   d f_ext_(A,i) / d u_(B,k) = -p int N_A d(n da)_i / d u_(B,k)
//     3D: d(n da)/du_(B,k) = s' (dN_B/dxi_2 x_,1 x e_k + dN_B/dxi_1 e_k x x_,2) dxi
//     2D: d(n da)/du_(B,k) = s' dN_B/dxi_1 rot(e_k) dxi
// is not symmetric in general (its symmetric part integrates to a symmetric
// form only for closed or fixed boundaries), so it is assembled as it is.
// The dead load uses the reference normal: f_ext = -p int N_A N dA, the load
// of add_pressure_load (assembly.hpp).
//
// Quadrature: (p+1)^(dim-1) Gauss points per face element, p the largest
// degree of the patch (the rule of the volume assembly and of
// add_pressure_load); the weights are the parametric Gauss weights, so a
// face that degenerates somewhere (zero area) needs no special case.  The
// faces are walked by FaceQuadrature (face_quadrature.hpp), the element
// values are ElementValues<dim - 1, dim>, and each face element's vector and
// matrix go into f and K by the one scatter (sparsity.hpp).
//
// Owner: engine/ (loads).  The load-step driver calls these with the full
// displacement u (n_cp x dim, prescribed values included) and the tangent K
// of TotalLagrangianAssembler (whose pattern holds every face coupling: face
// control points share elements).
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "engine/assembly.hpp"

namespace igac {

// Per side of a face list, per face element of it (PatchQuadrature's
// order): a flag.  As a pressure's `wet` mask: the elements it acts on (a
// fluid's pressure that reaches only part of the faces,
// contact/pressure_penetration.hpp); null: every element.
using FaceElementFlags = std::vector<std::vector<char>>;

// Adds the external force of a follower pressure p on `faces` to f_ext (free
// numbering; rows of prescribed dofs skipped) and, when K is not null,
// subtracts the load stiffness d f_ext / du from K, so that K stays the
// tangent of the residual f_int - f_ext.  K must already hold every entry
// the load couples (the TotalLagrangianAssembler pattern does); it is
// compressed if it is not.  Throws std::invalid_argument when u has the wrong
// shape and std::logic_error when K lacks an entry.
void add_follower_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                           const Eigen::MatrixXd& u, Eigen::VectorXd& f_ext, Eigen::SparseMatrix<double>* K,
                           const FaceElementFlags* wet = nullptr);

// The pattern of the load stiffness of add_follower_pressure on `faces`
// (free x free, every coupling of two equations of one face element, values
// zero): a matrix of the faces' size to receive it apart from the volume's
// tangent.
Eigen::SparseMatrix<double> follower_pressure_pattern(const Body& body, const DofMap& dofs,
                                                      const std::vector<PatchSide>& faces);

// Adds the external force of a dead pressure p (acting on the reference face
// with its reference normal, independent of u: no load stiffness).
void add_dead_pressure(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces, double p,
                       Eigen::VectorXd& f_ext, const FaceElementFlags* wet = nullptr);

// Adds the external force of a dead traction t (dim components, force per
// unit reference area of the faces, any direction: a shear load such as
// Cook's membrane's), f_ext_(A,i) += int N_A t_i dA on the reference faces;
// the face loop of the pressures.  Throws std::invalid_argument when t has
// the wrong size.
void add_dead_traction(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces,
                       const Eigen::VectorXd& traction, Eigen::VectorXd& f_ext);

}  // namespace igac
