#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""What `preconditioner = "auto"` chooses, against both of its choices, on
2D and 3D Hertz meshes: PETSc's factorisation (MUMPS, the default), the
spline multigrid and auto, one process, in one run of this script.

    /usr/bin/python3 bench/preconditioner_choice.py [--runs 2d:1 2d:2 2d:3 3d:1 3d:2 3d:3]
                                                    [--csv FILE] [--plot FILE]

2d:L is cases/hertz2d.toml at --refine L (L = 3: 133k unknowns), 3d:L
cases/hertz3d_study.toml at --refine L (L = 3: 225k).  Per run: unknowns,
wall time, the peak resident memory, Krylov iterations per solve, what auto
chose and why (summary.json's solver.choice), and a, p0 against the MUMPS run
of the same mesh.  The ratio column is each run's wall time over the faster
of MUMPS and the multigrid on that mesh: auto's is 1 where it chose well.
Writes bench/results/preconditioner_choice.csv and a plot of wall time
against unknowns.  Never run by the tests.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from results_io import pyplot, write_rows  # noqa: E402

ROOT = os.path.dirname(HERE)
IGAC = os.path.join(ROOT, "build", "igac")
CASES = {"2d": "cases/hertz2d.toml", "3d": "cases/hertz3d_study.toml"}
PRECONDITIONERS = {"mumps": "options", "multigrid": "spline_multigrid", "auto": "auto"}


def run(case, level, preconditioner, out):
    # A copy of the case without ParaView files (--no-output would leave no summary.json).
    copy = out + ".toml"
    with open(copy, "w") as f:
        f.write(open(os.path.join(ROOT, case)).read() + "\n[output]\nvtk = false\n")
    cmd = [IGAC, "run", copy, "--refine", str(level), "--out", out, "--quiet", "--solver", "petsc",
           "--preconditioner", PRECONDITIONERS[preconditioner]]
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ, OMP_NUM_THREADS="2"))
    wall = time.time() - t0
    path = os.path.join(out, "summary.json")
    if p.returncode != 0 or not os.path.exists(path):
        return {"status": f"exit {p.returncode}: {p.stderr.strip().splitlines()[-1] if p.stderr.strip() else ''}",
                "wall_s": round(wall, 2)}
    s = json.load(open(path))
    solver = s.get("solver", {})
    its = solver.get("krylov_iterations", [])
    return {
        "dofs": s["dofs"], "status": s["status"], "method": solver.get("method", ""),
        "choice": solver.get("choice", ""),
        "krylov_iterations": " ".join(str(i) for i in its) if "multigrid" in solver.get("method", "") else "",
        "wall_s": round(wall, 2),
        "peak_gib": round(solver.get("peak_resident_all_ranks_gib") or s["memory_gib"]["peak_resident"], 3),
        "half_width": s["contact"]["half_width"], "max_pressure": s["contact"]["max_pressure"],
    }


def plot(rows, path):
    plt = pyplot()
    if plt is None:
        return
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, dim in zip(axes, ("2d", "3d")):
        for pre, marker in (("mumps", "o-"), ("multigrid", "s-"), ("auto", "x--")):
            pts = [(r["dofs"], r["wall_s"]) for r in rows if r["mesh"].startswith(dim) and r["preconditioner"] == pre
                   and "dofs" in r]
            if pts:
                ax.loglog(*zip(*sorted(pts)), marker, label=pre)
        ax.set_title(f"Hertz {dim.upper()}, one process")
        ax.set_xlabel("unknowns")
        ax.set_ylabel("wall time (s)")
        ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    print(f"wrote {path}", file=sys.stderr)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", nargs="+", default=["2d:1", "2d:2", "2d:3", "3d:1", "3d:2", "3d:3"])
    ap.add_argument("--csv", default=os.path.join(HERE, "results", "preconditioner_choice.csv"))
    ap.add_argument("--plot", default=os.path.join(HERE, "results", "preconditioner_choice.png"))
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for mesh in a.runs:
            dim, level = mesh.split(":")
            done = {}
            for pre in PRECONDITIONERS:
                r = run(CASES[dim], int(level), pre, os.path.join(tmp, f"{dim}_{level}_{pre}"))
                r.update(mesh=mesh, preconditioner=pre)
                done[pre] = r
                rows.append(r)
                print(json.dumps(r), flush=True)
            times = [done[p]["wall_s"] for p in ("mumps", "multigrid") if "dofs" in done[p]]
            for r in done.values():
                if times and "dofs" in r:
                    r["over_faster"] = round(r["wall_s"] / min(times), 2)
                if "dofs" in r and "dofs" in done["mumps"]:
                    for key in ("half_width", "max_pressure"):
                        m = done["mumps"][key]
                        r[key + "_vs_mumps"] = f"{abs(r[key] - m) / abs(m):.1e}"
    keys = ["mesh", "preconditioner", "dofs", "status", "method", "choice", "wall_s", "over_faster", "peak_gib",
            "krylov_iterations", "half_width", "max_pressure", "half_width_vs_mumps", "max_pressure_vs_mumps"]
    write_rows(a.csv, [{k: r.get(k, "") for k in keys} for r in rows])
    print(f"wrote {a.csv}", file=sys.stderr)
    plot(rows, a.plot)


if __name__ == "__main__":
    main()
