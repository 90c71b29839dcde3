// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <omp.h>
#include "engine/assembly.hpp"
#include "engine/follower_pressure.hpp"
#include "engine/sparsity.hpp"

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
                                    mixed_pressure_blocks(quad, formulations));
}

namespace {

// values[k] += scale g_r g_c for the rank-one block term (scatter_element_matrix's ElementMatrix).
struct RankOne {
  const Eigen::VectorXd& g;
  double scale;
  double operator()(int r, int c) const { return scale * g[r] * g[c]; }
};

}  // namespace

LinearSystem assemble_linear_elasticity(const Body& body, const DofMap& dofs,
                                        const std::vector<LinearElastic>& materials,
                                        const Eigen::VectorXd& body_force, ElementRange elements,
                                        const std::vector<Formulation>& formulations, const ElementBlocks& blocks) {
  const int dim = body.space_dim();
  const BodyQuadrature quad(body, gauss_points_for(body.degree()));
  const int e_end = elements.end < 0 ? quad.num_elements() : std::min(elements.end, quad.num_elements());
  const int e_begin = std::clamp(elements.begin, 0, e_end);
  if (materials.size() != 1 && int(materials.size()) != body.num_patches())
    throw std::invalid_argument(fmt::format("{} materials for {} patches", materials.size(), body.num_patches()));
  if (formulations.size() > 1 && int(formulations.size()) != body.num_patches())
    throw std::invalid_argument(fmt::format("{} formulations for {} patches", formulations.size(), body.num_patches()));
  if (blocks.num_elements() != quad.num_elements())
    throw std::invalid_argument(
        fmt::format("{} elements in the pressure blocks for {} in the body", blocks.num_elements(), quad.num_elements()));
  const int k_pressure = pressure_degree(body.degree());
  const int n_free = dofs.num_free();
  const bool has_body_force = body_force.size() == dim && body_force.norm() > 0;
  // Blocks of one element each: the element loop of the displacement
  // formulation, unchanged (a mixed element is then its own block).  Else a
  // thread owns whole blocks: their elements, then the block term.
  const bool by_blocks = !blocks.per_element();

  LinearSystem s;
  s.K = coupling_pattern(quad, dofs, blocks, e_begin, e_end);  // the element pattern for blocks of one

  // Colour by colour: no two units (elements, or blocks) of a colour share
  // an equation, so threads add straight into K's values and f
  // (engine/sparsity.hpp), and the sums are the same whatever the number of
  // threads.  One thread adds the units in their own order instead, the
  // order the sums had before colouring (the shipped cases' recorded results
  // are reproduced bit for bit; colour order moves hertz2d's peak pressure
  // by 3e-12 relative).
  std::vector<std::vector<int>> colours;
  if (omp_get_max_threads() > 1) {
    colours = by_blocks ? colour_blocks(quad, dofs, blocks, e_begin, e_end) : colour_elements(quad, dofs, e_begin, e_end);
  } else {
    colours.emplace_back();
    if (by_blocks) {
      for (int b = 0; b < blocks.num_blocks(); ++b)
        if (const int e = blocks.elements[blocks.start[b]]; e >= e_begin && e < e_end) colours.back().push_back(b);
    } else {
      for (int e = e_begin; e < e_end; ++e) colours.back().push_back(e);
    }
  }
  double* val = s.K.valuePtr();  // zero: the pattern's values
  s.f = Eigen::VectorXd::Zero(n_free);
  double* f = s.f.data();
  double min_det = std::numeric_limits<double>::infinity();

#pragma omp parallel reduction(min : min_det)
  {
    ElementValues<2, 2> v2;  // of the one element kernel (element_values.hpp)
    ElementValues<3, 3> v3;
    Eigen::MatrixXd Ke, Gw;
    std::array<Eigen::MatrixXd, 3> Gd;  // per direction: n_loc x n_q gradients
    std::array<std::array<Eigen::MatrixXd, 3>, 3> M;
    std::vector<int> eq;
    ElementProjection projection;
    Eigen::MatrixXd B, Bbar;
    // The block term's row: g_b = int_b div N (= V_b mB_b), by dof of the
    // block's control points (a dof met by several elements summed).
    std::vector<std::pair<int, double>> block_row;
    std::vector<int> block_dof, block_eq;
    Eigen::VectorXd g;
    // Adds element e's matrix and loads; a mixed element adds its int div N
    // to block_row and returns its bulk modulus (else 0).
    auto assemble_element = [&](int e, auto& ed) -> double {
      quad.evaluate(e, ed, true);
      const int patch = materials.size() > 1 || formulations.size() > 1 ? quad.patch_of(e) : 0;
      const LinearElastic& mat = materials[materials.size() == 1 ? 0 : patch];
      // mixed: the deviatoric part with lambda - K = -2 mu / 3, the
      // stabilisation mu (B^T W B - V_e mB_e^T mB_e) per element, and the
      // block's K V_b mB_b^T mB_b after its elements (volumetric_projection.hpp)
      const bool mixed = !formulations.empty() &&
                         is_mixed(formulations[formulations.size() == 1 ? 0 : patch]);
      const double bulk = mat.lambda() + 2 * mat.mu() / 3;
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
      if (mixed) {  // + mu (B - Bbar)^T W (B - Bbar), B(q, a dim + i) = dN_a/dX_i, Bbar = Pi_e B
        projection.build(ed.xi, ed.JxW, k_pressure);
        B.resize(nq, nd);
        for (int q = 0; q < nq; ++q)
          for (int c = 0; c < nd; ++c) B(q, c) = ed.gradients(q)[c];
        add_volumetric_tangent(projection.matrix(), ed.JxW, Eigen::VectorXd::Zero(nq), mu, B, Bbar, Ke);
        const Eigen::VectorXd ge = B.transpose() * Eigen::Map<const Eigen::VectorXd>(ed.JxW.data(), nq);
        for (int c = 0; c < nd; ++c) block_row.emplace_back(ed.cps[c / dim] * dim + c % dim, ge[c]);
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
      return mixed ? bulk : 0.0;
    };
    // The unit's elements, then (mixed) its block term K / V_b g_b g_b^T.
    auto assemble_unit = [&](const int* first, const int* past) {
      block_row.clear();
      double bulk = 0, volume = 0;
      for (const int* e = first; e != past; ++e) {
        if (dim == 2) {
          bulk = assemble_element(*e, v2);
          for (double w : v2.JxW) volume += w;
        } else {
          bulk = assemble_element(*e, v3);
          for (double w : v3.JxW) volume += w;
        }
      }
      if (bulk == 0.0) return;  // a block lies in one patch: one material, one formulation
      std::sort(block_row.begin(), block_row.end(),
                [](const auto& x, const auto& y) { return x.first < y.first; });
      block_dof.clear();  // the block's dofs, each once, and g_b on them
      g.resize(Eigen::Index(block_row.size()));
      for (const auto& [dof, value] : block_row) {
        if (!block_dof.empty() && block_dof.back() == dof) {
          g[Eigen::Index(block_dof.size()) - 1] += value;
          continue;
        }
        g[Eigen::Index(block_dof.size())] = value;
        block_dof.push_back(dof);
      }
      const int n = int(block_dof.size());
      g.conservativeResize(n);
      block_eq.resize(size_t(n));
      for (int c = 0; c < n; ++c) block_eq[size_t(c)] = dofs.equation(block_dof[size_t(c)]);
      const RankOne Kb{g, bulk / volume};
      for (int c = 0; c < n; ++c) {  // prescribed: lift its value into the right-hand side
        if (block_eq[size_t(c)] >= 0) continue;
        const double gv = dofs.prescribed_value(block_dof[size_t(c)]);
        if (gv != 0.0)
          for (int r = 0; r < n; ++r)
            if (block_eq[size_t(r)] >= 0) f[block_eq[size_t(r)]] -= Kb(r, c) * gv;
      }
      scatter_element_matrix(s.K, val, block_eq, Kb);
    };
    for (const std::vector<int>& colour : colours) {
      const int n_colour = int(colour.size());
#pragma omp for schedule(dynamic, 16)
      for (int idx = 0; idx < n_colour; ++idx) {
        if (by_blocks) {
          const int b = colour[idx];
          assemble_unit(blocks.elements.data() + blocks.start[b], blocks.elements.data() + blocks.start[b + 1]);
        } else {
          assemble_unit(&colour[idx], &colour[idx] + 1);
        }
      }
    }
  }
  s.min_det_J = min_det;
  if (!(s.min_det_J > 0))
    throw std::runtime_error(fmt::format("the geometry map folds: det J = {:.3g} at a Gauss point", s.min_det_J));
  return s;
}

ElementRange whole_blocks(const ElementBlocks& blocks, ElementRange range) {
  const int n = blocks.num_elements();
  // reach[c]: one past the last element of any block with an element below c;
  // c is a cut between blocks when reach[c] <= c
  std::vector<int> last(size_t(blocks.num_blocks()), -1);
  for (int e = 0; e < n; ++e) last[size_t(blocks.block_of[size_t(e)])] = e;
  const auto next_cut = [&](int c) {
    c = std::clamp(c, 0, n);
    int reach = 0;
    for (int e = 0; e < n; ++e) {
      if (e >= c && reach <= e) return e;
      reach = std::max(reach, last[size_t(blocks.block_of[size_t(e)])] + 1);
    }
    return n;
  };
  const int end = range.end < 0 ? n : next_cut(range.end);
  return {std::min(next_cut(range.begin), end), range.end < 0 ? -1 : end};
}

void add_pressure_load(const Body& body, const DofMap& dofs, const std::vector<PatchSide>& faces,
                       double pressure, Eigen::VectorXd& f) {
  add_dead_pressure(body, dofs, faces, pressure, f);  // the one face loop of the pressure loads
}

}  // namespace igac
