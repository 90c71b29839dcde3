// From a case to a solution: build the refined patch, the dofs and the loads,
// then solve — one Cholesky solve for a linear case, the active-set contact
// solve when the case has an obstacle.  No Newton loop, no multipliers and no
// stress recovery unless the case needs them.
#pragma once

#include <functional>
#include <memory>
#include <optional>

#include "contact/pressure.hpp"
#include "engine/load_stepping.hpp"
#include "materials/hyperelastic.hpp"
#include "contact/small_strain_contact.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/error_norms.hpp"
#include "io/case_file.hpp"

namespace igac {

struct Model {
  CaseSpec spec;
  Geometry geometry;  // geometry.patch is the refined patch
  std::unique_ptr<DofMap> dofs;
  LinearElastic material{1.0, 0.0};
  std::unique_ptr<HyperelasticLaw> law;  // large deformation only
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
    for (const auto& c : contacts) m += c.face->space.size();
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
};

Model build_model(const CaseSpec& spec);
// `on_step` (large deformation) sees the state after each converged load step.
using StepObserver = std::function<void(const RunResult&, double load_factor)>;
RunResult solve_model(const Model& model, const StepObserver& on_step = {});
// The large-deformation path (io/finite_strain_run.cpp).
RunResult solve_finite_strain(const Model& model, const StepObserver& on_step);

// Throws InputError (naming the case) when free rigid motions (`modes`, not
// held by Dirichlet conditions) are not held: no contact, a contact that
// cannot stop them, or a load `f` that pulls the body off the obstacle.
void check_body_is_held(const Model& model, const RigidModes& modes, const Eigen::VectorXd& f);
// The stacked weighted-gap operator of every contact (small deformation).
WeightedGapOperator assemble_contact_operator(const Model& model);
// Per contact: the normal force -sum lambda_K K_K of its multipliers and how many are active.
std::vector<ObstacleReaction> obstacle_reactions(const Model& model, const Eigen::VectorXd& lambda,
                                                const Eigen::VectorXd& weights, const std::vector<char>& active);
// |int P n dGamma| summed over the pressure loads (the modelled part).
double pressure_resultant(const Model& model);
// Closed-form displacement of the case's reference solution, if it has one.
std::optional<ExactDisplacement> exact_displacement(const CaseSpec& spec);

}  // namespace igac
