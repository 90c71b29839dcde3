// SPDX-License-Identifier: BSD-3-Clause
// A case as data: what a case file (io/case_file) or a program says to
// simulate, free of any file format.  model/build_model makes it a Model.
#pragma once

#include "contact/mortar_integration.hpp"

#include <map>
#include <memory>
#include <stdexcept>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/geometry/multipatch.hpp"
#include "engine/load_curve.hpp"
#include "engine/volumetric_projection.hpp"
#include "materials/hyperelastic.hpp"

namespace igac {

// Bad input: a one-line message naming the file, the key and the reason.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct GradingSpec {
  int direction = 0;
  bool at_start = true;
  double span_fraction = 0.8, range_fraction = 0.1;
  bool geometric_coarse = false;  // coarse = "geometric": the other spans grow from the fine size
};

// Every load (a prescribed value, a pressure, the body force, an obstacle's
// motion) is its value times the factor its curve gives at the time t
// (engine/load_curve.hpp): without curves in the case, t itself, ramped from
// 0 to 1; with curves, a load without one follows LoadCurve::ramp_and_hold().
// [faces.NAME] side = "...", range = ...: part of one side, a parameter
// range along it (fractions of the side's range, one [from, to] pair per
// direction along the side); the model cuts the patch where the range ends
// (engine/geometry/patch_partition.hpp).
struct PartialFaceSpec {
  std::string name, side;
  std::vector<std::array<double, 2>> range;
};

struct DirichletSpec {
  std::vector<std::string> faces;
  int component = 0;
  double value = 0;
  LoadCurve curve;
};

struct PressureSpec {
  std::vector<std::string> faces;
  double value = 0;
  LoadCurve curve;
  // A fluid's pressure (pressure penetration, contact/pressure_penetration.hpp):
  // it enters at the face element nearest this point and acts as far as it
  // reaches without crossing a pressed element.  Empty: on the whole faces.
  std::vector<double> fluid_entry;
};

// [[traction]]: a dead traction (force per unit reference area, any
// direction) on faces; in large deformation on the reference faces (a
// constant force, ramped with the load factor or its curve).
struct TractionSpec {
  std::vector<std::string> faces;
  std::vector<double> value;
  LoadCurve curve;
};

struct ObstacleSpec {
  std::string type;  // a registered obstacle type (contact/obstacle.hpp): plane | sphere | cylinder
  std::map<std::string, std::vector<double>, std::less<>> values;  // its declared keys (scalars as one entry)
  std::vector<double> motion;  // rigid translation: applied with the load factor (large deformation) or whole
  LoadCurve curve;             // of the motion
};

struct ContactSpec {
  std::string face;      // the slave face: the multipliers live on it
  ObstacleSpec obstacle;  // a rigid obstacle, or:
  std::string master;     // the face of a second deformable body (empty: the obstacle)
  std::vector<double> master_motion;  // a rigid translation of the master body with its supports (as an obstacle's
                                      // motion; small deformation, refused in large)
  double friction = 0;    // Coulomb coefficient (small and large deformation, obstacle or master); 0: frictionless
  std::string law;        // the interface law (contact/interface_law.hpp); empty: coulomb where friction > 0, else
                          // frictionless
  MortarIntegration integration = MortarIntegration::segmented;  // with master (contact/mortar_gap.hpp)
  // The faces start overlapping on purpose (a shrink or press fit): the
  // overlap is removed gradually, the gaps offset by (1 - t) times it over
  // the load (Model::Contact::interference).  Without it, two bodies that
  // start inside one another are an error.
  bool interference = false;
};

// Large deformation (hyperelastic models): how the load is applied.
struct LoadingSpec {
  int steps = 10;
  double first_increment = 0;  // > 0: overrides steps
  double min_increment = 1e-4;
  double max_increment = 1.0;  // caps the growth after fast steps
  int max_newton_iterations = 30;
  bool line_search = true;         // [loading] line_search = true | false | "halving"
  bool halving_line_search = false;  // "halving": the driver's own (engine/load_stepping.hpp)
  bool tangent_predictor = true;   // [loading] predictor = "tangent" | "tangent_every_step" | "none"
  bool tangent_every_step = false;
  bool linearised_active_set = true;  // [loading] active_set = "linearised" | "semismooth"
  bool follower_pressure = true;  // false: dead load (reference normal)
};

// [solver]: who solves the small-deformation linear systems.  "direct":
// CHOLMOD on one process (engine/cholesky); "petsc": PETSc on one or more
// MPI processes (solvers/petsc_contact), `options` passed to PETSc's
// options database as on a PETSc command line ("-ksp_type cg -pc_type gamg").
// `preconditioner`: "options" (what `options` say; default MUMPS),
// "spline_multigrid" (geometric multigrid over the case's nested meshes
// --refine r, ..., 0, solvers/petsc_multigrid; PETSc only) or
// "algebraic_multigrid" (FGMRES with a Schur field split, GAMG on the
// displacements: PETSc options that `options` may override; PETSc only),
// or "auto" (one of the first two, chosen per mesh: model/solver_choice).
// [solver], resolved when the case (or the command line) is read.
enum class SolverType { direct, petsc };
enum class Preconditioner { options, spline_multigrid, algebraic_multigrid };
// The names a case file and the command line give, and back.
std::optional<SolverType> solver_type_named(std::string_view name);
std::optional<Preconditioner> preconditioner_named(std::string_view name);
std::string_view name_of(SolverType type);
std::string_view name_of(Preconditioner preconditioner);

// [model] kind: what a 2D case models in the third direction.  plane_strain
// (a long body: eps_zz = 0) or plane_stress (a thin plate: sigma_zz = 0, the
// thickness free; materials/plane_stress.hpp), forces per unit thickness
// either way; or axisymmetric (x = r >= 0, y = z the axis: the solid the
// section sweeps turning about the y axis, hoop strain u_r / r), forces per
// full circumference.  A 3D case is none (its kind stays plane_strain, unread).
enum class ModelKind { plane_strain, plane_stress, axisymmetric };
std::optional<ModelKind> model_kind_named(std::string_view name);
std::string_view name_of(ModelKind kind);

struct SolverSpec {
  SolverType type = SolverType::direct;
  std::string options;
  Preconditioner preconditioner = Preconditioner::options;
  // preconditioner = "auto": model/solver_choice picks `preconditioner` for
  // each mesh the case is run on (a study's levels each), and says why.
  bool automatic = false;
  std::string choice;  // why auto chose what it chose ("" without auto)
  int processes = 1;  // MPI processes of the run (set by the launcher, not by the case file)
  bool petsc() const { return type == SolverType::petsc; }
  bool spline_multigrid() const { return preconditioner == Preconditioner::spline_multigrid; }
  bool algebraic_multigrid() const { return preconditioner == Preconditioner::algebraic_multigrid; }
};

// [units]: the names of the case's units, labels only (the console,
// summary.json, the plots' axes); igac converts nothing.  Empty: not
// declared ("consistent units").
struct UnitsSpec {
  std::string system;                 // "mm-N-MPa", "SI" or "" (the three given one by one, or none)
  std::string length, force, stress;
  bool declared() const { return !length.empty() || !force.empty() || !stress.empty(); }
  // A force of the model: per unit thickness in 2D (force / length); dim 3
  // for a total force (3D, and 2D axisymmetric: per full circumference).
  std::string force_of_model(int dim) const {
    if (force.empty()) return "";
    return dim == 2 && !length.empty() ? force + "/" + length : force;
  }
  // " [unit]" for an axis label, or nothing.
  static std::string bracket(const std::string& unit) { return unit.empty() ? "" : " [" + unit + "]"; }
};

// One deformable body: its geometry (a built-in shape or a geometry file,
// one or several patches), its mesh and its material.  A case with one body
// is the CaseSpec itself; a case of several lists them in CaseSpec::bodies.
struct BodySpec {
  std::string body_name;  // [[body]] name (empty: the case's one body)
  // geometry: a built-in shape, or a G+Smo XML file
  std::string shape;
  std::map<std::string, std::vector<double>, std::less<>> shape_values;  // the shape's declared keys
  std::string geometry_file;  // as resolved (relative to the case file); then shape == "file"
  // The patches of the geometry file as its reader found them (before any
  // refinement); null for a built-in shape.
  std::shared_ptr<const MultiPatch> file_body;
  int dimension = 0;          // the body's, from the shape's registry entry or the file (0: from the shape name)
  double radius = 1, inner_radius = 1, outer_radius = 2;
  std::vector<double> size;
  // Where the body stands: its shape or file's patches scaled about the
  // origin, mirrored across coordinate planes, rotated about the origin and
  // translated, in that order (place_patch, model/case_body.hpp).
  double scale = 1;
  std::vector<int> mirror;        // the axes (0, 1, 2) whose coordinate changes sign, in order
  std::vector<double> rotate;     // degrees: one angle in 2D; about x, then y, then z in 3D (empty: none)
  std::vector<double> translate;  // moves the shape or the file's patches (empty: where they stand)
  // mesh
  int degree = 2;
  std::vector<int> elements;
  int refine = 0;
  std::vector<GradingSpec> gradings;  // at most one per direction
  // material
  std::string model = "linear_elastic";  // or a hyperelastic law: large deformation
  double E = 1, nu = 0.3;                  // the law's small-strain equivalent (Hertz, scales)
  MaterialParameters material_parameters;  // as the law declares them (E, nu or its own keys)
  // displacement | mixed | mixed_element (engine/volumetric_projection.hpp:
  // the volumetric part projected onto the pressure space,
  // engine/pressure_space.hpp; nearly incompressible solids do not lock)
  Formulation formulation = Formulation::displacement;
  // [material] incompressible = true: the mixed formulation's fully
  // incompressible limit (K = infinity, engine/total_lagrangian.hpp's
  // augmented Lagrangian; the law's bulk modulus is its penalty)
  bool incompressible = false;

  bool finite_strain() const { return model != "linear_elastic"; }
  int dim() const {
    if (dimension > 0) return dimension;
    return shape == "box" || shape == "sphere_octant" ? 3 : 2;  // a CaseSpec made in code
  }
};

// Where a case file gives its keys: what a check made after reading
// (build_model, the solve, the memory guard) names in its message,
// "file:line: [table] key: why", as the reader's own checks do.
struct CaseSource {
  struct Key {
    std::string table;  // "dirichlet", "body.mesh", "contact.obstacle" ([x] and [[x]] alike; "" the top level)
    int index = 0;      // which of the tables of that name, in file order
    int body = -1;      // which [[body]] table it lies in (-1: none)
    std::string key;    // "" the table's own header
    int line = 0;
    std::vector<std::string> words;  // the strings of the value (a face name, a list of them)
  };
  // Which key: `key` ("*": any) of a table named `table`, the index-th of
  // that name (-1: any), in the body-th [[body]] (-1: any), whose value
  // holds `word` (empty: any value).
  struct Query {
    std::string table = {}, key = "*", word = {};
    int index = -1, body = -1;
  };
  std::vector<Key> keys;  // in file order

  // The first key the query matches (null: none).
  const Key* find(const Query& q) const;
  // "path:line" of the key, else of the header of the table it would be
  // in, else "path" (the file says nothing of it, or a case made in code).
  std::string at(const std::string& path, const Query& q) const;
};

// A case.  Its BodySpec part is its one body; with [[body]] tables (bodies
// not empty) it holds what the bodies share: the dimension, the smallest
// degree (what the contact check needs), the model path (every body small or every body large
// deformation), the largest E and its nu (the contact's scales), and in
// `refine` the refinement added to every body's own (--refine r: every
// body r times finer than its [mesh] says).
struct CaseSpec : BodySpec {
  std::string path, name, description;
  std::vector<BodySpec> bodies;  // [[body]] tables; empty: the case is one body
  std::map<std::string, std::vector<std::string>> face_sets;  // [faces] NAME = ["0:south", ...]
  std::vector<PartialFaceSpec> partial_faces;                 // [faces.NAME] side = ..., range = ...
  // The face names a name stands for: a [faces] set's members, the side a
  // partial face lies on, else the name itself.
  std::vector<std::string> face_members(const std::string& name) const {
    const auto side_of = [&](const std::string& n) {
      for (const PartialFaceSpec& pf : partial_faces)
        if (pf.name == n) return pf.side;
      return n;
    };
    const auto set = face_sets.find(name);
    if (set == face_sets.end()) return {side_of(name)};
    std::vector<std::string> out;
    for (const std::string& member : set->second) out.push_back(side_of(member));
    return out;
  }
  LoadingSpec loading;
  ModelKind kind = ModelKind::plane_strain;  // [model] kind (2D)
  bool plane_stress() const { return kind == ModelKind::plane_stress && dim() == 2; }
  bool axisymmetric() const { return kind == ModelKind::axisymmetric && dim() == 2; }
  // conditions and loads
  std::vector<DirichletSpec> dirichlet;
  std::vector<PressureSpec> pressure;
  std::vector<TractionSpec> traction;
  std::vector<double> body_force;
  LoadCurve body_force_curve;
  std::vector<ContactSpec> contacts;  // [contact] or [[contact]]: each face with its rigid obstacle
  std::string reference = "none";  // hertz | lame | none
  bool write_vtk = true;
  SolverSpec solver;
  UnitsSpec units;
  CaseSource source;  // the case file's lines (empty: a case made in code)
  // "path:line" of a key (CaseSource::at): where a message after reading points.
  std::string where(const CaseSource::Query& q) const { return source.at(path, q); }
  // The same for a key of body b's table `table` ("geometry", "mesh",
  // "mesh.grading", "material"): [table] for the case's one body, the
  // [body.table] of b's [[body]] for one of several.
  std::string where(const BodySpec& b, const std::string& table, const std::string& key) const;

  // Every load's curve (dirichlet, pressure, body force, obstacles), in that order.
  std::vector<const LoadCurve*> load_curves() const {
    std::vector<const LoadCurve*> out;
    for (const auto& d : dirichlet) out.push_back(&d.curve);
    for (const auto& p : pressure) out.push_back(&p.curve);
    for (const auto& p : traction) out.push_back(&p.curve);
    out.push_back(&body_force_curve);
    for (const auto& c : contacts) out.push_back(&c.obstacle.curve);
    return out;
  }
  // Does some load follow a curve of its own (then the run is a load
  // history, its time running to the curves' last corner)?
  bool has_load_curves() const {
    for (const LoadCurve* c : load_curves())
      if (c->has_points()) return true;
    return false;
  }

  // Every body as build_model refines it: the case itself, or each [[body]]
  // with the case's added refinement.
  std::vector<BodySpec> body_list() const {
    if (bodies.empty()) return {static_cast<const BodySpec&>(*this)};
    std::vector<BodySpec> out = bodies;
    for (BodySpec& b : out) b.refine += refine;
    return out;
  }
};

}  // namespace igac
