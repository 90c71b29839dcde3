#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""oring_rubber_speed.py: the O-ring with real rubber against today's O-ring,
in the same run (issue 24: time within 2x of cases/oring.toml).

    python3 bench/oring_rubber_speed.py [--igac build/igac] [--repeat N]

Runs, one after the other (OMP_NUM_THREADS=1), N times each:
  oring                 cases/oring.toml (K/G = 50, displacement formulation)
  rubber_kinsol         cases/oring_rubber.toml with KINSOL's line search and
                        the extrapolating predictor (the driver's defaults)
  rubber                cases/oring_rubber.toml as shipped (line_search =
                        "halving", predictor = "tangent_every_step")
  rubber_fixed_steps    as shipped with max_increment = 0.05: the load factors
                        of rubber_kinsol, to compare the force-squeeze curves
  rubber_incompressible as shipped with [material] incompressible = true: the
                        limit K = infinity (augmented Lagrangian); its cost per
                        Newton iteration against rubber's, same mesh
and writes bench/results/oring_rubber_speed.csv: steps, Newton iterations,
cut-backs, user CPU seconds (the least of the N runs: the machine is shared),
the force at full squeeze, the pressure wiggle (pressure_oscillation.py), and
for the rubber runs the largest relative difference of load_curve.csv's
contact force from rubber_kinsol's at the load factors both have.
"""
import argparse
import csv
import json
import os
import resource
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE))
from case_toml import write_case  # noqa: E402
from pressure_oscillation import oscillation  # noqa: E402


def variant(tmp, name, loading, material=None):
    case = tomllib.loads((ROOT / "cases" / "oring_rubber.toml").read_text())
    case["geometry"]["file"] = str(ROOT / "cases" / "oring_quarter.xml")
    case["loading"].update(loading)
    case["material"].update(material or {})
    path = Path(tmp) / f"{name}.toml"
    write_case(case, path, f"# cases/oring_rubber.toml, [loading] {loading}, [material] {material or {}} "
                           "(bench/oring_rubber_speed.py)")
    return path


def run(igac, case, out):
    before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run([igac, "run", str(case), "--out", str(out), "--quiet"], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_utime - before


def curve(out):
    with open(Path(out) / "load_curve.csv") as f:
        return {round(float(r["load_factor"]), 9): float(r["contact_force"]) for r in csv.DictReader(f)}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--igac", default=str(ROOT / "build" / "igac"))
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        runs = [("oring", ROOT / "cases" / "oring.toml"),
                ("rubber_kinsol", variant(tmp, "rubber_kinsol", {"line_search": True, "predictor": "tangent"})),
                ("rubber", ROOT / "cases" / "oring_rubber.toml"),
                ("rubber_fixed_steps", variant(tmp, "rubber_fixed_steps", {"max_increment": 0.05})),
                ("rubber_incompressible", variant(tmp, "rubber_incompressible", {}, {"incompressible": True}))]
        curves = {}
        for name, case in runs:
            out = Path(tmp) / name
            cpu = min(run(args.igac, case, out) for _ in range(args.repeat))
            s = json.load(open(out / "summary.json"))
            steps = s["load_steps"]
            curves[name] = curve(out)
            wiggle, _, _, _ = oscillation(out / "pressure.csv")
            iterations = sum(x["newton_iterations"] for x in steps)
            rows.append({"run": name, "status": s["status"], "steps": len(steps), "newton_iterations": iterations,
                         "augmentations": sum(x.get("augmentations", 0) for x in steps),
                         "cut_backs": sum(x["cut_backs"] for x in steps), "user_cpu_s": f"{cpu:.3f}",
                         "cpu_per_iteration_ms": f"{1000 * cpu / max(iterations, 1):.2f}",
                         "force": f"{s['contact']['total_force']:.10g}", "wiggle_percent": f"{100 * wiggle:.2f}"})
        base = curves["rubber_kinsol"]
        for r in rows:
            if r["run"].startswith("rubber"):
                common = [t for t in curves[r["run"]] if t in base]
                r["common_load_factors"] = len(common)
                r["curve_max_rel_diff"] = f"{max(abs(curves[r['run']][t] - base[t]) / abs(base[t]) for t in common):.2e}"
    oring_cpu = float(rows[0]["user_cpu_s"])
    for r in rows:
        r["cpu_vs_oring"] = f"{float(r['user_cpu_s']) / oring_cpu:.2f}"
    out = HERE / "results" / "oring_rubber_speed.csv"
    keys = list(rows[1].keys()) + [k for k in rows[0] if k not in rows[1]]
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    for r in rows:
        print("  ".join(f"{k}={r.get(k, '')}" for k in keys))
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
