// SPDX-License-Identifier: BSD-3-Clause
// Weighted gaps and their linearisation (paper, eq. (8) and Appendix 1):
//   (Pi g)_K = int_{Gamma_C} g_n B_K dGamma / K_K,   K_K = int_{Gamma_C} B_K dGamma,
// integrated on the reference contact face.  In small deformation the gap is
// linearised at the reference position X:  g_n(u) = g_n(X) + n(X) . u(X), so
//   K_K (Pi g)_K = g0_K + (G u)_K,  g0_K = int g_n(X) B_K,  G_{K,(A,i)} = int B_K N_A n_i.
// G is also the coupling block of the saddle-point system: the contact
// virtual work is sum_K lambda_K (G du)_K.  Prescribed displacements on the
// face move into g0.
#pragma once

#include "contact/interface_law.hpp"

#include <Eigen/Sparse>

#include "contact/multiplier_space.hpp"
#include "contact/obstacle.hpp"
#include "engine/assembly.hpp"
#include "engine/face_quadrature.hpp"

namespace igac {

// One patch side of a contact face and its multipliers S^{p-2}.
struct ContactSide {
  PatchSide side;
  NurbsPatch face_patch;      // the side as a patch
  std::vector<int> face_cps;  // body numbers of the side's control points
  MultiplierSpace space;
  int first_multiplier = 0;   // of the contact face's numbering
  ContactSide(const Body& body, const PatchSide& s, int first);
  Face face() const { return side.face; }
  PatchQuadrature quadrature(int points) const { return PatchQuadrature(face_patch, points, side.face, face_cps); }
};

// The contact face Gamma_C: one or more patch sides (a face of a multi-patch
// body may span several), each with its own multiplier space S^{p-2} (paper,
// eq. (7), per side); the multipliers are numbered side after side.
struct ContactFace {
  std::vector<ContactSide> sides;
  int degree = 2;  // of the body: the quadrature of the contact integrals
  ContactFace(const Body& body, const std::vector<PatchSide>& sides);
  ContactFace(const Body& body, const PatchSide& side) : ContactFace(body, std::vector<PatchSide>{side}) {}
  int num_multipliers() const { return sides.back().first_multiplier + sides.back().space.size(); }
  // Gauss points per direction of the contact integrals.
  int quadrature_points() const;
  // The face loop over every side with `points` Gauss points per direction.
  FaceQuadrature face_quadrature(int points) const;
};

// The quadrature of the contact integrals over every side of a contact face,
// tabulated once ((p+2) Gauss points per face direction): the face loop of
// engine/ (FaceQuadrature) with, at each point, the nonzero multiplier
// functions B_K (K in the face's numbering).  The one face loop of the
// weighted gaps, their linearisation and the large-deformation contact
// (FiniteStrainProblem).  Keeps a pointer to `cf`, which must outlive it.
class ContactQuadrature {
 public:
  explicit ContactQuadrature(const ContactFace& cf);
  // visit(const ElementValues<dim - 1, dim>& v, int q, const std::vector<int>& K,
  //       const std::vector<double>& B) per face point: a generic lambda
  // (`const auto& v`) serves 2D and 3D.
  template <class Visit>
  void for_each_point(Visit&& visit) const {
    std::vector<int> kidx;
    std::vector<double> kval;
    Eigen::VectorXd xi;
    faces_.for_each_element([&](int s, const auto& v) {
      const ContactSide& side = cf_->sides[s];
      for (int q = 0; q < v.n_q; ++q) {
        xi = v.xi[q];
        side.space.basis(xi, kidx, kval);
        for (int& K : kidx) K += side.first_multiplier;
        visit(v, q, static_cast<const std::vector<int>&>(kidx), static_cast<const std::vector<double>&>(kval));
      }
    });
  }

 private:
  const ContactFace* cf_;
  FaceQuadrature faces_;
};

struct WeightedGapOperator {
  Eigen::SparseMatrix<double, Eigen::RowMajor> G;  // m x n_free
  Eigen::VectorXd weights;                         // K_K
  Eigen::VectorXd g0;                              // int g_n(X) B_K (+ prescribed part)
  // Coulomb friction (contact/small_strain_friction.hpp), empty when every
  // contact is frictionless: dim-1 tangential rows per multiplier, row
  // K (dim-1) + j along the obstacle's tangent t_j at the point,
  //   T_{(K,j),(a,i)} = int B_K N_a (t_j)_i,  t0_(K,j) = -int B_K (shift . t_j) (+ prescribed part),
  // so that T u + t0 is the weighted tangential displacement of the body
  // relative to the obstacle moved by `shift`; and the coefficient f per multiplier.
  Eigen::SparseMatrix<double, Eigen::RowMajor> T;
  Eigen::VectorXd t0;
  Eigen::VectorXd friction;
  // The couplings to the prescribed dofs, whose values went into g0 and t0:
  // the rows of G and T, columns numbered by dof (control point * dim +
  // component).  G_held^T lambda + T_held^T lambda_t is what the contact
  // pushes on the supports (model/reactions.hpp); the solve never reads them.
  Eigen::SparseMatrix<double, Eigen::RowMajor> G_held, T_held;
  // int B_K n dGamma per multiplier (m x dim), n the partner's normal the
  // gap is measured along: the normal force on the (slave) face is
  // -sum_K lambda_K directions_K (ContactResult::resultant).
  Eigen::MatrixXd directions;
  // The interface law of each multiplier (contact/interface_law.hpp; empty:
  // frictionless everywhere).  T and t0 are there when one law has
  // tangential rows (Coulomb, a tie): then every contact has them (zero for
  // a law without).
  std::vector<const InterfaceLaw*> laws;
  const InterfaceLaw& law(int K) const { return laws.empty() ? frictionless_law() : *laws[size_t(K)]; }
  bool tangential() const { return T.rows() > 0; }
  // Whether a multiplier may pull (a tie): no "pulled off" check applies.
  bool bilateral() const {
    for (const InterfaceLaw* l : laws)
      if (l->bilateral()) return true;
    return false;
  }
  // Weighted gaps (Pi g)_K for free displacements u.
  Eigen::VectorXd weighted_gaps(const Eigen::VectorXd& u_free) const {
    return (g0 + G * u_free).cwiseQuotient(weights);
  }
};

// The triplets of G (or T) under assembly: `free` numbered by the free
// equations, `held` the prescribed dofs' (column: the dof).
struct GapCouplings {
  std::vector<Eigen::Triplet<double>> free, held;
  // Into G (T) and G_held (T_held), `rows` rows.
  void build(const DofMap& dofs, int rows, Eigen::SparseMatrix<double, Eigen::RowMajor>& G,
             Eigen::SparseMatrix<double, Eigen::RowMajor>& G_held) const;
};
// One coupling of multiplier K to body control point a with weight w along
// the normal n: G_{K,(a,i)} += w n_i for a free dof, or its prescribed value
// moved into g0 (and the coupling kept in `held`).  The one scatter of the
// obstacle and the mortar gaps.
void add_gap_coupling(const DofMap& dofs, int K, int a, double w, const Eigen::Ref<const Eigen::VectorXd>& n,
                      GapCouplings& out, Eigen::VectorXd& g0);

// Several operators (one per contact) as one: rows stacked in order.
WeightedGapOperator stack(const std::vector<WeightedGapOperator>& ops);
// With a law that has them (Coulomb, a tie) also the tangential rows T, t0 (the obstacle translated
// by `shift` from where its tangential displacement counts; empty: none).
// `u` (n_cp x dim; null: none): the obstacle probed at the displaced points
// X + u(X) (its normals and tangents there; the integrals stay on the
// reference face): large-deformation friction's rows of a load step
// (contact/finite_strain_friction.hpp).
WeightedGapOperator assemble_weighted_gaps(const DofMap& dofs, const ContactFace& cf, const Obstacle& obstacle,
                                           const ContactLaw& law = {}, const Eigen::VectorXd& shift = {},
                                           const Eigen::MatrixXd* u = nullptr);
// The obstacle's tangents at a point of normal n: t (2D, n rotated by -90
// degrees: (n_y, -n_x)) or t1, t2 (3D, t1 the coordinate axis least aligned
// with n projected on the tangent plane, t2 = n x t1), as columns.
Eigen::MatrixXd tangent_basis(const Eigen::VectorXd& n);

// Weighted gaps of the exact (not linearised) gap at the displaced position
// X + u(X), u given per control point (n_cp x dim): what G linearises.
Eigen::VectorXd exact_weighted_gaps(const Eigen::MatrixXd& u, const ContactFace& cf, const Obstacle& obstacle);

}  // namespace igac
