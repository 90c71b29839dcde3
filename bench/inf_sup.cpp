// SPDX-License-Identifier: BSD-3-Clause
// bench/inf_sup: the discrete inf-sup constant of a displacement-pressure
// pair: NURBS displacements of degree p (C^{p-1}) on the unit square, n x n
// elements, the clamped sides' displacements zero, and a pressure space of
// engine/pressure_space.hpp (the one the mixed formulation assembles):
//   beta_h = inf_q sup_v (div v, q) / (|v|_A |q|_M),   |v|_A^2 = int eps(v) : eps(v),
// the square root of the smallest non-zero eigenvalue lambda of
//   S x = lambda M x,   S = B A^{-1} B^T,   B(A, j) = int N_A div N_j,
// A the stiffness of E = 1, nu = 0 (2 mu = 1), M the pressure mass
// M_AB = int N_A N_B (consistent), or with --lumped its row sums
// diag(m_A), m_A = int N_A: the lumped mass the formulation's local
// pressure uses (so beta_h of --lumped is the one of its own operator).
// Eigenvalues below 1e-10 of the largest are the pressures no displacement
// sees: the constant (every side clamped) and any spurious mode; their
// number is printed too (zero_modes).
//
// The pairs:
//   --formulation mixed          (the default) mixed_pressure_space's:
//                                degree p-1, C^{p-2}, on breakpoints twice
//                                coarser (the sub-grid pair: stable)
//   --formulation mixed_element  constants per element (beta_h ~ h)
//   --same-grid                  degree p-1, C^{p-2} on the displacement's
//                                own breakpoints (not stable: beta_h ~ h)
//   --macro M                    constants on M x M blocks of elements (the
//                                pair of before the pressure space, M = 2)
// --clamp SIDES: the clamped sides among l(eft) r(ight) b(ottom) t(op),
// default lrbt.
//
//   build/bench/inf_sup [--degree P] [--formulation F | --same-grid | --macro M]
//                       [--lumped] [--clamp SIDES] [--csv FILE] N ...
#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/assembly.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/pressure_space.hpp"
#include "engine/spline/refinement.hpp"

using namespace igac;

namespace {

struct Options {
  int degree = 2, macro = 0;
  std::string pair = "mixed", clamp = "lrbt", csv_path;
  bool lumped = false;
  std::vector<int> sizes;
};

int to_int(const std::string& option, const std::string& text) {
  size_t used = 0;
  int v = 0;
  try {
    v = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty())
    throw std::invalid_argument(fmt::format("{}: '{}' is not a whole number", option, text));
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  int pairs = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--degree") o.degree = to_int(a, value());
    else if (a == "--csv") o.csv_path = value();
    else if (a == "--macro") o.macro = to_int(a, value()), o.pair = "macro", ++pairs;
    else if (a == "--formulation") o.pair = value(), ++pairs;
    else if (a == "--same-grid") o.pair = "same_grid", ++pairs;
    else if (a == "--lumped") o.lumped = true;
    else if (a == "--clamp") o.clamp = value();
    else if (a.rfind("-", 0) == 0) throw std::invalid_argument("unknown option " + a);
    else o.sizes.push_back(to_int("elements per side", a));
  }
  if (pairs > 1) throw std::invalid_argument("one of --formulation, --same-grid, --macro");
  if (o.pair != "mixed" && o.pair != "mixed_element" && o.pair != "same_grid" && o.pair != "macro")
    throw std::invalid_argument("--formulation " + o.pair + ": mixed or mixed_element");
  if (o.degree < 1) throw std::invalid_argument(fmt::format("--degree {}: at least 1", o.degree));
  if (o.pair == "macro" && o.macro < 1) throw std::invalid_argument(fmt::format("--macro {}: at least 1", o.macro));
  if (o.clamp.empty() || o.clamp.find_first_not_of("lrbt") != std::string::npos)
    throw std::invalid_argument("--clamp '" + o.clamp + "': one or more of l r b t");
  if (o.sizes.empty()) o.sizes = {4, 8, 16, 32};
  for (const int n : o.sizes) {
    if (n < 1) throw std::invalid_argument(fmt::format("{} elements per side", n));
    if (o.pair == "macro" && n % o.macro != 0)
      throw std::invalid_argument(fmt::format("{} elements per side is not a whole number of {} x {} blocks", n,
                                              o.macro, o.macro));
  }
  return o;
}

PressureSpace pair_space(const Options& o, const BodyQuadrature& quad) {
  if (o.pair == "mixed") return mixed_pressure_space(quad, {Formulation::mixed});
  if (o.pair == "mixed_element") return mixed_pressure_space(quad, {Formulation::mixed_element});
  if (o.pair == "same_grid") return PressureSpace(quad, {{o.degree - 1, o.degree - 1, 0}}, {1});
  return PressureSpace(quad, {{0, 0, 0}}, {o.macro});
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "inf_sup: {}\n", e.what());
    return 2;
  }
  std::string csv =
      "degree,macro,elements_per_side,displacement_dofs,pressures,zero_modes,beta,pair,pressure_degree,mass,clamped\n";
  fmt::print("{}", csv);  // stdout is the CSV of --csv FILE, its header first
  for (const int n : o.sizes) {
    const Geometry g = rectangle(1.0, 1.0);
    const NurbsPatch patch = subdivide(elevate_to(g.patch, o.degree), n);
    std::vector<DirichletCondition> clamp;
    for (const char side : o.clamp) {
      const char* face = side == 'l' ? "left" : side == 'r' ? "right" : side == 'b' ? "bottom" : "top";
      for (int c = 0; c < 2; ++c) clamp.push_back({g.faces.at(face), c, 0.0});
    }
    const DofMap dofs(patch, clamp);
    const Body body(patch);
    const LinearSystem a = assemble_linear_elasticity(body, dofs, LinearElastic{1.0, 0.0}, Eigen::VectorXd::Zero(2));
    // B and M: the element loop of the quadrature every assembler uses, the
    // pressure functions of each element at its quadrature points
    const BodyQuadrature quad(body, gauss_points_for(o.degree));
    const PressureSpace space = pair_space(o, quad);
    const int nf = dofs.num_free(), np = space.num_functions();
    Eigen::MatrixXd Bt = Eigen::MatrixXd::Zero(nf, np), M = Eigen::MatrixXd::Zero(np, np);
    ElementValues<2, 2> ed;
    PressureSpace::Scratch scratch;
    std::vector<double> nv;
    std::vector<int> eq;
    for (int e = 0; e < quad.num_elements(); ++e) {
      quad.evaluate(e, ed, true);
      dofs.element_equations(ed.cps, eq);
      const int* fa = space.functions_begin(e);
      for (int q = 0; q < ed.n_q; ++q) {
        space.values(e, ed.xi[size_t(q)].data(), nv, scratch);
        for (size_t i = 0; i < nv.size(); ++i) {
          const double w = nv[i] * ed.JxW[q];
          for (size_t k = 0; k < nv.size(); ++k) M(fa[i], fa[k]) += w * nv[k];
          for (int c = 0; c < int(eq.size()); ++c)
            if (eq[size_t(c)] >= 0) Bt(eq[size_t(c)], fa[i]) += ed.gradients(q)[c] * w;  // dN_a/dX_i, c = a dim + i
        }
      }
    }
    if (o.lumped) M = Eigen::VectorXd(M.rowwise().sum()).asDiagonal();
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> A(a.K);
    const Eigen::MatrixXd S = Bt.transpose() * A.solve(Bt);
    const Eigen::VectorXd ev =
        Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(S, M, Eigen::EigenvaluesOnly).eigenvalues();
    const double top = ev.maxCoeff();
    int zero = 0;
    double smallest = top;
    for (int k = 0; k < ev.size(); ++k) {
      if (ev[k] < 1e-10 * top) ++zero;
      else smallest = std::min(smallest, ev[k]);
    }
    const int pressure_degree = o.pair == "mixed" || o.pair == "same_grid" ? o.degree - 1 : 0;
    const int coarsening = o.pair == "macro" ? o.macro : o.pair == "mixed" ? kPressureCoarsening : 1;
    const std::string row =
        fmt::format("{},{},{},{},{},{},{:.6g},{},{},{},{}\n", o.degree, coarsening, n, nf, np, zero,
                    std::sqrt(smallest), o.pair, pressure_degree, o.lumped ? "lumped" : "consistent", o.clamp);
    fmt::print("{}", row);
    std::fflush(stdout);
    csv += row;
  }
  if (!o.csv_path.empty()) std::ofstream(o.csv_path) << csv;
  return 0;
}
