// SPDX-License-Identifier: BSD-3-Clause
#include "model/reactions.hpp"
#include "model/solve.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "engine/assembly.hpp"
#include "engine/follower_pressure.hpp"

namespace igac {

ReactionEvaluator::ReactionEvaluator(const Model& m) : model_(m), all_free_(m.body, {}) {
  const HyperelasticLaw* law = m.law.get();
  if (!law) {  // a Model made in code: the linear law of its Lame constants
    const double l = m.material.lambda(), mu = m.material.mu();
    own_law_ = make_law("linear_elastic", MaterialParameters{mu * (3 * l + 2 * mu) / (l + mu), l / (2 * (l + mu)), {}});
    law = own_law_.get();
  }
  // Small deformation with bodies of several materials or the mixed
  // formulation: f_int = K u of the solve's own assembler (one material and
  // formulation per patch); otherwise the law's internal force.
  const std::vector<Formulation> formulations = m.patch_formulations();
  const bool mixed = std::any_of(formulations.begin(), formulations.end(), is_mixed);
  if (!m.spec.finite_strain() && (m.parts.size() > 1 || mixed))
    linear_K_ = assemble_linear_elasticity(m.body, all_free_, m.patch_materials(),
                                           Eigen::VectorXd::Zero(m.body.space_dim()), {}, formulations).K;
  else if (m.parts.size() > 1)  // several hyperelastic bodies: each patch with its body's law
    assembler_ = std::make_unique<TotalLagrangianAssembler>(m.body, all_free_, m.patch_laws(), formulations, false);
  else
    assembler_ = std::make_unique<TotalLagrangianAssembler>(m.body, all_free_, *law, m.spec.formulation, false);
  const int dim = m.body.space_dim();
  std::set<int> claimed;  // equations of all_free_ already some face set's
  for (const DirichletSpec& d : m.spec.dirichlet)
    for (const std::string& name : d.faces) {
      size_t k = std::find(faces_.begin(), faces_.end(), name) - faces_.begin();
      if (k == faces_.size()) {
        faces_.push_back(name);
        equations_.emplace_back();
      }
      for (const PatchSide& side : resolve_faces(m, {name}, "dirichlet"))
        for (int cp : m.body.side_control_points(side)) {
          const int dof = cp * dim + d.component;
          if (m.dofs->equation(dof) >= 0) continue;  // not prescribed after all
          if (claimed.insert(all_free_.equation(dof)).second) equations_[k].push_back({all_free_.equation(dof), d.component});
        }
    }
  for (const PressureSpec& p : m.spec.pressure) pressure_faces_.push_back(resolve_faces(m, p.faces, "pressure"));
}

std::vector<FaceReaction> ReactionEvaluator::operator()(const Eigen::MatrixXd& u, double t,
                                                        const Eigen::VectorXd& contact_forces,
                                                        const std::vector<FaceElementFlags>& wet) const {
  std::vector<FaceReaction> out;
  if (faces_.empty()) return out;
  const Model& m = model_;
  const int dim = m.body.space_dim();
  Eigen::VectorXd residual;
  if (assembler_) {
    if (!assembler_->assemble(u, residual, nullptr)) residual.setConstant(all_free_.num_free(), std::nan(""));
  } else {
    Eigen::VectorXd x(all_free_.num_free());
    for (int dof = 0; dof < all_free_.num_dofs(); ++dof) x[all_free_.equation(dof)] = u(dof / dim, dof % dim);
    residual = linear_K_ * x;
  }
  Eigen::VectorXd f_ext = Eigen::VectorXd::Zero(all_free_.num_free());
  for (size_t i = 0; i < pressure_faces_.size(); ++i) {
    const double p = m.spec.pressure[i].curve(t) * m.spec.pressure[i].value;
    const FaceElementFlags* mask = i < wet.size() && !wet[i].empty() ? &wet[i] : nullptr;
    if (m.spec.finite_strain() && m.spec.loading.follower_pressure)
      add_follower_pressure(m.body, all_free_, pressure_faces_[i], p, u, f_ext, nullptr, mask);
    else
      add_dead_pressure(m.body, all_free_, pressure_faces_[i], p, f_ext, mask);
  }
  add_traction_loads(m, all_free_, t, f_ext);
  if (!m.spec.body_force.empty())  // dead, per unit reference volume, in both kinematics
    f_ext += m.spec.body_force_curve(t) *
             body_force_load(m.body, all_free_, Eigen::Map<const Eigen::VectorXd>(m.spec.body_force.data(), dim));
  residual -= f_ext;
  // The dofs of a collapsed point share one equation and each holds its
  // force: added once per equation.
  std::vector<char> added(size_t(all_free_.num_free()), 0);
  for (int dof = 0; dof < int(contact_forces.size()); ++dof)
    if (const int eq = all_free_.equation(dof); !added[size_t(eq)]) {
      residual[eq] += contact_forces[dof];
      added[size_t(eq)] = 1;
    }
  for (size_t k = 0; k < faces_.size(); ++k) {
    FaceReaction r{faces_[k], Eigen::VectorXd::Zero(dim)};
    for (const auto& [eq, c] : equations_[k]) r.force[c] += residual[eq];
    out.push_back(std::move(r));
  }
  return out;
}

double driven_reaction(const Model& m, const std::vector<FaceReaction>& reactions) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(m.body.space_dim());
  bool driven = false;
  for (const DirichletSpec& d : m.spec.dirichlet) {
    if (d.value == 0) continue;
    for (const FaceReaction& r : reactions)
      if (std::find(d.faces.begin(), d.faces.end(), r.face) != d.faces.end()) {
        sum[d.component] += r.force[d.component];
        driven = true;
      }
  }
  return driven ? sum.norm() : 0.0;
}

}  // namespace igac
