// SPDX-License-Identifier: BSD-3-Clause
// What part of the body a model is (modelled_part, summary.json
// contact.model_part), from the case's planes of symmetry: faces held to
// zero along one axis only, lying in a plane normal to it (issue 21,
// "Labels").  A face also held along another axis is clamped, not a plane
// of symmetry; two parallel planes make a repeated cell, not a fraction.
#include <gtest/gtest.h>

#include <string>

#include "io/case_file.hpp"
#include "model/model.hpp"

namespace {

using igac::CaseSpec;
using igac::DirichletSpec;

const std::string kSource = IGAC_SOURCE_DIR;

// The contact patch-test block [0, 1] x [0, 0.5], with u_x = 0 on x = 0.
CaseSpec flat_block() { return igac::read_case(kSource + "/tests/data/contact_flat_block.toml"); }

std::string part_of(const CaseSpec& spec) { return igac::modelled_part(igac::build_model(spec)).value_or("(none)"); }

TEST(ModelPart, OneSymmetryPlaneIsHalf) {
  EXPECT_EQ(part_of(flat_block()), "half (forces per unit thickness of the modelled half)");
}

TEST(ModelPart, AClampedFaceIsNoSymmetryPlane) {
  CaseSpec s = flat_block();
  s.dirichlet.push_back(DirichletSpec{{"left"}, 1, 0.0});  // u_y = 0 too: clamped
  EXPECT_EQ(part_of(s), "whole cross-section (forces per unit thickness)");
}

TEST(ModelPart, AFaceMovedAlongItsNormalIsNoSymmetryPlane) {
  CaseSpec s = flat_block();
  s.dirichlet.front().value = 0.01;
  EXPECT_EQ(part_of(s), "whole cross-section (forces per unit thickness)");
}

TEST(ModelPart, ARollerAcrossTheFaceIsNoSymmetryPlane) {
  CaseSpec s = flat_block();
  s.dirichlet.front().component = 1;  // u_y = 0 on x = 0: held along the face, free across it
  EXPECT_EQ(part_of(s), "whole cross-section (forces per unit thickness)");
}

TEST(ModelPart, TwoPerpendicularPlanesAreAQuarterAndTwoParallelOnesARepeatedCell) {
  CaseSpec s = flat_block();
  s.dirichlet.push_back(DirichletSpec{{"top"}, 1, 0.0});  // y = 0.5
  EXPECT_EQ(part_of(s), "quarter (forces per unit thickness of the modelled quarter)");
  s = flat_block();
  s.dirichlet.push_back(DirichletSpec{{"right"}, 0, 0.0});  // x = 1, parallel to x = 0
  EXPECT_EQ(part_of(s), "modelled part (symmetry; forces per unit thickness)");
}

TEST(ModelPart, HertzBodiesKeepTheirNames) {
  EXPECT_EQ(part_of(igac::read_case(kSource + "/cases/hertz2d.toml")),
            "quarter (forces per unit thickness of the modelled quarter)");
  CaseSpec s3 = igac::read_case(kSource + "/cases/hertz3d.toml");
  s3.elements = {4, 2, 4};
  s3.gradings.clear();
  EXPECT_EQ(part_of(s3), "modelled part (symmetry)");
}

TEST(ModelPart, ThreeDimensionalBodyWithoutSymmetryHasNone) {
  CaseSpec s = igac::read_case(kSource + "/cases/indented_block.toml");
  s.elements = {2, 2, 2};
  EXPECT_EQ(part_of(s), "(none)");
  s.dirichlet.clear();
  s.dirichlet.push_back(DirichletSpec{{"base"}, 2, 0.0});  // the base on rollers: z = 0 is a plane of symmetry
  EXPECT_EQ(part_of(s), "half (symmetry)");
}

}  // namespace
