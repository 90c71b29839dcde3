// SPDX-License-Identifier: BSD-3-Clause
// A case made into something to solve: the refined patches joined into one
// body, the named faces, the dofs with their Dirichlet conditions, the law
// and the contacts (each face with its obstacle).  build_model makes it from
// a CaseSpec; model/solve solves it.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "contact/master_surface.hpp"
#include "contact/mortar_gap.hpp"
#include "contact/obstacle.hpp"
#include "contact/pressure.hpp"
#include "contact/weighted_gap.hpp"
#include "engine/geometry/conforming_interfaces.hpp"
#include "engine/geometry/patch_partition.hpp"
#include "engine/body.hpp"
#include "engine/discretisation.hpp"
#include "materials/hyperelastic.hpp"
#include "materials/linear_elastic.hpp"
#include "model/case_spec.hpp"
#include "model/run_result.hpp"

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
  // The case's bodies: its one body (name empty), or its [[body]] tables in
  // their order, each with its patches of `body` and its own material.
  struct Part {
    std::string name;
    int first_patch = 0, num_patches = 0;
    int file_patches = 0;  // as the shape or the file gives them (num_patches counts the pieces of cut patches)
    LinearElastic material{1.0, 0.0};
    std::shared_ptr<const HyperelasticLaw> law;
    Formulation formulation = Formulation::displacement;
  };
  std::vector<Part> parts;
  // The formulation of each patch of `body` (one entry: every patch's).
  std::vector<Formulation> patch_formulations() const {
    if (parts.size() <= 1) return {spec.formulation};
    std::vector<Formulation> out;
    for (const Part& p : parts) out.insert(out.end(), size_t(p.num_patches), p.formulation);
    return out;
  }
  // The law of each patch of `body` (one entry: every patch's).
  std::vector<const HyperelasticLaw*> patch_laws() const {
    if (parts.size() <= 1) return {law.get()};
    std::vector<const HyperelasticLaw*> out;
    for (const Part& p : parts) out.insert(out.end(), size_t(p.num_patches), p.law.get());
    return out;
  }
  // The small-strain material of each patch of `body` (one entry: every patch's).
  std::vector<LinearElastic> patch_materials() const {
    if (parts.size() <= 1) return {material};
    std::vector<LinearElastic> out;
    for (const Part& p : parts) out.insert(out.end(), size_t(p.num_patches), p.material);
    return out;
  }
  // [contact] / [[contact]]: each face with its obstacle; the multipliers of
  // all of them are stacked in this order.
  struct Contact {
    std::string face_name;
    std::unique_ptr<ContactFace> face;
    std::unique_ptr<Obstacle> obstacle;  // where it stands (small deformation: after its motion); with a
                                         // master, the master at its reference position (MasterAsObstacle:
                                         // the reports and checks read it, the coupling does not)
    std::unique_ptr<MasterSurface> master;  // the face of a second deformable body (null: a rigid obstacle)
    std::string master_name;
    bool self_contact = false;           // the master is a face of the slave's own body
    Eigen::VectorXd motion;              // large deformation: the obstacle is moved by curve(t) * motion; a master
                                         // body: moved rigidly with its supports (small deformation)
    LoadCurve curve;                     // of the motion (no points: the factor is t)
    double friction = 0;                 // Coulomb coefficient (small and large deformation, obstacle or master)
    const InterfaceLaw* law = nullptr;   // [contact] law; null: by the coefficient (default_interface_law)
    ContactLaw contact_law() const { return law ? ContactLaw(*law, friction) : ContactLaw(friction); }
    MortarIntegration integration = MortarIntegration::segmented;  // with a master
    // [contact] interference = true: the faces start overlapping on purpose.
    // Each weighted gap is offset by (1 - s(t)) o_K, o_K = max(0, -g_K) of
    // the reference configuration (the overlap's part of multiplier K), with
    // s(t) the load factor (with load curves: ramp and hold, min(t, 1)); so
    // the run starts with no overlap and the full fit is reached at the end
    // of the load (of the first unit of time), as Abaqus' interference fit
    // removes it over a step.  A small-deformation solve without steps is
    // at s = 1 only: the fit at once, which linear elasticity allows.
    bool interference = false;
    // Small deformation: o_K, computed once when the model is built (empty
    // without interference).  The large-deformation problem takes its own
    // from its own gaps at u = 0 (model/finite_strain_problem.hpp), so that
    // its run starts exactly clear.
    Eigen::VectorXd interference_overlap;
  };
  std::vector<Contact> contacts;
  double mesh_size = 0;  // largest element diameter
  // Patches of a geometry file that were left-handed (det J < 0 throughout)
  // and run with their first direction backwards; their faces keep the
  // file's names.
  std::vector<int> reoriented_patches;
  // Patches cut where a [faces.NAME] range ends (model/partial_faces.hpp):
  // the pieces of each, by the number of its first piece (the patch's own).
  std::map<int, std::vector<PatchPiece>> cut_patches;
  // Sides of a geometry file that coincide and that its topology did not
  // join (a closed seam, a file without <interfaces>), joined by igac; in
  // the file's side names.
  std::vector<PatchInterface> joined_sides;
  // Knots inserted so that the two sides of every interface have the same
  // breakpoints (engine/geometry/conforming_interfaces.hpp).
  std::vector<InsertedKnots> interface_knots;
  std::vector<std::string> warnings;  // where the case contradicts itself (printed unless quiet)
  int num_multipliers() const {
    int m = 0;
    for (const auto& c : contacts) m += c.face->num_multipliers();
    return m;
  }
};


Model build_model(const CaseSpec& spec);
// The sides a face name stands for on the model's body: a name of the shape
// or of [faces], "PATCH:SIDE" with SIDE one of west east south north front
// back or u0 u1 v0 v1 w0 w1, and on a one-patch body u0 ... w1 alone.
// nothing when the name is unknown.
std::optional<std::vector<PatchSide>> find_faces(const Model& m, const std::string& name);
// The sides of every face in `names`, checked: an unknown name or an
// interface inside the body is an InputError naming [section].
std::vector<PatchSide> resolve_faces(const Model& m, const std::vector<std::string>& names, const char* section);
// What part of the physical body the model is, for the reports (summary.json
// contact.model_part): the Hertz quarter disc / sphere octant, else from the
// case's planes of symmetry (faces held to zero along their normal axis
// only): in 2D "whole cross-section", "half" or "quarter" (forces per unit
// thickness), in 3D "half", "quarter" or "eighth (symmetry)"; nothing for a
// 3D body without symmetry; "modelled part (symmetry...)" for two parallel
// planes (a repeated cell).
std::optional<std::string> modelled_part(const Model& m);
// Every accepted face name, for error messages.
std::vector<std::string> face_names(const Model& m);

}  // namespace igac
