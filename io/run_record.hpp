// What a case is made into and what a run of it produces: the model (the
// case, the refined geometry, the dofs, the law, the contacts) and the
// result (displacements, contact multipliers and reports, errors, timings,
// load steps).  Plain data: app/case_run builds and solves them, the writers
// here (json_out, vtk_output) put them in files.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact/pressure.hpp"
#include "contact/small_strain_contact.hpp"
#include "engine/error_norms.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/load_stepping.hpp"
#include "io/case_file.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {

struct Model {
  CaseSpec spec;
  Body body;  // the refined patches, joined C0 across their interfaces
  // Named faces: the built-in shape's names (on patch 0) and the case's
  // [faces] sets; "PATCH:SIDE" and u0 ... w1 are found by find_faces.
  std::map<std::string, std::vector<PatchSide>> faces;
  std::unique_ptr<DofMap> dofs;
  LinearElastic material{1.0, 0.0};
  std::unique_ptr<HyperelasticLaw> law;  // the case's law (small strain too: the ParaView stress)
  // [contact] / [[contact]]: each face with its obstacle; the multipliers of
  // all of them are stacked in this order.
  struct Contact {
    std::string face_name;
    std::unique_ptr<ContactFace> face;
    std::unique_ptr<Obstacle> obstacle;  // where it stands (small deformation: after its motion)
    Eigen::VectorXd motion;              // large deformation: the obstacle is moved by t * motion
  };
  std::vector<Contact> contacts;
  double mesh_size = 0;  // largest element diameter
  bool quiet = false;    // no progress lines
  std::vector<std::string> warnings;  // where the case contradicts itself (printed unless quiet)
  int num_multipliers() const {
    int m = 0;
    for (const auto& c : contacts) m += c.face->num_multipliers();
    return m;
  }
};

struct ContactResult {
  ContactSolution solution;
  WeightedGapOperator op;
  Eigen::VectorXd X0, normal;
  PressureReport report;
  std::unique_ptr<ContactPressure> pressure;
};

// The force each obstacle exerts on the body: -sum_K lambda_K K_K over its
// multipliers (the normal force, per unit thickness in 2D, on the modelled part).
struct ObstacleReaction {
  std::string face, obstacle;
  double normal_force = 0;
  int active = 0;
};

struct Timing {
  double setup = 0, assembly = 0, factorization = 0, linear_solve = 0, contact = 0, postprocess = 0, total = 0;
};

// One point of the load curve of a large-deformation run.
struct LoadCurvePoint {
  double load_factor = 0;
  double contact_force = 0;    // sum_K -lambda_K K_K (modelled part)
  double face_displacement = 0;  // mean displacement of the loaded face along the last axis
  double obstacle_displacement = 0;  // how far a moving obstacle has moved (t |motion|)
};

// Who solved the linear systems, and how (summary.json "solver").
struct LinearSolverRecord {
  std::string type = "direct";        // direct | petsc
  std::string method;                 // e.g. "preonly + cholesky (mumps)", "fgmres + fieldsplit"
  std::vector<int> iterations;        // Krylov iterations per active-set iteration
  int ranks = 1;
  double peak_resident_all_ranks_gib = 0;
};

struct RunResult {
  std::string status = "converged";
  Eigen::MatrixXd u;  // n_cp x dim
  std::unique_ptr<ContactResult> contact;  // the first contact's pressure and report (Hertz, pressure.csv, VTK)
  std::vector<ObstacleReaction> reactions;  // every contact, in case order
  std::optional<HertzSolution> hertz;
  std::optional<ErrorNorms> displacement_errors;           // against a closed form
  std::optional<std::pair<double, double>> pressure_error;  // against Hertz: (error, norm)
  double applied_force = 0;                                 // resultant of the pressure loads (modelled part)
  std::optional<LoadSteppingSummary> load_steps;            // large deformation only
  std::vector<LoadCurvePoint> load_curve;
  double half_width_deformed = 0, max_pressure_cauchy = 0;  // large deformation contact
  Timing timing;
  LinearSolverRecord linear_solver;
};

// pressure.csv and pressure.svg scale r by Hertz's a and p by its p0 when
// the case has Hertz and both are positive (a zero load has no Hertz scale).
inline bool has_hertz_scale(const RunResult& r) { return r.hertz && r.hertz->a > 0 && r.hertz->p0 > 0; }

}  // namespace igac
