// SPDX-License-Identifier: BSD-3-Clause
#include "model/memory_estimate.hpp"

#include <cmath>
#include <fmt/format.h>
#include <unistd.h>

namespace igac {

double estimated_peak_bytes(const CaseSpec& c) {
  // Stiffness nonzeros, and the Cholesky factor: its fill was measured at
  // ~10 x nnz(K)/2 in 2D (slowly growing) and ~7 x nnz(K)/2 at 18k dofs in
  // 3D, where the model takes 8 and grows it like dofs^(1/3) (nested
  // dissection); times kCalibration, fitted so that
  // the estimate covers the peak resident memory measured by
  // bench/memory_guard.py (docs/benchmarks.md, "Memory guard").
  constexpr double kCalibration = 1.35;
  constexpr double kBase = 80.0 * (1 << 20);  // the program itself: libraries, VTK, tables
  double cps = 1;
  for (int e : c.elements) cps *= std::ldexp(double(e), std::min(c.refine, 60)) + c.degree;
  const int dim = c.dim();
  const double dofs = cps * dim;
  const double nnz = dofs * std::pow(2.0 * c.degree + 1, dim) * dim;
  // 2D: the fill of nested dissection grows slowly (measured: +10 % per doubling of the dofs beyond 33k).
  const double fill = dim == 2 ? 10.0 * (1 + 0.1 * std::max(0.0, std::log2(std::max(dofs, 1.0) / 33000.0)))
                               : 8.0 * std::cbrt(std::max(dofs, 1.0) / 18000.0);
  // PETSc with multigrid: no factor; the matrix, its copies (assembly,
  // PETSc, the saddle-point matrix) and the multigrid hierarchy.  PETSc
  // with a factorisation (MUMPS, the default): a factor as CHOLMOD's.
  const std::string& o = c.solver.options;
  const bool multigrid = o.find("gamg") != std::string::npos || o.find("hypre") != std::string::npos ||
                         o.find("-pc_type ml") != std::string::npos;
  if (c.solver.type == "petsc" && multigrid) return kBase + kCalibration * 4 * 12 * nnz;
  // The spline multigrid: K, on several processes PETSc's copy of it (one
  // process works on K's arrays), the Galerkin levels, the ICC factors and
  // on several processes the overlap of their subdomains.  The factors
  // (one process, several) are set from the peaks of hertz3d level 3
  // (225k dofs) on one and two processes (measured: docs/petsc.md,
  // "Measured").
  if (c.solver.type == "petsc" && c.solver.preconditioner == "spline_multigrid") {
    const bool several = c.solver.processes > 1;
    return kBase + kCalibration * (several ? 4.9 : 2.3) * 12 * nnz;
  }
  return kBase + kCalibration * (12 * nnz + 10 * fill * nnz / 2);
}

void apply_overrides(CaseSpec& c, std::optional<int> degree, std::optional<int> refine) {
  if (degree) {
    if (*degree < 1 || *degree > 10) throw InputError(fmt::format("--degree {}: must lie in 1..10", *degree));
    if (!c.contacts.empty() && *degree < 2) throw InputError(fmt::format("--degree {}: contact needs degree >= 2", *degree));
    c.degree = *degree;
  }
  if (refine) {
    if (*refine < 0) throw InputError(fmt::format("--refine {}: must be >= 0", *refine));
    c.refine = *refine;
  }
  // Memory check before anything is built.
  const double bytes = estimated_peak_bytes(c);
  double elements = 1;
  for (int e : c.elements) elements *= std::ldexp(double(e), std::min(c.refine, 60));
  double dofs = c.dim();
  for (int e : c.elements) dofs *= std::ldexp(double(e), std::min(c.refine, 60)) + c.degree;
  const double physical = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (!(bytes < physical) || elements > 2e9)
    throw InputError(fmt::format(
        "{}: [mesh] refine = {}: {:.3g} elements and {:.3g} unknowns need about {:.3g} GiB, more than this "
        "machine's {:.1f} GiB",
        c.path, c.refine, elements, dofs, bytes / (1 << 30), physical / (1 << 30)));
}

}  // namespace igac
