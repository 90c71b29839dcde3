#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""locking_study.py: the thick cylinder under internal pressure (Lame, plane
strain, cases/lame_cylinder.toml) at nu = 0.3 ... 0.49999, with
[material] formulation = "displacement" and "mixed", on a sequence of meshes.

Writes results/locking_study.csv (formulation, degree, refine, nu, relative
L2 and H1 displacement errors against the closed form) and
results/locking_study.png (relative L2 error against 0.5 - nu).

    /usr/bin/python3 bench/locking_study.py [--igac build/igac] [--degrees 2 3] [--refine 1 2 3]
"""
import argparse
import json
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

here = Path(__file__).resolve().parent
sys.path.insert(0, str(here))
from case_toml import write_case  # noqa: E402
from results_io import pyplot, write_rows  # noqa: E402

NUS = [0.3, 0.49, 0.499, 0.4999, 0.49999]
FORMULATIONS = ["displacement", "mixed"]


def run(igac, case, tmp, name):
    path = Path(tmp) / f"{name}.toml"
    write_case(case, path, "locking_study.py variant of cases/lame_cylinder.toml")
    out = Path(tmp) / name
    subprocess.run([igac, "run", str(path), "--out", str(out)], check=True, capture_output=True)
    errors = json.loads((out / "summary.json").read_text())["errors"]
    return errors["displacement_l2_rel"], errors["displacement_h1_rel"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--igac", default=str(here.parent / "build" / "igac"))
    ap.add_argument("--degrees", type=int, nargs="+", default=[2, 3])
    ap.add_argument("--refine", type=int, nargs="+", default=[1, 2, 3])
    ap.add_argument("--csv", default=str(here / "results" / "locking_study.csv"))
    args = ap.parse_args()
    base = tomllib.loads((here.parent / "cases" / "lame_cylinder.toml").read_text())
    base.setdefault("output", {})["vtk"] = False
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for p in args.degrees:
            for r in args.refine:
                for f in FORMULATIONS:
                    for nu in NUS:
                        case = json.loads(json.dumps(base))
                        case["mesh"]["degree"] = p
                        case["mesh"]["refine"] = r
                        case["material"]["nu"] = nu
                        case["material"]["formulation"] = f
                        l2, h1 = run(args.igac, case, tmp, f"{f}_p{p}_r{r}_{nu}")
                        rows.append({"formulation": f, "degree": p, "refine": r, "nu": nu, "l2_rel": l2, "h1_rel": h1})
                        print(f"{f:12s} p={p} refine={r} nu={nu:<8} L2 {l2:.3e}  H1 {h1:.3e}", flush=True)
    write_rows(args.csv, rows)
    plt = pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(7, 5))
    for f, style in zip(FORMULATIONS, ["--", "-"]):
        for p in args.degrees:
            for r in args.refine:
                pts = [(0.5 - x["nu"], x["l2_rel"]) for x in rows if x["formulation"] == f and x["degree"] == p and x["refine"] == r]
                ax.loglog(*zip(*pts), style, marker="o", label=f"{f} p={p} refine={r}")
    ax.invert_xaxis()
    ax.set_xlabel("0.5 - nu")
    ax.set_ylabel("relative L2 displacement error")
    ax.set_title("Lame cylinder: locking as nu -> 0.5")
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(Path(args.csv).with_suffix(".png"), dpi=120)


if __name__ == "__main__":
    main()
