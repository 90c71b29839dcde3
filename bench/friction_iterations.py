#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""friction_iterations.py: the frictional active set's iterations against the
frictionless one's on the same case (issue 23: at most 1.5x).

    python3 bench/friction_iterations.py [--igac build/igac] [CASE ...]

For each shipped frictional case (default: cattaneo_mindlin and
cattaneo_mindlin_two_bodies) runs it as shipped and once more without
friction (its `friction` and `[loading]` removed: the press alone, a moving
obstacle or master body applied whole, which along a flat face changes no
gap), and compares the frictionless solve's active-set iterations with the
frictional press step's (`contact.friction_step_iterations[0]`); the drag
steps are listed beside.  Prints a table and writes
bench/results/friction_iterations.csv (a few seconds).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import tomllib
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from case_toml import contacts_of, write_case  # noqa: E402


def absolute_files(table, folder):
    """Geometry `file` keys made absolute: the variant is written elsewhere."""
    if isinstance(table, dict):
        for k, v in table.items():
            if k == "file" and isinstance(v, str):
                table[k] = str((folder / v).resolve())
            else:
                absolute_files(v, folder)
    elif isinstance(table, list):
        for v in table:
            absolute_files(v, folder)


def read_shipped_case(name):
    """cases/NAME.toml: its path and its tables, geometry files made absolute."""
    path = HERE.parent / "cases" / f"{name}.toml"
    with open(path, "rb") as f:
        case = tomllib.load(f)
    absolute_files(case, path.parent)
    return path, case


def shipped_case_arguments(default_cases):
    """The options of a bench over shipped cases: --igac and the case names."""
    ap = argparse.ArgumentParser(description=sys.modules["__main__"].__doc__.splitlines()[0])
    ap.add_argument("--igac", default=str(HERE.parent / "build" / "igac"))
    ap.add_argument("cases", nargs="*", default=default_cases)
    return ap


def shipped_cases(names):
    """Each shipped case as (name, path, tables, a temporary folder for its variants and outputs)."""
    with tempfile.TemporaryDirectory() as tmp:
        for name in names:
            yield (name, *read_shipped_case(name), Path(tmp))


def iterations(igac, case, out):
    subprocess.run([igac, "run", str(case), "--out", str(out), "--quiet"], check=True)
    with open(out / "summary.json") as f:
        contact = json.load(f)["contact"]
    return contact["active_set_iterations"], contact.get("friction_step_iterations", [])


def main():
    args = shipped_case_arguments(["cattaneo_mindlin", "cattaneo_mindlin_two_bodies"]).parse_args()
    rows = []
    for name, path, case, tmp in shipped_cases(args.cases):
        case.pop("loading", None)
        for c in contacts_of(case):
            c.pop("friction", None)
        variant = tmp / f"{name}_frictionless.toml"
        write_case(case, variant, f"{name} without friction (bench/friction_iterations.py)")
        plain, _ = iterations(args.igac, variant, tmp / f"{name}_frictionless")
        total, steps = iterations(args.igac, path, tmp / name)
        rows.append({"case": name, "frictionless": plain, "frictional_press": steps[0],
                     "ratio": round(steps[0] / plain, 3), "drag_steps": " ".join(map(str, steps[1:])),
                     "frictional_total": total})
    print(f"{'case':32s} {'frictionless':>12s} {'press':>6s} {'ratio':>6s}  drag steps")
    for r in rows:
        print(f"{r['case']:32s} {r['frictionless']:12d} {r['frictional_press']:6d} {r['ratio']:6.2f}  {r['drag_steps']}")
    out = HERE / "results" / "friction_iterations.csv"
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {os.path.relpath(out)}")


if __name__ == "__main__":
    main()
