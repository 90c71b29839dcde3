// SPDX-License-Identifier: BSD-3-Clause
#include "model/solver_choice.hpp"

#include <fmt/format.h>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "model/memory_estimate.hpp"

namespace igac {

namespace {

// The tokens of a PETSc options string.
std::vector<std::string> tokens_of(const std::string& options) {
  std::istringstream in(options);
  std::vector<std::string> out;
  for (std::string t; in >> t;) out.push_back(t);
  return out;
}

// Whether `auto` takes the spline multigrid for this case; `why` says why,
// either way.
bool multigrid_is_faster(const CaseSpec& c, double memory_bytes, std::string& why) {
  if (c.dim() != 3) {
    why = "2D, where a factorisation was the faster at every size measured";
    return false;
  }
  for (const std::string& t : tokens_of(c.solver.options))
    if (t == "-pc_type" || t == "-ksp_type") {
      why = fmt::format("the options name {}", t);
      return false;
    }
  CaseSpec multigrid = c;
  multigrid.solver.preconditioner = Preconditioner::spline_multigrid;
  multigrid.solver.automatic = false;
  if (const std::string refused = check_petsc_case(multigrid); !refused.empty()) {
    why = "the spline multigrid does not run this case: " + refused.substr(0, refused.find(';'));
    return false;
  }
  if (c.refine < 1) {
    why = "--refine 0, no coarser mesh for a multigrid";
    return false;
  }
  const double unknowns = c.dim() * estimated_mesh(c).control_points;
  if (unknowns >= kMultigridUnknowns) {
    why = fmt::format("3D, about {:.0f} unknowns ({:.0f} or more)", unknowns, kMultigridUnknowns);
    return true;
  }
  const double factor = estimated_peak_bytes(c), levels = estimated_peak_bytes(multigrid);
  if (factor > memory_bytes && levels <= memory_bytes) {
    why = fmt::format("3D, about {:.0f} unknowns, and a factorisation would need about {:.3g} GiB, more than "
                      "this machine's {:.1f}",
                      unknowns, factor / (1 << 30), memory_bytes / (1 << 30));
    return true;
  }
  why = fmt::format("3D, about {:.0f} unknowns (fewer than {:.0f})", unknowns, kMultigridUnknowns);
  return false;
}

// -u_pc_mg_levels L asks for the L finest of the case's --refine + 1 meshes.
void check_multigrid_levels(const CaseSpec& c) {
  const std::vector<std::string> t = tokens_of(c.solver.options);
  for (size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i] != "-u_pc_mg_levels") continue;
    char* end = nullptr;
    const long levels = std::strtol(t[i + 1].c_str(), &end, 10);
    if (*end != '\0' || levels < 1 || levels > c.refine + 1)
      throw InputError(fmt::format("{}: PETSc option -u_pc_mg_levels {}: the spline multigrid of --refine {} has "
                                   "1 to {} levels (the case's meshes --refine {}, ..., 0)",
                                   c.path, t[i + 1], c.refine, c.refine + 1, c.refine));
  }
}

}  // namespace

std::string check_petsc_case(const CaseSpec& c) {
  // Both multigrids need the multipliers apart from the displacements
  // (the field split's fields, the spline multigrid's block triangular
  // preconditioner); friction and ties solve them in one block.
  if (c.solver.algebraic_multigrid() || c.solver.spline_multigrid())
    for (const ContactSpec& cs : c.contacts)
      if (cs.friction > 0 || (!cs.law.empty() && cs.law != "frictionless"))
        return fmt::format("the {} needs the multipliers apart from the displacements, and the {} of contact face "
                           "'{}' solves them in one block with the displacements; leave preconditioner at "
                           "\"options\" (default MUMPS LU)",
                           c.solver.spline_multigrid() ? "spline multigrid" : "algebraic multigrid's field split",
                           cs.friction > 0 ? fmt::format("friction = {:g}", cs.friction) : "law \"" + cs.law + "\"",
                           cs.face);
  // Large deformation: every Newton step's linear solve in PETSc
  // (solvers/petsc_newton.hpp), whatever the contacts, laws and curves.
  if (c.finite_strain()) return {};
  if (c.has_load_curves() && c.solver.spline_multigrid())
    return "the spline multigrid preconditions a small-deformation run without load curves only (the case has a "
           "curve); leave preconditioner at \"options\"";
  return {};
}

std::string unknown_preconditioner(const std::string& name) {
  return fmt::format("unknown preconditioner '{}' (options: as [solver] options say, default MUMPS; "
                     "spline_multigrid: geometric multigrid over the nested meshes; algebraic_multigrid: FGMRES "
                     "with a field split, GAMG on the displacements; auto: one of the first two, chosen for the "
                     "mesh)", name);
}

std::string check_preconditioner(const SolverSpec& s) {
  if (s.automatic && !s.petsc()) return "auto chooses among PETSc's preconditioners: needs type = \"petsc\"";
  if (s.spline_multigrid() && !s.petsc())
    return "spline_multigrid runs in the PETSc solver: needs type = \"petsc\"";
  if (s.algebraic_multigrid() && !s.petsc())
    return "algebraic_multigrid runs in the PETSc solver: needs type = \"petsc\"";
  return {};
}

bool set_preconditioner(SolverSpec& solver, std::string_view name) {
  if (name == "auto") {
    solver.automatic = true;
    solver.preconditioner = Preconditioner::options;  // until settle_preconditioner knows the mesh
    return true;
  }
  const auto p = preconditioner_named(name);
  if (!p) return false;
  solver.automatic = false;
  solver.choice.clear();
  solver.preconditioner = *p;
  return true;
}

void settle_preconditioner(CaseSpec& c, double memory_bytes) {
  SolverSpec& s = c.solver;
  if (s.automatic) {
    std::string why;
    const bool multigrid = multigrid_is_faster(c, memory_bytes, why);
    s.preconditioner = multigrid ? Preconditioner::spline_multigrid : Preconditioner::options;
    s.choice = fmt::format("auto chose {}: {}", multigrid ? "the spline multigrid" : "MUMPS", why);
  }
  if (s.spline_multigrid()) check_multigrid_levels(c);
}

}  // namespace igac
