#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""memory_guard.py [--max-gib G] — calibrate igac's memory guard.

Runs small-deformation cases at growing refinement and reads from each
summary.json the memory the guard estimated before the run
(memory_gib.estimated, io/case_file.cpp estimated_peak_bytes) and the peak
resident memory the run measured (memory_gib.peak_resident, getrusage).
Writes bench/results/memory_guard.csv; the guard is calibrated when every
ratio estimated / measured is at least 1 (it never lets through a run that
would not fit) and not far above it.  The sizes stay below a few GiB (the
largest, hertz3d, about 1 GiB and 15 s); --large adds hertz2d --refine 4
(530k dofs, 2.6 GiB, 30 s).
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IGAC = os.path.join(ROOT, "build", "igac")
RUNS = [("hertz2d", r) for r in range(0, 4)] + [("lame_cylinder", r) for r in range(2, 7)] + [("hertz3d", 0)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--large", action="store_true")
    args = ap.parse_args()
    runs = RUNS + ([("hertz2d", 4)] if args.large else [])
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for case, refine in runs:
            cmd = [IGAC, "run", os.path.join(ROOT, "cases", case + ".toml"), "--quiet", "--out", os.path.join(tmp, "o")]
            cmd += ["--refine", str(refine)]
            done = subprocess.run(cmd, capture_output=True, text=True)
            if done.returncode != 0:
                print(f"{case} refine {refine}: {done.stderr.strip()}", file=sys.stderr)
                continue
            with open(os.path.join(tmp, "o", "summary.json")) as f:
                s = json.load(f)
            est, peak = s["memory_gib"]["estimated"], s["memory_gib"]["peak_resident"]
            rows.append({"case": case, "refine": refine, "dofs": s["dofs"],
                         "estimated_gib": f"{est:.4f}", "measured_gib": f"{peak:.4f}", "ratio": f"{est / peak:.3f}"})
            print(f"{case:14} refine {refine:>2}  {s['dofs']:>8} dofs  estimated {est:7.3f} GiB  measured {peak:7.3f} GiB"
                  f"  ratio {est / peak:.2f}")
    out = os.path.join(HERE, "results", "memory_guard.csv")
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
