// SPDX-License-Identifier: BSD-3-Clause
#include "model/case_spec.hpp"

#include <algorithm>

namespace igac {

const CaseSource::Key* CaseSource::find(const Query& q) const {
  for (const Key& k : keys)
    if (k.table == q.table && (q.index < 0 || k.index == q.index) && (q.body < 0 || k.body == q.body) &&
        (q.key == "*" ? !k.key.empty() : k.key == q.key) &&
        (q.word.empty() || std::find(k.words.begin(), k.words.end(), q.word) != k.words.end()))
      return &k;
  return nullptr;
}

std::string CaseSource::at(const std::string& path, const Query& q) const {
  const Key* k = find(q);
  if (!k) {
    Query table = q;
    table.key = "";
    table.word.clear();
    k = find(table);
  }
  return k ? path + ":" + std::to_string(k->line) : path;
}

std::string CaseSpec::where(const BodySpec& b, const std::string& table, const std::string& key) const {
  if (b.body_name.empty()) return where({.table = table, .key = key});
  int index = -1;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].body_name == b.body_name) index = int(i);
  return where({.table = "body." + table, .key = key, .body = index});
}

std::optional<SolverType> solver_type_named(std::string_view name) {
  if (name == "direct") return SolverType::direct;
  if (name == "petsc") return SolverType::petsc;
  return std::nullopt;
}

std::optional<Preconditioner> preconditioner_named(std::string_view name) {
  if (name == "options") return Preconditioner::options;
  if (name == "spline_multigrid") return Preconditioner::spline_multigrid;
  if (name == "algebraic_multigrid") return Preconditioner::algebraic_multigrid;
  return std::nullopt;
}

std::optional<ModelKind> model_kind_named(std::string_view name) {
  if (name == "plane_strain") return ModelKind::plane_strain;
  if (name == "plane_stress") return ModelKind::plane_stress;
  if (name == "axisymmetric") return ModelKind::axisymmetric;
  return std::nullopt;
}

std::string_view name_of(ModelKind kind) {
  switch (kind) {
    case ModelKind::plane_stress: return "plane_stress";
    case ModelKind::axisymmetric: return "axisymmetric";
    case ModelKind::plane_strain: break;
  }
  return "plane_strain";
}

std::string_view name_of(SolverType type) { return type == SolverType::petsc ? "petsc" : "direct"; }

std::string_view name_of(Preconditioner p) {
  switch (p) {
    case Preconditioner::spline_multigrid: return "spline_multigrid";
    case Preconditioner::algebraic_multigrid: return "algebraic_multigrid";
    case Preconditioner::options: break;
  }
  return "options";
}

}  // namespace igac
