// SPDX-License-Identifier: BSD-3-Clause
// Error norms of a displacement field on a body (one or more patches): L2 and the H1 seminorm,
//   ||u - u_h||_0 = (int |u - u_h|^2 dX)^1/2,  |u - u_h|_1 = (int |grad(u - u_h)|^2 dX)^1/2,
// against a closed-form solution or against a reference solution on a finer
// nested mesh of the same geometry (then the integral runs over the fine
// mesh, on whose elements the coarse field is smooth; the fine body's patch k
// refines the coarse body's patch k).  Each result also holds
// the norm of the reference so that relative errors can be formed.
#pragma once

#include <functional>

#include "engine/body.hpp"

namespace igac {

struct ErrorNorms {
  double l2 = 0, h1 = 0;            // absolute errors
  double ref_l2 = 0, ref_h1 = 0;    // norms of the reference
};

// u(X) and grad u(X) (dim x dim, row i = gradient of component i).
using ExactDisplacement = std::function<void(const Eigen::VectorXd& X, Eigen::VectorXd& u, Eigen::MatrixXd& grad)>;

// u: one row per body control point.
ErrorNorms errors_against_exact(const Body& body, const Eigen::MatrixXd& u, const ExactDisplacement& exact,
                                int points_per_direction);
ErrorNorms errors_against_reference(const Body& coarse, const Eigen::MatrixXd& u_coarse,
                                    const Body& fine, const Eigen::MatrixXd& u_fine, int points_per_direction);

}  // namespace igac
