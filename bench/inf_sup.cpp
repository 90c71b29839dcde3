// SPDX-License-Identifier: BSD-3-Clause
// bench/inf_sup: the discrete inf-sup constant of the mixed formulation's
// pair (engine/volumetric_projection.hpp): NURBS displacements of degree p
// (C^{p-1}) and one pressure constant per element, on the unit square with
// every side clamped, n x n elements:
//   beta_h = inf_q sup_v (div v, q) / (|v|_A |q|_0),   |v|_A^2 = int eps(v) : eps(v),
// computed as the square root of the smallest non-zero eigenvalue of
// M^{-1/2} B A^{-1} B^T M^{-1/2} (B(e, j) = int_e div N_j, M = diag |Omega_e|,
// A the stiffness of E = 1, nu = 0: 2 mu = 1).  Eigenvalues below 1e-10 of
// the largest are the pressures no displacement sees: the constant (every
// side clamped) and any checkerboard mode; their number is printed too.
//
// --macro M takes the pressure constant on M x M blocks of elements instead
// (the pressure of a mesh M times coarser: B(b, j) = int_b div N_j over the
// block's elements, M = diag |Omega_b|), the candidate stable pair.
//
//   build/bench/inf_sup [--degree P] [--macro M] [--csv FILE] N ...
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <vector>

#include "engine/assembly.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"

using namespace igac;

int main(int argc, char** argv) {
  int degree = 2, macro = 1;
  std::string csv_path;
  std::vector<int> sizes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--degree" && i + 1 < argc) degree = std::stoi(argv[++i]);
    else if (a == "--csv" && i + 1 < argc) csv_path = argv[++i];
    else if (a == "--macro" && i + 1 < argc) macro = std::stoi(argv[++i]);
    else sizes.push_back(std::stoi(a));
  }
  if (sizes.empty()) sizes = {4, 8, 16, 32};
  for (const int n : sizes)
    if (macro < 1 || n % macro != 0) {
      fmt::print(stderr, "inf_sup: {} elements per side is not a whole number of {} x {} blocks\n", n, macro, macro);
      return 2;
    }
  std::string csv = "degree,macro,elements_per_side,displacement_dofs,pressures,zero_modes,beta\n";
  fmt::print("{}", csv);  // stdout is the CSV of --csv FILE, its header first
  for (const int n : sizes) {
    const Geometry g = rectangle(1.0, 1.0);
    const NurbsPatch patch = subdivide(elevate_to(g.patch, degree), n);
    std::vector<DirichletCondition> clamp;
    for (const char* face : {"left", "right", "bottom", "top"})
      for (int c = 0; c < 2; ++c) clamp.push_back({g.faces.at(face), c, 0.0});
    const DofMap dofs(patch, clamp);
    const Body body(patch);
    const LinearSystem a = assemble_linear_elasticity(body, dofs, LinearElastic{1.0, 0.0}, Eigen::VectorXd::Zero(2));
    // B and M: the element loop of the quadrature every assembler uses
    const BodyQuadrature quad(body, gauss_points_for(degree));
    const int ne_el = quad.num_elements(), nf = dofs.num_free();
    const int nm = n / macro, ne = nm * nm;
    auto group = [&](int e) { return (e % n) / macro + nm * ((e / n) / macro); };
    Eigen::MatrixXd Bt = Eigen::MatrixXd::Zero(nf, ne);
    Eigen::VectorXd area = Eigen::VectorXd::Zero(ne);
    ElementValues<2, 2> ed;
    std::vector<int> eq;
    for (int e = 0; e < ne_el; ++e) {
      quad.evaluate(e, ed, true);
      const int g = group(e);
      dofs.element_equations(ed.cps, eq);
      for (int q = 0; q < ed.n_q; ++q) {
        area[g] += ed.JxW[q];
        for (int c = 0; c < int(eq.size()); ++c)
          if (eq[c] >= 0) Bt(eq[c], g) += ed.gradients(q)[c] * ed.JxW[q];  // dN_a/dX_i, c = a dim + i
      }
    }
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> A(a.K);
    const Eigen::MatrixXd AiBt = A.solve(Bt);
    const Eigen::VectorXd s = area.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd S = s.asDiagonal() * (Bt.transpose() * AiBt) * s.asDiagonal();
    const Eigen::VectorXd ev = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S, Eigen::EigenvaluesOnly).eigenvalues();
    const double top = ev.maxCoeff();
    int zero = 0;
    double smallest = top;
    for (int k = 0; k < ev.size(); ++k) {
      if (ev[k] < 1e-10 * top) ++zero;
      else smallest = std::min(smallest, ev[k]);
    }
    const double beta = std::sqrt(smallest);
    const std::string row = fmt::format("{},{},{},{},{},{},{:.6g}\n", degree, macro, n, nf, ne, zero, beta);
    fmt::print("{}", row);
    std::fflush(stdout);
    csv += row;
  }
  if (!csv_path.empty()) std::ofstream(csv_path) << csv;
  return 0;
}
