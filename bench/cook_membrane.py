#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""cook_membrane.py: Cook's membrane, nearly incompressible
(cases/cook_membrane.toml: plane strain, E = 250, nu = 0.4999, shear load
100), the vertical displacement of the top right corner (48, 60) on N x N
meshes for [material] formulation = "displacement" and "mixed", at p = 2
and 3.

Writes results/cook_membrane.csv (formulation, degree, elements per side,
unknowns, tip u_y) and results/cook_membrane.png (tip u_y against N, with
the literature's 7.7), and prints Aitken's extrapolation of the last three
meshes.  Needs the Python module (build/python).

    PYTHONPATH=build/python /usr/bin/python3 bench/cook_membrane.py [--elements 2 4 8 16 32 64] [--degrees 2 3]
"""
import argparse
import sys
from pathlib import Path

here = Path(__file__).resolve().parent
sys.path.insert(0, str(here))
from results_io import pyplot, write_rows  # noqa: E402

import igac  # noqa: E402

FORMULATIONS = ["displacement", "mixed"]
REFERENCE = 7.7


def tip(formulation, degree, n):
    res = igac.run(str(here.parent / "cases" / "cook_membrane.toml"),
                   {"material.formulation": formulation, "mesh.elements": [n, n], "output.vtk": False},
                   degree=degree)
    assert res["status"] == "converged", res["status"]
    pts = res["control_points"]
    k = int(((pts[:, 0] - 48.0) ** 2 + (pts[:, 1] - 60.0) ** 2).argmin())
    return float(res["displacement"][k, 1]), int(res["summary"]["dofs"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--elements", type=int, nargs="+", default=[2, 4, 8, 16, 32, 64])
    ap.add_argument("--degrees", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--csv", default=str(here / "results" / "cook_membrane.csv"))
    args = ap.parse_args()
    rows = []
    for p in args.degrees:
        for f in FORMULATIONS:
            for n in args.elements:
                uy, dofs = tip(f, p, n)
                rows.append({"formulation": f, "degree": p, "elements": n, "dofs": dofs, "tip_uy": uy})
                print(f"{f:12s} p={p} {n:3d} x {n:<3d} {dofs:6d} dofs  tip u_y {uy:.5f}", flush=True)
    write_rows(args.csv, rows)
    # Aitken's extrapolation of the last three meshes (the mixed values converge at first order)
    for p in args.degrees:
        for f in FORMULATIONS:
            u = [x["tip_uy"] for x in rows if x["formulation"] == f and x["degree"] == p]
            if len(u) >= 3 and (u[-1] - u[-2]) != (u[-2] - u[-3]):
                d1, d2 = u[-2] - u[-3], u[-1] - u[-2]
                print(f"{f:12s} p={p} extrapolated (Aitken, last three meshes) {u[-1] - d2 * d2 / (d2 - d1):.4f}")
    plt = pyplot()
    if plt is None:
        return
    series = {}
    for x in rows:
        series.setdefault((x["formulation"], x["degree"]), []).append((x["elements"], x["tip_uy"]))
    fig, ax = plt.subplots(figsize=(7, 5))
    for (f, p), pts in series.items():
        ax.semilogx(*zip(*pts), "--" if f == "displacement" else "-", marker="o", label=f"{f} p={p}")
    ax.axhline(REFERENCE, color="k", lw=0.8, label="literature 7.7")
    ax.set(xlabel="elements per side", ylabel="tip vertical displacement",
           title="Cook's membrane, nu = 0.4999: locking and convergence")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(Path(args.csv).with_suffix(".png"), dpi=120)

if __name__ == "__main__":
    main()
