// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <omp.h>
#include "engine/assembly.hpp"
#include "engine/follower_pressure.hpp"
#include "engine/sparsity.hpp"
#include "engine/free_cores.hpp"

#include <fmt/format.h>
#include <limits>
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

// The same for a body: each patch's collapsed lines, in body numbering.
std::vector<int> merge_collapsed_lines(const Body& body) {
  if (body.numbered_as_patch()) return merge_collapsed_lines(body.patch(0));
  std::vector<int> rep(body.num_control_points());
  for (int i = 0; i < int(rep.size()); ++i) rep[i] = i;
  auto find = [&](int i) {
    while (rep[i] != i) i = rep[i] = rep[rep[i]];
    return i;
  };
  for (int k = 0; k < body.num_patches(); ++k) {
    const std::vector<int> local = merge_collapsed_lines(body.patch(k));
    const std::vector<int>& to_body = body.body_cps(k);
    for (size_t i = 0; i < local.size(); ++i) {
      const int a = find(to_body[i]), b = find(to_body[local[i]]);
      if (a != b) rep[std::max(a, b)] = std::min(a, b);
    }
  }
  for (int i = 0; i < int(rep.size()); ++i) rep[i] = find(i);
  return rep;
}

}  // namespace

DofMap::DofMap(const Body& body, const std::vector<DirichletCondition>& conditions)
    : dim_(body.space_dim()) {
  const int n = body.num_control_points() * dim_;
  const std::vector<int> rep = merge_collapsed_lines(body);
  auto rep_dof = [&](int cp, int c) { return rep[cp] * dim_ + c; };
  equation_.assign(n, 0);
  value_.assign(n, 0.0);
  for (const auto& c : conditions) {
    if (c.component < 0 || c.component >= dim_)
      throw std::invalid_argument(fmt::format("Dirichlet component {} out of range", c.component));
    for (const auto& f : c.faces)
      for (int cp : body.side_control_points(f)) {
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

PatchQuadrature face_quadrature(const Body& body, const PatchSide& side, int points) {
  return body.side_quadrature(side, points);
}


LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const LinearElastic& mat, const Eigen::VectorXd& body_force,
                                        ElementRange elements, Formulation formulation) {
  return assemble_linear_elasticity(body, dofs, std::vector<LinearElastic>{mat}, body_force, elements,
                                    std::vector<Formulation>{formulation});
}

LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const std::vector<LinearElastic>& materials,
                                        const Eigen::VectorXd& body_force, ElementRange elements,
                                        const std::vector<Formulation>& formulations) {
  if (formulations.size() > 1 && int(formulations.size()) != body.num_patches())
    throw std::invalid_argument(fmt::format("{} formulations for {} patches", formulations.size(), body.num_patches()));
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  return assemble_linear_elasticity(body, dofs, materials, body_force, elements, formulations,
                                    mixed_pressure_space(quad, formulations));
}

namespace {

// values[k] += scale g_r g_c for a function's rank-one term (scatter_element_matrix's ElementMatrix).
struct RankOne {
  const Eigen::VectorXd& g;
  double scale;
  double operator()(int r, int c) const { return scale * g[r] * g[c]; }
};

// What a mixed element gives the rank-one terms of its pressure functions:
// per function i of the element (space.functions_begin(e)[i]), the row
// int_e N_i div N dX on the element's dofs (cp * dim + component) and
// int_e N_i dX.  Kept per element, so the threads of the element pass never
// share one.
struct ElementDivergence {
  std::vector<int> dof;
  Eigen::MatrixXd g;  // n_dofs x n_functions
  Eigen::VectorXd m;  // n_functions
};

// The axisymmetric model's hoop terms of a linear elastic element matrix:
// eps_theta = u_r / r adds (lambda + 2 mu) h_a h_b to the (r, r) blocks and
// lambda (h_a dN_b/dX_j + dN_a/dX_i h_b) to the (r, j) and (i, r) blocks,
// h_a = N_a / r (tr eps = div u + u_r / r).
template <int dim>
void add_hoop_stiffness(const ElementValues<dim, dim>& ed, double lambda, double mu, Eigen::MatrixXd& Ke) {
  const int nl = ed.n_loc;
  for (int q = 0; q < ed.n_q; ++q) {
    const double* dN = ed.gradients(q);
    const double w = ed.JxW[q];
    for (int b = 0; b < nl; ++b) {
      const double hb = w * ed.hoop(q, b);
      for (int a = 0; a < nl; ++a) {
        const double ha = ed.hoop(q, a);
        Ke(a * dim, b * dim) += (lambda + 2 * mu) * ha * hb;
        for (int j = 0; j < dim; ++j) {
          Ke(a * dim, b * dim + j) += lambda * ha * w * dN[b * dim + j];
          Ke(a * dim + j, b * dim) += lambda * dN[a * dim + j] * hb;
        }
      }
    }
  }
}

}  // namespace

LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const std::vector<LinearElastic>& materials,
                                        const Eigen::VectorXd& body_force, ElementRange elements,
                                        const std::vector<Formulation>& formulations, const PressureSpace& space) {
  const int dim = body.space_dim();
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  const int e_end = elements.end < 0 ? quad.num_elements() : std::min(elements.end, quad.num_elements());
  const int e_begin = std::clamp(elements.begin, 0, e_end);
  if (materials.size() != 1 && int(materials.size()) != body.num_patches())
    throw std::invalid_argument(fmt::format("{} materials for {} patches", materials.size(), body.num_patches()));
  if (formulations.size() > 1 && int(formulations.size()) != body.num_patches())
    throw std::invalid_argument(fmt::format("{} formulations for {} patches", formulations.size(), body.num_patches()));
  if (space.num_elements() != quad.num_elements())
    throw std::invalid_argument(
        fmt::format("{} elements in the pressure space for {} in the body", space.num_elements(), quad.num_elements()));
  const int k_pressure = pressure_degree(body.degree());
  const int n_free = dofs.num_free();
  const bool has_body_force = body_force.size() == dim && body_force.norm() > 0;
  const auto material_of = [&](int patch) -> const LinearElastic& {
    return materials[materials.size() == 1 ? 0 : size_t(patch)];
  };
  const auto mixed_patch = [&](int patch) {
    return !formulations.empty() && is_mixed(formulations[formulations.size() == 1 ? 0 : size_t(patch)]);
  };
  // Constants per element: each element adds its function's rank-one term
  // right after its matrix (the element loop of before, term for term).
  // Else an element pass keeps every mixed element's ElementDivergence, then
  // a function pass gathers g_A = int N_A div N dX from its support and adds
  // K / m_A g_A g_A^T.  The range owns the functions whose first support
  // element it holds (engine/sparsity.hpp) and evaluates their support
  // elements outside it again, for g_A only.
  const bool per_element = space.per_element();
  const auto owned = [&](int a) {
    if (space.support_begin(a) == space.support_end(a)) return false;
    const int first = *space.support_begin(a);
    return first >= e_begin && first < e_end && mixed_patch(space.patch_of_function(a));
  };
  std::vector<int> outside;  // elements outside the range in the support of an owned function
  if (!per_element) {
    for (int a = 0; a < space.num_functions(); ++a)
      if (owned(a))
        for (const int* e = space.support_begin(a); e != space.support_end(a); ++e)
          if (*e >= e_end) outside.push_back(*e);  // the first element is in the range, the others after it
    std::sort(outside.begin(), outside.end());
    outside.erase(std::unique(outside.begin(), outside.end()), outside.end());
  }

  LinearSystem s;
  s.K = coupling_pattern(quad, dofs, space, e_begin, e_end);  // the element pattern for constants per element

  // Colour by colour: no two elements (or functions) of a colour share an
  // equation, so threads add straight into K's values and f
  // (engine/sparsity.hpp), and the sums are the same whatever the number of
  // threads.  One thread adds the elements, then the functions, in their own
  // order instead, the order the sums had before colouring (the shipped
  // cases' recorded results are reproduced bit for bit; colour order moves
  // hertz2d's peak pressure by 3e-12 relative).
  std::vector<std::vector<int>> colours, function_colours;
  if (omp_get_max_threads() > 1) {
    colours = colour_elements(quad, dofs, e_begin, e_end);
    if (!per_element) {
      function_colours = colour_functions(quad, dofs, space, e_begin, e_end);
      for (std::vector<int>& colour : function_colours)
        colour.erase(std::remove_if(colour.begin(), colour.end(), [&](int a) { return !owned(a); }), colour.end());
    }
  } else {
    colours.emplace_back();
    for (int e = e_begin; e < e_end; ++e) colours.back().push_back(e);
    if (!per_element) {
      function_colours.emplace_back();
      for (int a = 0; a < space.num_functions(); ++a)
        if (owned(a)) function_colours.back().push_back(a);
    }
  }
  std::vector<ElementDivergence> divergence(per_element ? 0 : size_t(quad.num_elements()));
  double* val = s.K.valuePtr();  // zero: the pattern's values
  s.f = Eigen::VectorXd::Zero(n_free);
  double* f = s.f.data();
  double min_det = std::numeric_limits<double>::infinity();

#pragma omp parallel reduction(min : min_det) num_threads(free_cores())
  {
    ElementValues<2, 2> v2;  // of the one element kernel (element_values.hpp)
    ElementValues<3, 3> v3;
    Eigen::MatrixXd Ke, Gw;
    std::array<Eigen::MatrixXd, 3> Gd;  // per direction: n_loc x n_q gradients
    std::array<std::array<Eigen::MatrixXd, 3>, 3> M;
    std::vector<int> eq;
    ElementProjection projection;
    Eigen::MatrixXd B, Bbar;
    PressureSpace::Scratch scratch;
    Eigen::MatrixXd N;
    Eigen::VectorXd weights;
    ElementDivergence own;  // constants per element: the element's, used at once
    // A function's rank-one term: its row (dof, value) pairs, a dof met by
    // several elements summed, then K / m_A g_A g_A^T.
    std::vector<std::pair<int, double>> row;
    std::vector<int> row_dof, row_eq;
    Eigen::VectorXd g;
    // Element e's int N_i div N dX and int N_i dX per function i (B, the
    // points' div N, filled).
    auto divergence_rows = [&](int e, const auto& ed, ElementDivergence& d) {
      const int nd = ed.n_loc * dim, nq = ed.n_q, nf = space.num_element_functions(e);
      d.dof.resize(size_t(nd));
      for (int c = 0; c < nd; ++c) d.dof[size_t(c)] = ed.cps[size_t(c / dim)] * dim + c % dim;
      d.g.resize(nd, nf);
      d.m.resize(nf);
      space.values_at(e, ed.xi, N, scratch);  // N(q, i): function i at point q
      weights.resize(nq);
      for (int i = 0; i < nf; ++i) {
        double m = 0;
        for (int q = 0; q < nq; ++q) {
          weights[q] = ed.JxW[size_t(q)] * N(q, i);
          m += weights[q];
        }
        d.g.col(i).noalias() = B.transpose() * weights;
        d.m[i] = m;
      }
    };
    auto fill_divergence = [&](const auto& ed) {  // B(q, a dim + i) = dN_a/dX_i (+ N_a / r: the hoop strain's)
      const int nd = ed.n_loc * dim;
      B.resize(ed.n_q, nd);
      for (int q = 0; q < ed.n_q; ++q) {
        for (int c = 0; c < nd; ++c) B(q, c) = ed.gradients(q)[c];
        if (ed.revolved)
          for (int a = 0; a < ed.n_loc; ++a) B(q, a * dim) += ed.hoop(q, a);
      }
    };
    // Adds element e's matrix and loads; a mixed element fills its
    // ElementDivergence too.  Returns whether it is mixed.
    auto assemble_element = [&](int e, auto& ed) -> bool {
      quad.evaluate(e, ed, true);
      const int patch = materials.size() > 1 || formulations.size() > 1 ? quad.patch_of(e) : 0;
      const LinearElastic& mat = material_of(patch);
      // mixed: the deviatoric part with lambda - K = -2 mu / 3, the
      // stabilisation mu (B^T W B - V_e mB_e^T mB_e) per element, and the
      // functions' K / m_A g_A g_A^T after (volumetric_projection.hpp)
      const bool mixed = mixed_patch(patch);
      const double lambda = mixed ? -2 * mat.mu() / 3 : mat.lambda(), mu = mat.mu();
      min_det = std::min(min_det, ed.min_det_J);
      const int nl = ed.n_loc, nq = ed.n_q, nd = nl * dim;
      // M_ij = sum_q JxW dN/dX_i dN/dX_j^T, then
      // K_(a i)(b j) = lambda M_ij + mu M_ji + mu delta_ij sum_k M_kk.
      for (int i = 0; i < dim; ++i) {
        Gd[i].resize(nl, nq);
        for (int q = 0; q < nq; ++q)
          for (int a = 0; a < nl; ++a) Gd[i](a, q) = ed.gradients(q)[a * dim + i];
      }
      for (int i = 0; i < dim; ++i) {
        Gw.noalias() = Gd[i] * Eigen::Map<const Eigen::VectorXd>(ed.JxW.data(), nq).asDiagonal();
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
      if (ed.revolved) add_hoop_stiffness(ed, lambda, mu, Ke);
      if (mixed) {  // + mu (B - Bbar)^T W (B - Bbar), Bbar = Pi_e B
        projection.build(ed.xi, ed.JxW, k_pressure);
        fill_divergence(ed);
        add_volumetric_tangent(projection.matrix(), ed.JxW, Eigen::VectorXd::Zero(nq), mu, B, Bbar, Ke);
        divergence_rows(e, ed, per_element ? own : divergence[size_t(e)]);
      }
      dofs.element_equations(ed.cps, eq);
      for (int c = 0; c < nd; ++c) {  // prescribed: lift its value into the right-hand side
        if (eq[c] >= 0) continue;
        const double gv = dofs.prescribed_value(ed.cps[c / dim] * dim + c % dim);
        if (gv != 0.0)
          for (int r = 0; r < nd; ++r)
            if (eq[r] >= 0) f[eq[r]] -= Ke(r, c) * gv;
      }
      scatter_element_matrix(s.K, val, eq, Ke);
      if (has_body_force)
        for (int q = 0; q < nq; ++q)
          for (int a = 0; a < nl; ++a)
            for (int i = 0; i < dim; ++i)
              if (eq[a * dim + i] >= 0) f[eq[a * dim + i]] += ed.N(q, a) * body_force[i] * ed.JxW[q];
      return mixed;
    };
    // K / m g g^T for the row gathered in `row` (sorted by dof here).
    auto add_rank_one = [&](double bulk, double m) {
      std::sort(row.begin(), row.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
      row_dof.clear();  // the support's dofs, each once, and g_A on them
      g.resize(Eigen::Index(row.size()));
      for (const auto& [dof, value] : row) {
        if (!row_dof.empty() && row_dof.back() == dof) {
          g[Eigen::Index(row_dof.size()) - 1] += value;
          continue;
        }
        g[Eigen::Index(row_dof.size())] = value;
        row_dof.push_back(dof);
      }
      const int n = int(row_dof.size());
      g.conservativeResize(n);
      row_eq.resize(size_t(n));
      for (int c = 0; c < n; ++c) row_eq[size_t(c)] = dofs.equation(row_dof[size_t(c)]);
      const RankOne Ka{g, bulk / m};
      for (int c = 0; c < n; ++c) {  // prescribed: lift its value into the right-hand side
        if (row_eq[size_t(c)] >= 0) continue;
        const double gv = dofs.prescribed_value(row_dof[size_t(c)]);
        if (gv != 0.0)
          for (int r = 0; r < n; ++r)
            if (row_eq[size_t(r)] >= 0) f[row_eq[size_t(r)]] -= Ka(r, c) * gv;
      }
      scatter_element_matrix(s.K, val, row_eq, Ka);
    };
    const auto bulk_of = [&](int patch) {
      const LinearElastic& mat = material_of(patch);
      return mat.lambda() + 2 * mat.mu() / 3;
    };
    // Function a's term from the ElementDivergence of its support.
    auto add_function = [&](int a) {
      row.clear();
      double m = 0;
      for (const int* e = space.support_begin(a); e != space.support_end(a); ++e) {
        const ElementDivergence& d = divergence[size_t(*e)];
        const int i = int(std::find(space.functions_begin(*e), space.functions_end(*e), a) - space.functions_begin(*e));
        for (size_t c = 0; c < d.dof.size(); ++c) row.emplace_back(d.dof[c], d.g(Eigen::Index(c), i));
        m += d.m[i];
      }
      add_rank_one(bulk_of(space.patch_of_function(a)), m);
    };
    auto element = [&](int e) {
      const bool mixed = dim == 2 ? assemble_element(e, v2) : assemble_element(e, v3);
      if (!mixed || !per_element) return;
      row.clear();  // the element's one function, at once
      for (size_t c = 0; c < own.dof.size(); ++c) row.emplace_back(own.dof[c], own.g(Eigen::Index(c), 0));
      add_rank_one(bulk_of(quad.patch_of(e)), own.m[0]);
    };
    // Outside the range: an element's divergence rows only (its matrix is
    // another range's).
    auto divergence_only = [&](int e, auto& ed) {
      quad.evaluate(e, ed, true);
      fill_divergence(ed);
      divergence_rows(e, ed, divergence[size_t(e)]);
    };
    for (const std::vector<int>& colour : colours) {
      const int n_colour = int(colour.size());
#pragma omp for schedule(dynamic, 16)
      for (int idx = 0; idx < n_colour; ++idx) element(colour[idx]);
    }
    const int n_outside = int(outside.size());
#pragma omp for schedule(dynamic, 16)
    for (int idx = 0; idx < n_outside; ++idx) {  // on a mixed patch: an owned function's support
      if (dim == 2)
        divergence_only(outside[size_t(idx)], v2);
      else
        divergence_only(outside[size_t(idx)], v3);
    }
    for (const std::vector<int>& colour : function_colours) {
      const int n_colour = int(colour.size());
#pragma omp for schedule(dynamic, 16)
      for (int idx = 0; idx < n_colour; ++idx) add_function(colour[size_t(idx)]);
    }
  }
  s.min_det_J = min_det;
  if (!(s.min_det_J > 0))
    throw std::runtime_error(fmt::format("the geometry map folds: det J = {:.3g} at a Gauss point", s.min_det_J));
  return s;
}

void add_pressure_load(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces,
                       double pressure, Eigen::VectorXd& f) {
  add_dead_pressure(body, dofs, faces, pressure, f);  // the one face loop of the pressure loads
}

Eigen::VectorXd body_force_load(const Body& body, const DofMap& dofs, const Eigen::VectorXd& b) {
  const int dim = body.space_dim();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(dofs.num_free());
  if (b.size() != dim || b.norm() == 0) return f;
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  ElementData ed;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, false);
    for (int q = 0; q < ed.N.rows(); ++q)
      for (size_t a = 0; a < ed.cps.size(); ++a)
        for (int i = 0; i < dim; ++i)
          if (const int eq = dofs.equation(ed.cps[a] * dim + i); eq >= 0) f[eq] += ed.N(q, a) * b[i] * ed.JxW[q];
  }
  return f;
}

}  // namespace igac
