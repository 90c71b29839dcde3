#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""getfem_two_bodies.py --N 8 16 32 [--csv out.csv] — GetFEM's side of the two-body race (issue 22).

cases/roller_on_block.toml posed in GetFEM: the hertz2d quarter-disc roller
(R = 1, E = 1, nu = 0.3, pressure P = 0.003 on its top face y = 0, x = 0
symmetry) on an elastic block [0,4] x [-5,-1] (E = 3, nu = 0.3, bottom held
in y, x = 0 symmetry), plane strain, small strain.  Hertz with the combined
modulus (1/E* = sum (1 - nu_i^2)/E_i, i.e. E = 0.75 at nu = 0.3):
a = 0.096277, p0 = 0.039674.

GetFEM at the settings its Hertz peer (../shared/peers/getfem/hertz2d.py)
found best: Q2 isoparametric meshes (the roller is hertz_mesh.quarter_disc_mesh,
graded toward the contact point; the block a graded Q2 grid, fine at (0,-1)),
P2 displacements, P2 multipliers on the roller's arc (the slave), the
integral Alart-Curnier (unsymmetric) contact between the two meshes,
augmentation r = 0.75/h (h: the arc element at the contact point), contact
integrals on a 4x composite rule, MUMPS, Newton to 1e-8, started from a rigid approach of the roller.

--brick gwfl (the default) writes that augmented Lagrangian in GetFEM's weak
form language: the slave point X meets the block's flat top at (X(1), -1), an
interpolate transformation between the meshes.  --brick integral is GetFEM's
packaged add_integral_contact_between_nonmatching_meshes_brick with the same
settings: in Debian's GetFEM 5.4.2 its pressure piles up on the first arc
elements (N = 16: peak 6.8 times Hertz's, see docs/benchmarks.md).  --brick
nodal is add_nodal_contact_between_nonmatching_meshes_brick (one multiplier, a
nodal force, per slave node; the pressure recovered as the P2 field p with
M p = F on the arc): right, but slower to each accuracy than gwfl and stalled
at 1.5 % L2 (N = 48, 64), so the race uses gwfl.

Each N is a fresh subprocess; times are mesh, setup and solve (import excluded).
"""
import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from getfem_per_mesh import main_per_mesh, zero_crossing  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
PEER = os.path.normpath(os.path.join(HERE, "..", "..", "shared", "peers", "getfem"))

FIELDS = ["N", "n_elem", "n_dof_u", "n_dof_lambda", "n_dof_total", "h_contact", "t_mesh_s", "t_setup_s", "t_solve_s",
          "newton_iter", "a_exact", "a_h", "p0_exact", "p0_h", "a_rel_err", "p0_rel_err", "peak_err",
          "L2_err_rel", "force_h"]

R, E1, E2, NU, P = 1.0, 1.0, 3.0, 0.3, 0.003
E_EQ = 1.0 / (1.0 / E1 + 1.0 / E2)            # same nu: the plane-strain combined modulus is E_EQ/(1-nu^2)
A_H = np.sqrt(8.0 * R ** 2 * P * (1.0 - NU ** 2) / (np.pi * E_EQ))
P0_H = 4.0 * R * P / (np.pi * A_H)


def block_mesh(gf, hertz_mesh, nx, ny, alpha_x=0.05, q_x=3.0, alpha_y=0.05, q_y=3.0, size=(4.0, 4.0)):
    """Q2 grid of [0,w] x [-1-h,-1] (size = (w, h)), graded toward x = 0 and toward y = -1 (vertices
    graded, mid-nodes between)."""
    w, h = size
    gx = lambda xi: hertz_mesh.grad_fun(xi, alpha_x, q_x)
    gy = lambda z: 1.0 - hertz_mesh.grad_fun(1.0 - z, alpha_y, q_y)
    Pn = hertz_mesh._fix_orientation(
        hertz_mesh._block_nodes_2d(nx, ny, lambda A, B: (w * A, -1.0 - h + h * B), gx, gy), 2)
    m = gf.Mesh("empty", 2)
    m.add_convex(gf.GeoTrans("GT_QK(2,2)"), Pn)
    of = m.outer_faces()
    nrm = m.normal_of_faces(of)
    TOPB, SYMB, BOT = 11, 12, 13
    m.set_region(TOPB, of[:, nrm[1] > 0.999])
    m.set_region(SYMB, of[:, nrm[0] < -0.999])
    m.set_region(BOT, of[:, nrm[1] < -0.999])
    return m, w * alpha_x / nx, dict(TOP=TOPB, SYM=SYMB, BOT=BOT)


def solve_one(args, N):
    import getfem as gf
    sys.path.insert(0, PEER)
    import hertz_mesh
    gf.util_trace_level(0)

    t0 = time.perf_counter()
    mp = hertz_mesh.MeshParams()  # the hertz2d defaults: poly alpha_t 0.15 q 4, radial 0.25 q 3, s = R/2
    m1, rg1 = hertz_mesh.quarter_disc_mesh(N, mp, Nr=N, Nc=max(1, N // 2))
    m2, h2, rg2 = block_mesh(gf, hertz_mesh, N, N)
    t_mesh = time.perf_counter() - t0
    h_t = R * mp.alpha_t / N

    t0 = time.perf_counter()
    k = args.u_deg
    mfu1, mfu2 = gf.MeshFem(m1, 2), gf.MeshFem(m2, 2)
    mfu1.set_classical_fem(k)
    mfu2.set_classical_fem(k)
    mfl = gf.MeshFem(m1, 1)
    mfl.set_classical_fem(args.lambda_deg)
    ldof = mfl.basic_dof_on_region(rg1["ARC"])
    mfl_p = gf.MeshFem("partial", mfl, ldof)
    mfs1, mfs2 = gf.MeshFem(m1, 1), gf.MeshFem(m2, 1)
    mfs1.set_classical_fem(k)
    mfs2.set_classical_fem(k)
    mim1 = gf.MeshIm(m1, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,%d)" % (2 * k + 1)))
    mim2 = gf.MeshIm(m2, gf.Integ("IM_GAUSS_PARALLELEPIPED(2,%d)" % (2 * k + 1)))
    mim_c = gf.MeshIm(m1, gf.Integ("IM_STRUCTURED_COMPOSITE(IM_GAUSS_PARALLELEPIPED(2,%d),%d)"
                                   % (2 * k + 1, args.contact_subdiv)))

    md = gf.Model("real")
    md.add_fem_variable("u1", mfu1)
    md.add_fem_variable("u2", mfu2)
    md.add_initialized_data("E1", [E1])
    md.add_initialized_data("E2", [E2])
    md.add_initialized_data("nu", [NU])
    md.add_isotropic_linearized_elasticity_pstrain_brick(mim1, "u1", "E1", "nu")
    md.add_isotropic_linearized_elasticity_pstrain_brick(mim2, "u2", "E2", "nu")
    md.add_initialized_data("P", [P])
    md.add_source_term_brick(mim1, "u1", "[0,-P]", rg1["TOP"])
    md.add_normal_Dirichlet_condition_with_multipliers(mim1, "u1", mfs1, rg1["SYM"])
    md.add_normal_Dirichlet_condition_with_multipliers(mim2, "u2", mfs2, rg2["SYM"])
    md.add_normal_Dirichlet_condition_with_multipliers(mim2, "u2", mfs2, rg2["BOT"])
    r = args.r if args.r > 0 else E_EQ / h_t
    md.add_initialized_data("r", [r])
    if args.brick == "gwfl":
        # The same integral Alart-Curnier augmented Lagrangian written in GetFEM's weak form language: the
        # slave point X of the arc meets the block's top at (X(1), -1) (the closest point of a flat master),
        # an interpolate transformation between the two meshes; gap along the master normal (0, 1).
        md.add_fem_variable("lambda_n", mfl_p)
        md.add_interpolate_transformation_from_expression("proj", m1, m2, "[X(1), -1]")
        gap = "(X(2) + 1 + u1(2) - Interpolate(u2, proj)(2))"
        md.add_nonlinear_term(mim_c, "-lambda_n*(Test_u1(2) - Interpolate(Test_u2, proj)(2))", rg1["ARC"])
        md.add_nonlinear_term(mim_c, "(lambda_n - pos_part(lambda_n - r*%s))*Test_lambda_n/r" % gap, rg1["ARC"])
    elif args.brick == "integral":
        md.add_fem_variable("lambda_n", mfl_p)
        md.add_integral_contact_between_nonmatching_meshes_brick(mim_c, "u1", "u2", "lambda_n", "r",
                                                                 rg1["ARC"], rg2["TOP"], args.option)
    else:   # nodal: one multiplier per slave node of the arc
        nslave = mfu1.basic_dof_on_region(rg1["ARC"]).size // 2
        # the brick adds lambda_n itself (one per slave node)
        md.add_nodal_contact_between_nonmatching_meshes_brick(mim1, mim2, "u1", "u2", "lambda_n", "r",
                                                              rg1["ARC"], rg2["TOP"], 1, 0, args.option)
    U0 = np.zeros(mfu1.nbdof())
    U0[1::2] = -3.0 * (3 * h_t) ** 2 / (2 * R)   # a rigid approach: a few roller elements in contact
    md.set_variable("u1", U0)
    t_setup = time.perf_counter() - t0

    t0 = time.perf_counter()
    res = md.solve("max_res", args.tol, "max_iter", args.max_iter, "lsolver", "mumps")
    t_solve = time.perf_counter() - t0
    nit = int(np.atleast_1d(res)[0])

    n_dof_total = md.nbdof()
    if args.brick == "nodal":
        # nodal forces F_i = int p phi_i on the slave nodes -> the P2 pressure p, M p = F on the arc (the
        # pressure then sits in a fem datum 'lambda_n' on mfl, minus the pressure as the bricks have it)
        F = np.asarray(md.variable("lambda_n")).ravel()
        sdof = mfu1.basic_dof_on_region(rg1["ARC"])[0::2] // 2
        M = gf.asm_mass_matrix(mim1, mfl, mfl, rg1["ARC"]).full()[np.ix_(sdof, sdof)]
        lam = np.zeros(mfl.nbdof())
        lam[sdof] = np.linalg.solve(M, F)
        md2 = gf.Model("real")
        md2.add_initialized_fem_data("lambda_n", mfl, lam)
        md = md2
        ldof = sdof
    else:
        lam = np.asarray(mfl_p.extension_matrix().mult(md.variable("lambda_n"))).ravel()
    xl = mfl.basic_dof_nodes(ldof)
    order = np.argsort(xl[0])
    sgn = 1.0 if args.brick == "gwfl" else -1.0   # the bricks' multiplier is minus the pressure
    xs, ps = xl[0][order], sgn * lam[ldof][order]
    p0h = ps.max()
    a_h = zero_crossing(xs, ps)   # as hertz2d.py
    md.add_initialized_data("aH", [A_H])
    md.add_initialized_data("p0H", [P0_H])
    mim_e = gf.MeshIm(m1, gf.Integ("IM_STRUCTURED_COMPOSITE(IM_GAUSS_PARALLELEPIPED(2,11),16)"))
    pH = "p0H*sqrt(pos_part(1-sqr(X(1)/aH)))"
    err2 = gf.asm_generic(mim_e, 0, "sqr(%g*lambda_n-%s)" % (sgn, pH), rg1["ARC"], md)
    nrm2 = gf.asm_generic(mim_e, 0, "sqr(%s)" % pH, rg1["ARC"], md)
    force = sgn * gf.asm_generic(mim_e, 0, "lambda_n", rg1["ARC"], md)
    a_err, p_err = (a_h - A_H) / A_H, (p0h - P0_H) / P0_H
    return dict(N=N, n_elem=m1.nbcvs() + m2.nbcvs(), n_dof_u=mfu1.nbdof() + mfu2.nbdof(),
                n_dof_lambda=ldof.size, n_dof_total=n_dof_total, h_contact=h_t,
                t_mesh_s=t_mesh, t_setup_s=t_setup, t_solve_s=t_solve, newton_iter=nit,
                a_exact=A_H, a_h=a_h, p0_exact=P0_H, p0_h=p0h, a_rel_err=a_err, p0_rel_err=p_err,
                peak_err=max(abs(a_err), abs(p_err)), L2_err_rel=np.sqrt(err2 / nrm2), force_h=force)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--N", type=int, nargs="+", default=[8, 16, 32])
    ap.add_argument("--u-deg", type=int, default=2)
    ap.add_argument("--lambda-deg", type=int, default=2)
    ap.add_argument("--option", type=int, default=1, help="1 Alart-Curnier unsym, 2 sym, 3 unsym+augm, 4 new unsym")
    ap.add_argument("--brick", default="gwfl", choices=["gwfl", "integral", "nodal"])
    ap.add_argument("--r", type=float, default=-1, help="augmentation (<= 0: 0.75/h, h the arc element at the contact)")
    main_per_mesh(ap, __file__, solve_one, "N=%(N)d dofs=%(n_dof_total)d t=%(t_solve_s).3f it=%(newton_iter)d a_h=%(a_h).5f (%(a_exact).5f) "
                 "p0_h=%(p0_h).5f (%(p0_exact).5f) L2rel=%(L2_err_rel).3e F=%(force_h).6f", FIELDS)

if __name__ == "__main__":
    main()
