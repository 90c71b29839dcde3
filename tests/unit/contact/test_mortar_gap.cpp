// SPDX-License-Identifier: BSD-3-Clause
// Two deformable bodies in small-deformation contact (contact/mortar_gap.hpp)
// through the same active-set solve as an obstacle:
//  - the contact patch test of Taylor and Papadopoulos: a block pressed
//    uniformly on a second block carries the pressure exactly; to round-off
//    when the meshes match, to the element-based quadrature's error when
//    they do not (measured below, both degrees);
//  - the force on the slave is minus the force on the master to round-off;
//  - friction's tangential rows are the relative tangential displacement;
//  - a body held only by the contact with the other body (its own rigid
//    motion: engine/linear_static.hpp counts each body's).
#include <gtest/gtest.h>

#include <map>

#include "contact/mortar_cells.hpp"
#include "contact/mortar_gap.hpp"
#include "contact/small_strain_contact.hpp"
#include "engine/assembly.hpp"
#include "engine/cholesky.hpp"
#include "engine/geometry/shapes.hpp"
#include "engine/linear_static.hpp"
#include "engine/spline/refinement.hpp"

namespace igac {
namespace {

constexpr double kPressure = 0.01;
const Face kLeft{0, false}, kBottom{1, false}, kTop{1, true};

NurbsPatch block(int p, int nx, int ny, double y0, double height) {
  NurbsPatch r = elevate_to(rectangle(1.0, height).patch, p);
  r = refine_to(r, 0, KnotVector::uniform(p, nx));
  r = refine_to(r, 1, KnotVector::uniform(p, ny));
  Eigen::MatrixXd P = r.points();
  P.col(1).array() += y0;
  return NurbsPatch(r.all_knots(), P, r.weights());
}

struct TwoBlocks {
  ContactSolution sol;
  WeightedGapOperator op;
  int free_modes = 0;
  double slave_force = 0, master_force = 0;  // along the load (y in 2D, z in 3D)
};

// The contact of `slave` on `master` solved with the body's free rigid
// motions; the contact forces -G^T lambda (K u + G^T lambda = f) along
// `load_dir`, summed per body.
TwoBlocks solve_pair(const Body& body, const DofMap& dofs, const LinearSystem& sys, const PatchSide& slave,
                     const PatchSide& master, int load_dir,
                     MortarIntegration integration = MortarIntegration::element) {
  TwoBlocks out;
  const RigidModes modes = free_rigid_modes(body, dofs);
  out.free_modes = int(modes.modes.cols());
  out.op = assemble_mortar_gaps(dofs, ContactFace(body, slave), MasterSurface(body, {master}), integration);
  SparseCholesky chol;
  ContactSolverOptions opt;
  opt.complementarity_scale = 1.0 / 0.1;
  out.sol = solve_small_strain_contact(sys.K, sys.f, out.op, modes, chol, opt);
  const Eigen::VectorXd force = -(out.op.G.transpose() * out.sol.lambda);
  const int dim = body.space_dim();
  for (int k = 0; k < 2; ++k)
    for (int a : body.body_cps(k)) {
      const int eq = dofs.equation(a * dim + load_dir);
      if (eq >= 0) (k == 1 ? out.slave_force : out.master_force) += force[eq];
    }
  return out;
}

// Patch 0: the lower block [0, 1] x [0, 1], held at its bottom (u_y) and
// left side (u_x), the master.  Patch 1: the upper block [0, 1] x [1, 1.5],
// its left side held in x, pressed by kPressure on top, its bottom the slave.
TwoBlocks press(int p, int n_lower, int n_upper, MortarIntegration integration = MortarIntegration::element,
                int p_upper = 0) {
  const Body body({block(p, n_lower, n_lower, 0.0, 1.0), block(p_upper > 0 ? p_upper : p, n_upper, 2, 1.0, 0.5)}, {});
  const DofMap dofs(body, {{{PatchSide{0, kBottom}}, 1, 0.0}, {{PatchSide{0, kLeft}}, 0, 0.0}, {{PatchSide{1, kLeft}}, 0, 0.0}});
  LinearSystem sys = assemble_linear_elasticity(body, dofs, LinearElastic{1.0, 0.3}, Eigen::VectorXd::Zero(2));
  add_pressure_load(body, dofs, {PatchSide{1, kTop}}, kPressure, sys.f);
  return solve_pair(body, dofs, sys, PatchSide{1, kBottom}, PatchSide{0, kTop}, 1, integration);
}

double worst_pressure_error(const TwoBlocks& r) {
  return (r.sol.lambda.array() + kPressure).abs().maxCoeff() / kPressure;
}

TEST(MortarGap, MatchingMeshesCarryTheUniformPressureToRoundOff) {
  for (int p : {2, 3}) {
    SCOPED_TRACE(p);
    const TwoBlocks r = press(p, 4, 4);
    ASSERT_TRUE(r.sol.converged) << r.sol.status;
    EXPECT_EQ(r.free_modes, 1);  // the upper block's vertical motion: held by contact alone
    EXPECT_LT(worst_pressure_error(r), 1e-10);
  }
}

TEST(MortarGap, NonMatchingMeshesCarryItToTheQuadratureError) {
  // Slave 3 elements on a master of 5 (and 7 on 5): the master's element
  // edges cut slave elements, where element-based integration is inexact.
  // Measured (largest |lambda_K + P| / P): p = 2: 1.3e-3 (3 on 5),
  // 6.7e-4 (7 on 5); p = 3: 4.4e-5, 5.0e-5.
  for (int p : {2, 3})
    for (int n_upper : {3, 7}) {
      SCOPED_TRACE(::testing::Message() << "p = " << p << ", slave " << n_upper << " on master 5");
      const TwoBlocks r = press(p, 5, n_upper);
      ASSERT_TRUE(r.sol.converged) << r.sol.status;
      const double e = worst_pressure_error(r);
      EXPECT_LT(e, p == 2 ? 2e-3 : 1e-4);
      EXPECT_GT(e, 1e-8);  // (not round-off: the quadrature does not see the master's kinks)
      // Equilibrium: the contact force on the upper block (upward) is the load.
      EXPECT_NEAR(r.slave_force, kPressure * 1.0, 1e-14);
    }
}

TEST(MortarGap, SegmentedIntegrationCarriesItToRoundOffOnAnyMeshes) {
  // The slave elements cut at the master's element edges: the integrand is
  // smooth on every piece, so the patch test holds to round-off, also
  // between blocks of different degrees (lower p = 3, upper p = 2 and the
  // reverse).
  constexpr double kRoundOff = 1e-10;
  for (int p : {2, 3})
    for (int p_upper : {2, 3})
      for (int n_upper : {3, 7}) {
        SCOPED_TRACE(::testing::Message() << "master p = " << p << ", slave p = " << p_upper << ", slave " << n_upper
                                          << " on master 5");
        const TwoBlocks r = press(p, 5, n_upper, MortarIntegration::segmented, p_upper);
        ASSERT_TRUE(r.sol.converged) << r.sol.status;
        EXPECT_LT(worst_pressure_error(r), kRoundOff);
        EXPECT_NEAR(r.slave_force, kPressure * 1.0, 1e-14);
        EXPECT_NEAR(r.slave_force + r.master_force, 0.0, 1e-14);
      }
}

// The same in 3D: a box [0, 1]^2 x [1, 1.5] on a box [0, 1]^3, n x n and
// m x m elements across the contact (degrees p below, p_upper above), held
// on x = 0 and y = 0 (symmetry) and the lower one on z = 0.
TwoBlocks press_3d(int p, int n_lower, int n_upper, MortarIntegration integration = MortarIntegration::element,
                   int p_upper = 0) {
  auto box3 = [&](int q, int n, double z0, double height) {
    NurbsPatch b = elevate_to(box(1.0, 1.0, height).patch, q);
    for (int d : {0, 1}) b = refine_to(b, d, KnotVector::uniform(q, n));
    b = refine_to(b, 2, KnotVector::uniform(q, 2));
    Eigen::MatrixXd P = b.points();
    P.col(2).array() += z0;
    return NurbsPatch(b.all_knots(), P, b.weights());
  };
  const Face x0{0, false}, y0{1, false}, z0{2, false}, z1{2, true};
  const Body body({box3(p, n_lower, 0.0, 1.0), box3(p_upper > 0 ? p_upper : p, n_upper, 1.0, 0.5)}, {});
  const DofMap dofs(body, {{{PatchSide{0, z0}}, 2, 0.0},
                           {{PatchSide{0, x0}, PatchSide{1, x0}}, 0, 0.0},
                           {{PatchSide{0, y0}, PatchSide{1, y0}}, 1, 0.0}});
  LinearSystem sys = assemble_linear_elasticity(body, dofs, LinearElastic{1.0, 0.3}, Eigen::VectorXd::Zero(3));
  add_pressure_load(body, dofs, {PatchSide{1, z1}}, kPressure, sys.f);
  return solve_pair(body, dofs, sys, PatchSide{1, z0}, PatchSide{0, z1}, 2, integration);
}

TEST(MortarGap, BoxOnBoxIn3D) {
  // Matching: round-off; 3 x 3 slave elements on 4 x 4, element-based: the
  // quadrature's error (measured 2.5e-3 at p = 2).
  const TwoBlocks matching = press_3d(2, 3, 3);
  ASSERT_TRUE(matching.sol.converged) << matching.sol.status;
  EXPECT_EQ(matching.free_modes, 1);
  EXPECT_LT(worst_pressure_error(matching), 1e-10);
  const TwoBlocks other = press_3d(2, 4, 3);
  ASSERT_TRUE(other.sol.converged) << other.sol.status;
  const double e = worst_pressure_error(other);
  EXPECT_LT(e, 5e-3);
  EXPECT_GT(e, 1e-8);
  EXPECT_NEAR(other.slave_force, kPressure, 1e-14);  // the load, through the contact (z here)
  EXPECT_NEAR(other.slave_force + other.master_force, 0.0, 1e-14);
}

TEST(MortarGap, SegmentedIntegrationPassesThe3DPatchTestToRoundOff) {
  // The slave elements cut into polygons where the master's element edges
  // project (contact/mortar_cells.hpp): 3 x 3 slave elements on 4 x 4,
  // degrees 2 and 3 either way, and 5 x 5 on 4 x 4 (elements cut in one
  // direction, in two, or not).  Measured: 3e-14 to 2e-12 (element-based:
  // 2.5e-3, BoxOnBoxIn3D).
  constexpr double kRoundOff = 1e-10;
  struct Pair {
    int p, p_upper, n_upper;
  };
  for (const Pair& c : {Pair{2, 2, 3}, Pair{2, 3, 3}, Pair{3, 2, 3}, Pair{3, 3, 3}, Pair{2, 2, 5}}) {
    SCOPED_TRACE(::testing::Message() << "master p = " << c.p << ", slave p = " << c.p_upper << ", slave " << c.n_upper
                                      << " x " << c.n_upper << " on master 4 x 4");
    const TwoBlocks r = press_3d(c.p, 4, c.n_upper, MortarIntegration::segmented, c.p_upper);
    ASSERT_TRUE(r.sol.converged) << r.sol.status;
    EXPECT_LT(worst_pressure_error(r), kRoundOff);
    EXPECT_NEAR(r.slave_force, kPressure, 1e-14);
    EXPECT_NEAR(r.slave_force + r.master_force, 0.0, 1e-14);
  }
}

// The same in 3D, element-based and segmented: the sphere octant's curved
// face over a block's top with a gap of 0.1 under its lowest point, 2 x 2
// slave elements on 3 x 3 (segmented: the cuts of the reference surface
// held).  Central differences in every fifth equation of the two faces'
// control points (all three components in turn; the octant's control
// points collapsed on its axis share theirs: moved together).
TEST(MortarGap, OperatorIsTheDerivativeOfTheExactGapsIn3D) {
  NurbsPatch ball = sphere_octant(1.0).patch;
  for (int d : {0, 2}) ball = refine_to(ball, d, KnotVector::uniform(2, 2));
  NurbsPatch under = elevate_to(box(1.0, 1.0, 0.5).patch, 2);
  for (int d : {0, 1}) under = refine_to(under, d, KnotVector::uniform(2, 3));
  Eigen::MatrixXd P = under.points();
  P.col(2).array() -= 1.6;  // [0, 1]^2 x [-1.6, -1.1]
  const Body body({ball, NurbsPatch(under.all_knots(), P, under.weights())}, {});
  const DofMap dofs(body, {});
  const PatchSide slave_side{0, Face{1, false}}, master_side{1, Face{2, true}};
  const ContactFace slave(body, slave_side);
  MasterSurface master(body, {master_side});
  {  // (segmented indeed: elements cut into several cells, not all integrated whole)
    const BezierMesh mesh(slave.sides[0].face_patch);
    std::vector<MortarCell> cells;
    int cut = 0;
    for (int e = 0; e < mesh.num_elements(); ++e) cut += mortar_cells(mesh, e, master, cells);
    EXPECT_EQ(cut, mesh.num_elements());
  }
  std::map<int, std::vector<int>> face_equations;  // equation -> its dofs
  for (const PatchSide& s : {slave_side, master_side})
    for (int a : body.side_control_points(s))
      for (int i = 0; i < 3; ++i)
        if (dofs.equation(3 * a + i) % 5 == 0) face_equations[dofs.equation(3 * a + i)].push_back(3 * a + i);
  for (MortarIntegration integration : {MortarIntegration::element, MortarIntegration::segmented}) {
    SCOPED_TRACE(integration == MortarIntegration::element ? "element-based" : "segmented");
    const WeightedGapOperator op = assemble_mortar_gaps(dofs, slave, MasterSurface(body, {master_side}), integration);
    const Eigen::MatrixXd J = op.weights.cwiseInverse().asDiagonal() * Eigen::MatrixXd(op.G);
    const Eigen::MatrixXd zero = Eigen::MatrixXd::Zero(body.num_control_points(), 3);
    EXPECT_LE((exact_mortar_gaps(zero, slave, master, integration) - op.g0.cwiseQuotient(op.weights)).cwiseAbs().maxCoeff(),
              1e-14);
    const double h = 1e-6;
    double worst = 0;
    for (const auto& [eq, list] : face_equations) {
      Eigen::MatrixXd up = zero, down = zero;
      for (int dof : list) up(dof / 3, dof % 3) = h, down(dof / 3, dof % 3) = -h;
      const Eigen::VectorXd fd =
          (exact_mortar_gaps(up, slave, master, integration) - exact_mortar_gaps(down, slave, master, integration)) / (2 * h);
      worst = std::max(worst, (fd - J.col(eq)).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-6 * J.cwiseAbs().maxCoeff());
    EXPECT_GT(J.cwiseAbs().maxCoeff(), 0.1);
  }
}

// Friction's tangential rows T (the slave's tangential displacement
// relative to the master's, along the master's tangent at the projection,
// here the block's top: t = (1, 0)): a translation d of both bodies slips
// nothing, T d = 0; of the slave alone it slips d . t on every multiplier,
// (T d)_K = K_K d_x; a master moved by `shift` (master_motion) gives
// t0_K = -K_K shift_x and g0 loses K_K shift_y.  Round-off identities (the
// bases are partitions of unity), element-based and segmented.
TEST(MortarGap, TangentialRowsAreTheRelativeTangentialDisplacement) {
  NurbsPatch disc = elevate_to(quarter_disc(1.0).patch, 2);
  disc = refine_to(disc, 0, KnotVector::uniform(2, 6));
  disc = refine_to(disc, 1, KnotVector::uniform(2, 2));
  const Body body({disc, block(2, 5, 2, -1.6, 0.5)}, {});
  const DofMap dofs(body, {});
  const ContactFace slave(body, PatchSide{0, Face{1, false}});
  const MasterSurface master(body, {PatchSide{1, kTop}});
  const Eigen::Vector2d d(0.3, -0.2), shift(0.05, 0.01);
  for (MortarIntegration integration : {MortarIntegration::element, MortarIntegration::segmented}) {
    SCOPED_TRACE(integration == MortarIntegration::element ? "element-based" : "segmented");
    const WeightedGapOperator plain = assemble_mortar_gaps(dofs, slave, master, integration);
    const WeightedGapOperator op = assemble_mortar_gaps(dofs, slave, master, integration, 0.3);
    const WeightedGapOperator moved = assemble_mortar_gaps(dofs, slave, master, integration, 0.3, shift);
    ASSERT_EQ(op.T.rows(), op.G.rows());
    EXPECT_EQ(plain.T.rows(), 0);
    EXPECT_EQ(Eigen::MatrixXd(op.G), Eigen::MatrixXd(plain.G));  // friction adds rows, changes none
    EXPECT_EQ(op.g0, plain.g0);
    Eigen::VectorXd both(dofs.num_free()), slave_only = Eigen::VectorXd::Zero(dofs.num_free());
    for (int a = 0; a < body.num_control_points(); ++a)
      for (int i = 0; i < 2; ++i) {
        both[dofs.equation(2 * a + i)] = d[i];
        if (a < disc.num_control_points()) slave_only[dofs.equation(2 * a + i)] = d[i];
      }
    const double scale = op.weights.maxCoeff();
    EXPECT_LT((op.T * both).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_LT((op.T * slave_only - d[0] * op.weights).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_LT((moved.t0 + shift[0] * op.weights).cwiseAbs().maxCoeff(), 1e-14 * scale);
    EXPECT_LT((moved.g0 - op.g0 + shift[1] * op.weights).cwiseAbs().maxCoeff(), 1e-14 * scale);
  }
}

TEST(MortarGap, ForceOnTheSlaveIsMinusTheForceOnTheMaster) {
  const TwoBlocks r = press(2, 5, 3);
  ASSERT_TRUE(r.sol.converged);
  EXPECT_GT(std::abs(r.slave_force), 0.5 * kPressure);
  EXPECT_NEAR(r.slave_force + r.master_force, 0.0, 1e-14);
}

}  // namespace
}  // namespace igac
