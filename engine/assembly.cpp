#include <algorithm>
#include "engine/assembly.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <stdexcept>

namespace igac {

namespace {

// Representative control point of each control point: lines of coincident
// control points on a face (a face collapsed onto a curve or a point, as on
// the axis of a body of revolution) share one set of unknowns, so the
// displacement there is single-valued.
std::vector<int> merge_collapsed_lines(const NurbsPatch& patch) {
  const int n = patch.num_control_points(), pd = patch.param_dim();
  std::vector<int> rep(n);
  for (int i = 0; i < n; ++i) rep[i] = i;
  const double size = (patch.points().colwise().maxCoeff() - patch.points().colwise().minCoeff()).norm();
  const double tol = 1e-10 * size;
  for (int d = 0; d < pd; ++d)
    for (int end = 0; end < 2; ++end) {
      const std::vector<int> cps = patch.face_control_points(Face{d, end == 1});
      for (int along = 0; along < pd; ++along) {
        if (along == d) continue;
        // lines of the face along `along`: group by the other multi-indices
        bool collapsed = true;
        for (int cp : cps) {
          auto mi = patch.multi_index(cp);
          if (mi[along] == 0) continue;
          mi[along] -= 1;
          if ((patch.points().row(cp) - patch.points().row(patch.index(mi))).norm() > tol) {
            collapsed = false;
            break;
          }
        }
        if (!collapsed) continue;
        for (int cp : cps) {
          auto mi = patch.multi_index(cp);
          mi[along] = 0;
          rep[cp] = rep[patch.index(mi)];
        }
      }
    }
  for (int i = 0; i < n; ++i)  // resolve chains (a face collapsed to a point)
    while (rep[rep[i]] != rep[i]) rep[i] = rep[rep[i]];
  return rep;
}

}  // namespace

DofMap::DofMap(const NurbsPatch& patch, const std::vector<DirichletCondition>& conditions)
    : dim_(patch.space_dim()) {
  const int n = patch.num_control_points() * dim_;
  const std::vector<int> rep = merge_collapsed_lines(patch);
  auto rep_dof = [&](int cp, int c) { return rep[cp] * dim_ + c; };
  equation_.assign(n, 0);
  value_.assign(n, 0.0);
  for (const auto& c : conditions) {
    if (c.component < 0 || c.component >= dim_)
      throw std::invalid_argument(fmt::format("Dirichlet component {} out of range", c.component));
    for (const auto& f : c.faces)
      for (int cp : patch.face_control_points(f)) {
        equation_[rep_dof(cp, c.component)] = -1;
        value_[rep_dof(cp, c.component)] = c.value;
      }
  }
  for (int i = 0; i < n; ++i)
    if (rep[i / dim_] == i / dim_) equation_[i] = equation_[i] == 0 ? n_free_++ : -1;
  for (int i = 0; i < n; ++i) {
    equation_[i] = equation_[rep_dof(i / dim_, i % dim_)];
    value_[i] = value_[rep_dof(i / dim_, i % dim_)];
  }
}

Eigen::MatrixXd DofMap::expand(const Eigen::VectorXd& free) const {
  if (free.size() != n_free_)
    throw std::invalid_argument(fmt::format("{} free values given for {} free dofs", free.size(), n_free_));
  Eigen::MatrixXd u(num_dofs() / dim_, dim_);
  for (int i = 0; i < num_dofs(); ++i)
    u(i / dim_, i % dim_) = equation_[i] >= 0 ? free[equation_[i]] : value_[i];
  return u;
}

PatchQuadrature face_quadrature(const NurbsPatch& patch, const Face& f, int points) {
  return PatchQuadrature(patch.face_patch(f), points, f, patch.face_control_points(f));
}

namespace {

// Sparsity pattern of the stiffness matrix in the free numbering: equations
// are coupled when their control points share an element.  Values are zero.
Eigen::SparseMatrix<double> stiffness_pattern(const PatchQuadrature& quad, const DofMap& dofs) {
  const int dim = dofs.dim(), n_free = dofs.num_free();
  const int n_cp = dofs.num_dofs() / dim;
  // node adjacency through elements (nodes = representative control points,
  // identified by their first free equation or, if none, the cp itself)
  std::vector<std::vector<int>> adj(n_cp);
  std::vector<int> cps;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.control_points(e, cps);
    for (int a : cps)
      for (int b : cps) adj[a].push_back(b);
  }
  std::vector<std::vector<int>> cols(n_free);
  for (int a = 0; a < n_cp; ++a) {
    auto& v = adj[a];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    for (int i = 0; i < dim; ++i) {
      const int r = dofs.equation(a * dim + i);
      if (r < 0) continue;
      for (int b : v)
        for (int j = 0; j < dim; ++j) {
          const int c = dofs.equation(b * dim + j);
          if (c >= 0) cols[r].push_back(c);
        }
    }
    std::vector<int>().swap(v);
  }
  Eigen::SparseMatrix<double> K(n_free, n_free);
  std::vector<int> nnz(n_free);
  for (int r = 0; r < n_free; ++r) {
    auto& v = cols[r];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    nnz[r] = int(v.size());
  }
  K.reserve(nnz);
  // symmetric: row r's columns are column r's rows
  for (int r = 0; r < n_free; ++r)
    for (int c : cols[r]) K.insert(c, r) = 0.0;
  K.makeCompressed();
  return K;
}

}  // namespace

LinearSystem assemble_linear_elasticity(const NurbsPatch& patch, const DofMap& dofs,
                                        const LinearElastic& mat, const Eigen::VectorXd& body_force) {
  const int dim = patch.space_dim();
  int max_degree = 0;
  for (int d = 0; d < patch.param_dim(); ++d) max_degree = std::max(max_degree, patch.degree(d));
  const PatchQuadrature quad(patch, gauss_points_for(max_degree));
  const int n_el = quad.num_elements();
  const double lambda = mat.lambda(), mu = mat.mu();
  const int n_free = dofs.num_free();
  const bool has_body_force = body_force.size() == dim && body_force.norm() > 0;

  LinearSystem s;
  s.K = stiffness_pattern(quad, dofs);
  const int* outer = s.K.outerIndexPtr();
  const int* inner = s.K.innerIndexPtr();
  const int nnz = int(s.K.nonZeros());

  const int n_threads = omp_get_max_threads();
  // Each thread adds into its own copy of the values (no races, also where
  // collapsed control points join elements that are far apart).
  std::vector<std::vector<double>> values(n_threads);
  std::vector<Eigen::VectorXd> rhs(n_threads);
  std::vector<double> min_det(n_threads, std::numeric_limits<double>::infinity());

#pragma omp parallel
  {
    const int tid = omp_get_thread_num();
    values[tid].assign(nnz, 0.0);
    rhs[tid].setZero(n_free);
    double* val = values[tid].data();
    ElementData ed;
    Eigen::MatrixXd Ke, Gw;
    std::array<Eigen::MatrixXd, 3> Gd;  // per direction: n_loc x n_q gradients
    std::array<std::array<Eigen::MatrixXd, 3>, 3> M;
    std::vector<int> eq;
#pragma omp for schedule(dynamic, 64)
    for (int e = 0; e < n_el; ++e) {
      quad.evaluate(e, ed, true);
      min_det[tid] = std::min(min_det[tid], ed.min_det_J);
      const int nl = int(ed.cps.size()), nq = int(ed.JxW.size()), nd = nl * dim;
      // M_ij = sum_q JxW dN/dX_i dN/dX_j^T, then
      // K_(a i)(b j) = lambda M_ij + mu M_ji + mu delta_ij sum_k M_kk.
      for (int i = 0; i < dim; ++i) {
        Gd[i].resize(nl, nq);
        for (int q = 0; q < nq; ++q) Gd[i].col(q) = ed.dN[q].col(i);
      }
      for (int i = 0; i < dim; ++i) {
        Gw.noalias() = Gd[i] * ed.JxW.asDiagonal();
        for (int j = i; j < dim; ++j) M[i][j].noalias() = Gw * Gd[j].transpose();
      }
      Eigen::MatrixXd trace = M[0][0];
      for (int k = 1; k < dim; ++k) trace += M[k][k];
      Ke.resize(nd, nd);
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j) {
          const Eigen::MatrixXd& Mij = i <= j ? M[i][j] : M[j][i];
          for (int b = 0; b < nl; ++b)
            for (int a = 0; a < nl; ++a) {
              const double mij = i <= j ? Mij(a, b) : Mij(b, a);  // M_ij(a, b)
              const double mji = i <= j ? Mij(b, a) : Mij(a, b);  // M_ji(a, b)
              Ke(a * dim + i, b * dim + j) = lambda * mij + mu * mji + (i == j ? mu * trace(a, b) : 0.0);
            }
        }
      eq.resize(nd);
      for (int a = 0; a < nl; ++a)
        for (int i = 0; i < dim; ++i) eq[a * dim + i] = dofs.equation(ed.cps[a] * dim + i);
      for (int c = 0; c < nd; ++c) {
        if (eq[c] < 0) {  // prescribed: lift its value into the right-hand side
          const double g = dofs.prescribed_value(ed.cps[c / dim] * dim + c % dim);
          if (g != 0.0)
            for (int r = 0; r < nd; ++r)
              if (eq[r] >= 0) rhs[tid][eq[r]] -= Ke(r, c) * g;
          continue;
        }
        const int* first = inner + outer[eq[c]];
        const int* past = inner + outer[eq[c] + 1];
        for (int r = 0; r < nd; ++r) {
          if (eq[r] < 0) continue;
          const int* pos = std::lower_bound(first, past, eq[r]);
          val[pos - inner] += Ke(r, c);
        }
      }
      if (has_body_force)
        for (int q = 0; q < nq; ++q)
          for (int a = 0; a < nl; ++a)
            for (int i = 0; i < dim; ++i)
              if (eq[a * dim + i] >= 0) rhs[tid][eq[a * dim + i]] += ed.N(q, a) * body_force[i] * ed.JxW[q];
    }
  }
  s.min_det_J = *std::min_element(min_det.begin(), min_det.end());
  if (!(s.min_det_J > 0))
    throw std::runtime_error(fmt::format("the geometry map folds: det J = {:.3g} at a Gauss point", s.min_det_J));
  // The team may have had fewer threads than omp_get_max_threads() (dynamic
  // threads on a loaded machine): sum the copies that were filled.
  std::vector<const double*> parts;
  for (const auto& v : values)
    if (!v.empty()) parts.push_back(v.data());
  double* out = s.K.valuePtr();
#pragma omp parallel for schedule(static)
  for (int k = 0; k < nnz; ++k) {
    double v = 0;
    for (const double* p : parts) v += p[k];
    out[k] = v;
  }
  s.f = Eigen::VectorXd::Zero(n_free);
  for (const auto& r : rhs)
    if (r.size() == n_free) s.f += r;
  return s;
}

void add_pressure_load(const NurbsPatch& patch, const DofMap& dofs, const std::vector<Face>& faces,
                       double pressure, Eigen::VectorXd& f) {
  const int dim = patch.space_dim();
  for (const Face& face : faces) {
    const PatchQuadrature quad = face_quadrature(patch, face, gauss_points_for(patch.degree(0)));
    ElementData ed;
    for (int e = 0; e < quad.num_elements(); ++e) {
      quad.evaluate(e, ed, false);
      for (int q = 0; q < ed.JxW.size(); ++q)
        for (size_t a = 0; a < ed.cps.size(); ++a)
          for (int i = 0; i < dim; ++i) {
            const int eq = dofs.equation(ed.cps[a] * dim + i);
            if (eq >= 0) f[eq] -= pressure * ed.normal(q, i) * ed.N(q, a) * ed.JxW[q];
          }
    }
  }
}

}  // namespace igac
