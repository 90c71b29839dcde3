# SPDX-License-Identifier: BSD-3-Clause
"""The driver the GetFEM peer scripts of bench/ share: every mesh N in a
fresh Python process (GetFEM's memory and caches start clean, as the
timings of ../shared/peers' scripts do), its row printed with `line` and
appended to the CSV file `csv_path` (columns `fields`)."""
import argparse
import csv
import json
import os
import subprocess
import sys


def add_solver_arguments(ap):
    """The options both scripts take: contact quadrature, Newton, output, and the child's mesh."""
    ap.add_argument("--contact-subdiv", type=int, default=4)
    ap.add_argument("--tol", type=float, default=1e-8)
    ap.add_argument("--max-iter", type=int, default=100)
    ap.add_argument("--csv", default="")
    ap.add_argument("--json-one", type=int, default=0, help=argparse.SUPPRESS)


def one_mesh_row(row):
    """What a child process prints for run_per_mesh to read back."""
    print("JSON " + json.dumps({k: (v.item() if hasattr(v, "item") else v) for k, v in row.items()}), flush=True)


def run_per_mesh(script, meshes, line, csv_path, fields):
    for N in meshes:
        out = subprocess.run([sys.executable, os.path.abspath(script)] + sys.argv[1:] + ["--json-one", str(N)],
                             capture_output=True, text=True)
        if out.returncode != 0:
            print("N=%d: FAILED\n%s" % (N, out.stderr[-3000:]), flush=True)
            continue
        row = json.loads([l for l in out.stdout.splitlines() if l.startswith("JSON ")][-1][5:])
        print(line % row, flush=True)
        if csv_path:
            new = not os.path.exists(csv_path)
            with open(csv_path, "a", newline="") as f:
                w = csv.DictWriter(f, fieldnames=fields)
                if new:
                    w.writeheader()
                w.writerow({k: row.get(k, "") for k in fields})


def main_per_mesh(ap, script, solve_one, line, fields):
    """A peer script's main: the shared options added to its own (ap, which has --N), then either one
    mesh in this process (the child's --json-one N) or every mesh of --N, each in a child."""
    add_solver_arguments(ap)
    args = ap.parse_args()
    if args.json_one:
        one_mesh_row(solve_one(args, args.json_one))
        return
    run_per_mesh(script, args.N, line, args.csv, fields)


def zero_crossing(x, p):
    """Where the nodal pressure p (nodes at x, ordered from the contact point outwards) first falls to
    zero, linearly between the last positive and the first non-positive node: the half width."""
    nonpos = [k for k, v in enumerate(p) if v <= 0.0]
    kz = nonpos[0] if nonpos else len(x)
    if kz == 0:
        return 0.0
    if kz == len(x):
        return x[-1]
    return x[kz - 1] + (x[kz] - x[kz - 1]) * p[kz - 1] / (p[kz - 1] - p[kz])
