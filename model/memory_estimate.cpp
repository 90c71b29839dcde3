// SPDX-License-Identifier: BSD-3-Clause
#include "model/memory_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include "model/case_body.hpp"
#include "model/solver_choice.hpp"

namespace igac {

namespace {

// One direction of one patch after refine_patch (model/build_model.cpp):
// the requested breakpoints (uniform or graded, each span split 2^refine
// times) united with the coarse patch's own, the patch's knots keeping
// their multiplicity raised by the degree elevation.  Counted, not built:
// a refinement far beyond the machine costs nothing here.
void count_direction(const BodySpec& c, const KnotVector* own, int d, double& spans, double& basis) {
  const int p = std::max(c.degree, own ? own->degree() : 0);
  const int e = c.elements[d];
  std::vector<double> coarse;  // the requested breakpoints before refine, on [0, 1]
  for (const GradingSpec& g : c.gradings)
    if (g.direction == d) try {
        coarse = KnotVector::graded(std::max(c.degree, 1), e, g.span_fraction, g.range_fraction, g.at_start,
                                    g.geometric_coarse ? KnotVector::CoarseSpans::geometric
                                                       : KnotVector::CoarseSpans::uniform)
                     .breakpoints();
      } catch (const SplineError&) {
        coarse.clear();  // build_model says what is wrong with it
      }
  if (coarse.empty())
    for (int i = 0; i <= e; ++i) coarse.push_back(double(i) / e);
  const double parts = std::ldexp(1.0, std::min(c.refine, 60));
  spans = e * parts;
  basis = spans + p;  // simple interior knots
  if (!own) return;
  const std::vector<double> b = own->breakpoints();
  const std::vector<int> mult = own->multiplicities();
  const double first = b.front(), length = b.back() - b.front();
  for (size_t i = 1; i + 1 < b.size(); ++i) {
    const double x = (b[i] - first) / length;  // build_model normalises the patch's knots to [0, 1]
    const size_t j = std::min<size_t>(std::upper_bound(coarse.begin(), coarse.end(), x) - coarse.begin(), coarse.size() - 1) - 1;
    const double h = coarse[j + 1] - coarse[j];
    const double nearest = coarse[j] + std::round((x - coarse[j]) / h * parts) / parts * h;
    const bool shared = std::abs(x - nearest) <= 1e-10;  // KnotVector::united_with's snap
    const int m = mult[i] + p - own->degree();           // after elevation to degree p
    if (!shared) spans += 1;
    basis += shared ? m - 1 : m;
  }
}

}  // namespace

namespace {
MeshCount estimated_body_mesh(const CaseSpec& spec, const BodySpec& c) {
  MeshCount n;
  {
    MultiPatch coarse;
    try {
      coarse = body_patches(spec, c);
    } catch (const std::exception&) {
      coarse = {};  // build_model says what is wrong; count the requested mesh alone
    }
    const size_t patches = std::max<size_t>(coarse.patches.size(), 1);
    for (size_t k = 0; k < patches; ++k) {
      double elements = 1, points = 1;
      for (int d = 0; d < int(c.elements.size()); ++d) {
        const bool own = k < coarse.patches.size() && d < coarse.patches[k].param_dim();
        double spans = 0, basis = 0;
        count_direction(c, own ? &coarse.patches[k].knots(d) : nullptr, d, spans, basis);
        elements *= spans;
        points *= basis;
      }
      n.elements += elements;
      n.control_points += points;  // an interface's points counted on both sides
    }
  }
  return n;
}
}  // namespace

MeshCount estimated_mesh(const CaseSpec& spec) {
  MeshCount n;
  for (const BodySpec& c : spec.body_list()) {
    const MeshCount b = estimated_body_mesh(spec, c);
    n.elements += b.elements;
    n.control_points += b.control_points;
  }
  return n;
}

double estimated_peak_bytes(const CaseSpec& c) {
  // Stiffness nonzeros, and the Cholesky factor: its fill was measured at
  // ~10 x nnz(K)/2 in 2D (slowly growing) and ~7 x nnz(K)/2 at 18k dofs in
  // 3D, where the model takes 8 and grows it like dofs^(1/3) (nested
  // dissection); times kCalibration, fitted so that
  // the estimate covers the peak resident memory measured by
  // bench/memory_guard.py (docs/benchmarks.md, "Memory guard").
  constexpr double kCalibration = 1.35;
  constexpr double kBase = 80.0 * (1 << 20);  // the program itself: libraries, VTK, tables
  const double cps = estimated_mesh(c).control_points;
  const int dim = c.dim();
  const double dofs = cps * dim;
  // A row couples the control points within 2p + 1 per direction (those
  // sharing an element), or with the mixed formulation's sub-grid pressure
  // (engine/pressure_space.hpp) those sharing a pressure function's support
  // of 2p elements: 6p - 1 per direction (the highest of the bodies': an
  // upper bound).
  double window = 0;
  for (const BodySpec& b : c.body_list())
    window = std::max(window, b.formulation == Formulation::mixed ? 6.0 * b.degree - 1 : 2.0 * b.degree + 1);
  const double nnz = dofs * std::pow(window, dim) * dim;
  // 2D: the fill of nested dissection grows slowly (measured: +10 % per doubling of the dofs beyond 33k).
  const double fill = dim == 2 ? 10.0 * (1 + 0.1 * std::max(0.0, std::log2(std::max(dofs, 1.0) / 33000.0)))
                               : 8.0 * std::cbrt(std::max(dofs, 1.0) / 18000.0);
  // PETSc with multigrid: no factor; the matrix, its copies (assembly,
  // PETSc, the saddle-point matrix) and the multigrid hierarchy.  PETSc
  // with a factorisation (MUMPS, the default): a factor as CHOLMOD's.
  const std::string& o = c.solver.options;
  const bool multigrid = o.find("gamg") != std::string::npos || o.find("hypre") != std::string::npos ||
                         o.find("-pc_type ml") != std::string::npos;
  if (c.solver.petsc() && multigrid) return kBase + kCalibration * 4 * 12 * nnz;
  // The spline multigrid: K, on several processes PETSc's copy of it (one
  // process works on K's arrays), the Galerkin levels, the ICC factors and
  // on several processes the overlap of their subdomains.  The factors
  // (one process, several) are set from the peaks of hertz3d level 3
  // (225k dofs) on one and two processes (measured: docs/petsc.md,
  // "Measured").
  if (c.solver.petsc() && c.solver.spline_multigrid()) {
    const bool several = c.solver.processes > 1;
    return kBase + kCalibration * (several ? 4.9 : 2.3) * 12 * nnz;
  }
  return kBase + kCalibration * (12 * nnz + 10 * fill * nnz / 2);
}

double physical_memory_bytes() { return double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE)); }

void apply_overrides(CaseSpec& c, std::optional<int> degree, std::optional<int> refine) {
  if (degree) {
    if (*degree < 1 || *degree > 10) throw InputError(fmt::format("--degree {}: must lie in 1..10", *degree));
    if (!c.contacts.empty() && *degree < 2) throw InputError(fmt::format("--degree {}: contact needs degree >= 2", *degree));
    c.degree = *degree;
    for (BodySpec& b : c.bodies) b.degree = *degree;
  }
  if (refine) {
    if (*refine < 0) throw InputError(fmt::format("--refine {}: must be >= 0", *refine));
    c.refine = *refine;
  }
  // The solver for this mesh (preconditioner = "auto"), which the memory
  // estimate depends on.
  settle_preconditioner(c);
  // Memory check before anything is built.
  const double bytes = estimated_peak_bytes(c);
  const MeshCount mesh = estimated_mesh(c);
  const double elements = mesh.elements, dofs = c.dim() * mesh.control_points;
  const double physical = physical_memory_bytes();
  if (bytes < physical && elements <= 2e9) return;
  const std::string need = fmt::format("{:.3g} elements and {:.3g} unknowns need about {:.3g} GiB, more than this "
                                       "machine's {:.1f} GiB",
                                       elements, dofs, bytes / (1 << 30), physical / (1 << 30));
  if (refine) throw InputError(fmt::format("{}: --refine {}: {}", c.path, *refine, need));
  // The key that makes the mesh: the refine, else the elements, of the
  // body with the most elements ([mesh], or its [body.mesh]).
  const std::vector<BodySpec> bodies = c.body_list();
  size_t big = 0;
  double most = -1;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (const double e = estimated_body_mesh(c, bodies[i]).elements; e > most) {
      most = e;
      big = i;
    }
  const BodySpec& b = c.bodies.empty() ? static_cast<const BodySpec&>(c) : c.bodies[big];
  const char* table = c.bodies.empty() ? "mesh" : "body.mesh";
  const std::string which = c.bodies.empty() ? "" : fmt::format(" (body '{}')", b.body_name);
  if (b.refine > 0)
    throw InputError(fmt::format("{}: [{}] refine = {}{}: {}", c.where(b, "mesh", "refine"), table, b.refine, which, need));
  throw InputError(fmt::format("{}: [{}] elements = [{}]{}: {}", c.where(b, "mesh", "elements"), table,
                               fmt::join(b.elements, ", "), which, need));
}

}  // namespace igac
