// SPDX-License-Identifier: BSD-3-Clause
// Linear elasticity, mathematics first.
//  - Patch tests: a linear displacement lies in every NURBS space (affine
//    invariance), so prescribing it on the boundary of a patch must give it
//    back inside to round-off, on distorted meshes too as long as the
//    quadrature integrates int grad R_i dX = 0 exactly (polynomial maps: the
//    integrand dR/dxi cof(J)^T has degree 2p-1 per direction in 2D, 3p-1 in
//    3D, within reach of p+1 Gauss points for 2D and for 3D at p = 2).  A
//    uniform traction gives the uniform stress state.
//  - Convergence: the Lame thick cylinder (cases/lame_cylinder.toml) has a
//    closed form; on nested meshes the L2 error falls as h^(p+1) and the H1
//    seminorm error as h^p.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <omp.h>
#include <random>
#include <set>
#include <string>

#include "engine/assembly.hpp"
#include "engine/cholesky.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/spline/refinement.hpp"
#include "io/case_file.hpp"
#include "model/model.hpp"
#include "model/solve.hpp"
#include "tests/support/distort.hpp"

namespace {

using igac::NurbsPatch;

// Solved displacements against the exact linear field, relative to its size:
// K_II has condition ~1e3 on these meshes, so ~1e-13 is round-off; 1e-11
// leaves a margin and still catches any inconsistency (which would show
// at ~1e-3, the discretisation error of a non-polynomial solution).
constexpr double kPatchTest = 1e-11;
// Stresses (relative to the traction) are derivatives: a factor p/h (~10-30
// here) above the displacement round-off; measured ~1e-14.
constexpr double kPatchStress = 1e-11;
// A resultant summed over a few dozen face quadrature points.
constexpr double kSumRoundoff = 1e-13;
// Band around the expected convergence rates p+1 (L2) and p (H1 seminorm),
// measured 3.02 / 2.01 (p = 2) and 3.98 / 2.98 (p = 3) on the finest pair.
constexpr double kRateBand = 0.2;

using igac_test::distort_interior;  // tests/support/distort.hpp

std::set<int> boundary_control_points(const NurbsPatch& p) {
  std::set<int> b;
  for (int d = 0; d < p.param_dim(); ++d)
    for (bool e : {false, true})
      for (int cp : p.face_control_points(igac::Face{d, e})) b.insert(cp);
  return b;
}

// Prescribes u = c + A X on every boundary control point, solves for the
// interior ones and returns max |u_h - u| / max |u| over the interior
// control points (coefficients of a linear field are its values at the
// control points, by affine invariance).
double patch_test_error(const NurbsPatch& patch, unsigned seed) {
  const int dim = patch.space_dim();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixXd A(dim, dim);
  Eigen::VectorXd c(dim);
  for (int i = 0; i < A.size(); ++i) A.data()[i] = U(rng);
  for (int i = 0; i < dim; ++i) c[i] = U(rng);

  const igac::DofMap all(patch, {});  // every dof free: the whole matrix
  const igac::LinearElastic material(210.0, 0.3);
  const igac::LinearSystem sys =
      igac::assemble_linear_elasticity(patch, all, material, Eigen::VectorXd::Zero(dim));
  const auto boundary = boundary_control_points(patch);
  const int n = patch.num_control_points() * dim;
  std::vector<int> interior_of(n, -1);
  std::vector<int> interior;
  Eigen::VectorXd u_exact(n);
  for (int cp = 0; cp < patch.num_control_points(); ++cp) {
    const Eigen::VectorXd u = c + A * patch.points().row(cp).transpose();
    for (int i = 0; i < dim; ++i) {
      u_exact[cp * dim + i] = u[i];
      if (!boundary.count(cp)) {
        interior_of[cp * dim + i] = int(interior.size());
        interior.push_back(cp * dim + i);
      }
    }
  }
  EXPECT_GT(interior.size(), 0u);
  // K_II u_I = -K_IB u_B
  const int ni = int(interior.size());
  std::vector<Eigen::Triplet<double>> t;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(ni);
  for (int k = 0; k < sys.K.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(sys.K, k); it; ++it) {
      const int r = interior_of[it.row()];
      if (r < 0) continue;
      const int col = interior_of[it.col()];
      if (col >= 0) t.emplace_back(r, col, it.value());
      else rhs[r] -= it.value() * u_exact[it.col()];
    }
  Eigen::SparseMatrix<double> Kii(ni, ni);
  Kii.setFromTriplets(t.begin(), t.end());
  igac::SparseCholesky chol;
  chol.factorize(Kii);
  const Eigen::VectorXd ui = chol.solve(rhs);
  double err = 0;
  for (int r = 0; r < ni; ++r) err = std::max(err, std::abs(ui[r] - u_exact[interior[r]]));
  return err / u_exact.cwiseAbs().maxCoeff();
}

TEST(ElasticPatchTest, LinearDisplacementReproduced2D) {
  for (int p : {2, 3, 4}) {
    SCOPED_TRACE("degree " + std::to_string(p));
    const NurbsPatch square = igac::subdivide(igac::elevate_to(igac::rectangle(2.0, 1.0).patch, p), 3);
    EXPECT_LE(patch_test_error(square, 100 + p), kPatchTest) << "affine map";
    // Interior points moved by up to ~15 % of an element: curved elements.
    EXPECT_LE(patch_test_error(distort_interior(square, 0.05, 7 + p), 200 + p), kPatchTest) << "distorted map";
  }
}

TEST(ElasticPatchTest, LinearDisplacementReproduced3D) {
  const NurbsPatch box2 = igac::subdivide(igac::elevate_to(igac::box(1.0, 0.8, 0.6).patch, 2), 2);
  EXPECT_LE(patch_test_error(box2, 1), kPatchTest) << "degree 2, affine";
  EXPECT_LE(patch_test_error(distort_interior(box2, 0.04, 3), 2), kPatchTest) << "degree 2, distorted";
  const NurbsPatch box3 = igac::subdivide(igac::elevate_to(igac::box(1.0, 0.8, 0.6).patch, 3), 2);
  EXPECT_LE(patch_test_error(box3, 4), kPatchTest) << "degree 3, affine";
}

// A case in code: a rectangle or box pulled by a uniform traction t on its
// right face, held by symmetry conditions only (u_x = 0 on the left, u_y = 0
// on the bottom/front, u_z = 0 on the bottom in 3D).
igac::CaseSpec traction_case(int dim, int degree, double E, double nu, double t) {
  igac::CaseSpec s;
  s.path = "<traction test>";
  s.name = "uniform_traction";
  s.shape = dim == 2 ? "rectangle" : "box";
  s.size = dim == 2 ? std::vector<double>{2.0, 1.0} : std::vector<double>{2.0, 1.0, 0.5};
  s.degree = degree;
  s.elements = dim == 2 ? std::vector<int>{3, 2} : std::vector<int>{2, 2, 1};
  s.E = E;
  s.nu = nu;
  s.dirichlet.push_back({{"left"}, 0, 0.0});
  if (dim == 2) {
    s.dirichlet.push_back({{"bottom"}, 1, 0.0});
  } else {
    s.dirichlet.push_back({{"front"}, 1, 0.0});
    s.dirichlet.push_back({{"bottom"}, 2, 0.0});
  }
  s.pressure.push_back({{"right"}, -t});  // a pressure -t is a pull t
  s.write_vtk = false;
  return s;
}

TEST(ElasticPatchTest, UniformTractionGivesUniformStress) {
  const double E = 200.0, nu = 0.3, t = 1.5;
  for (int dim : {2, 3})
    for (int p : {2, 3}) {
      SCOPED_TRACE(std::to_string(dim) + "D, degree " + std::to_string(p));
      igac::Model m = igac::build_model(traction_case(dim, p, E, nu, t));
      // Curve the elements (faces keep their control points, hence stay
      // flat) where the quadrature stays exact: 2D any p, 3D p = 2.
      if (dim == 2 || p == 2) m.body = igac::Body(distort_interior(m.body.patch(0), 0.03, 11 * p + dim));
      const igac::RunResult r = igac::solve_model(m);
      ASSERT_EQ(r.status, "converged");
      const NurbsPatch& patch = m.body.patch(0);
      // sigma = t e_x e_x: plane strain (eps_zz = 0) in 2D, sigma_zz = 0 in 3D.
      Eigen::VectorXd strain(dim);  // principal strains along x, y, z
      if (dim == 2) {
        strain << (1 - nu * nu) / E * t, -nu * (1 + nu) / E * t;
      } else {
        strain << t / E, -nu * t / E, -nu * t / E;
      }
      double err = 0;
      for (int cp = 0; cp < patch.num_control_points(); ++cp)
        for (int i = 0; i < dim; ++i)
          err = std::max(err, std::abs(r.u(cp, i) - strain[i] * patch.points()(cp, i)));
      EXPECT_LE(err, kPatchTest * strain.cwiseAbs().maxCoeff() * 2.0) << "displacement";

      // Stresses at every Gauss point.
      const igac::PatchQuadrature quad(patch, igac::gauss_points_for(p));
      igac::ElementData ed;
      const double lambda = m.material.lambda(), mu = m.material.mu();
      double stress_err = 0, szz_err = 0;
      for (int e = 0; e < quad.num_elements(); ++e) {
        quad.evaluate(e, ed, true);
        for (int q = 0; q < ed.JxW.size(); ++q) {
          Eigen::MatrixXd grad = Eigen::MatrixXd::Zero(dim, dim);
          for (size_t a = 0; a < ed.cps.size(); ++a)
            grad += r.u.row(ed.cps[a]).transpose() * ed.dN[q].row(a);
          const Eigen::MatrixXd eps = 0.5 * (grad + grad.transpose());
          Eigen::MatrixXd sigma = lambda * eps.trace() * Eigen::MatrixXd::Identity(dim, dim) + 2 * mu * eps;
          sigma(0, 0) -= t;
          stress_err = std::max(stress_err, sigma.cwiseAbs().maxCoeff());
          if (dim == 2) szz_err = std::max(szz_err, std::abs(lambda * eps.trace() - nu * t));
        }
      }
      EXPECT_LE(stress_err, kPatchStress * t) << "stress differs from t e_x e_x";
      EXPECT_LE(szz_err, kPatchStress * t) << "plane strain sigma_zz = nu sigma_xx";
      // The pull's resultant is t times the loaded area.
      EXPECT_NEAR(r.applied_force, t * (dim == 2 ? 1.0 : 0.5), kSumRoundoff * t);
    }
}

// ------------------------------------------------------------ convergence

struct Level {
  double h, l2, h1;
};

std::vector<Level> lame_study(int degree, int levels) {
  igac::CaseSpec spec = igac::read_case(IGAC_SOURCE_DIR "/cases/lame_cylinder.toml");
  const int r0 = spec.refine;
  std::vector<Level> out;
  for (int l = 0; l < levels; ++l) {
    igac::apply_overrides(spec, degree, r0 + l);
    const igac::Model m = igac::build_model(spec);
    const igac::RunResult r = igac::solve_model(m);
    EXPECT_EQ(r.status, "converged");
    EXPECT_TRUE(r.displacement_errors.has_value());
    if (!r.displacement_errors) return out;
    out.push_back({m.mesh_size, r.displacement_errors->l2, r.displacement_errors->h1});
  }
  return out;
}

void expect_lame_rates(int p) {
  const auto lv = lame_study(p, 4);
  ASSERT_EQ(lv.size(), 4u);
  for (size_t l = 0; l + 1 < lv.size(); ++l) {
    EXPECT_LT(lv[l + 1].h, lv[l].h);
    EXPECT_LT(lv[l + 1].l2, lv[l].l2) << "L2 error must fall at level " << l + 1;
    EXPECT_LT(lv[l + 1].h1, lv[l].h1) << "H1 error must fall at level " << l + 1;
  }
  const Level& a = lv[2];
  const Level& b = lv[3];
  // Rate with the measured mesh sizes, and with the nominal halving (the
  // meshes are nested, each level splits every span in two): the two agree.
  const double rate_l2 = std::log(a.l2 / b.l2) / std::log(a.h / b.h);
  const double rate_h1 = std::log(a.h1 / b.h1) / std::log(a.h / b.h);
  const double rate_l2_halving = std::log2(a.l2 / b.l2);
  const double rate_h1_halving = std::log2(a.h1 / b.h1);
  EXPECT_NEAR(rate_l2, p + 1, kRateBand) << "L2 rate, should be about p+1";
  EXPECT_NEAR(rate_h1, p, kRateBand) << "H1 rate, should be about p";
  EXPECT_NEAR(rate_l2_halving, p + 1, kRateBand);
  EXPECT_NEAR(rate_h1_halving, p, kRateBand);
  // The last halving gains at least a factor 4 in L2 (8 expected at p = 2).
  EXPECT_LT(b.l2, a.l2 / 4);
}

TEST(ElasticConvergence, LameCylinderDegree2) { expect_lame_rates(2); }
TEST(ElasticConvergence, LameCylinderDegree3) { expect_lame_rates(3); }

// Threads add straight into K and f, one colour of elements at a time
// (engine/sparsity.hpp's colouring): the sums are the same, bit for bit,
// whatever the number of threads (the per-thread copies K had before were
// summed in an order that depended on the schedule).  On the sphere octant
// (a face collapsed onto its pole line joins elements far apart), the
// quarter disc and a body of two patches, with a body force so that f
// comes from the elements too; more threads than cores interleave the
// most.  A race (two elements of one colour sharing an equation) would lose
// additions.  The same with the mixed formulation, whose pressure functions
// add their terms colour by colour after the elements, and with constants
// per element, added with their element.
TEST(ElasticAssembly, SameSumsWhateverTheThreadCount) {
  // Several threads add colour by colour: the same sums with 2 and 5
  // threads, bit for bit.  One thread adds in element order: the same matrix
  // to round-off (summation order only).
  for (const auto f : {igac::Formulation::displacement, igac::Formulation::mixed, igac::Formulation::mixed_element}) {
    for (const std::string case_name : {"hertz3d_study", "hertz2d", "hertz2d_two_patches"}) {
      const std::string name = case_name + " " + std::string(igac::formulation_name(f));
      const igac::CaseSpec spec = igac::read_case(std::string(IGAC_SOURCE_DIR) + "/cases/" + case_name + ".toml");
      const igac::Model m = igac::build_model(spec);
      const Eigen::VectorXd g = Eigen::VectorXd::Constant(m.body.space_dim(), -0.3);
      const int threads = omp_get_max_threads();
      omp_set_num_threads(1);
      const igac::LinearSystem one = igac::assemble_linear_elasticity(m.body, *m.dofs, m.material, g, {}, f);
      omp_set_num_threads(2);
      const igac::LinearSystem two = igac::assemble_linear_elasticity(m.body, *m.dofs, m.material, g, {}, f);
      omp_set_num_threads(5);
      const igac::LinearSystem five = igac::assemble_linear_elasticity(m.body, *m.dofs, m.material, g, {}, f);
      omp_set_num_threads(threads);
      ASSERT_EQ(two.K.nonZeros(), five.K.nonZeros()) << name;
      EXPECT_TRUE(std::equal(two.K.valuePtr(), two.K.valuePtr() + two.K.nonZeros(), five.K.valuePtr())) << name;
      EXPECT_TRUE(two.f == five.f) << name;
      EXPECT_GT(two.K.norm(), 0) << name;
      ASSERT_EQ(one.K.nonZeros(), two.K.nonZeros()) << name;
      EXPECT_LE((one.K - two.K).norm(), 1e-14 * two.K.norm()) << name;
      EXPECT_LE((one.f - two.f).norm(), 1e-14 * two.f.norm()) << name;
    }
  }
}

}  // namespace
