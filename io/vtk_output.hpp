// SPDX-License-Identifier: BSD-3-Clause
// ParaView output: VTK XML unstructured grids of exact rational Bezier cells
// (written with VTK's vtkXMLUnstructuredGridWriter), one set per load step,
// and a .pvd collection that plays the loading.
//
// Files of step k in DIR (XXXX = k, zero-padded):
//   solution_XXXX.vtu   the body.  Every NURBS element, Bezier-extracted
//       (engine/spline/bezier_extraction.hpp), is one VTK_BEZIER_QUADRILATERAL
//       (2D) or VTK_BEZIER_HEXAHEDRON (3D) cell whose points are the element's
//       Bezier control points (z = 0 in 2D), with
//         point data "RationalWeights" (the active rational weights) and
//         cell data "HigherOrderDegrees" (the active degrees, 3 components),
//       so ParaView draws the exact geometry (circles stay circles).
//       Points are not shared between cells: each cell has its own copy of
//       its boundary points (geometry and displacement agree on both copies;
//       the recovered stress does not, and must not).
//       Point fields:
//         "displacement"  3 components (z = 0 in 2D): Warp By Vector shows
//                         the deformed body; exact (the displacement's own
//                         Bezier coefficients).
//         "stress"        Cauchy stress, 6 components XX YY ZZ XY YZ XZ
//                         (ParaView's symmetric tensor order);
//                         linear elastic sigma = lambda tr(eps) I + 2 mu eps,
//                         plane strain in 2D (eps_zz = 0, sigma_zz = lambda tr eps).
//         "von_mises"     sqrt(3/2 s:s), s the deviator of sigma.
//         "stress_magnitude"  the Frobenius norm |sigma| = sqrt(sigma:sigma),
//                         the "stress magnitude" of the paper's figures.
//         "J"             det F (1 + tr eps to first order in small strain):
//                         where the body kept its volume.
//         "hydrostatic_pressure"  -tr(sigma)/3; with formulation = "mixed"
//                         the formulation's projected pressure
//                         (model/field_recovery.hpp: recover_body_fields).
//         "principal_stress"  3 components sigma_1 >= sigma_2 >= sigma_3.
//         "strain"        6 components as "stress" (tensor components, not
//                         engineering shear): eps = sym grad u in small
//                         deformation, Green-Lagrange E = (F^T F - I)/2 in
//                         large deformation; zz = 0 in 2D (plane strain).
//         "patch"         the patch number of the point's cell (also as
//                         cell data "patch").
//       How stress reaches the Bezier points: the stress is discontinuous
//       between elements, so it is brought onto each element by an
//       element-local L2 projection onto the element's rational Bezier basis
//       R_i (the basis ParaView interpolates point data with):
//           sum_j (int_e R_i R_j dX) c_j = int_e R_i f dX,
//       Gauss rule with max(p)+2 points per direction, for f each stress
//       component.  A stress in the span of the R_i -- in particular a
//       constant one (patch test) -- is reproduced exactly; otherwise the
//       projection is the element's best L2 approximation.  Von Mises and
//       |sigma| are not projected themselves (the projection of a
//       nonnegative scalar dips below zero next to steep gradients): their
//       Bezier coefficients are the scalar of the tensor's coefficients, so
//       they are never negative, exact at element corners, and (both are
//       convex in sigma) never below the scalar of the drawn tensor
//       (model/field_recovery.hpp).  This runs only when output is written.
//   contact_XXXX.vtu    (contact cases) the contact face Gamma_C, Bezier
//       extracted the same way: VTK_BEZIER_CURVE cells in 2D,
//       VTK_BEZIER_QUADRILATERAL in 3D, with
//         point data "displacement" (exact) and "pressure" p_h = -lambda_h
//                    (element-local L2 projection of sum_K -lambda_K B_K;
//                    exact for S0, one constant per element);
//         point data "traction" (3 components: the projection of p_h n, the
//                    force per area the contact exerts on the body, n the
//                    obstacle's unit normal at the deformed point, or minus
//                    the face's outward normal against a second body) and,
//                    against an obstacle, "normal_gap" (projection of the
//                    signed distance g_n(X + u) of the deformed face, a length);
//         cell data  "normal_gap" (element mean of g_n(X + u), or against a
//                    second body of sum_K (Pi g)_K / K_K B_K: a length),
//                    "pressure" (element mean of p_h over the reference face;
//                    for S0 exactly -lambda_K), "weighted_gap" (element mean
//                    of sum_K (Pi g)_K B_K; for S0 exactly (Pi g)_K) and
//                    "active" (1 when a multiplier whose support meets the
//                    element is active; for S0 exactly the multiplier's flag).
//   multipliers_XXXX.vtu  (contact cases) one VTK_VERTEX per multiplier K at
//       its anchor (Greville point on the reference face), with point data
//       "lambda", "pressure" = -lambda_K, "weighted_gap" = (Pi g)_K,
//       "active", "weight" = int B_K dGamma, "normal_gap" = (Pi g)_K / K_K
//       (a length), "displacement": exact values for any degree.
//   With several contacts, each has its own two files, named after its face
//   (io/json_out.hpp, contact_file_tags): contact_<face>_XXXX.vtu and
//   multipliers_<face>_XXXX.vtu, in case order.
//   solution.pvd        a Collection with one DataSet per file and step:
//       step 0 (`igac run`) is the undeformed body alone at timestep 0, then
//       one step per load step (small deformation: one, step 1);
//       timestep = the step's load factor, part 0 body (name "body"), 1
//       contact face ("contact_face"), 2 multipliers ("multipliers"); with
//       several contacts, parts 1, 2 the first contact's ("contact_face_<face>",
//       "multipliers_<face>"), 3, 4 the second's, and so on (ParaView opens it
//       as a multiblock per time).
// A value that is not finite is never written: writing throws
// std::runtime_error naming the file and the array.  Each file is written to
// a temporary name and renamed, so a file that exists is complete.
#pragma once

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/spline/bezier_extraction.hpp"
#include "model/model.hpp"
#include "model/run_result.hpp"

namespace igac {

// The files of one load step (names relative to the output folder).
struct VtkStep {
  int step = 0;
  double load_factor = 1.0;
  std::vector<std::string> files;  // body, then each contact's face and multipliers
  std::vector<std::string> parts;  // the .pvd's name of each file: body, contact_face, multipliers (_<face>)
};

// Writes the .vtu files of one step into dir (created if missing).
VtkStep write_vtk(const std::string& dir, const Model& model, const RunResult& result, int step_index,
                  double load_factor);
// Writes dir/solution.pvd listing every step's files.
void write_pvd(const std::string& dir, const std::vector<VtkStep>& steps);

// A load-step series: write_step() writes the step's files and rewrites the
// .pvd, so an interrupted run leaves a collection of the steps it finished.
class VtkSeries {
 public:
  explicit VtkSeries(std::string dir) : dir_(std::move(dir)) {}
  const VtkStep& write_step(const Model& model, const RunResult& result, double load_factor);
  const std::vector<VtkStep>& steps() const { return steps_; }
  // A restart: the series goes on after `earlier` (files already in dir).
  void resume(std::vector<VtkStep> earlier) { steps_ = std::move(earlier); }

 private:
  std::string dir_;
  std::vector<VtkStep> steps_;
};

}  // namespace igac
