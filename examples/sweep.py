#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""examples/sweep.py [--out DIR] [--compare-cli] — an O-ring parameter sweep from Python.

cases/oring.toml (NBR-like Mooney-Rivlin O-ring squeezed by a moving rigid
plate) run for 5 squeezes x 4 hardnesses = 20 runs through the igac module,
each overriding the plate's travel and the Mooney-Rivlin constants (shear
modulus 2 (C10 + C01) scaled, C01/C10 and the bulk modulus ratio kept).
Writes DIR/sweep.csv (squeeze, shear modulus, contact force per mm of the
quarter, Newton iterations) and DIR/sweep.png (force against squeeze, one
line per hardness).  With --compare-cli the same 20 runs go through
`build/igac run` as well, and the two wall times are printed: the module
must cost no more than the command line (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep.py --out out/sweep
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

import igac

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CASE = os.path.join(ROOT, "cases", "oring.toml")
DIAMETER = 5.33                      # mm
SQUEEZES = [0.05, 0.10, 0.15, 0.20, 0.25]
SHEAR_SCALES = [0.5, 1.0, 1.5, 2.0]  # times the shipped NBR's 0.96 MPa
C10, C01, K = 0.37, 0.11, 48.0


def overrides(squeeze, scale):
    # half the squeeze on the modelled side (the mid-plane is a symmetry plane)
    return {"contact.obstacle.motion": [0.0, squeeze * DIAMETER / 2],
            "material.C10": C10 * scale, "material.C01": C01 * scale, "material.bulk_modulus": K * scale}


def cli_run(squeeze, scale, tmp):
    """The same run through the command line, the case file edited."""
    text = open(CASE).read()
    o = overrides(squeeze, scale)
    text = text.replace("motion = [0.0, 0.66625]", f"motion = [0.0, {o['contact.obstacle.motion'][1]!r}]")
    text = text.replace("C10 = 0.37", f"C10 = {o['material.C10']!r}").replace("C01 = 0.11", f"C01 = {o['material.C01']!r}")
    text = text.replace("bulk_modulus = 48.0", f"bulk_modulus = {o['material.bulk_modulus']!r}")
    path = os.path.join(tmp, "oring.toml")
    with open(path, "w") as f:
        f.write(text)
    for xml in ("oring_quarter.xml",):
        target = os.path.join(tmp, xml)
        if not os.path.exists(target):
            os.symlink(os.path.join(ROOT, "cases", xml), target)
    subprocess.run([os.path.join(ROOT, "build", "igac"), "run", path, "--no-output", "--quiet"], check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/sweep")
    ap.add_argument("--compare-cli", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    start = time.perf_counter()
    for scale in SHEAR_SCALES:
        for squeeze in SQUEEZES:
            r = igac.run(CASE, overrides(squeeze, scale))
            s = r["summary"]
            newton = sum(step["newton_iterations"] for step in s["load_steps"])
            rows.append([squeeze, 2 * (C10 + C01) * scale, s["contact"]["total_force"], newton, r["status"]])
    module_s = time.perf_counter() - start
    with open(os.path.join(a.out, "sweep.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["squeeze", "shear_modulus_MPa", "contact_force_N_per_mm", "newton_iterations", "status"])
        w.writerows(rows)
    print(f"sweep: {len(rows)} runs through the module in {module_s:.2f} s; {a.out}/sweep.csv")
    if a.compare_cli:
        with tempfile.TemporaryDirectory() as tmp:
            start = time.perf_counter()
            for scale in SHEAR_SCALES:
                for squeeze in SQUEEZES:
                    cli_run(squeeze, scale, tmp)
            cli_s = time.perf_counter() - start
        print(f"sweep: the same {len(rows)} runs through build/igac run: {cli_s:.2f} s "
              f"(module / command line = {module_s / cli_s:.2f})")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fig, ax = plt.subplots(figsize=(6, 4))
    for scale in SHEAR_SCALES:
        pts = [(r[0] * 100, r[2]) for r in rows if abs(r[1] - 2 * (C10 + C01) * scale) < 1e-12]
        ax.plot(*zip(*pts), marker="o", label=f"G = {2 * (C10 + C01) * scale:.2f} MPa")
    ax.set_xlabel("squeeze (% of the cross-section diameter)")
    ax.set_ylabel("contact force on the quarter (N/mm)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "sweep.png"), dpi=120)


if __name__ == "__main__":
    sys.exit(main())
