// SPDX-License-Identifier: BSD-3-Clause
// preconditioner = "auto" (model/solver_choice): the spline multigrid for a
// 3D mesh of at least 100k unknowns that it can run, a factorisation
// otherwise, decided again for every mesh the case is run on; and the
// spline multigrid's -u_pc_mg_levels checked against the case's meshes.
// Nothing is built or solved: the choice is made from the case alone
// (settle_preconditioner, without apply_overrides' memory check where the
// case would be factorised: that check depends on the machine).
#include <gtest/gtest.h>

#include <string>

#include "io/case_file.hpp"
#include "model/memory_estimate.hpp"
#include "model/solver_choice.hpp"

namespace igac {
namespace {

CaseSpec petsc_case(const std::string& file, const std::string& preconditioner) {
  CaseSpec spec = read_case(std::string(IGAC_SOURCE_DIR) + "/" + file);
  spec.solver.type = SolverType::petsc;
  EXPECT_TRUE(set_preconditioner(spec.solver, preconditioner));
  return spec;
}

CaseSpec settled(CaseSpec spec, int refine) {
  spec.refine = refine;
  settle_preconditioner(spec);
  return spec;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(SolverChoice, TakesTheSplineMultigridForALarge3DMesh) {
  const CaseSpec spec = settled(petsc_case("cases/hertz3d_study.toml", "auto"), 3);  // 225k unknowns
  EXPECT_TRUE(spec.solver.spline_multigrid());
  EXPECT_TRUE(contains(spec.solver.choice, "auto chose the spline multigrid: 3D, about")) << spec.solver.choice;
}

TEST(SolverChoice, FactorisesASmaller3DMeshAndEvery2DMesh) {
  const CaseSpec small = settled(petsc_case("cases/hertz3d_study.toml", "auto"), 2);  // 32k unknowns
  EXPECT_FALSE(small.solver.spline_multigrid());
  EXPECT_TRUE(contains(small.solver.choice, "auto chose MUMPS: 3D, about")) << small.solver.choice;
  const CaseSpec flat = settled(petsc_case("cases/hertz2d.toml", "auto"), 4);  // 528k unknowns
  EXPECT_FALSE(flat.solver.spline_multigrid());
  EXPECT_TRUE(contains(flat.solver.choice, "auto chose MUMPS: 2D")) << flat.solver.choice;
}

// A mesh below 100k unknowns whose factorisation would not fit where the
// multigrid's would: the multigrid (the memory given between the two
// estimates, so that the test does not depend on the machine's).
TEST(SolverChoice, TakesTheSplineMultigridWhenTheFactorWouldNotFit) {
  CaseSpec spec = petsc_case("cases/hertz3d_study.toml", "auto");
  spec.refine = 2;  // 32k unknowns
  CaseSpec factor = spec, multigrid = spec;
  factor.solver.preconditioner = Preconditioner::options;
  multigrid.solver.preconditioner = Preconditioner::spline_multigrid;
  const double direct = estimated_peak_bytes(factor), levels = estimated_peak_bytes(multigrid);
  ASSERT_GT(direct, levels);
  settle_preconditioner(spec, 0.5 * (direct + levels));
  EXPECT_TRUE(spec.solver.spline_multigrid());
  EXPECT_TRUE(contains(spec.solver.choice, "a factorisation would need about")) << spec.solver.choice;
  settle_preconditioner(spec, 2 * direct);
  EXPECT_FALSE(spec.solver.spline_multigrid());
}

// A study runs its levels from the same spec through apply_overrides: each
// level decides anew (the finest, on the multigrid, fits any machine that
// runs the suite).
TEST(SolverChoice, DecidesAgainForEveryMesh) {
  CaseSpec spec = petsc_case("cases/hertz3d_study.toml", "auto");
  apply_overrides(spec, {}, 3);
  EXPECT_TRUE(spec.solver.spline_multigrid());
  apply_overrides(spec, {}, 1);
  EXPECT_FALSE(spec.solver.spline_multigrid());
  apply_overrides(spec, {}, 3);
  EXPECT_TRUE(spec.solver.spline_multigrid());
}

TEST(SolverChoice, FactorisesWhatTheMultigridDoesNotRun) {
  CaseSpec friction = petsc_case("cases/hertz3d_study.toml", "auto");
  friction.contacts.at(0).friction = 0.3;
  friction = settled(friction, 3);
  EXPECT_FALSE(friction.solver.spline_multigrid());
  EXPECT_TRUE(contains(friction.solver.choice, "friction = 0.3")) << friction.solver.choice;
  CaseSpec told = petsc_case("cases/hertz3d_study.toml", "auto");
  told.solver.options = "-ksp_type cg -pc_type gamg";
  told = settled(told, 3);
  EXPECT_FALSE(told.solver.spline_multigrid());
  EXPECT_TRUE(contains(told.solver.choice, "the options name -ksp_type")) << told.solver.choice;
}

TEST(SolverChoice, AutoNeedsPetscAndLeavesOtherChoicesAlone) {
  CaseSpec direct = read_case(std::string(IGAC_SOURCE_DIR) + "/cases/hertz3d_study.toml");
  ASSERT_TRUE(set_preconditioner(direct.solver, "auto"));
  EXPECT_EQ(check_preconditioner(direct.solver),
            "auto chooses among PETSc's preconditioners: needs type = \"petsc\"");
  const CaseSpec asked = settled(petsc_case("cases/hertz3d_study.toml", "options"), 3);
  EXPECT_FALSE(asked.solver.spline_multigrid());
  EXPECT_TRUE(asked.solver.choice.empty());
  SolverSpec s;
  EXPECT_FALSE(set_preconditioner(s, "automatic"));
}

// -u_pc_mg_levels L keeps the L finest of the --refine + 1 meshes.
TEST(SolverChoice, RefusesMoreMultigridLevelsThanMeshes) {
  CaseSpec spec = petsc_case("cases/hertz2d.toml", "spline_multigrid");
  spec.solver.options = "-u_pc_mg_levels 3";
  EXPECT_NO_THROW(settled(spec, 2));
  try {
    settled(spec, 1);
    ADD_FAILURE() << "3 levels on 2 meshes accepted";
  } catch (const InputError& e) {
    EXPECT_TRUE(contains(e.what(), "PETSc option -u_pc_mg_levels 3: the spline multigrid of --refine 1 has 1 to 2 "
                                   "levels"))
        << e.what();
  }
  spec.solver.options = "-u_pc_mg_levels 0";
  EXPECT_THROW(settled(spec, 2), InputError);
}

}  // namespace
}  // namespace igac
