#include "engine/assembly.hpp"

#include <fmt/format.h>
#include <omp.h>
#include <stdexcept>

namespace igac {

DofMap::DofMap(const NurbsPatch& patch, const std::vector<DirichletCondition>& conditions)
    : dim_(patch.space_dim()) {
  const int n = patch.num_control_points() * dim_;
  equation_.assign(n, 0);
  value_.assign(n, 0.0);
  for (const auto& c : conditions) {
    if (c.component < 0 || c.component >= dim_)
      throw std::invalid_argument(fmt::format("Dirichlet component {} out of range", c.component));
    for (const auto& f : c.faces)
      for (int cp : patch.face_control_points(f)) {
        equation_[cp * dim_ + c.component] = -1;
        value_[cp * dim_ + c.component] = c.value;
      }
  }
  for (int& e : equation_) e = (e == 0) ? n_free_++ : -1;
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

LinearSystem assemble_linear_elasticity(const NurbsPatch& patch, const DofMap& dofs,
                                        const LinearElastic& mat, const Eigen::VectorXd& body_force) {
  const int dim = patch.space_dim();
  const PatchQuadrature quad(patch, gauss_points_for(patch.degree(0)));
  const int n_el = quad.num_elements();
  const double lambda = mat.lambda(), mu = mat.mu();
  const int n_free = dofs.num_free();
  const bool has_body_force = body_force.size() == dim && body_force.norm() > 0;

  const int n_threads = omp_get_max_threads();
  std::vector<std::vector<Eigen::Triplet<double>>> triplets(n_threads);
  std::vector<Eigen::VectorXd> rhs(n_threads, Eigen::VectorXd::Zero(n_free));
  std::vector<double> min_det(n_threads, std::numeric_limits<double>::infinity());

#pragma omp parallel
  {
    const int tid = omp_get_thread_num();
    ElementData ed;
    Eigen::MatrixXd Ke;
    std::vector<int> eq;
    auto& trip = triplets[tid];
    trip.reserve(size_t(n_el / n_threads + 1) * quad.num_local() * quad.num_local() * dim * dim);
#pragma omp for schedule(static)
    for (int e = 0; e < n_el; ++e) {
      quad.evaluate(e, ed, true);
      min_det[tid] = std::min(min_det[tid], ed.min_det_J);
      const int nl = int(ed.cps.size()), nd = nl * dim;
      Ke.setZero(nd, nd);
      for (int q = 0; q < ed.JxW.size(); ++q) {
        const Eigen::MatrixXd& G = ed.dN[q];
        const double jw = ed.JxW[q];
        const Eigen::MatrixXd GG = G * G.transpose() * (mu * jw);
        for (int a = 0; a < nl; ++a)
          for (int b = 0; b < nl; ++b)
            for (int i = 0; i < dim; ++i) {
              Ke(a * dim + i, b * dim + i) += GG(a, b);
              for (int j = 0; j < dim; ++j)
                Ke(a * dim + i, b * dim + j) += jw * (lambda * G(a, i) * G(b, j) + mu * G(a, j) * G(b, i));
            }
      }
      eq.resize(nd);
      for (int a = 0; a < nl; ++a)
        for (int i = 0; i < dim; ++i) eq[a * dim + i] = dofs.equation(ed.cps[a] * dim + i);
      for (int r = 0; r < nd; ++r) {
        if (eq[r] < 0) continue;
        for (int c = 0; c < nd; ++c) {
          if (eq[c] >= 0) {
            trip.emplace_back(eq[r], eq[c], Ke(r, c));
          } else {
            const double g = dofs.prescribed_value(ed.cps[c / dim] * dim + c % dim);
            if (g != 0.0) rhs[tid][eq[r]] -= Ke(r, c) * g;
          }
        }
      }
      if (has_body_force)
        for (int q = 0; q < ed.JxW.size(); ++q)
          for (int a = 0; a < nl; ++a)
            for (int i = 0; i < dim; ++i)
              if (eq[a * dim + i] >= 0) rhs[tid][eq[a * dim + i]] += ed.N(q, a) * body_force[i] * ed.JxW[q];
    }
  }
  LinearSystem s;
  s.min_det_J = *std::min_element(min_det.begin(), min_det.end());
  if (!(s.min_det_J > 0))
    throw std::runtime_error(fmt::format("the geometry map folds: det J = {:.3g} at a Gauss point", s.min_det_J));
  size_t total = 0;
  for (const auto& t : triplets) total += t.size();
  std::vector<Eigen::Triplet<double>> all;
  all.reserve(total);
  for (auto& t : triplets) {
    all.insert(all.end(), t.begin(), t.end());
    std::vector<Eigen::Triplet<double>>().swap(t);
  }
  s.K.resize(n_free, n_free);
  s.K.setFromTriplets(all.begin(), all.end());
  s.f = Eigen::VectorXd::Zero(n_free);
  for (const auto& r : rhs) s.f += r;
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
