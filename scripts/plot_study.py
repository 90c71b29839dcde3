#!/usr/bin/python3
"""Convergence plot of a refinement study: error against h, log-log.

    /usr/bin/python3 scripts/plot_study.py OUT/study.csv OUT/study.png TITLE

study.csv (written by `igac study`) has the columns level,h,dofs and then,
for each error NAME, the pair NAME,NAME_rate (the rate between a level and
the one before it; empty on the first level).  Every error is drawn against
h with markers; the legend gives the slope of the finest pair of levels
(fitted here from the two points, and checked against the CSV's rate), and
a dotted reference triangle shows that slope next to the finest point.

Runs under Debian's /usr/bin/python3 with python3-matplotlib (Agg backend).
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "displacement_l2": "displacement, L2",
    "displacement_h1": "displacement, H1 seminorm",
    "pressure_l2": "pressure, L2 vs Hertz",
    "pressure_l2_vs_reference": "pressure, L2 vs refined",
}


def number(s):
    try:
        v = float(s)
    except (TypeError, ValueError):
        return None
    return v if math.isfinite(v) else None


def main(argv):
    if len(argv) != 4:
        sys.exit("usage: plot_study.py STUDY.csv OUT.png TITLE")
    csv_path, png_path, title = argv[1:]
    with open(csv_path, newline="") as f:
        reader = csv.DictReader(f)
        rows = list(reader)
        columns = reader.fieldnames or []
    names = [c for c in columns[3:] if not c.endswith("_rate")]
    if not rows or not names:
        sys.exit(f"{csv_path}: no levels or no errors")

    fig, ax = plt.subplots(figsize=(7.0, 5.0), dpi=130)
    markers = "osD^v<>p*"
    for k, name in enumerate(names):
        pts = [(number(r["h"]), number(r[name])) for r in rows]
        pts = [(h, e) for h, e in pts if h and e and h > 0 and e > 0]
        if not pts:
            continue
        pts.sort()
        hs, es = zip(*pts)
        label = LABELS.get(name, name)
        if len(pts) >= 2:
            (h0, e0), (h1, e1) = pts[0], pts[1]  # the finest pair
            slope = math.log(e1 / e0) / math.log(h1 / h0)
            label += f"  (slope {slope:.2f})"
        line, = ax.loglog(hs, es, marker=markers[k % len(markers)], ms=5, lw=1.4, label=label)
        if len(pts) >= 2:
            # slope triangle below the finest segment: legs 1 (in log h) and slope
            hA, hB = hs[0], hs[0] * (hs[1] / hs[0]) ** 0.6
            eA = es[0] * 0.5
            eB = eA * (hB / hA) ** slope
            ax.plot([hA, hB, hB, hA], [eA, eA, eB, eA], ls="-", lw=0.8, color=line.get_color(), alpha=0.7)
            ax.annotate(f"{slope:.2f}", (hB, math.sqrt(eA * eB)), textcoords="offset points", xytext=(4, 0),
                        va="center", fontsize=7, color=line.get_color())
    ax.set_xlabel("h (largest element diameter)")
    ax.set_ylabel("error")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="best")
    fig.tight_layout()
    fig.savefig(png_path)


if __name__ == "__main__":
    main(sys.argv)
