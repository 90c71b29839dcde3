#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""getfem_friction.py --N 16 32 64 [--csv out.csv] — GetFEM's side of the friction race (issue 23).

cases/cattaneo_mindlin.toml posed in GetFEM: a half disc (R = 1, E = 1,
nu = 0.45, plane strain) clamped at its flat top y = 0, pushed down by 0.02
onto the rigid plane y = -1, then sheared by 0.008 along x in 4 increments
with Coulomb friction f = 0.3 (small deformation).  igac moves the plane by
+0.008; GetFEM's rigid obstacle is a signed distance, blind to a plane sliding
along itself, so here the clamped top moves by -0.008 instead: the same
relative motion, the displacement differing by a rigid translation, the same
stresses and forces.

GetFEM at its Hertz peer's settings: the quarter disc of
../shared/peers/getfem/hertz_mesh.py and its mirror image (Q2 isoparametric,
graded toward the contact point), P2 displacements, P2 vector multipliers on
the arc, add_integral_contact_with_rigid_obstacle_brick with the friction
coefficient (Alart-Curnier, unsymmetric), evolutionary friction (alpha = 1,
wt = the previous step's displacement: the slip is the increment), 4x composite
contact integration, MUMPS, Newton to 1e-8 per step.

Reported: the normal force N, the tangential force Q, Hertz's half width a
(the pressure's zero crossing) and the stick zone's half width c (the
multiplier nodes where |t| < 0.99 f p, to the zero crossing of 0.99 f p - |t|),
against the Cattaneo-Mindlin law c = a sqrt(1 - Q / (f N)).  Times are mesh,
setup and the five solves (import excluded), each N a fresh subprocess.
"""
import argparse
import os
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from getfem_per_mesh import main_per_mesh  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PEER = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "peers", "getfem"))
FIELDS = ["N", "n_elem", "n_dof_u", "n_dof_lambda", "n_dof_total", "h_contact", "t_mesh_s", "t_setup_s", "t_solve_s",
          "newton_iter", "normal_force", "tangential_force", "half_width", "stick_half_width", "stick_law",
          "stick_err", "max_pressure"]
R, E, NU, F, PUSH, SHEAR, STEPS = 1.0, 1.0, 0.45, 0.3, 0.02, 0.008, 4


def half_disc_mesh(gf, hertz_mesh, N):
    q, rg = hertz_mesh.quarter_disc_mesh(N, hertz_mesh.MeshParams(), Nr=N, Nc=max(1, N // 2))
    m = gf.Mesh("empty", 2)
    gt = gf.GeoTrans("GT_QK(2,2)")
    cvs = q.cvid()
    P = np.zeros((2, 9, len(cvs)))
    for k, cv in enumerate(cvs):
        P[:, :, k] = q.pts_from_cvid(int(cv))[0]
    m.add_convex(gt, P)
    Pm = P.copy()
    Pm[0] *= -1.0
    m.add_convex(gt, hertz_mesh._fix_orientation(Pm, 2))
    of = m.outer_faces()
    nrm = m.normal_of_faces(of)
    TOP, ARC = 1, 3
    top = nrm[1] > 0.999
    m.set_region(TOP, of[:, top])
    m.set_region(ARC, of[:, ~top])
    return m, TOP, ARC


def crossing(x, g):
    """x where g (positive inside, sorted by x from the centre outward) first goes <= 0, interpolated."""
    bad = np.nonzero(g <= 0.0)[0]
    if bad.size == 0:
        return x[-1]
    k = bad[0]
    if k == 0:
        return 0.0
    return x[k - 1] + (x[k] - x[k - 1]) * g[k - 1] / (g[k - 1] - g[k])


def solve_one(args, N):
    import getfem as gf
    sys.path.insert(0, PEER)
    import hertz_mesh
    gf.util_trace_level(0)

    t0 = time.perf_counter()
    m, TOP, ARC = half_disc_mesh(gf, hertz_mesh, N)
    t_mesh = time.perf_counter() - t0
    h_t = R * hertz_mesh.MeshParams().alpha_t / N

    t0 = time.perf_counter()
    mfu = gf.MeshFem(m, 2)
    mfu.set_classical_fem(2)
    mfl = gf.MeshFem(m, 2)
    mfl.set_classical_fem(2)
    ldof = mfl.basic_dof_on_region(ARC)
    mfl_p = gf.MeshFem("partial", mfl, ldof)
    mfobs = gf.MeshFem(m, 1)
    mfobs.set_classical_fem(2)
    mim = gf.MeshIm(m, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,5)"))
    mim_c = gf.MeshIm(m, gf.Integ("IM_STRUCTURED_COMPOSITE(IM_GAUSS_PARALLELEPIPED(2,5),%d)" % args.contact_subdiv))
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    md.add_initialized_data("E", [E])
    md.add_initialized_data("nu", [NU])
    md.add_isotropic_linearized_elasticity_pstrain_brick(mim, "u", "E", "nu")
    md.add_initialized_data("Utop", [0.0, -PUSH])
    md.add_Dirichlet_condition_with_simplification("u", TOP, "Utop")
    md.add_fem_variable("lambda", mfl_p)
    md.add_initialized_data("r", [args.r if args.r > 0 else E / h_t])
    md.add_initialized_data("fr", [F])
    md.add_initialized_data("alpha", [1.0])
    md.add_initialized_fem_data("wt", mfu, np.zeros(mfu.nbdof()))
    md.add_initialized_fem_data("obstacle", mfobs, mfobs.basic_dof_nodes()[1] + R)
    md.add_integral_contact_with_rigid_obstacle_brick(mim_c, "u", "lambda", "obstacle", "r", "fr", ARC,
                                                      args.option, "alpha", "wt")
    U0 = np.zeros(mfu.nbdof())
    U0[1::2] = -PUSH
    md.set_variable("u", U0)
    t_setup = time.perf_counter() - t0

    t0 = time.perf_counter()
    nit = 0
    for step in range(STEPS + 1):   # the press, then the shear in STEPS increments
        md.set_variable("Utop", [-SHEAR * step / STEPS, -PUSH])
        res = md.solve("max_res", args.tol, "max_iter", args.max_iter, "lsolver", "mumps")
        nit += int(np.atleast_1d(res)[0])
        md.set_variable("wt", md.variable("u"))
    t_solve = time.perf_counter() - t0

    lam = np.asarray(mfl_p.extension_matrix().mult(md.variable("lambda"))).ravel()
    xy = mfl.basic_dof_nodes(ldof[0::2])
    lx, ly = lam[ldof[0::2]], lam[ldof[1::2]]
    mim_e = gf.MeshIm(m, gf.Integ("IM_STRUCTURED_COMPOSITE(IM_GAUSS_PARALLELEPIPED(2,11),16)"))
    fx = gf.asm_generic(mim_e, 0, "lambda(1)", ARC, md)
    fy = gf.asm_generic(mim_e, 0, "lambda(2)", ARC, md)
    sgn = 1.0 if fy > 0 else -1.0   # the pressure is the multiplier's normal part, signed as the force is
    Nf, Q = abs(fy), abs(fx)
    p, t = sgn * ly, np.abs(lx)
    # on each side, from the lowest point outward: the pressure's zero crossing (a) and the stick edge (c)
    ah, ch = [], []
    for side in (1.0, -1.0):
        sel = (side * xy[0] >= -1e-12) & (xy[1] < -0.5)
        x = side * xy[0][sel]
        o = np.argsort(x)
        ah.append(crossing(x[o], p[sel][o]))
        ch.append(crossing(x[o], 0.99 * F * p[sel][o] - t[sel][o]))
    a_h, c_h = 0.5 * sum(ah), 0.5 * sum(ch)
    law = a_h * np.sqrt(max(0.0, 1.0 - Q / (F * Nf)))
    return dict(N=N, n_elem=m.nbcvs(), n_dof_u=mfu.nbdof(), n_dof_lambda=mfl_p.nbdof(), n_dof_total=md.nbdof(),
                h_contact=h_t, t_mesh_s=t_mesh, t_setup_s=t_setup, t_solve_s=t_solve, newton_iter=nit,
                normal_force=Nf, tangential_force=Q, half_width=a_h, stick_half_width=c_h, stick_law=law,
                stick_err=abs(c_h - law) / a_h, max_pressure=float(p.max()))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--N", type=int, nargs="+", default=[16, 32, 64])
    ap.add_argument("--option", type=int, default=1)
    ap.add_argument("--r", type=float, default=-1, help="augmentation (<= 0: E/h at the contact point)")
    main_per_mesh(ap, __file__, solve_one, "N=%(N)d dofs=%(n_dof_total)d t=%(t_solve_s).3f it=%(newton_iter)d N=%(normal_force).6f "
                 "Q=%(tangential_force).6f a=%(half_width).5f c=%(stick_half_width).5f law %(stick_law).5f "
                 "err/a %(stick_err).4f", FIELDS)

if __name__ == "__main__":
    main()
