// Weighted gaps and their linearisation (paper, eq. (8) and Appendix 1):
//   (Pi g)_K = int_{Gamma_C} g_n B_K dGamma / K_K,   K_K = int_{Gamma_C} B_K dGamma,
// integrated on the reference contact face.  In small deformation the gap is
// linearised at the reference position X:  g_n(u) = g_n(X) + n(X) . u(X), so
//   K_K (Pi g)_K = g0_K + (G u)_K,  g0_K = int g_n(X) B_K,  G_{K,(A,i)} = int B_K N_A n_i.
// G is also the coupling block of the saddle-point system: the contact
// virtual work is sum_K lambda_K (G du)_K.  Prescribed displacements on the
// face move into g0.
#pragma once

#include <Eigen/Sparse>

#include "contact/multiplier_space.hpp"
#include "contact/obstacle.hpp"
#include "engine/assembly.hpp"

namespace igac {

struct ContactFace {
  NurbsPatch face_patch;
  std::vector<int> face_cps;  // parent numbers of the face's control points
  Face face;
  MultiplierSpace space;
  ContactFace(const NurbsPatch& patch, const Face& f);
  PatchQuadrature quadrature(int points) const { return PatchQuadrature(face_patch, points, face, face_cps); }
};

struct WeightedGapOperator {
  Eigen::SparseMatrix<double, Eigen::RowMajor> G;  // m x n_free
  Eigen::VectorXd weights;                         // K_K
  Eigen::VectorXd g0;                              // int g_n(X) B_K (+ prescribed part)
  // Weighted gaps (Pi g)_K for free displacements u.
  Eigen::VectorXd weighted_gaps(const Eigen::VectorXd& u_free) const {
    return (g0 + G * u_free).cwiseQuotient(weights);
  }
};

// Several operators (one per contact) as one: rows stacked in order.
WeightedGapOperator stack(const std::vector<WeightedGapOperator>& ops);
WeightedGapOperator assemble_weighted_gaps(const NurbsPatch& patch, const DofMap& dofs, const ContactFace& cf,
                                           const Obstacle& obstacle);

// Weighted gaps of the exact (not linearised) gap at the displaced position
// X + u(X), u given per control point (n_cp x dim): what G linearises.
Eigen::VectorXd exact_weighted_gaps(const NurbsPatch& patch, const Eigen::MatrixXd& u, const ContactFace& cf,
                                    const Obstacle& obstacle);

}  // namespace igac
