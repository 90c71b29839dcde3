// SPDX-License-Identifier: BSD-3-Clause
// The discrete inf-sup constant of the mixed formulation's pair (issue 24),
// measured on the formulation's own operator: C = the pressure functions'
// rows mB_A = (1/m_A) int N_A dJ/du dX at u = 0
// (TotalLagrangianAssembler::LocalDilatation::mean_B), on the unit square
// with every side clamped, p = 2, n x n elements; A = the stiffness of E = 1,
// nu = 0 (|v|_A^2 = int eps : eps, as bench/inf_sup), M = diag(m_A), the
// lumped pressure mass the formulation uses:
//   beta_h^2 = the smallest non-zero eigenvalue of
//              M^{1/2} C A^{-1} C^T M^{1/2}   (= M^{-1/2} B A^{-1} B^T M^{-1/2}, B = M C).
// The sub-grid continuous pressure (`mixed`, linear C^0 on breakpoints twice
// coarser): beta_h stays near 0.3 from n = 4 to 16 (with the consistent mass
// near 0.6: bench/inf_sup).  One constant per element (`mixed_element`):
// beta_h falls like h, so the test fails for that pair.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <cmath>

#include "engine/assembly.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/pressure_space.hpp"
#include "engine/spline/refinement.hpp"
#include "engine/total_lagrangian.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {
namespace {

// beta_h of the pair on n x n elements; `per_element`: constants per element.
double inf_sup_constant(int n, bool per_element) {
  const Geometry g = rectangle(1.0, 1.0);
  const NurbsPatch patch = subdivide(elevate_to(g.patch, 2), n);
  std::vector<DirichletCondition> clamp;
  for (const char* face : {"left", "right", "bottom", "top"})
    for (int c = 0; c < 2; ++c) clamp.push_back({g.faces.at(face), c, 0.0});
  const DofMap dofs(patch, clamp);
  const auto law = make_law("neo_hookean", MaterialParameters{1.0, 0.3, {}});
  TotalLagrangianAssembler tl(patch, dofs, *law, Formulation::mixed);
  if (per_element)
    tl.set_pressure_space(mixed_pressure_space(BodyQuadrature(Body(patch), gauss_points_for(2)), {Formulation::mixed_element}));
  Eigen::VectorXd f;
  Eigen::SparseMatrix<double> K;
  TotalLagrangianAssembler::LocalDilatation local;
  const Eigen::VectorXd z = Eigen::VectorXd::Zero(tl.num_pressures());
  EXPECT_TRUE(tl.assemble(Eigen::MatrixXd::Zero(patch.num_control_points(), 2), f, &K, &z, &local));
  const LinearSystem a = assemble_linear_elasticity(patch, dofs, LinearElastic{1.0, 0.0}, Eigen::VectorXd::Zero(2));
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> A(a.K);
  const Eigen::MatrixXd Ct = Eigen::MatrixXd(Eigen::SparseMatrix<double>(local.mean_B.transpose()));
  const Eigen::VectorXd s = local.volume.cwiseSqrt();
  const Eigen::MatrixXd S = s.asDiagonal() * (Ct.transpose() * A.solve(Ct)) * s.asDiagonal();
  const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
  const double top = ev.maxCoeff();
  double smallest = top;
  for (int k = 0; k < ev.size(); ++k)
    if (ev[k] >= 1e-10 * top) smallest = std::min(smallest, ev[k]);  // below: pressures no displacement sees
  return std::sqrt(smallest);
}

TEST(InfSup, SubGridContinuousPressureStaysBoundedOnePerElementFalls) {
  const double sub4 = inf_sup_constant(4, false), sub8 = inf_sup_constant(8, false),
               sub16 = inf_sup_constant(16, false);
  const double element4 = inf_sup_constant(4, true), element16 = inf_sup_constant(16, true);
  std::cout << "  inf-sup, p = 2, n = 4/8/16: sub-grid continuous " << sub4 << " " << sub8 << " " << sub16
            << "; per element (n = 4/16) " << element4 << " " << element16 << "\n";
  // the lumped-mass numbers of bench/inf_sup (the same pair, norms and mesh)
  EXPECT_NEAR(sub4, 0.258, 1e-3);
  EXPECT_NEAR(sub8, 0.288, 1e-3);
  EXPECT_NEAR(sub16, 0.301, 1e-3);
  EXPECT_GE(sub16, sub8) << "bounded below: not falling with h";
  // bench/inf_sup --formulation mixed_element's (indicators: the lumped mass is the consistent one)
  EXPECT_NEAR(element4, 0.513, 1e-3);
  EXPECT_NEAR(element16, 0.165, 1e-3);
  EXPECT_LT(element16, 0.6 * element4) << "per element, beta_h falls like h";
}

}  // namespace
}  // namespace igac
