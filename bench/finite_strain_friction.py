#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""finite_strain_friction.py: large-deformation friction on the shipped
large-deformation cases, against the same cases frictionless (issue 23:
Newton at most 1.5x the frictionless iterations).

    python3 bench/finite_strain_friction.py [--igac build/igac] [--friction 0.3] [CASE ...]

For each case (default: the shipped large-deformation cases with contact,
rigid obstacles and two bodies) runs it as shipped and once more with
`friction = F` in every contact table, and compares the load steps, the
Newton iterations, the cut-backs, the normal contact force and the
tangential force; the order of the last two Newton residuals of each
frictional step whose first lies in (1e-11, 1e-1) (quadratic: about 2) is
summarised by its smallest value.  Prints a table and writes
bench/results/finite_strain_friction.csv (a minute or so).
"""
import json
import math
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from case_toml import contacts_of, write_case  # noqa: E402
from friction_iterations import shipped_case_arguments, shipped_cases  # noqa: E402
from results_io import write_rows  # noqa: E402

DEFAULT_CASES = ["hertz2d_neohookean_pressure", "hertz2d_neohookean_displacement", "hertz3d_neohookean", "oring",
                 "oring_unloading", "oring_rubber", "oring_two_plates", "oring_on_plate", "roller_on_block_neohookean"]


def run(igac, case, out):
    subprocess.run([igac, "run", str(case), "--out", str(out), "--quiet"], check=True)
    with open(out / "summary.json") as f:
        s = json.load(f)
    steps = s["load_steps"]
    obstacle = s["obstacles"][0]
    orders = []
    for st in steps:
        r = st["residual_norms"]
        for k in range(len(r) - 1, 0, -1):
            if 1e-11 < r[k] and 1e-11 < r[k - 1] < 1e-1:
                orders.append(math.log(r[k]) / math.log(r[k - 1]))
                break
    return {"status": s["status"], "steps": len(steps), "newton": sum(st["newton_iterations"] for st in steps),
            "cut_backs": sum(st["cut_backs"] for st in steps), "normal_force": obstacle["normal_force"],
            "tangential_force": obstacle.get("tangential_force", {}).get("magnitude", 0.0),
            "min_order": min(orders) if orders else float("nan")}


def main():
    ap = shipped_case_arguments(DEFAULT_CASES)
    ap.add_argument("--friction", type=float, default=0.3)
    args = ap.parse_args()
    rows = []
    for name, path, case, tmp in shipped_cases(args.cases):
        for c in contacts_of(case):
            c["friction"] = args.friction
        case.setdefault("output", {})["vtk"] = False
        variant = tmp / f"{name}_friction.toml"
        write_case(case, variant, f"{name} with friction {args.friction} (bench/finite_strain_friction.py)")
        plain = run(args.igac, path, tmp / name)
        frictional = run(args.igac, variant, tmp / f"{name}_friction")
        rows.append({"case": name, "friction": args.friction, "status": frictional["status"],
                     "steps_frictionless": plain["steps"], "steps": frictional["steps"],
                     "newton_frictionless": plain["newton"], "newton": frictional["newton"],
                     "ratio": round(frictional["newton"] / plain["newton"], 3),
                     "cut_backs": frictional["cut_backs"],
                     "normal_force_frictionless": plain["normal_force"], "normal_force": frictional["normal_force"],
                     "tangential_force": frictional["tangential_force"],
                     "min_order": round(frictional["min_order"], 3)})
        r = rows[-1]
        print(f"{name:34s} steps {r['steps_frictionless']:3d} -> {r['steps']:3d}  Newton {r['newton_frictionless']:4d} "
              f"-> {r['newton']:4d} ({r['ratio']:.2f}x)  N {r['normal_force_frictionless']:.6g} -> "
              f"{r['normal_force']:.6g}  T {r['tangential_force']:.6g}  min order {r['min_order']}  {r['status']}",
              flush=True)
    out = HERE / "results" / "finite_strain_friction.csv"
    write_rows(out, rows)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
