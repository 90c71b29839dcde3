// SPDX-License-Identifier: BSD-3-Clause
// What the PETSc solvers of solvers/ share (petsc_contact.cpp,
// petsc_multigrid.cpp, petsc_newton.cpp; not part of igac's interface):
// error checking with PETSc's own words, PETSc objects owned by scope,
// igac's default options (set unless the user gave them; never reported as
// unused), the check for options nothing used, the peak memory.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <petscksp.h>
#include <string>
#include <utility>
#include <vector>

namespace igac::petsc {

// Throws on a PETSc error: a PetscOptionError when the options may be the
// cause (`options_phase`) and the code says so, std::bad_alloc when PETSc
// ran out of memory, else std::runtime_error.
void check(PetscErrorCode e, const char* what, bool options_phase = false);

// Sets an option unless the user gave it; remembers it as igac's own.
void default_option(const char* name, const char* value);

// This process's contiguous share (first, count) of n rows, as PETSc splits
// them (PETSC_DECIDE).  Collective.
std::pair<PetscInt, PetscInt> share(PetscInt n);

// Throws PetscOptionError naming the first option no PETSc object used
// (misspelt, or an option of another solver type); call after the first solve.
void refuse_unused_options();

// This process's peak resident memory so far, GiB.
double peak_resident_gib();

// PETSc objects destroyed at scope exit (also when an exception leaves).
template <class T, PetscErrorCode (*Destroy)(T*)>
struct Owned {
  T p = nullptr;
  Owned() = default;
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
  Owned(Owned&& o) noexcept : p(o.p) { o.p = nullptr; }
  Owned& operator=(Owned&& o) noexcept {
    std::swap(p, o.p);
    return *this;
  }
  ~Owned() {
    if (p) Destroy(&p);
  }
  operator T() const { return p; }
  T* operator&() { return &p; }
};
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedKSP = Owned<KSP, KSPDestroy>;
using OwnedIS = Owned<IS, ISDestroy>;
using OwnedScatter = Owned<VecScatter, VecScatterDestroy>;
using OwnedNullSpace = Owned<MatNullSpace, MatNullSpaceDestroy>;

}  // namespace igac::petsc

namespace igac::petsc {

// The distributed layout of the saddle-point system: N = n + m equations
// split in contiguous blocks (PETSc's default), displacements first; this
// process owns rows [r0, r1), i.e. displacements [u0, u1) and multipliers
// [l0, l1) (numbered from n), stored in this order in its part of a vector.
struct SaddleLayout {
  PetscInt n = 0, m = 0, r0 = 0, r1 = 0, u0 = 0, u1 = 0, l0 = 0, l1 = 0;
  PetscInt local_u() const { return u1 - u0; }
  PetscInt local_l() const { return l1 - l0; }
  // n displacements and m multipliers of which this process owns rows [r0, r1).
  static SaddleLayout of(PetscInt n, PetscInt m, PetscInt r0, PetscInt r1) {
    return {.n = n, .m = m, .r0 = r0, .r1 = r1, .u0 = std::min(r0, n), .u1 = std::min(r1, n),
            .l0 = std::max(r0, n), .l1 = std::max(r1, n)};
  }
};

// The two fields of a field split over a SaddleLayout, named `u` and
// `lambda` for the options (-fieldsplit_u_pc_type gamg), and the
// displacement field's near null space: the columns of near_null (n rows,
// whole on every process: rigid motions; other rows: none), orthonormalised,
// for algebraic multigrid.  Without multipliers (L.m = 0) the whole matrix A
// is the field u: the PC becomes the one the options give u (default gamg)
// and A gets the near null space.  The objects live in SaddleFields as long
// as the PC uses them.
struct SaddleFields {
  OwnedIS is_u, is_l;
  std::vector<OwnedVec> null_vecs;
  OwnedNullSpace near;
};
void set_fields(PC pc, Mat A, const Eigen::MatrixXd& near_null, const SaddleLayout& L, SaddleFields& fields);
// The near null space alone (fields.near, fields.null_vecs), over L's displacements.
void set_near_null_space(const Eigen::MatrixXd& near_null, const SaddleLayout& L, SaddleFields& fields);

}  // namespace igac::petsc
