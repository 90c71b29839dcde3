#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The Newton driver's two linear backends on the same large-deformation run:
the direct one (CHOLMOD + Schur complement on the active set) against PETSc's
(MUMPS L D L^T on the symmetric form, LU otherwise; FGMRES with the
algebraic multigrid's field split, `--preconditioner algebraic_multigrid`;
FGMRES with the spline multigrid, `--preconditioner spline_multigrid`) on 1
and 2 MPI processes, one after the other in the same run.

    /usr/bin/python3 bench/petsc_newton.py [--case cases/hertz3d_neohookean.toml]
                                           [--refine 0 1] [--runs direct mumps1 ...] [--csv FILE]

--runs picks among direct, mumps1, mumps2, amg1, amg2, smg1, smg2 (the
backend and the number of processes; default all; direct, when first, is the
reference of the ratios and differences: without it they are left blank, as
on a mesh whose direct solve does not fit the machine).

Threads: the cores shared among the processes (one process: all of them).
Per run: unknowns, load steps, Newton iterations, the Newton time and the
time per Newton iteration (summary.json newton_seconds over the iterations),
that time over the direct run's of the same mesh, the Krylov iterations per
linear solve (mean and largest; an iterative solve), the peak resident memory
summed over the processes, and the largest relative difference of the final
contact force and reactions from the direct run's.  Writes
bench/results/petsc_newton.csv.  Never run by the tests.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IGAC = os.path.join(ROOT, "build", "igac")
MPIRUN = os.path.join(ROOT, "scripts", "mpirun.sh")


def run(case, refine, solver, ranks, preconditioner, out):
    args = ["run", case, "--refine", str(refine), "--quiet", "--out", out]
    if solver == "petsc":
        args += ["--solver", "petsc", "--preconditioner", preconditioner]
    cmd = ([MPIRUN, str(ranks)] if solver == "petsc" else [IGAC]) + args
    # each run its best use of the cores: one process takes them all for its
    # threads (assembly, BLAS), two processes one each
    threads = str(max(1, (os.cpu_count() or 1) // ranks))
    env = dict(os.environ, IGAC_BINARY=IGAC, OMP_NUM_THREADS=threads, OPENBLAS_NUM_THREADS=threads)
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


RUNS = {"direct": ("direct", 1, ""), "mumps1": ("petsc", 1, "options"), "mumps2": ("petsc", 2, "options"),
        "amg1": ("petsc", 1, "algebraic_multigrid"), "amg2": ("petsc", 2, "algebraic_multigrid"),
        "smg1": ("petsc", 1, "spline_multigrid"), "smg2": ("petsc", 2, "spline_multigrid")}


def forces(summary):
    values = [summary.get("contact", {}).get("total_force", 0.0)]
    for r in summary.get("dirichlet_reactions", []):
        values += r.get("force", [])
    return values


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--case", default=os.path.join(ROOT, "cases", "hertz3d_neohookean.toml"))
    ap.add_argument("--refine", type=int, nargs="+", default=[0, 1])
    ap.add_argument("--runs", nargs="+", choices=list(RUNS), default=list(RUNS))
    ap.add_argument("--csv", default=os.path.join(HERE, "results", "petsc_newton.csv"))
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for refine in a.refine:
            direct = None
            for solver, ranks, pc in (RUNS[name] for name in a.runs):
                s = run(a.case, refine, solver, ranks, pc, os.path.join(tmp, f"{refine}_{solver}_{ranks}_{pc}"))
                krylov = s["solver"].get("krylov_iterations", [])
                iterations = sum(step["newton_iterations"] for step in s["load_steps"])
                per_iteration = s["newton_seconds"] / max(iterations, 1)
                if direct is None:
                    direct = (s, per_iteration)
                scale = max(abs(v) for v in forces(direct[0])) or 1.0
                diff = max(abs(x - y) for x, y in zip(forces(s), forces(direct[0]))) / scale
                row = {"case": os.path.basename(a.case), "refine": refine, "dofs": s["dofs"], "solver": solver,
                       "ranks": ranks, "method": s["solver"].get("method", "CHOLMOD + Schur"),
                       "steps": len(s["load_steps"]), "newton_iterations": iterations,
                       "newton_s": round(s["newton_seconds"], 3), "s_per_iteration": round(per_iteration, 4),
                       "over_direct": round(per_iteration / direct[1], 2) if a.runs[0] == "direct" else "",
                       "krylov_mean": round(sum(krylov) / len(krylov), 1) if krylov else "",
                       "krylov_max": max(krylov) if krylov else "",
                       "peak_gib": round(s["solver"].get("peak_resident_all_ranks_gib",
                                                         s.get("memory_gib", {}).get("peak_resident", 0)), 3),
                       "force_difference": f"{diff:.2e}" if a.runs[0] == "direct" else ""}
                rows.append(row)
                print(", ".join(f"{k} {v}" for k, v in row.items()), flush=True)
    os.makedirs(os.path.dirname(a.csv), exist_ok=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {a.csv}")


if __name__ == "__main__":
    sys.exit(main())
