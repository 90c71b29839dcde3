#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Direct (CHOLMOD) against PETSc (MUMPS LDL^T, the algebraic-multigrid field
split and the spline multigrid) on 1 and 2 MPI processes, for the 3D Hertz
study's meshes.

    /usr/bin/python3 bench/petsc_scaling.py [--levels 0 1 2] [--ranks 1 2]
                                             [--solvers direct mumps krylov multigrid]
                                             [--elements 15 3 15] [--csv FILE]

--elements replaces the case's level-0 mesh (levels stay nested: level L is
it refined L times); the spline multigrid's hierarchy is levels L, ..., 0.
a and p0 are compared with the direct run of the same level when the bench
ran it (relative differences in the CSV).

Level L is cases/hertz3d_study.toml refined L times (level 2 is the shipped
hertz3d mesh, 32k unknowns; level 3 the 225k-unknown reference).  One process
per run (scripts/mpirun.sh for PETSc on 2); per run: unknowns, active-set
iterations, Krylov iterations per solve, wall time, the peak resident memory
summed over the processes (summary.json), and the contact results, so that
every solver is checked against the direct one.  Writes
bench/results/petsc_scaling.csv.  Never run by the tests.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IGAC = os.path.join(ROOT, "build", "igac")
MPIRUN = os.path.join(ROOT, "scripts", "mpirun.sh")
CASE = os.path.join(ROOT, "cases", "hertz3d_study.toml")

KRYLOV = ("-ksp_type fgmres -pc_type fieldsplit -pc_fieldsplit_type schur "
          "-pc_fieldsplit_schur_fact_type full -pc_fieldsplit_schur_precondition selfp "
          "-fieldsplit_u_ksp_type preonly -fieldsplit_u_pc_type gamg "
          "-fieldsplit_lambda_ksp_type preonly -fieldsplit_lambda_pc_type jacobi")
OPTIONS = {"direct": None, "mumps": "", "krylov": KRYLOV, "multigrid": ""}


def case_with_elements(elements, folder):
    """cases/hertz3d_study.toml with its level-0 mesh replaced, no ParaView files."""
    text = open(CASE).read()
    if elements:
        at = text.index("elements = [")
        text = text[:at] + "elements = [" + ", ".join(str(e) for e in elements) + text[text.index("]", at):]
    text += "\n[output]\nvtk = false\n"
    path = os.path.join(folder, "hertz3d_study_" + "x".join(str(e) for e in elements or []) + ".toml")
    with open(path, "w") as f:
        f.write(text)
    return path


def run(case, level, solver, ranks, out):
    args = ["run", case, "--refine", str(level), "--out", out, "--quiet"]
    if solver != "direct":
        args += ["--solver", "petsc"]
        if OPTIONS[solver]:
            args += ["--petsc-options", OPTIONS[solver]]
        if solver == "multigrid":
            args += ["--preconditioner", "spline_multigrid"]
    cmd = [IGAC] + args if ranks == 1 else [MPIRUN, str(ranks)] + args
    env = dict(os.environ, OMP_NUM_THREADS=str(max(1, 2 // ranks)))
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env)
    wall = time.time() - t0
    path = os.path.join(out, "summary.json")
    if os.path.exists(path) and os.path.getmtime(path) < t0:
        os.remove(path)
    if not os.path.exists(path):
        return {"status": f"exit {p.returncode}: {p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ''}",
                "wall_s": wall}
    s = json.load(open(path))
    solver_rec = s.get("solver", {})
    its = solver_rec.get("krylov_iterations", [])
    mem = solver_rec.get("peak_resident_all_ranks_gib") or s["memory_gib"]["peak_resident"]
    return {
        "dofs": s["dofs"], "status": s["status"],
        "active_set_iterations": s["contact"]["active_set_iterations"],
        "krylov_iterations": " ".join(str(i) for i in its),
        "krylov_mean": round(sum(its) / len(its), 1) if its and solver != "mumps" else "",
        "krylov_max": max(its) if its and solver != "mumps" else "",
        "setup_s": round(s["timing_s"].get("factorization", 0), 2),
        "wall_s": round(wall, 2), "solve_s": round(s["timing_s"]["total"], 2),
        "peak_gib_all_ranks": round(mem, 3),
        "half_width": s["contact"]["half_width"], "max_pressure": s["contact"]["max_pressure"],
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--levels", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--solvers", nargs="+", default=["direct", "mumps", "krylov"], choices=list(OPTIONS))
    ap.add_argument("--elements", type=int, nargs="+", help="level-0 elements (default: the case's)")
    ap.add_argument("--csv", default=os.path.join(HERE, "results", "petsc_scaling.csv"))
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        case = case_with_elements(a.elements, tmp)
        for level in a.levels:
            direct = None
            for solver in a.solvers:
                for ranks in (a.ranks if solver != "direct" else [1]):
                    r = run(case, level, solver, ranks, os.path.join(tmp, f"{level}_{solver}_{ranks}"))
                    r.update(level=level, solver=solver, ranks=ranks,
                             elements=" ".join(map(str, a.elements)) if a.elements else "")
                    if solver == "direct" and "half_width" in r:
                        direct = r
                    elif direct and "half_width" in r:
                        for key in ("half_width", "max_pressure"):
                            r[key + "_vs_direct"] = f"{abs(r[key] - direct[key]) / abs(direct[key]):.1e}"
                    rows.append(r)
                    print(json.dumps(r), flush=True)
    keys = ["elements", "level", "solver", "ranks", "dofs", "status", "active_set_iterations", "krylov_mean",
            "krylov_max", "krylov_iterations", "wall_s", "solve_s", "setup_s", "peak_gib_all_ranks", "half_width",
            "max_pressure", "half_width_vs_direct", "max_pressure_vs_direct"]
    os.makedirs(os.path.dirname(a.csv), exist_ok=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {a.csv}", file=sys.stderr)


if __name__ == "__main__":
    main()
