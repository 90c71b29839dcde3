#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""getfem_two_bodies_largedef.py --N 8 16 32 [--csv out.csv] — GetFEM's side of the large-deformation
two-body race (issue 22).

cases/roller_on_block_neohookean.toml posed in GetFEM: the hertz2d quarter-disc roller (R = 1,
top face y = 0, symmetry x = 0) pressed by the follower pressure P = 0.1 into a block
[0,3] x [-3,-1] (bottom held in y, symmetry x = 0), both of the compressible Neo-Hookean rubber
E = 1, nu = 0.3 that igac and the large-deformation GetFEM peer use,

    Psi = mu/2 (|F|^2 - 2) - mu ln J + lambda/2 (ln J)^2   (plane strain),

written as a GWFL potential (GetFEM derives residual and tangent).  The follower pressure is
-P J F^-T N on the roller's top face, as in ../shared/peers/getfem-largedef/largedef2d.py.

Contact: GetFEM's own large-deformation, large-sliding contact between two deformable bodies,
add_integral_large_sliding_contact_brick_raytracing (Alart-Curnier augmented Lagrangian, the
master found by ray tracing in the current configuration of both bodies at every assembly),
frictionless; the slave is the roller's arc with a vector multiplier of degree --lambda-deg,
the master the block's top.  Meshes as the small-deformation race (bench/getfem_two_bodies.py):
Q2 isoparametric, the roller graded toward its contact point, the block a graded Q2 grid.

Load: --steps equal increments of the pressure, each Newton (GetFEM's md.solve, MUMPS) started
from the linear extrapolation of the last two converged states, the first from a rigid approach.

Reported (the quantities igac's summary gives for its contact): the applied vertical force (the
follower pressure's resultant on the deformed top face), the deformed contact half width (the
deformed x where the nodal nominal pressure falls to zero on the arc) and the peak nominal
pressure (the largest nodal |lambda| where lambda pushes the arc in).

Each N is a fresh subprocess; times are mesh, setup and solve (import excluded).
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from getfem_per_mesh import main_per_mesh, zero_crossing  # noqa: E402
from getfem_two_bodies import block_mesh  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PEER = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "peers", "getfem"))

FIELDS = ["N", "n_elem", "n_dof_u", "n_dof_lambda", "n_dof_total", "h_contact", "t_mesh_s", "t_setup_s",
          "t_solve_s", "steps", "newton_iter", "force", "half_width", "max_pressure", "min_J"]

R, E, NU, P = 1.0, 1.0, 0.3, 0.1
MU, LMB = E / (2 * (1 + NU)), E * NU / ((1 + NU) * (1 - 2 * NU))
BLOCK = (3.0, 2.0)   # width, height: [0,3] x [-3,-1]


def solve_one(args, N):
    import getfem as gf
    sys.path.insert(0, PEER)
    import hertz_mesh
    gf.util_trace_level(0)

    t0 = time.perf_counter()
    mp = hertz_mesh.MeshParams()
    m1, rg1 = hertz_mesh.quarter_disc_mesh(N, mp, Nr=N, Nc=max(1, N // 2))
    m2, _, rg2 = block_mesh(gf, hertz_mesh, N, max(2, N // 2), alpha_x=args.block_alpha_x,
                            alpha_y=args.block_alpha_y, size=BLOCK)
    t_mesh = time.perf_counter() - t0
    h_t = R * mp.alpha_t / N

    t0 = time.perf_counter()
    mfu1, mfu2 = gf.MeshFem(m1, 2), gf.MeshFem(m2, 2)
    mfu1.set_classical_fem(2)
    mfu2.set_classical_fem(2)
    mfl = gf.MeshFem(m1, 2)
    mfl.set_classical_fem(args.lambda_deg)
    mfs1, mfs2 = gf.MeshFem(m1, 1), gf.MeshFem(m2, 1)
    mfs1.set_classical_fem(2)
    mfs2.set_classical_fem(2)
    mim1 = gf.MeshIm(m1, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,5)"))
    mim2 = gf.MeshIm(m2, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,5)"))
    composite = "IM_STRUCTURED_COMPOSITE(IM_GAUSS_PARALLELEPIPED(2,5),%d)" % args.contact_subdiv
    mim1_c, mim2_c = gf.MeshIm(m1, gf.Integ(composite)), gf.MeshIm(m2, gf.Integ(composite))

    md = gf.Model("real")
    md.add_fem_variable("u1", mfu1)
    md.add_fem_variable("u2", mfu2)
    md.add_initialized_data("mu", [MU])
    md.add_initialized_data("lmb", [LMB])
    for b, mim in (("1", mim1), ("2", mim2)):
        md.add_macro("F" + b, "Id(2)+Grad_u" + b)
        md.add_nonlinear_term(mim, "mu/2*(Norm_sqr(F{0})-2) - mu*log(Det(F{0})) + lmb/2*sqr(log(Det(F{0})))"
                              .format(b), -1, 1, 0)
    md.add_initialized_data("Pt", [0.0])
    md.add_nonlinear_term(mim1, "Pt*Det(F1)*((Inv(F1)')*Normal).Test_u1", rg1["TOP"])
    md.add_normal_Dirichlet_condition_with_multipliers(mim1, "u1", mfs1, rg1["SYM"])
    md.add_normal_Dirichlet_condition_with_multipliers(mim2, "u2", mfs2, rg2["SYM"])
    md.add_normal_Dirichlet_condition_with_multipliers(mim2, "u2", mfs2, rg2["BOT"])

    mfl_arc = gf.MeshFem("partial", mfl, mfl.basic_dof_on_region(rg1["ARC"]))
    md.add_fem_variable("lambda1", mfl_arc)
    r = args.r if args.r > 0 else E / h_t
    md.add_initialized_data("r", [r])
    md.add_initialized_data("f", [0.0])
    md.add_initialized_data("alpha", [1.0])
    ind = md.add_integral_large_sliding_contact_brick_raytracing("r", args.release, "f", "alpha", 0)
    md.add_slave_contact_boundary_to_large_sliding_contact_brick(ind, mim1_c, rg1["ARC"], "u1", "lambda1", "")
    md.add_master_contact_boundary_to_large_sliding_contact_brick(ind, mim2_c, rg2["TOP"], "u2", "")
    t_setup = time.perf_counter() - t0

    # a rigid approach of the roller for the first step (the pressure alone leaves it floating)
    a1 = np.sqrt(8.0 * R ** 2 * (P / args.steps) * (1.0 - NU ** 2) / (np.pi * E / 2))
    U0 = np.zeros(mfu1.nbdof())
    U0[1::2] = -a1 ** 2 / (2 * R)
    md.set_variable("u1", U0)

    t0 = time.perf_counter()
    states, nit = [], 0
    for step in range(1, args.steps + 1):
        lf = step / args.steps
        if len(states) >= 2:
            (l0, x0), (l1, x1) = states[-2], states[-1]
            md.to_variables(x1 + (x1 - x0) * (lf - l1) / (l1 - l0))
        md.set_variable("Pt", [P * lf])
        res = md.solve("max_res", args.tol, "max_iter", args.max_iter, "lsolver", "mumps")
        its = int(np.atleast_1d(res)[0])
        if its >= args.max_iter:
            raise SystemExit("N=%d: Newton did not converge at load step %d" % (N, step))
        nit += its
        states = (states + [(lf, np.asarray(md.from_variables(), dtype=float).ravel().copy())])[-2:]
    t_solve = time.perf_counter() - t0

    mim_e = gf.MeshIm(m1, gf.Integ("IM_STRUCTURED_COMPOSITE(IM_GAUSS_PARALLELEPIPED(2,11),16)"))
    force = gf.asm_generic(mim_e, 0, "Pt*Det(F1)*((Inv(F1)')*Normal)(2)", rg1["TOP"], md)
    # nodal multipliers on the arc, ordered from the contact point outwards
    lam = np.asarray(mfl_arc.extension_matrix().mult(md.variable("lambda1"))).ravel()
    ldof = mfl.basic_dof_on_region(rg1["ARC"])[0::2]
    xl = mfl.basic_dof_nodes(ldof)
    order = np.argsort(np.arctan2(xl[0], -xl[1]))
    X, Y = xl[0][order], xl[1][order]
    lx, ly = lam[ldof[order]], lam[ldof[order] + 1]
    U1 = np.asarray(md.variable("u1")).ravel()
    xu = mfu1.basic_dof_nodes()
    where = {(round(xu[0, d], 11), round(xu[1, d], 11)): d for d in range(0, xu.shape[1], 2)}
    ud = np.array([where[(round(x, 11), round(y, 11))] for x, y in zip(X, Y)])
    xd = X + U1[ud]
    # the multiplier is the traction the master exerts on the arc: it pushes inwards (toward the
    # roller's centre, -X/|X| up to the rotation of the normal) where the arc is pressed
    push = -(lx * X + ly * Y) / np.hypot(X, Y)
    p = np.where(push > 0, np.hypot(lx, ly), -np.hypot(lx, ly))
    a_def = zero_crossing(xd, p)
    mimd = gf.MeshImData(mim1)
    min_j = float(np.asarray(md.interpolation("Det(F1)", mimd)).min())
    return dict(N=N, n_elem=m1.nbcvs() + m2.nbcvs(), n_dof_u=mfu1.nbdof() + mfu2.nbdof(),
                n_dof_lambda=md.interval_of_variable("lambda1")[1], n_dof_total=md.nbdof(), h_contact=h_t,
                t_mesh_s=t_mesh, t_setup_s=t_setup, t_solve_s=t_solve, steps=args.steps, newton_iter=nit,
                force=force, half_width=a_def, max_pressure=p.max(), min_J=min_j)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--N", type=int, nargs="+", default=[8, 16, 32])
    ap.add_argument("--lambda-deg", type=int, default=2)
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--block-alpha-x", type=float, default=0.3,
                    help="share of the block's width meshed as finely as the roller's contact zone")
    ap.add_argument("--block-alpha-y", type=float, default=0.15)
    ap.add_argument("--release", type=float, default=0.5, help="ray-tracing release distance")
    ap.add_argument("--r", type=float, default=-1, help="augmentation (<= 0: E/h, h the arc element at the contact)")
    main_per_mesh(ap, __file__, solve_one, "N=%(N)d dofs=%(n_dof_total)d t=%(t_solve_s).3f it=%(newton_iter)d "
                 "force=%(force).6f a=%(half_width).5f p=%(max_pressure).5f minJ=%(min_J).3f", FIELDS)


if __name__ == "__main__":
    main()
