// SPDX-License-Identifier: BSD-3-Clause
// The ParaView `hydrostatic_pressure` field of the mixed formulation
// (recover_volume, model/field_recovery.hpp): one constant per pressure
// block (mixed_pressure_blocks), the formulation's -K Pi_b tr eps in small
// strain and -U'(Pi_b J) in large deformation, checked against Pi_b
// computed here from the assembly's own quadrature; and the run's block
// pressures (the incompressible limit) shown as they are.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "engine/assembly.hpp"
#include "engine/pressure_blocks.hpp"
#include "io/case_file.hpp"
#include "model/field_recovery.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"

namespace igac {
namespace {

// theta_b = Pi_b tr eps (small strain) or Pi_b J of u on every block.
std::vector<double> block_means(const Model& m, const Eigen::MatrixXd& u, const ElementBlocks& blocks, bool small) {
  const BodyQuadrature quad(m.body, gauss_points_for(m.body.degree()));
  const int dim = m.body.space_dim();
  std::vector<double> integral(size_t(blocks.num_blocks()), 0.0), volume(integral);
  ElementData ed;
  for (int e = 0; e < quad.num_elements(); ++e) {
    quad.evaluate(e, ed, true);
    for (int q = 0; q < int(ed.JxW.size()); ++q) {
      Eigen::MatrixXd grad = Eigen::MatrixXd::Zero(dim, dim);  // du_i/dX_j
      for (size_t a = 0; a < ed.cps.size(); ++a) grad += u.row(ed.cps[a]).transpose() * ed.dN[size_t(q)].row(Eigen::Index(a));
      const double value = small ? grad.trace() : (Eigen::MatrixXd::Identity(dim, dim) + grad).determinant();
      integral[size_t(blocks.block_of[size_t(e)])] += ed.JxW[q] * value;
      volume[size_t(blocks.block_of[size_t(e)])] += ed.JxW[q];
    }
  }
  for (size_t b = 0; b < integral.size(); ++b) integral[b] /= volume[b];
  return integral;
}

// Every Bezier coefficient of element e's pressure against expected[block of e].
void expect_block_constants(const RecoveredVolume& v, const BezierMesh& mesh, const ElementBlocks& blocks,
                            const std::vector<double>& expected, double tolerance) {
  const int nl = mesh.num_local();
  for (int e = 0; e < mesh.num_elements(); ++e)
    for (int a = 0; a < nl; ++a)
      ASSERT_NEAR(v.pressure[e * nl + a], expected[size_t(blocks.block_of[size_t(e)])], tolerance)
          << "element " << e << ", coefficient " << a;
}

// Cook's membrane on 5 x 5 elements (blocks of 2 and 3 per direction).  Its
// bilinear geometry makes tr eps det J a polynomial, integrated exactly by
// both Gauss rules: Pi_b agrees to round-off.
TEST(PressureField, SmallStrainIsMinusKTimesTheBlockMeanOfTrEps) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/cook_membrane.toml");
  spec.elements = {5, 5};
  spec.write_vtk = false;
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  const BodyQuadrature quad(m.body, gauss_points_for(m.body.degree()));
  const ElementBlocks blocks = mixed_pressure_blocks(quad, m.patch_formulations());
  ASSERT_EQ(blocks.num_blocks(), 4);
  const double bulk = m.material.lambda() + 2 * m.material.mu() / 3;
  std::vector<double> expected = block_means(m, r.u, blocks, true);
  double scale = 0;
  for (double& p : expected) {
    p *= -bulk;
    scale = std::max(scale, std::abs(p));
  }
  ASSERT_GT(scale, 0.0);
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  expect_block_constants(recover_volume(mesh, m), mesh, blocks, expected, 1e-10 * scale);
  // the run's own block pressures, when it has them, are shown as they are
  Eigen::VectorXd given(blocks.num_blocks());
  for (int b = 0; b < blocks.num_blocks(); ++b) given[b] = 10.0 + b;
  std::vector<double> minus_given(size_t(blocks.num_blocks()));
  for (int b = 0; b < blocks.num_blocks(); ++b) minus_given[size_t(b)] = -given[b];
  expect_block_constants(recover_volume(mesh, m, given), mesh, blocks, minus_given, 1e-12 * 13);
  // the displacement formulation: the pointwise -tr sigma / 3, not constant per block
  CaseSpec disp_spec = spec;
  disp_spec.formulation = Formulation::displacement;
  const Model d = build_model(disp_spec);
  const RecoveredVolume vd = recover_volume(body_bezier_mesh(d.body, r.u), d);
  EXPECT_GT(vd.pressure.maxCoeff() - vd.pressure.minCoeff(), 0.0);
  EXPECT_THROW(recover_volume(body_bezier_mesh(m.body, r.u, 0, 0), m), std::invalid_argument);
}

// The Lame cylinder inflated (Neo-Hookean, K/mu = 5000, mixed): -U'(Pi_b J)
// per block.  The recovery integrates J with its own rule (p + 3 points per
// direction against the assembly's p + 1) on the rational geometry, so the
// two Pi_b J differ by quadrature error, far below the pressure.
TEST(PressureField, LargeDeformationIsMinusUPrimeOfTheBlockMeanOfJ) {
  CaseSpec spec = read_case(IGAC_SOURCE_DIR "/cases/lame_cylinder.toml");
  spec.model = "neo_hookean";
  const double nu = 0.4999, mu = 1.0;
  spec.E = 2 * mu * (1 + nu);
  spec.nu = nu;
  spec.material_parameters = {spec.E, nu, {}};
  spec.formulation = Formulation::mixed;
  spec.write_vtk = false;
  spec.pressure.at(0).value = 0.2;
  spec.loading.steps = 2;
  spec.reference = "none";
  apply_overrides(spec, 2, 1);
  const Model m = build_model(spec);
  const RunResult r = solve_model(m);
  ASSERT_EQ(r.status, "converged");
  const BodyQuadrature quad(m.body, gauss_points_for(m.body.degree()));
  const ElementBlocks blocks = mixed_pressure_blocks(quad, m.patch_formulations());
  ASSERT_FALSE(blocks.per_element());
  std::vector<double> expected = block_means(m, r.u, blocks, false);
  double scale = 0;
  for (double& theta : expected) {
    VolumetricValues v;
    ASSERT_TRUE(m.law->volumetric(theta, v));
    theta = -v.dU;
    scale = std::max(scale, std::abs(theta));
  }
  ASSERT_GT(scale, 0.01);
  const BezierMesh mesh = body_bezier_mesh(m.body, r.u);
  expect_block_constants(recover_volume(mesh, m), mesh, blocks, expected, 1e-3 * scale);
  // per element (the projection of before the blocks) the field would differ by more
  const ElementBlocks ones = block_elements(quad, {1});
  const std::vector<double> theta_e = block_means(m, r.u, ones, false);
  double differ = 0;
  for (int e = 0; e < quad.num_elements(); ++e) {
    VolumetricValues v;
    ASSERT_TRUE(m.law->volumetric(theta_e[size_t(e)], v));
    differ = std::max(differ, std::abs(-v.dU - expected[size_t(blocks.block_of[size_t(e)])]));
  }
  std::cout << "  inflated tube: block pressures up to " << scale << ", element ones differ by up to " << differ << "\n";
  EXPECT_GT(differ, 1e-2 * scale);
}

}  // namespace
}  // namespace igac
