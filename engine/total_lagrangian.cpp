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

// Element internal force and (when `tangent`) the tangent at the Gauss
// points of ws.geo; false when F is inadmissible at a point.
// Mixed formulation, before the point loop: theta = Pi_e J and
// p = Pi_e U'(theta) + mu_s (J - theta) at the points
// (volumetric_projection.hpp); false when the projected dilatation leaves
// U's domain.
// The augmented Lagrangian of the incompressible limit (make_incompressible):
// U(theta) = lambda_e (theta - 1) + kappa/2 (theta - 1)^2 in place of the
// law's, lambda_e the element's pressure multiplier.
struct Augmentation {
  const double* lambda = nullptr;  // null: the law's U
  double kappa = 0;
};

// `given` (the u-p Newton, TotalLagrangianAssembler::LocalDilatation): the
// element's theta_e - 1, at which U', U'' are taken in place of Pi_e J's.
template <int dim>
bool condense_volumetric(const HyperelasticLaw& law, int pressure_degree, double stabilisation, Augmentation aug,
                         const double* given, Workspace<dim>& ws) {
  const ElementValues<dim, dim>& geo = ws.geo;
  const int nq = geo.n_q;
  ws.projection.build(geo.xi, geo.JxW, pressure_degree);
  const Eigen::MatrixXd& Pi = ws.projection.matrix();
  // theta = 1 + Pi_e (J - 1): at rest theta is 1 exactly (Pi_e 1 is 1 only
  // to round-off), so p = 0 and f_int = 0 exactly, as in the displacement
  // formulation (a round-off residual at rest stalls Newton at load factor 0)
  ws.J.resize(nq);
  for (int q = 0; q < nq; ++q) ws.J[q] = ws.F[q].determinant() - 1;
  ws.theta.noalias() = Pi * ws.J;
  ws.theta.array() += 1;
  ws.J.array() += 1;
  ws.dU.resize(nq);
  ws.d2U.resize(nq);
  VolumetricValues v;
  for (int q = 0; q < nq; ++q) {
    const double theta = given ? 1 + *given : ws.theta[q];
    if (aug.lambda) {
      if (!(theta > 0)) return false;
      ws.dU[q] = *aug.lambda + aug.kappa * (given ? *given : ws.theta[q] - 1);
      ws.d2U[q] = aug.kappa;
      continue;
    }
    if (!law.volumetric(theta, v)) return false;
    ws.dU[q] = v.dU;
    ws.d2U[q] = v.d2U;
  }
  if (given) ws.pressure = ws.dU;  // the constant U'(theta_e)
  else ws.pressure.noalias() = Pi * ws.dU;
  // the stabilisation's pressure mu_s (J - theta): the element's volume
  // modes that the projection does not see (volumetric_projection.hpp)
  ws.pressure += stabilisation * (ws.J - ws.theta);
  return true;
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

template <int dim>
bool element_kernel(const HyperelasticLaw& law, Formulation formulation, int pressure_degree, double stabilisation,
                    Augmentation aug, const double* given, const Eigen::MatrixXd& u, bool tangent, Workspace<dim>& ws) {
  const ElementValues<dim, dim>& geo = ws.geo;
  const int nl = geo.n_loc, nq = geo.n_q, nd = nl * dim;
  const bool mixed = formulation == Formulation::mixed;
  ws.ue.resize(nl, dim);
  for (int a = 0; a < nl; ++a) ws.ue.row(a) = u.row(geo.cps[a]);
  ws.fe.setZero(nd);
  if (tangent) {
    ws.Ke.setZero(nd, nd);
    ws.G.resize(nd, dim * dim);
  }
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
  if (mixed && !condense_volumetric<dim>(law, pressure_degree, stabilisation, aug, given, ws)) return false;
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
  if (mixed && tangent)  // + Bbar^T W U''(theta) Bbar + mu_s (B - Bbar)^T W (B - Bbar)
    add_volumetric_tangent(ws.projection.matrix(), geo.JxW, ws.d2U, stabilisation, ws.B, ws.Bbar, ws.Ke);
  return true;
}

constexpr int kElementsPerColourForThreads = 64;

template <int dim>
bool assemble_dim(const BodyQuadrature& quad, const DofMap& dofs, const std::vector<const HyperelasticLaw*>& laws,
                  const std::vector<Formulation>& formulations, int pressure_degree,
                  const std::vector<double>& stabilisations, const TotalLagrangianAssembler::Incompressibility* inc,
                  const std::vector<std::vector<int>>& colours, const Eigen::SparseMatrix<double>& pattern,
                  const Eigen::MatrixXd& u, Eigen::VectorXd& f_int, Eigen::SparseMatrix<double>* K,
                  const Eigen::VectorXd* given, TotalLagrangianAssembler::LocalDilatation* local) {
  const bool tangent = K != nullptr;
  // the element rows of the u-p Newton: each element's mean B, kept per element, then one matrix
  const int n_elements = quad.num_elements();
  std::vector<Eigen::VectorXd> mean_B(local && tangent ? size_t(n_elements) : 0);
  std::vector<std::vector<int>> mean_B_eq(mean_B.size());
  if (local) {
    local->projected = Eigen::VectorXd::Zero(n_elements);
    local->stiffness = Eigen::VectorXd::Zero(n_elements);
    local->volume = Eigen::VectorXd::Zero(n_elements);
    local->shear = Eigen::VectorXd::Zero(n_elements);
  }
  f_int.setZero(dofs.num_free());
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
  for (const auto& c : colours) n_el += int(c.size());
  const bool threaded = n_el >= kElementsPerColourForThreads * int(colours.size());

#pragma omp parallel if (threaded)
  {
    if (tangent) {
#pragma omp for schedule(static)
      for (Eigen::Index k = 0; k < nnz; ++k) val[k] = 0.0;
    }
    Workspace<dim> ws;
    for (const std::vector<int>& colour : colours) {
      const int n = int(colour.size());
      // no two elements of a colour share an equation: plain adds, no races
#pragma omp for schedule(dynamic, 16)
      for (int j = 0; j < n; ++j) {
        if (failed.load(std::memory_order_relaxed)) continue;
        quad.evaluate(colour[j], ws.geo, true);
        const int patch = laws.size() > 1 || formulations.size() > 1 ? quad.patch_of(colour[j]) : 0;
        const HyperelasticLaw& law = *laws[laws.size() == 1 ? 0 : patch];
        const Formulation formulation = formulations[formulations.size() == 1 ? 0 : patch];
        const double stabilisation = stabilisations[stabilisations.size() == 1 ? 0 : patch];
        Augmentation aug;
        if (inc && formulation == Formulation::mixed)
          aug = {&inc->multipliers[colour[j]], inc->penalties[inc->penalties.size() == 1 ? 0 : patch]};
        const double* theta_e = given && formulation == Formulation::mixed ? &(*given)[colour[j]] : nullptr;
        if (!element_kernel<dim>(law, formulation, pressure_degree, stabilisation, aug, theta_e, u, tangent, ws)) {
          failed.store(true, std::memory_order_relaxed);
          continue;
        }
        dofs.element_equations(ws.geo.cps, ws.eq);
        if (local && formulation == Formulation::mixed) {  // the element's mean of theta - 1 (= Pi_e (J - 1)), V_e, ...
          const int e = colour[j];
          double s = 0, w = 0, d2U = 0;
          for (int q = 0; q < ws.geo.n_q; ++q) {
            s += ws.geo.JxW[q] * (ws.theta[q] - 1), w += ws.geo.JxW[q];
            d2U += ws.geo.JxW[q] * ws.d2U[q];
          }
          local->projected[e] = s / w;
          local->volume[e] = w;
          local->stiffness[e] = d2U;
          local->shear[e] = stabilisation;
          if (tangent) {  // every row of Bbar = Pi_e B is the mean (constants per element)
            mean_B[e] = ws.Bbar.row(0).transpose();
            mean_B_eq[e] = ws.eq;
          }
        }
        scatter_element_vector(ws.eq, ws.fe, f);
        if (!tangent) continue;
        scatter_element_matrix(pattern, val, ws.eq, ws.Ke);
      }
    }
  }
  if (failed.load()) return false;
  if (!mean_B.empty()) {
    std::vector<Eigen::Triplet<double>> t;
    for (int e = 0; e < n_elements; ++e)
      for (Eigen::Index k = 0; k < mean_B[size_t(e)].size(); ++k)
        if (mean_B_eq[size_t(e)][size_t(k)] >= 0) t.emplace_back(e, mean_B_eq[size_t(e)][size_t(k)], mean_B[size_t(e)][k]);
    local->mean_B.resize(n_elements, dofs.num_free());
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
    if (formulations_[formulations_.size() == 1 ? 0 : k] != Formulation::mixed) continue;
    if (!law.has_volumetric_split())
      throw std::invalid_argument(fmt::format("the mixed formulation needs a law with an isochoric/volumetric split; "
                                              "'{}' declares none", law.name()));
    stabilisations_[k] = stabilisation_modulus(law, dim);
  }
  if (tangent) pattern_ = coupling_pattern(quad_, dofs_);
  colours_ = colour_elements(quad_, dofs_);
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
  if (dilatation && dilatation->size() != quad_.num_elements())
    throw std::invalid_argument(fmt::format("{} element dilatations for {} elements", dilatation->size(),
                                            quad_.num_elements()));
  const Incompressibility* inc = incompressibility_ ? &*incompressibility_ : nullptr;
  return dim == 2 ? assemble_dim<2>(quad_, dofs_, laws_, formulations_, pressure_degree_, stabilisations_, inc, colours_,
                                   pattern_, u, f_int, K, dilatation, local)
                  : assemble_dim<3>(quad_, dofs_, laws_, formulations_, pressure_degree_, stabilisations_, inc, colours_,
                                    pattern_, u, f_int, K, dilatation, local);
}

bool TotalLagrangianAssembler::has_mixed() const {
  return std::find(formulations_.begin(), formulations_.end(), Formulation::mixed) != formulations_.end();
}

void TotalLagrangianAssembler::make_incompressible(double tolerance) {
  if (!(tolerance > 0)) throw std::invalid_argument("the incompressibility tolerance must be positive");
  if (std::find(formulations_.begin(), formulations_.end(), Formulation::mixed) == formulations_.end())
    throw std::invalid_argument("the incompressible limit needs the mixed formulation");
  Incompressibility inc;
  inc.tolerance = tolerance;
  for (const HyperelasticLaw* law : laws_) {  // kappa = U''(1), the law's bulk modulus
    VolumetricValues v;
    inc.penalties.push_back(law->volumetric(1.0, v) ? v.d2U : 0.0);
  }
  inc.multipliers = Eigen::VectorXd::Zero(quad_.num_elements());
  inc.accepted = inc.multipliers;
  incompressibility_ = std::move(inc);
}

bool TotalLagrangianAssembler::volume_changes(const Eigen::MatrixXd& u, Eigen::VectorXd& dilatation) const {
  LocalDilatation local;
  Eigen::VectorXd f;
  const bool ok = assemble(u, f, nullptr, nullptr, &local);
  dilatation = ok ? local.projected : Eigen::VectorXd::Zero(quad_.num_elements());
  return ok;
}

bool TotalLagrangianAssembler::element_pressures(const Eigen::MatrixXd& u, Eigen::VectorXd& pressure) const {
  if (!incompressibility_ || !volume_changes(u, pressure)) return false;
  const Incompressibility& inc = *incompressibility_;
  for (int e = 0; e < quad_.num_elements(); ++e)
    pressure[e] = inc.multipliers[e] + inc.penalties[inc.penalties.size() == 1 ? 0 : size_t(quad_.patch_of(e))] * pressure[e];
  return true;
}

bool TotalLagrangianAssembler::augment(const Eigen::MatrixXd& u) {
  if (!incompressibility_) return false;
  Incompressibility& inc = *incompressibility_;
  Eigen::VectorXd dil;
  if (!volume_changes(u, dil)) return false;
  inc.last_volume_change = dil.cwiseAbs().maxCoeff();
  if (inc.last_volume_change <= inc.tolerance) return false;
  for (int e = 0; e < quad_.num_elements(); ++e) {
    const int patch = inc.penalties.size() == 1 ? 0 : quad_.patch_of(e);
    inc.multipliers[e] += inc.penalties[size_t(patch)] * dil[e];
  }
  ++inc.augmentations;
  return true;
}

void TotalLagrangianAssembler::copy_multipliers(const TotalLagrangianAssembler& from) {
  if (!from.incompressibility_) return;
  if (!incompressibility_) make_incompressible(from.incompressibility_->tolerance);
  if (from.incompressibility_->multipliers.size() != incompressibility_->multipliers.size())
    throw std::invalid_argument("copy_multipliers: the assemblers do not have the same elements");
  incompressibility_->multipliers = from.incompressibility_->multipliers;
  incompressibility_->accepted = from.incompressibility_->accepted;
}

void TotalLagrangianAssembler::restore_multipliers(const Eigen::VectorXd& accepted) {
  if (!incompressibility_ || accepted.size() != incompressibility_->multipliers.size())
    throw std::invalid_argument("restore_multipliers: not the element multipliers of this incompressible body");
  incompressibility_->multipliers = accepted;
  incompressibility_->accepted = accepted;
}

void TotalLagrangianAssembler::keep_multipliers(bool accepted) {
  if (!incompressibility_) return;
  if (accepted) incompressibility_->accepted = incompressibility_->multipliers;
  else incompressibility_->multipliers = incompressibility_->accepted;
}

}  // namespace igac
