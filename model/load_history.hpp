// SPDX-License-Identifier: BSD-3-Clause
// Load histories: what the two solve paths share to follow the loads along
// their curves (engine/load_curve.hpp) and to record the load curve, and
// the small-deformation path along curves.
//
// Small deformation with load curves (docs/case_file.md, "Load curves"):
// the loads are linear in their factors, so the right-hand side at time t is
//   f(t) = c_b(t) f_b + sum_i c_i(t) f_i + sum_j c_j(t) l_j,
// f_b the body force, f_i the pressure loads, l_j = -K_fp u_p^j the lift of
// the values of the j-th [[dirichlet]] condition alone (each assembled once);
// K is factorised once.  At each step time (every corner a step) the
// solution is solved afresh at f(t) with each moving obstacle at c(t) motion:
// without contact one back-substitution, with it the active-set iteration
// from the closed gaps, so the active set is decided anew at every step
// (unloading opens the contact it closed).  Frictionless: the path does not
// matter, the steps are the frames of the history.
#pragma once

#include <vector>

#include "model/model.hpp"
#include "model/run_result.hpp"
#include "model/solve.hpp"

namespace igac {

// Per dof of m.dofs, the curve of the [[dirichlet]] condition that
// prescribes its value (the last one in case order, as DofMap applies
// them); empty when the case has no load curves.
std::vector<const LoadCurve*> prescribed_curves(const Model& model);

// What the load curve follows: the loaded faces (the pressure's, else the
// face a moving obstacle pushes, else the faces of nonzero prescribed
// values) and the first moving obstacle.
struct LoadCurveProbe {
  std::vector<PatchSide> faces;
  const Model::Contact* mover = nullptr;
  explicit LoadCurveProbe(const Model& model);
  // Mean of the last displacement component over the faces (reference measure).
  double face_displacement(const Body& body, const Eigen::MatrixXd& u) const;
  // How far the moving obstacle has moved at time t: curve(t) |motion|
  // (negative where the curve reverses the motion).
  double obstacle_displacement(double t) const;
};

// The small-deformation path of a case with load curves (above).
RunResult solve_small_strain_history(const Model& model, const RunControl& control);

}  // namespace igac
