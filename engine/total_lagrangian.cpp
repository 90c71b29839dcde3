// SPDX-License-Identifier: BSD-3-Clause
#include "engine/total_lagrangian.hpp"

#include "engine/quadrature.hpp"
#include "engine/sparsity.hpp"
#include "engine/free_cores.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>
#include <vector>

namespace igac {

namespace {

bool has_structure(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& pattern) {
  if (K.rows() != pattern.rows() || K.cols() != pattern.cols() || !K.isCompressed() ||
      K.nonZeros() != pattern.nonZeros())
    return false;
  return std::equal(pattern.outerIndexPtr(), pattern.outerIndexPtr() + pattern.outerSize() + 1, K.outerIndexPtr()) &&
         std::equal(pattern.innerIndexPtr(), pattern.innerIndexPtr() + pattern.nonZeros(), K.innerIndexPtr());
}

// Per-thread scratch of the element kernel: sized on the first element,
// reused afterwards (every element of a patch has the same size).
template <int dim>
struct Workspace {
  ElementValues<dim, dim> geo;
  Eigen::Matrix<double, Eigen::Dynamic, dim> ue;      // local displacements, n_loc x dim
  Eigen::VectorXd fe;                                 // element internal force
  Eigen::MatrixXd Ke;                                 // element tangent
  Eigen::Matrix<double, Eigen::Dynamic, dim * dim> G; // (a*dim+i, k*dim+L): w sum_J dN_aJ A_iJkL
  std::vector<int> eq;                                // free equation per local dof, or -1
  std::vector<DimMatrix<dim>> F;                      // per point
  std::vector<double> hoop;                           // per point: F_33 = 1 + u_r / r (axisymmetric), else 1
  // mixed formulation (volumetric_projection.hpp): per point J, theta, p, U''
  ElementProjection projection;
  Eigen::VectorXd J, theta, dU, pressure, d2U;
  Eigen::MatrixXd B, Bbar;                            // n_q x nd: dJ/du per point, projected
  // the element's pressure functions (pressure_space.hpp): N(q, i) = N_{A_i}(x_q)
  PressureSpace::Scratch space_scratch;
  Eigen::MatrixXd N;
  Eigen::VectorXd base;                               // sum_i N(q, i) U'(theta_{A_i}) per point
};

// c[i] = int_e N_{A_i} (J - 1) dX from ws.F and ws.N: the element's part of
// m_A (theta_A - 1), the one sum the projection pass and the assembly share
// (so LocalDilatation::projected is volume_changes' double).
template <int dim>
void element_function_dilatations(const Workspace<dim>& ws, double* c) {
  const int nq = ws.geo.n_q, nf = int(ws.N.cols());
  for (int i = 0; i < nf; ++i) c[i] = 0;
  for (int q = 0; q < nq; ++q) {
    const double w = ws.geo.JxW[size_t(q)] * (ws.F[size_t(q)].determinant() * ws.hoop[size_t(q)] - 1);
    for (int i = 0; i < nf; ++i) c[i] += ws.N(q, i) * w;
  }
}

// The augmented Lagrangian of the incompressible limit (make_incompressible):
// U(theta) = lambda_A (theta - 1) + kappa/2 (theta - 1)^2 in place of the
// law's, lambda_A the pressure function's multiplier.
struct Augmentation {
  const double* lambda = nullptr;  // null: the law's U
  double kappa = 0;
};

// U'(theta_A) and U''(theta_A) of a pressure function, z = theta_A - 1;
// false when theta_A leaves U's domain.
bool function_volumetric(const HyperelasticLaw& law, Augmentation aug, double z, double& dU, double& d2U) {
  if (aug.lambda) {
    if (!(1 + z > 0)) return false;
    dU = *aug.lambda + aug.kappa * z;
    d2U = aug.kappa;
    return true;
  }
  VolumetricValues v;
  if (!law.volumetric(1 + z, v)) return false;
  dU = v.dU;
  d2U = v.d2U;
  return true;
}

// ws.ue and F at the Gauss points of ws.geo from u; false when F is not
// finite or det F <= 0 at a point.
template <int dim>
bool element_deformation(const Eigen::MatrixXd& u, Workspace<dim>& ws) {
  const ElementValues<dim, dim>& geo = ws.geo;
  const int nl = geo.n_loc, nq = geo.n_q;
  ws.ue.resize(nl, dim);
  for (int a = 0; a < nl; ++a) ws.ue.row(a) = u.row(geo.cps[a]);
  ws.F.resize(nq);
  ws.hoop.assign(size_t(nq), 1.0);
  for (int q = 0; q < nq; ++q) {
    const double* dN = geo.gradients(q);  // dN[a*dim+J] = dN_a/dX_J
    DimMatrix<dim>& F = ws.F[q];
    F.setIdentity();
    for (int a = 0; a < nl; ++a)
      for (int J = 0; J < dim; ++J)
        for (int i = 0; i < dim; ++i) F(i, J) += ws.ue(a, i) * dN[a * dim + J];
    if (!F.allFinite() || !(F.determinant() > 0)) return false;
    if (geo.revolved) {  // the circle of radius r goes to one of radius r + u_r
      for (int a = 0; a < nl; ++a) ws.hoop[q] += ws.ue(a, 0) * geo.hoop(q, a);
      if (!std::isfinite(ws.hoop[q]) || !(ws.hoop[q] > 0)) return false;
    }
  }
  return true;
}

// Mixed formulation: J and theta = Pi_e J at the points (ws.J, ws.theta)
// from ws.F.  theta = 1 + Pi_e (J - 1): at rest theta is 1 exactly (Pi_e 1
// is 1 only to round-off), so p = 0 and f_int = 0 exactly, as in the
// displacement formulation (a round-off residual at rest stalls Newton at
// load factor 0).  Returns int_e (Pi_e J - 1) dX; *volume = V_e.
template <int dim>
double element_dilatation(int pressure_degree, Workspace<dim>& ws, double* volume) {
  const ElementValues<dim, dim>& geo = ws.geo;
  const int nq = geo.n_q;
  ws.projection.build(geo.xi, geo.JxW, pressure_degree);
  ws.J.resize(nq);
  for (int q = 0; q < nq; ++q) ws.J[q] = ws.F[q].determinant() * ws.hoop[q] - 1;
  ws.theta.noalias() = ws.projection.matrix() * ws.J;
  double s = 0, w = 0;
  for (int q = 0; q < nq; ++q) s += geo.JxW[q] * ws.theta[q], w += geo.JxW[q];
  ws.theta.array() += 1;
  ws.J.array() += 1;
  *volume = w;
  return s;
}

// P += p J F^{-T} and A += p d(J F^{-T})/dF, d(J F^{-T})_iJ/dF_kL =
// J (F^{-1}_Lk F^{-1}_Ji - F^{-1}_Jk F^{-1}_Li): the pressure's stress.
template <int dim>
void add_pressure_stress(const DimMatrix<dim>& F, double p, DimMatrix<dim>& P, TangentMatrix<dim>* A) {
  const double J = F.determinant();
  const DimMatrix<dim> Fi = F.inverse();
  P += p * J * Fi.transpose();
  if (!A) return;
  for (int i = 0; i < dim; ++i)
    for (int Jd = 0; Jd < dim; ++Jd)
      for (int k = 0; k < dim; ++k)
        for (int L = 0; L < dim; ++L)
          (*A)(i * dim + Jd, k * dim + L) += p * J * (Fi(L, k) * Fi(Jd, i) - Fi(Jd, k) * Fi(L, i));
}

// One Gauss point q of an axisymmetric element (a revolved patch): the law
// sees the 3D F = diag(F_rz, F_33), F_33 = 1 + u_r / r (ws.hoop), and a
// displacement's variation moves F through D, its row for dof (a, i) holding
// dN_a/dX_J at F_iJ and, for i = r, N_a / r at F_33.  With the five entries
// of F that are not zero (rr, rz, zr, zz, 33): f_e += w D P, K_e += w D A D^T
// (the full matrix, symmetric), and in the mixed formulation
// B = dJ/du = J F^{-T} : D.  False when the law refuses F.
bool revolved_point(const HyperelasticLaw& law, bool mixed, bool tangent, int q, Workspace<2>& ws) {
  static constexpr std::array<int, 5> kEntry{0, 1, 3, 4, 8};  // rr, rz, zr, zz, 33 in the 3x3 row-major layout
  const ElementValues<2, 2>& geo = ws.geo;
  const int nl = geo.n_loc, nd = 2 * nl;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero(), P;
  F.topLeftCorner<2, 2>() = ws.F[q];
  F(2, 2) = ws.hoop[q];
  Eigen::Matrix<double, 9, 9> A;
  if (!mixed) {
    if (!law.evaluate(F, P, tangent ? &A : nullptr)) return false;
  } else {
    if (!law.evaluate_isochoric(F, P, tangent ? &A : nullptr)) return false;
    add_pressure_stress<3>(F, ws.pressure[q], P, tangent ? &A : nullptr);
  }
  thread_local Eigen::Matrix<double, Eigen::Dynamic, 5> D;
  D.setZero(nd, 5);
  const double* dN = geo.gradients(q);
  for (int a = 0; a < nl; ++a) {
    D(2 * a, 0) = dN[2 * a], D(2 * a, 1) = dN[2 * a + 1];
    D(2 * a + 1, 2) = dN[2 * a], D(2 * a + 1, 3) = dN[2 * a + 1];
    D(2 * a, 4) = geo.hoop(q, a);
  }
  const double w = geo.JxW[q];
  Eigen::Matrix<double, 5, 1> p5;
  for (int m = 0; m < 5; ++m) p5[m] = P(kEntry[m] / 3, kEntry[m] % 3);
  ws.fe.noalias() += w * (D * p5);
  if (!tangent) return true;
  Eigen::Matrix<double, 5, 5> A5;
  for (int m = 0; m < 5; ++m)
    for (int n = 0; n < 5; ++n) A5(m, n) = w * A(kEntry[m], kEntry[n]);
  ws.Ke.noalias() += D * A5 * D.transpose();
  if (mixed) {  // B(q, a dim + i) = J F^{-T} : D(a dim + i)
    const Eigen::Matrix3d JFiT = ws.J[q] * F.inverse().transpose();
    Eigen::Matrix<double, 5, 1> c;
    for (int m = 0; m < 5; ++m) c[m] = JFiT(kEntry[m] / 3, kEntry[m] % 3);
    ws.B.row(q) = (D * c).transpose();
  }
  return true;
}

// Element internal force and (when `tangent`) the tangent at the Gauss
// points of ws.geo; false when F is inadmissible at a point.  Mixed
// formulation (volumetric_projection.hpp), before the point loop: the point
// pressure p_q = ws.base[q] + mu_s (J_q - Pi_e J), ws.base[q] = sum_A
// N_A(x_q) U'(theta_A) the caller's; the element's tangent carries mu_s (B^T W B -
// V_e mB_e^T mB_e) (ws.Bbar: every row mB_e), the pressure functions'
// rank-one terms (U''(theta_A)/m_A) g_A g_A^T are the caller's, from ws.B.
template <int dim>
bool element_kernel(const HyperelasticLaw& law, Formulation formulation, int pressure_degree, double stabilisation,
                    const Eigen::MatrixXd& u, bool tangent, Workspace<dim>& ws) {
  const ElementValues<dim, dim>& geo = ws.geo;
  const int nl = geo.n_loc, nq = geo.n_q, nd = nl * dim;
  const bool mixed = is_mixed(formulation);
  ws.fe.setZero(nd);
  if (tangent) {
    ws.Ke.setZero(nd, nd);
    ws.G.resize(nd, dim * dim);
  }
  if (!element_deformation<dim>(u, ws)) return false;
  if (mixed) {
    double volume = 0;
    element_dilatation<dim>(pressure_degree, ws, &volume);
    // the stabilisation's pressure mu_s (J - Pi_e J): the element's volume
    // modes that the pressure space does not see (volumetric_projection.hpp)
    ws.pressure = stabilisation * (ws.J - ws.theta);
    ws.pressure += ws.base;
  }
  if (mixed && tangent) ws.B.resize(nq, nd);
  DimMatrix<dim> P;
  TangentMatrix<dim> A;
  for (int q = 0; q < nq; ++q) {
    if constexpr (dim == 2)
      if (geo.revolved) {
        if (!revolved_point(law, mixed, tangent, q, ws)) return false;
        continue;
      }
    const double* dN = geo.gradients(q);  // dN[a*dim+J] = dN_a/dX_J
    const DimMatrix<dim>& F = ws.F[q];
    if (!mixed) {
      if (!law.evaluate(F, P, tangent ? &A : nullptr)) return false;
    } else {
      if (!law.evaluate_isochoric(F, P, tangent ? &A : nullptr)) return false;
      add_pressure_stress<dim>(F, ws.pressure[q], P, tangent ? &A : nullptr);
      if (tangent) {  // B(q, a dim + i) = dJ/du_ai = J F^{-T}_iJ dN_a/dX_J
        const DimMatrix<dim> JFiT = ws.J[q] * F.inverse().transpose();
        for (int a = 0; a < nl; ++a)
          for (int i = 0; i < dim; ++i) {
            double s = 0;
            for (int J = 0; J < dim; ++J) s += JFiT(i, J) * dN[a * dim + J];
            ws.B(q, a * dim + i) = s;
          }
      }
    }
    const double w = geo.JxW[q];
    const DimMatrix<dim> Pw = w * P;
    for (int a = 0; a < nl; ++a)
      for (int i = 0; i < dim; ++i) {
        double s = 0;
        for (int J = 0; J < dim; ++J) s += Pw(i, J) * dN[a * dim + J];
        ws.fe[a * dim + i] += s;
      }
    if (!tangent) continue;
    const TangentMatrix<dim> Aw = w * A;
    for (int a = 0; a < nl; ++a)
      for (int i = 0; i < dim; ++i)
        for (int kL = 0; kL < dim * dim; ++kL) {
          double s = 0;
          for (int J = 0; J < dim; ++J) s += dN[a * dim + J] * Aw(i * dim + J, kL);
          ws.G(a * dim + i, kL) = s;
        }
    // upper block triangle (b >= a, whole diagonal blocks; K is symmetric):
    // column (b, k) += sum_L G(:, k*dim+L) dN_bL, contiguous in the rows
    for (int b = 0; b < nl; ++b)
      for (int k = 0; k < dim; ++k) {
        double* col = ws.Ke.col(b * dim + k).data();
        const int rows = (b + 1) * dim;
        std::array<const double*, dim> g;
        std::array<double, dim> s;
        for (int L = 0; L < dim; ++L) {
          g[L] = ws.G.col(k * dim + L).data();
          s[L] = dN[b * dim + L];
        }
        for (int r = 0; r < rows; ++r) {
          double v = col[r];
          for (int L = 0; L < dim; ++L) v += g[L][r] * s[L];
          col[r] = v;
        }
      }
  }
  if (tangent)
    for (int c = 0; c < nd; ++c)
      for (int r = (c / dim + 1) * dim; r < nd; ++r) ws.Ke(r, c) = ws.Ke(c, r);
  if (mixed && tangent) {  // + mu_s (B - Bbar)^T W (B - Bbar), Bbar = Pi_e B: U'' is the functions'
    ws.d2U.setZero(nq);
    add_volumetric_tangent(ws.projection.matrix(), geo.JxW, ws.d2U, stabilisation, ws.B, ws.Bbar, ws.Ke);
  }
  return true;
}

constexpr int kElementsPerColourForThreads = 64;

// Everything one assembly needs besides u and its outputs.
struct AssemblyInput {
  const BodyQuadrature& quad;
  const DofMap& dofs;
  const std::vector<const HyperelasticLaw*>& laws;
  const std::vector<Formulation>& formulations;
  int pressure_degree;
  const std::vector<double>& stabilisations;
  const TotalLagrangianAssembler::Incompressibility* inc;
  const PressureSpace& space;
  const TotalLagrangianAssembler::PressureLayout& layout;
  const HyperelasticLaw& law(int patch) const { return *laws[laws.size() == 1 ? 0 : size_t(patch)]; }
  Formulation formulation(int patch) const { return formulations[formulations.size() == 1 ? 0 : size_t(patch)]; }
  double stabilisation(int patch) const { return stabilisations[stabilisations.size() == 1 ? 0 : size_t(patch)]; }
  bool mixed_function(int a) const { return is_mixed(formulation(space.patch_of_function(a))); }
  Augmentation augmentation(int a, int patch) const {
    if (!inc) return {};
    return {&inc->multipliers[a], inc->penalties[inc->penalties.size() == 1 ? 0 : size_t(patch)]};
  }
};

// Sums the elements' parts c (element e's at layout.function_entry[e], in
// the order of its functions) into one value per function, divided by m_A:
// theta_A - 1 (0 for the functions of displacement patches).  Elements in
// increasing order, so the sum does not depend on the threads.
Eigen::VectorXd gather_dilatations(const AssemblyInput& in, const std::vector<double>& c) {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(in.space.num_functions());
  for (int e = 0; e < in.space.num_elements(); ++e) {
    const int* a = in.space.functions_begin(e);
    const size_t first = size_t(in.layout.function_entry[size_t(e)]);
    for (int i = 0; i < in.space.num_element_functions(e); ++i) z[a[i]] += c[first + size_t(i)];
  }
  for (int a = 0; a < z.size(); ++a) z[a] = in.mixed_function(a) ? z[a] / in.layout.volume[a] : 0.0;
  return z;
}

// theta_A - 1 = (1/m_A) int N_A (J - 1) dX per pressure function (0 for a
// displacement patch's): a pass before the forces, as p_A needs the whole
// support.  False when u is inadmissible.
template <int dim>
bool function_dilatations_dim(const AssemblyInput& in, const Eigen::MatrixXd& u, Eigen::VectorXd& z) {
  const int n_el = in.quad.num_elements();
  std::vector<double> c(in.layout.function_entry.back(), 0.0);
  std::atomic<bool> failed{false};
#pragma omp parallel if (n_el >= 4 * kElementsPerColourForThreads) \
    num_threads(n_el >= 4 * kElementsPerColourForThreads ? free_cores() : 1)
  {
    Workspace<dim> ws;
#pragma omp for schedule(dynamic, 16)
    for (int e = 0; e < n_el; ++e) {
      if (failed.load(std::memory_order_relaxed)) continue;
      if (!is_mixed(in.formulation(in.quad.patch_of(e)))) continue;
      in.quad.evaluate(e, ws.geo, true);
      if (!element_deformation<dim>(u, ws)) {
        failed.store(true, std::memory_order_relaxed);
        continue;
      }
      in.space.values_at(e, ws.geo.xi, ws.N, ws.space_scratch);
      element_function_dilatations<dim>(ws, c.data() + in.layout.function_entry[size_t(e)]);
    }
  }
  if (failed.load()) return false;
  z = gather_dilatations(in, c);
  return true;
}

// Per-thread scratch of a pressure function's rank-one term: g_A on its
// support's free equations.
struct FunctionScratch {
  std::vector<std::pair<int, double>> entries;  // (free equation, int_e N_A B) of its elements
  std::vector<int> eq;                          // its free equations, increasing
  Eigen::VectorXd mB;                           // g_A / m_A on them
  Eigen::MatrixXd Kb;                           // m_A U'' mB mB^T = (U''/m_A) g_A g_A^T
  // sums the entries by equation into eq, mB (divided by m_A)
  void merge(double volume) {
    std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    eq.clear();
    std::vector<double> v;
    for (const auto& [e, x] : entries) {
      if (!eq.empty() && eq.back() == e) v.back() += x;
      else eq.push_back(e), v.push_back(x);
    }
    mB = Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())) / volume;
  }
};

template <int dim>
bool assemble_dim(const AssemblyInput& in, const std::vector<std::vector<int>>& colours,
                  const std::vector<std::vector<int>>& function_colours, const Eigen::SparseMatrix<double>& pattern,
                  const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K,
                  const Eigen::VectorXd* given, TotalLagrangianAssembler::LocalDilatation* local) {
  const bool tangent = K != nullptr;
  const PressureSpace& space = in.space;
  const TotalLagrangianAssembler::PressureLayout& layout = in.layout;
  const int nf = space.num_functions();
  const bool mixed_body = std::find_if(in.formulations.begin(), in.formulations.end(), is_mixed) !=
                          in.formulations.end();
  // theta_A - 1: the u-p Newton's, or (1/m_A) int N_A (J - 1) (a pass before the forces)
  Eigen::VectorXd z_projected;
  if (!given && mixed_body && !function_dilatations_dim<dim>(in, u, z_projected)) return false;
  const Eigen::VectorXd* z = given ? given : &z_projected;
  // U'(theta_A), U''(theta_A) per function
  Eigen::VectorXd dU = Eigen::VectorXd::Zero(nf), d2U = Eigen::VectorXd::Zero(nf);
  if (mixed_body)
    for (int a = 0; a < nf; ++a) {
      if (!in.mixed_function(a)) continue;
      const int patch = space.patch_of_function(a);
      if (!function_volumetric(in.law(patch), in.augmentation(a, patch), (*z)[a], dU[a], d2U[a])) return false;
    }
  // per element (mixed patches): its int_e N_A B (tangent) and int_e N_A (J - 1) (local), and its equations
  std::vector<double> g_store(mixed_body && tangent ? size_t(layout.g_entry.back()) : 0);
  std::vector<double> c_store(mixed_body && local ? size_t(layout.function_entry.back()) : 0);
  std::vector<int> eq_store(mixed_body && tangent ? size_t(layout.eq_entry.back()) : 0);
  f_int.setZero(in.dofs.num_free());
  if (tangent && !has_structure(*K, pattern)) *K = pattern;
  double* val = tangent ? K->valuePtr() : nullptr;
  const Eigen::Index nnz = pattern.nonZeros();
  double* f = f_int.data();
  std::atomic<bool> failed{false};
  // Threads meet at a barrier after every colour: worth it only when a colour
  // gives each thread real work.  Small meshes (tests, finite differences)
  // run on one thread, which also keeps them fast on a busy machine where a
  // descheduled thread would stall every barrier.
  const bool threaded = in.quad.num_elements() >= kElementsPerColourForThreads * int(colours.size());
  std::vector<Eigen::VectorXd> mean_B(local && tangent ? size_t(nf) : 0);
  std::vector<std::vector<int>> mean_B_eq(mean_B.size());

#pragma omp parallel if (threaded) num_threads(threaded ? free_cores() : 1)
  {
    if (tangent) {
#pragma omp for schedule(static)
      for (Eigen::Index k = 0; k < nnz; ++k) val[k] = 0.0;
    }
    Workspace<dim> ws;
    // Pass 1, the elements: no two elements of a colour share an equation
    for (const std::vector<int>& colour : colours) {
      const int n = int(colour.size());
#pragma omp for schedule(dynamic, 16)
      for (int j = 0; j < n; ++j) {
        if (failed.load(std::memory_order_relaxed)) continue;
        const int e = colour[size_t(j)];
        const int patch = in.laws.size() > 1 || in.formulations.size() > 1 ? in.quad.patch_of(e) : 0;
        const Formulation formulation = in.formulation(patch);
        const bool mixed = is_mixed(formulation);
        in.quad.evaluate(e, ws.geo, true);
        if (mixed) {
          space.values_at(e, ws.geo.xi, ws.N, ws.space_scratch);
          const int* a = space.functions_begin(e);
          ws.base.setZero(ws.geo.n_q);
          for (int i = 0; i < int(ws.N.cols()); ++i) ws.base += dU[a[i]] * ws.N.col(i);
        }
        if (!element_kernel<dim>(in.law(patch), formulation, in.pressure_degree, in.stabilisation(patch), u, tangent,
                                 ws)) {
          failed.store(true, std::memory_order_relaxed);
          continue;
        }
        in.dofs.element_equations(ws.geo.cps, ws.eq);
        scatter_element_vector(ws.eq, ws.fe, f);
        if (tangent) scatter_element_matrix(pattern, val, ws.eq, ws.Ke);
        if (!mixed) continue;
        if (local) element_function_dilatations<dim>(ws, c_store.data() + layout.function_entry[size_t(e)]);
        if (tangent) {  // G(i, :) = int_e N_{A_i} B dX, the element's part of g_{A_i}
          const Eigen::Map<const Eigen::VectorXd> w(ws.geo.JxW.data(), ws.geo.n_q);
          const Eigen::Index nd = ws.B.cols();
          Eigen::Map<Eigen::MatrixXd> G(g_store.data() + layout.g_entry[size_t(e)], nd, ws.N.cols());
          G.noalias() = ws.B.transpose() * (w.asDiagonal() * ws.N);
          std::copy(ws.eq.begin(), ws.eq.end(), eq_store.begin() + layout.eq_entry[size_t(e)]);
        }
      }
    }
    // Pass 2, the functions' rank-one terms (U''(theta_A)/m_A) g_A g_A^T:
    // no two functions of a colour share an equation
    FunctionScratch fs;
    if (tangent && mixed_body)
      for (const std::vector<int>& colour : function_colours) {
        const int n = int(colour.size());
#pragma omp for schedule(dynamic, 16)
        for (int j = 0; j < n; ++j) {
          if (failed.load(std::memory_order_relaxed)) continue;
          const int a = colour[size_t(j)];
          if (!in.mixed_function(a)) continue;
          fs.entries.clear();
          for (const int* e = space.support_begin(a); e != space.support_end(a); ++e) {
            const int i = int(std::find(space.functions_begin(*e), space.functions_end(*e), a) - space.functions_begin(*e));
            const int nd = layout.eq_entry[size_t(*e) + 1] - layout.eq_entry[size_t(*e)];
            const double* g = g_store.data() + layout.g_entry[size_t(*e)] + size_t(i) * size_t(nd);
            const int* eq = eq_store.data() + layout.eq_entry[size_t(*e)];
            for (int r = 0; r < nd; ++r)
              if (eq[r] >= 0) fs.entries.emplace_back(eq[r], g[r]);
          }
          const double m = layout.volume[a];
          fs.merge(m);
          fs.Kb.noalias() = (m * d2U[a]) * fs.mB * fs.mB.transpose();
          scatter_element_matrix(pattern, val, fs.eq, fs.Kb);
          if (local) {
            mean_B[size_t(a)] = fs.mB;
            mean_B_eq[size_t(a)] = fs.eq;
          }
        }
      }
  }
  if (failed.load()) return false;
  if (local) {
    local->projected = mixed_body ? gather_dilatations(in, c_store) : Eigen::VectorXd::Zero(nf);
    local->stiffness = Eigen::VectorXd::Zero(nf);
    local->volume = Eigen::VectorXd::Zero(nf);
    local->shear = Eigen::VectorXd::Zero(nf);
    for (int a = 0; a < nf; ++a) {
      if (!in.mixed_function(a)) continue;
      local->volume[a] = layout.volume[a];
      local->stiffness[a] = layout.volume[a] * d2U[a];
      local->shear[a] = in.stabilisation(space.patch_of_function(a));
    }
  }
  if (!mean_B.empty()) {
    std::vector<Eigen::Triplet<double>> t;
    for (int a = 0; a < nf; ++a)
      for (Eigen::Index k = 0; k < mean_B[size_t(a)].size(); ++k)
        t.emplace_back(a, mean_B_eq[size_t(a)][size_t(k)], mean_B[size_t(a)][k]);
    local->mean_B.resize(nf, in.dofs.num_free());
    local->mean_B.setFromTriplets(t.begin(), t.end());
  }
  return true;
}

}  // namespace

TotalLagrangianAssembler::TotalLagrangianAssembler(const Body& body, const DofMap& dofs,
                                                   const HyperelasticLaw& law, Formulation formulation, bool tangent)
    : TotalLagrangianAssembler(body, dofs, std::vector<const HyperelasticLaw*>{&law}, std::vector<Formulation>{formulation},
                               tangent) {}

TotalLagrangianAssembler::TotalLagrangianAssembler(const Body& body, const DofMap& dofs,
                                                   std::vector<const HyperelasticLaw*> patch_laws,
                                                   std::vector<Formulation> patch_formulations, bool tangent)
    : body_(body), quad_(body_, gauss_points_for(body_.degree())), dofs_(dofs), laws_(std::move(patch_laws)),
      formulations_(std::move(patch_formulations)), pressure_degree_(pressure_degree(body_.degree())) {
  const int dim = body_.space_dim();
  const size_t patches = size_t(body_.num_patches());
  if (laws_.empty() || (laws_.size() != 1 && laws_.size() != patches) || formulations_.empty() ||
      (formulations_.size() != 1 && formulations_.size() != patches))
    throw std::invalid_argument(fmt::format("total-Lagrangian assembly of {} patches got {} laws and {} formulations "
                                            "(one for all, or one per patch)", patches, laws_.size(),
                                            formulations_.size()));
  if ((dim != 2 && dim != 3) || body_.param_dim() != dim)
    throw std::invalid_argument(fmt::format(
        "total-Lagrangian assembly needs a 2D or 3D volume body, got {} parametric directions in R^{}",
        body_.param_dim(), dim));
  if (dofs.dim() != dim || dofs.num_dofs() != body_.num_control_points() * dim)
    throw std::invalid_argument(fmt::format("the dof map ({} dofs in {}D) does not belong to this body ({} control points in {}D)",
                                            dofs.num_dofs(), dofs.dim(), body_.num_control_points(), dim));
  // the mixed formulation's stabilisation modulus per law, once (volumetric_projection.hpp)
  stabilisations_.assign(std::max(laws_.size(), formulations_.size()), 0.0);
  for (size_t k = 0; k < stabilisations_.size(); ++k) {
    const HyperelasticLaw& law = *laws_[laws_.size() == 1 ? 0 : k];
    if (!is_mixed(formulations_[formulations_.size() == 1 ? 0 : k])) continue;
    if (!law.has_volumetric_split())
      throw std::invalid_argument(fmt::format("the mixed formulation needs a law with an isochoric/volumetric split; "
                                              "'{}' declares none", law.name()));
    stabilisations_[k] = stabilisation_modulus(law, dim);
  }
  tangent_ = tangent;
  set_pressure_space(mixed_pressure_space(quad_, formulations_));
  double min_det = std::numeric_limits<double>::infinity();
#pragma omp parallel num_threads(free_cores())
  {
    ElementValues<2, 2> g2;
    ElementValues<3, 3> g3;
#pragma omp for schedule(dynamic, 64) reduction(min : min_det)
    for (int e = 0; e < quad_.num_elements(); ++e) {
      if (dim == 2) {
        quad_.evaluate(e, g2, false);
        min_det = std::min(min_det, g2.min_det_J);
      } else {
        quad_.evaluate(e, g3, false);
        min_det = std::min(min_det, g3.min_det_J);
      }
    }
  }
  min_det_J_ = min_det;
  if (!(min_det_J_ > 0))
    throw std::runtime_error(fmt::format("the geometry map folds: det J = {:.3g} at a Gauss point", min_det_J_));
}

bool TotalLagrangianAssembler::assemble(const Eigen::MatrixXd& u, Eigen::VectorXd& f_int,
                                        Eigen::SparseMatrix<double>* K) const {
  return assemble(u, f_int, K, nullptr, nullptr);
}

bool TotalLagrangianAssembler::assemble(const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K,
                                        const Eigen::VectorXd* dilatation, LocalDilatation* local) const {
  const int dim = dofs_.dim();
  if (u.rows() * dim != dofs_.num_dofs() || u.cols() != dim)
    throw std::invalid_argument(fmt::format("displacement is {} x {}, the body needs {} x {}", u.rows(), u.cols(),
                                            dofs_.num_dofs() / dim, dim));
  if (K && pattern_.rows() != dofs_.num_free())
    throw std::logic_error("TotalLagrangianAssembler: a tangent asked of an assembler built without one");
  if (dilatation && dilatation->size() != num_pressures())
    throw std::invalid_argument(fmt::format("{} dilatations for {} pressure functions", dilatation->size(),
                                            num_pressures()));
  const AssemblyInput in{quad_, dofs_, laws_, formulations_, pressure_degree_, stabilisations_,
                         incompressibility_ ? &*incompressibility_ : nullptr, space_, layout_};
  return dim == 2 ? assemble_dim<2>(in, colours_, function_colours_, pattern_, u, f_int, K, dilatation, local)
                  : assemble_dim<3>(in, colours_, function_colours_, pattern_, u, f_int, K, dilatation, local);
}

void TotalLagrangianAssembler::set_element_range(ElementRange elements) {
  if (has_mixed())
    throw std::invalid_argument(
        "set_element_range: a mixed patch's pressure terms are not sums over elements; assemble it whole");
  elements_ = elements;
  colours_ = colour_elements(quad_, dofs_);
  keep_range_in_colours();
}

void TotalLagrangianAssembler::keep_range_in_colours() {
  const int begin = elements_.begin, end = elements_.end < 0 ? quad_.num_elements() : elements_.end;
  if (begin <= 0 && end >= quad_.num_elements()) return;
  for (std::vector<int>& colour : colours_) std::erase_if(colour, [&](int e) { return e < begin || e >= end; });
}

void TotalLagrangianAssembler::set_pressure_space(PressureSpace space) {
  if (incompressibility_)
    throw std::invalid_argument(
        "set_pressure_space: the incompressible limit's multipliers are per pressure function; set the space first");
  if (space.num_elements() != quad_.num_elements())
    throw std::invalid_argument(fmt::format("set_pressure_space: a space on {} elements for a body of {}",
                                            space.num_elements(), quad_.num_elements()));
  space_ = std::move(space);
  // the pattern (the element pattern for constants per element), the colourings
  if (tangent_) pattern_ = coupling_pattern(quad_, dofs_, space_);
  colours_ = colour_elements(quad_, dofs_);
  keep_range_in_colours();
  // a body without a mixed patch pays for no function colours nor volumes
  const bool mixed_body = has_mixed();
  function_colours_ = mixed_body ? colour_functions(quad_, dofs_, space_) : std::vector<std::vector<int>>{};
  // the assembly's per-element storage, and m_A = int N_A dX
  const int n_el = quad_.num_elements(), dim = dofs_.dim();
  layout_ = PressureLayout{};
  layout_.function_entry.assign(1, 0);
  layout_.g_entry.assign(1, 0);
  layout_.eq_entry.assign(1, 0);
  layout_.volume = Eigen::VectorXd::Zero(space_.num_functions());
  ElementValues<2, 2> g2;
  ElementValues<3, 3> g3;
  PressureSpace::Scratch scratch;
  Eigen::MatrixXd N;
  for (int e = 0; e < n_el; ++e) {
    const int k = quad_.patch_of(e), nf = space_.num_element_functions(e);
    const bool mixed = is_mixed(formulations_[formulations_.size() == 1 ? 0 : size_t(k)]);
    const int nd = mixed ? quad_.patch_quadrature(k).num_local() * dim : 0;
    layout_.function_entry.push_back(layout_.function_entry.back() + nf);
    layout_.g_entry.push_back(layout_.g_entry.back() + nf * nd);
    layout_.eq_entry.push_back(layout_.eq_entry.back() + nd);
    if (!mixed) continue;  // m_A only where a pressure acts
    const auto add_volume = [&](const auto& geo) {  // m_A += int_e N_A dX
      space_.values_at(e, geo.xi, N, scratch);
      const int* a = space_.functions_begin(e);
      for (int i = 0; i < nf; ++i)
        for (int q = 0; q < geo.n_q; ++q) layout_.volume[a[i]] += N(q, i) * geo.JxW[size_t(q)];
    };
    if (dim == 2) {
      quad_.evaluate(e, g2, false);
      add_volume(g2);
    } else {
      quad_.evaluate(e, g3, false);
      add_volume(g3);
    }
  }
}

bool TotalLagrangianAssembler::has_mixed() const {
  return std::any_of(formulations_.begin(), formulations_.end(), is_mixed);
}

void TotalLagrangianAssembler::make_incompressible(double tolerance) {
  if (!(tolerance > 0)) throw std::invalid_argument("the incompressibility tolerance must be positive");
  if (std::none_of(formulations_.begin(), formulations_.end(), is_mixed))
    throw std::invalid_argument("the incompressible limit needs the mixed formulation");
  Incompressibility inc;
  inc.tolerance = tolerance;
  for (const HyperelasticLaw* law : laws_) {  // kappa = U''(1), the law's bulk modulus
    VolumetricValues v;
    inc.penalties.push_back(law->volumetric(1.0, v) ? v.d2U : 0.0);
  }
  inc.multipliers = Eigen::VectorXd::Zero(num_pressures());
  inc.accepted = inc.multipliers;
  incompressibility_ = std::move(inc);
}

bool TotalLagrangianAssembler::volume_changes(const Eigen::MatrixXd& u, Eigen::VectorXd& dilatation) const {
  const int dim = dofs_.dim();
  if (u.rows() * dim != dofs_.num_dofs() || u.cols() != dim)
    throw std::invalid_argument(fmt::format("displacement is {} x {}, the body needs {} x {}", u.rows(), u.cols(),
                                            dofs_.num_dofs() / dim, dim));
  const AssemblyInput in{quad_, dofs_, laws_, formulations_, pressure_degree_, stabilisations_, nullptr, space_, layout_};
  const bool ok =
      dim == 2 ? function_dilatations_dim<2>(in, u, dilatation) : function_dilatations_dim<3>(in, u, dilatation);
  if (!ok) dilatation = Eigen::VectorXd::Zero(num_pressures());
  return ok;
}

bool TotalLagrangianAssembler::element_pressures(const Eigen::MatrixXd& u, Eigen::VectorXd& pressure) const {
  if (!incompressibility_ || !volume_changes(u, pressure)) return false;
  const Incompressibility& inc = *incompressibility_;
  for (int a = 0; a < num_pressures(); ++a)
    pressure[a] = inc.multipliers[a] +
                  inc.penalties[inc.penalties.size() == 1 ? 0 : size_t(space_.patch_of_function(a))] * pressure[a];
  return true;
}

bool TotalLagrangianAssembler::augment(const Eigen::MatrixXd& u) {
  if (!incompressibility_) return false;
  Incompressibility& inc = *incompressibility_;
  Eigen::VectorXd dil;
  if (!volume_changes(u, dil)) return false;
  inc.last_volume_change = dil.cwiseAbs().maxCoeff();
  if (inc.last_volume_change <= inc.tolerance) return false;
  for (int b = 0; b < num_pressures(); ++b) {
    const int patch = inc.penalties.size() == 1 ? 0 : space_.patch_of_function(b);
    inc.multipliers[b] += inc.penalties[size_t(patch)] * dil[b];
  }
  ++inc.augmentations;
  return true;
}

void TotalLagrangianAssembler::copy_multipliers(const TotalLagrangianAssembler& from) {
  if (!from.incompressibility_) return;
  if (!incompressibility_) make_incompressible(from.incompressibility_->tolerance);
  if (from.incompressibility_->multipliers.size() != incompressibility_->multipliers.size())
    throw std::invalid_argument("copy_multipliers: the assemblers do not have the same pressure space");
  incompressibility_->multipliers = from.incompressibility_->multipliers;
  incompressibility_->accepted = from.incompressibility_->accepted;
}

void TotalLagrangianAssembler::restore_multipliers(const Eigen::VectorXd& accepted) {
  if (!incompressibility_ || accepted.size() != incompressibility_->multipliers.size())
    throw std::invalid_argument("restore_multipliers: not the pressure multipliers of this incompressible body");
  incompressibility_->multipliers = accepted;
  incompressibility_->accepted = accepted;
}

void TotalLagrangianAssembler::keep_multipliers(bool accepted) {
  if (!incompressibility_) return;
  if (accepted) incompressibility_->accepted = incompressibility_->multipliers;
  else incompressibility_->multipliers = incompressibility_->accepted;
}

}  // namespace igac
