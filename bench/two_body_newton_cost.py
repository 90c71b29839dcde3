#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""two_body_newton_cost.py: what a Newton iteration of two deformable bodies
costs against one body on a rigid plane, same run, about the same unknowns.

    python3 bench/two_body_newton_cost.py [--igac build/igac] [--repeats 3]
        [--csv bench/results/two_body_newton_cost.csv]

Runs cases/roller_on_block_neohookean.toml (two Neo-Hookean bodies, mortar
contact in large deformation) and cases/hertz2d_neohookean_pressure.toml
(one body on a rigid plane, the same load) alternately, and
divides each run's Newton time (summary.json newton_seconds) by its Newton
iterations and by its unknowns; the ratio of the best of each is the cost
of the two-body iteration per unknown (issue target: at most 1.5).  Writes
the runs as CSV and a bar plot beside it (PNG, when matplotlib is there).
"""
import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from results_io import pyplot, write_rows  # noqa: E402

CASES = {"two bodies": HERE.parent / "cases/roller_on_block_neohookean.toml",
         "one body on a plane": HERE.parent / "cases/hertz2d_neohookean_pressure.toml"}


def run(igac, case, out):
    subprocess.run([igac, "run", str(case), "--out", str(out), "--quiet"], check=True)
    s = json.loads((out / "summary.json").read_text())
    iterations = sum(step["newton_iterations"] for step in s["load_steps"])
    return {"dofs": s["dofs"], "multipliers": s["multipliers"], "iterations": iterations,
            "newton_seconds": s["newton_seconds"],
            "us_per_iteration_per_dof": 1e6 * s["newton_seconds"] / iterations / s["dofs"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--igac", default=str(HERE.parent / "build/igac"))
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--csv", default=str(HERE / "results/two_body_newton_cost.csv"))
    args = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(args.repeats):
            for name, case in CASES.items():
                row = {"problem": name, "repeat": k, **run(args.igac, case, Path(tmp) / f"{k}_{case.stem}")}
                rows.append(row)
                print(f"{name:20s} {row['dofs']:6d} dofs {row['iterations']:3d} iterations "
                      f"{row['newton_seconds']:.3f} s  {row['us_per_iteration_per_dof']:.3f} us/iteration/dof", flush=True)
    best = {name: min(r["us_per_iteration_per_dof"] for r in rows if r["problem"] == name) for name in CASES}
    ratio = best["two bodies"] / best["one body on a plane"]
    print(f"two bodies / one body, per iteration and unknown (best of {args.repeats}): {ratio:.2f}")
    write_rows(args.csv, rows)
    plt = pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.bar(list(best.keys()), list(best.values()))
    ax.set_ylabel("Newton time per iteration and unknown (us)")
    ax.set_title(f"Large deformation: two bodies / one = {ratio:.2f}")
    fig.tight_layout()
    fig.savefig(Path(args.csv).with_suffix(".png"), dpi=120)


if __name__ == "__main__":
    main()
