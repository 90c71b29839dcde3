#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Runs every shipped case and compares the results of two builds.

    scripts/compare_cases.py run BINARY DIR      # cases/*.toml -> DIR/<case>/summary.json
    scripts/compare_cases.py compare DIR_A DIR_B [--tol 1e-12]

A change that should not change results (a different summation order, a
refactoring) is checked by running the build before and after it into two
folders and comparing them: every number of summary.json except timings and
memory, relative to the larger of the two (absolute below 1e-300).  Cases that
need more than --timeout seconds (studies, PETSc) are skipped and named.
"""
import argparse
import glob
import json
import math
import os
import subprocess
import sys
import time

SKIP_KEYS = {"timing_s", "memory_gib", "wall_s", "seconds", "newton_seconds", "residual_seconds",
             "jacobian_seconds", "factorize_s", "schur_s", "solve_s", "iterations_s", "analyze_s",
             "command", "version", "date", "output", "out", "host", "threads"}


def is_timing(key):
    return key in SKIP_KEYS or key.endswith("_s") or key.endswith("_seconds") or "gib" in key or "memory" in key


def leaves(node, path=""):
    if isinstance(node, dict):
        for k, v in node.items():
            if not is_timing(k):
                yield from leaves(v, f"{path}.{k}" if path else k)
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from leaves(v, f"{path}[{i}]")
    else:
        yield path, node


def run(binary, out, timeout):
    os.makedirs(out, exist_ok=True)
    for case in sorted(glob.glob("cases/*.toml")):
        name = os.path.splitext(os.path.basename(case))[0]
        dest = os.path.join(out, name)
        t0 = time.time()
        try:
            p = subprocess.run([binary, "run", case, "--out", dest, "--quiet"], capture_output=True, text=True,
                               timeout=timeout)
            note = f"exit {p.returncode}"
        except subprocess.TimeoutExpired:
            note = "skipped (timeout)"
        print(f"{name:40s} {note:20s} {time.time() - t0:7.1f} s", flush=True)


def compare(a, b, tol):
    worst, failed = 0.0, False
    for sa in sorted(glob.glob(os.path.join(a, "*", "summary.json"))):
        name = os.path.basename(os.path.dirname(sa))
        sb = os.path.join(b, name, "summary.json")
        if not os.path.exists(sb):
            print(f"{name}: missing in {b}")
            failed = True
            continue
        la, lb = dict(leaves(json.load(open(sa)))), dict(leaves(json.load(open(sb))))
        case_worst, where, n = 0.0, "", 0
        for k in sorted(set(la) | set(lb)):
            x, y = la.get(k), lb.get(k)
            if isinstance(x, bool) or isinstance(y, bool) or not isinstance(x, (int, float)) or \
                    not isinstance(y, (int, float)):
                if x != y:
                    print(f"{name}: {k}: {x!r} != {y!r}")
                    failed = True
                continue
            n += 1
            if math.isnan(x) and math.isnan(y):
                continue
            scale = max(abs(x), abs(y))
            rel = 0.0 if x == y else abs(x - y) / scale if scale > 1e-300 else abs(x - y)
            if rel > case_worst:
                case_worst, where = rel, k
        worst = max(worst, case_worst)
        print(f"{name:40s} {n:5d} numbers, max relative change {case_worst:.2e} {where}")
        failed |= case_worst > tol
    print(f"max relative change over all cases: {worst:.2e} (tolerance {tol:g})")
    return 1 if failed else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    r = sub.add_parser("run")
    r.add_argument("binary")
    r.add_argument("out")
    r.add_argument("--timeout", type=float, default=60)
    c = sub.add_parser("compare")
    c.add_argument("a")
    c.add_argument("b")
    c.add_argument("--tol", type=float, default=1e-12)
    a = ap.parse_args()
    if a.cmd == "run":
        run(a.binary, a.out, a.timeout)
        return 0
    return compare(a.a, a.b, a.tol)


if __name__ == "__main__":
    sys.exit(main())
