// SPDX-License-Identifier: BSD-3-Clause
#include "engine/total_lagrangian.hpp"

#include "engine/quadrature.hpp"
#include "engine/sparsity.hpp"

#include <algorithm>
#include <array>
#include <atomic>
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
  // mixed formulation (volumetric_projection.hpp): per point J, theta, p, U''
  ElementProjection projection;
  Eigen::VectorXd J, theta, dU, pressure, d2U;
  Eigen::MatrixXd B, Bbar;                            // n_q x nd: dJ/du per point, projected
};

// The augmented Lagrangian of the incompressible limit (make_incompressible):
// U(theta) = lambda_b (theta - 1) + kappa/2 (theta - 1)^2 in place of the
// law's, lambda_b the block's pressure multiplier.
struct Augmentation {
  const double* lambda = nullptr;  // null: the law's U
  double kappa = 0;
};

// U'(theta_b) and U''(theta_b) of a block, z = theta_b - 1; false when
// theta_b leaves U's domain.
bool block_volumetric(const HyperelasticLaw& law, Augmentation aug, double z, double& dU, double& d2U) {
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
  for (int q = 0; q < nq; ++q) {
    const double* dN = geo.gradients(q);  // dN[a*dim+J] = dN_a/dX_J
    DimMatrix<dim>& F = ws.F[q];
    F.setIdentity();
    for (int a = 0; a < nl; ++a)
      for (int J = 0; J < dim; ++J)
        for (int i = 0; i < dim; ++i) F(i, J) += ws.ue(a, i) * dN[a * dim + J];
    if (!F.allFinite() || !(F.determinant() > 0)) return false;
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
  for (int q = 0; q < nq; ++q) ws.J[q] = ws.F[q].determinant() - 1;
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

// Element internal force and (when `tangent`) the tangent at the Gauss
// points of ws.geo; false when F is inadmissible at a point.  Mixed
// formulation (volumetric_projection.hpp), before the point loop: the point
// pressure p_q = U'(theta_b) + mu_s (J_q - Pi_e J), dU = U'(theta_b) of the
// element's block; the element's tangent carries mu_s (B^T W B -
// V_e mB_e^T mB_e) (ws.Bbar: every row mB_e), the block's rank-one term
// V_b U''(theta_b) mB_b^T mB_b is the caller's.  *dilatation, *volume:
// int_e (Pi_e J - 1) dX and V_e.
template <int dim>
bool element_kernel(const HyperelasticLaw& law, Formulation formulation, int pressure_degree, double stabilisation,
                    double dU, const Eigen::MatrixXd& u, bool tangent, Workspace<dim>& ws, double* dilatation,
                    double* volume) {
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
    *dilatation = element_dilatation<dim>(pressure_degree, ws, volume);
    // the stabilisation's pressure mu_s (J - Pi_e J): the element's volume
    // modes that the block's projection does not see (volumetric_projection.hpp)
    ws.pressure = stabilisation * (ws.J - ws.theta);
    ws.pressure.array() += dU;
  }
  if (mixed && tangent) ws.B.resize(nq, nd);
  DimMatrix<dim> P;
  TangentMatrix<dim> A;
  for (int q = 0; q < nq; ++q) {
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
  if (mixed && tangent) {  // + mu_s (B - Bbar)^T W (B - Bbar), Bbar = Pi_e B: U'' is the block's
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
  const ElementBlocks& blocks;
  int patch_of_block(int b) const { return quad.patch_of(blocks.elements[size_t(blocks.start[size_t(b)])]); }
  const HyperelasticLaw& law(int patch) const { return *laws[laws.size() == 1 ? 0 : size_t(patch)]; }
  Formulation formulation(int patch) const { return formulations[formulations.size() == 1 ? 0 : size_t(patch)]; }
  double stabilisation(int patch) const { return stabilisations[stabilisations.size() == 1 ? 0 : size_t(patch)]; }
  Augmentation augmentation(int b, int patch) const {
    if (!inc) return {};
    return {&inc->multipliers[b], inc->penalties[inc->penalties.size() == 1 ? 0 : size_t(patch)]};
  }
};

// Pi_b J - 1 per block (0 for a displacement element's block): the block's
// elements in order, each int_e (Pi_e J - 1) dX as the kernel sums it, so
// the assembly's LocalDilatation::projected at the same u is the same
// double.  False when u is inadmissible.
template <int dim>
bool block_dilatations_dim(const AssemblyInput& in, const Eigen::MatrixXd& u, Eigen::VectorXd& z) {
  const int nb = in.blocks.num_blocks();
  z = Eigen::VectorXd::Zero(nb);
  std::atomic<bool> failed{false};
#pragma omp parallel if (in.quad.num_elements() >= 4 * kElementsPerColourForThreads)
  {
    Workspace<dim> ws;
#pragma omp for schedule(dynamic, 16)
    for (int b = 0; b < nb; ++b) {
      if (failed.load(std::memory_order_relaxed)) continue;
      if (!is_mixed(in.formulation(in.patch_of_block(b)))) continue;
      double s = 0, v = 0;
      for (int k = in.blocks.start[size_t(b)]; k < in.blocks.start[size_t(b) + 1]; ++k) {
        in.quad.evaluate(in.blocks.elements[size_t(k)], ws.geo, true);
        if (!element_deformation<dim>(u, ws)) {
          failed.store(true, std::memory_order_relaxed);
          break;
        }
        double ve = 0;
        s += element_dilatation<dim>(in.pressure_degree, ws, &ve);
        v += ve;
      }
      z[b] = s / v;
    }
  }
  return !failed.load();
}

// Per-thread scratch of a block: its mean of B over the free equations.
struct BlockScratch {
  std::vector<std::pair<int, double>> entries;  // (free equation, V_e mB_e) of its elements
  std::vector<int> eq;                          // the block's free equations, increasing
  Eigen::VectorXd mB;                           // mB_b on them
  Eigen::MatrixXd Kb;                           // V_b U'' mB_b mB_b^T
  // sums the entries by equation into eq, mB (divided by V_b)
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
                  const Eigen::SparseMatrix<double>& pattern, const Eigen::MatrixXd& u, Eigen::VectorXd& f_int,
                  Eigen::SparseMatrix<double>* K, const Eigen::VectorXd* given,
                  TotalLagrangianAssembler::LocalDilatation* local) {
  const bool tangent = K != nullptr;
  const ElementBlocks& blocks = in.blocks;
  const int nb = blocks.num_blocks();
  // theta_b - 1: the u-p Newton's, or Pi_b J - 1 (a pass before the forces: p_b needs the whole block)
  Eigen::VectorXd z_projected;
  const bool mixed_body = std::find_if(in.formulations.begin(), in.formulations.end(), is_mixed) !=
                          in.formulations.end();
  if (!given && mixed_body && !block_dilatations_dim<dim>(in, u, z_projected)) return false;
  const Eigen::VectorXd* z = given ? given : &z_projected;
  // the block rows of the u-p Newton: each block's mean B, kept per block, then one matrix
  std::vector<Eigen::VectorXd> mean_B(local && tangent ? size_t(nb) : 0);
  std::vector<std::vector<int>> mean_B_eq(mean_B.size());
  if (local) {
    local->projected = Eigen::VectorXd::Zero(nb);
    local->stiffness = Eigen::VectorXd::Zero(nb);
    local->volume = Eigen::VectorXd::Zero(nb);
    local->shear = Eigen::VectorXd::Zero(nb);
  }
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
  int n_el = 0;
  for (const auto& c : colours)
    for (int b : c) n_el += blocks.start[size_t(b) + 1] - blocks.start[size_t(b)];
  const bool threaded = n_el >= kElementsPerColourForThreads * int(colours.size());

#pragma omp parallel if (threaded)
  {
    if (tangent) {
#pragma omp for schedule(static)
      for (Eigen::Index k = 0; k < nnz; ++k) val[k] = 0.0;
    }
    Workspace<dim> ws;
    BlockScratch bs;
    for (const std::vector<int>& colour : colours) {
      const int n = int(colour.size());
      // no two blocks of a colour share an equation: plain adds, no races
#pragma omp for schedule(dynamic, 16)
      for (int j = 0; j < n; ++j) {
        if (failed.load(std::memory_order_relaxed)) continue;
        const int b = colour[j];
        const int patch = in.laws.size() > 1 || in.formulations.size() > 1 ? in.patch_of_block(b) : 0;
        const HyperelasticLaw& law = in.law(patch);
        const Formulation formulation = in.formulation(patch);
        const bool mixed = is_mixed(formulation);
        const double stabilisation = in.stabilisation(patch);
        double dU = 0, d2U = 0;  // U'(theta_b), U''(theta_b)
        if (mixed && !block_volumetric(law, in.augmentation(b, patch), (*z)[b], dU, d2U)) {
          failed.store(true, std::memory_order_relaxed);
          continue;
        }
        double s = 0, volume = 0;  // int_b (Pi_e J - 1), V_b
        bs.entries.clear();
        for (int k = blocks.start[size_t(b)]; k < blocks.start[size_t(b) + 1]; ++k) {
          in.quad.evaluate(blocks.elements[size_t(k)], ws.geo, true);
          double se = 0, ve = 0;
          if (!element_kernel<dim>(law, formulation, in.pressure_degree, stabilisation, dU, u, tangent, ws, &se,
                                   &ve)) {
            failed.store(true, std::memory_order_relaxed);
            break;
          }
          in.dofs.element_equations(ws.geo.cps, ws.eq);
          scatter_element_vector(ws.eq, ws.fe, f);
          if (tangent) scatter_element_matrix(pattern, val, ws.eq, ws.Ke);
          if (!mixed) continue;
          s += se, volume += ve;
          if (tangent)  // every row of Bbar = Pi_e B is the element's mean mB_e (constants per element)
            for (size_t r = 0; r < ws.eq.size(); ++r)
              if (ws.eq[r] >= 0) bs.entries.emplace_back(ws.eq[r], ve * ws.Bbar(0, Eigen::Index(r)));
        }
        if (!mixed || failed.load(std::memory_order_relaxed)) continue;
        if (tangent) {  // the block's + V_b U''(theta_b) mB_b^T mB_b
          bs.merge(volume);
          bs.Kb.noalias() = (volume * d2U) * bs.mB * bs.mB.transpose();
          scatter_element_matrix(pattern, val, bs.eq, bs.Kb);
        }
        if (local) {
          local->projected[b] = s / volume;
          local->volume[b] = volume;
          local->stiffness[b] = volume * d2U;
          local->shear[b] = stabilisation;
          if (tangent) {
            mean_B[size_t(b)] = bs.mB;
            mean_B_eq[size_t(b)] = bs.eq;
          }
        }
      }
    }
  }
  if (failed.load()) return false;
  if (!mean_B.empty()) {
    std::vector<Eigen::Triplet<double>> t;
    for (int b = 0; b < nb; ++b)
      for (Eigen::Index k = 0; k < mean_B[size_t(b)].size(); ++k)
        t.emplace_back(b, mean_B_eq[size_t(b)][size_t(k)], mean_B[size_t(b)][k]);
    local->mean_B.resize(nb, in.dofs.num_free());
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
  set_blocks(mixed_pressure_blocks(quad_, formulations_));
  double min_det = std::numeric_limits<double>::infinity();
#pragma omp parallel
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
  if (dilatation && dilatation->size() != num_blocks())
    throw std::invalid_argument(fmt::format("{} block dilatations for {} pressure blocks", dilatation->size(),
                                            num_blocks()));
  const AssemblyInput in{quad_, dofs_, laws_, formulations_, pressure_degree_, stabilisations_,
                         incompressibility_ ? &*incompressibility_ : nullptr, blocks_};
  return dim == 2 ? assemble_dim<2>(in, colours_, pattern_, u, f_int, K, dilatation, local)
                  : assemble_dim<3>(in, colours_, pattern_, u, f_int, K, dilatation, local);
}

void TotalLagrangianAssembler::set_blocks(ElementBlocks blocks) {
  if (incompressibility_)
    throw std::invalid_argument("set_blocks: the incompressible limit's multipliers are per block; set the blocks first");
  if (blocks.num_elements() != quad_.num_elements() || blocks.start.back() != quad_.num_elements())
    throw std::invalid_argument(fmt::format("set_blocks: blocks of {} elements for a body of {}", blocks.num_elements(),
                                            quad_.num_elements()));
  for (int b = 0; b < blocks.num_blocks(); ++b)
    for (int k = blocks.start[size_t(b)]; k < blocks.start[size_t(b) + 1]; ++k)
      if (quad_.patch_of(blocks.elements[size_t(k)]) != quad_.patch_of(blocks.elements[size_t(blocks.start[size_t(b)])]))
        throw std::invalid_argument(fmt::format("set_blocks: block {} spans two patches", b));
  blocks_ = std::move(blocks);
  if (blocks_.per_element()) {  // the element pattern and colouring, as the displacement formulation's
    if (tangent_) pattern_ = coupling_pattern(quad_, dofs_);
    colours_ = colour_elements(quad_, dofs_);
    for (auto& colour : colours_)
      for (int& e : colour) e = blocks_.block_of[size_t(e)];
  } else {
    if (tangent_) pattern_ = coupling_pattern(quad_, dofs_, blocks_);
    colours_ = colour_blocks(quad_, dofs_, blocks_);
  }
}

bool TotalLagrangianAssembler::has_mixed() const {
  return std::any_of(formulations_.begin(), formulations_.end(), is_mixed);
}

int TotalLagrangianAssembler::patch_of_block(int b) const {
  return quad_.patch_of(blocks_.elements[size_t(blocks_.start[size_t(b)])]);
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
  inc.multipliers = Eigen::VectorXd::Zero(num_blocks());
  inc.accepted = inc.multipliers;
  incompressibility_ = std::move(inc);
}

bool TotalLagrangianAssembler::volume_changes(const Eigen::MatrixXd& u, Eigen::VectorXd& dilatation) const {
  const int dim = dofs_.dim();
  if (u.rows() * dim != dofs_.num_dofs() || u.cols() != dim)
    throw std::invalid_argument(fmt::format("displacement is {} x {}, the body needs {} x {}", u.rows(), u.cols(),
                                            dofs_.num_dofs() / dim, dim));
  const AssemblyInput in{quad_, dofs_, laws_, formulations_, pressure_degree_, stabilisations_, nullptr, blocks_};
  const bool ok = dim == 2 ? block_dilatations_dim<2>(in, u, dilatation) : block_dilatations_dim<3>(in, u, dilatation);
  if (!ok) dilatation = Eigen::VectorXd::Zero(num_blocks());
  return ok;
}

bool TotalLagrangianAssembler::element_pressures(const Eigen::MatrixXd& u, Eigen::VectorXd& pressure) const {
  if (!incompressibility_ || !volume_changes(u, pressure)) return false;
  const Incompressibility& inc = *incompressibility_;
  for (int b = 0; b < num_blocks(); ++b)
    pressure[b] = inc.multipliers[b] + inc.penalties[inc.penalties.size() == 1 ? 0 : size_t(patch_of_block(b))] * pressure[b];
  return true;
}

bool TotalLagrangianAssembler::augment(const Eigen::MatrixXd& u) {
  if (!incompressibility_) return false;
  Incompressibility& inc = *incompressibility_;
  Eigen::VectorXd dil;
  if (!volume_changes(u, dil)) return false;
  inc.last_volume_change = dil.cwiseAbs().maxCoeff();
  if (inc.last_volume_change <= inc.tolerance) return false;
  for (int b = 0; b < num_blocks(); ++b) {
    const int patch = inc.penalties.size() == 1 ? 0 : patch_of_block(b);
    inc.multipliers[b] += inc.penalties[size_t(patch)] * dil[b];
  }
  ++inc.augmentations;
  return true;
}

void TotalLagrangianAssembler::copy_multipliers(const TotalLagrangianAssembler& from) {
  if (!from.incompressibility_) return;
  if (!incompressibility_) make_incompressible(from.incompressibility_->tolerance);
  if (from.incompressibility_->multipliers.size() != incompressibility_->multipliers.size())
    throw std::invalid_argument("copy_multipliers: the assemblers do not have the same pressure blocks");
  incompressibility_->multipliers = from.incompressibility_->multipliers;
  incompressibility_->accepted = from.incompressibility_->accepted;
}

void TotalLagrangianAssembler::restore_multipliers(const Eigen::VectorXd& accepted) {
  if (!incompressibility_ || accepted.size() != incompressibility_->multipliers.size())
    throw std::invalid_argument("restore_multipliers: not the block multipliers of this incompressible body");
  incompressibility_->multipliers = accepted;
  incompressibility_->accepted = accepted;
}

void TotalLagrangianAssembler::keep_multipliers(bool accepted) {
  if (!incompressibility_) return;
  if (accepted) incompressibility_->accepted = incompressibility_->multipliers;
  else incompressibility_->multipliers = incompressibility_->accepted;
}

}  // namespace igac
