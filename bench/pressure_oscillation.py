#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""pressure_oscillation.py: how much the contact pressure of a run wiggles.

Reads the run's pressure.csv (the multiplier rows: p = -lambda per
multiplier, along the contact face) and prints, over the active multipliers
(p > 0) that have an active neighbour on both sides,
max_k |p_k - (p_{k-1} + p_{k+1}) / 2| as a share of the active multipliers'
mean pressure: a checkerboard (one multiplier up, the next down) shows at
full size, a smooth pressure only through its curvature (which is steep at
the rim of the contact zone); and the largest dip, the same measure counting
only multipliers below their neighbours' mean (largest_dip).

    /usr/bin/python3 bench/pressure_oscillation.py OUT/pressure.csv
"""
import csv
import sys


def oscillation(path):
    p = [float(r["pressure"]) for r in csv.DictReader(open(path)) if r["kind"] == "multiplier"]
    active = [k for k, v in enumerate(p) if v > 0]
    if len(active) < 3:
        raise SystemExit(f"{path}: fewer than 3 active multipliers")
    mean = sum(p[k] for k in active) / len(active)
    inner = [k for k in active if 0 < k < len(p) - 1 and p[k - 1] > 0 and p[k + 1] > 0]
    worst = max(inner, key=lambda k: abs(p[k] - (p[k - 1] + p[k + 1]) / 2))
    return abs(p[worst] - (p[worst - 1] + p[worst + 1]) / 2) / mean, worst, len(active), mean


def largest_dip(path):
    """The largest max_k ((p_{k-1} + p_{k+1}) / 2 - p_k) over the same
    multipliers, as a share of the mean: only a multiplier below its
    neighbours' mean counts.  A smooth contact pressure of a convex body is
    concave over the contact zone (Hertz: p0 sqrt(1 - x^2/a^2)), so its dips
    are round-off small, while its steep concave fall at the rim is what
    oscillation() reads there; a checkerboard or a staircase dips every
    other multiplier."""
    p = [float(r["pressure"]) for r in csv.DictReader(open(path)) if r["kind"] == "multiplier"]
    active = [k for k, v in enumerate(p) if v > 0]
    mean = sum(p[k] for k in active) / len(active)
    inner = [k for k in active if 0 < k < len(p) - 1 and p[k - 1] > 0 and p[k + 1] > 0]
    return max([(p[k - 1] + p[k + 1]) / 2 - p[k] for k in inner] + [0.0]) / mean


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    share, k, n, mean = oscillation(sys.argv[1])
    print(f"oscillation {100 * share:.2f} % of the mean {mean:.6g} (at multiplier {k}; {n} active); "
          f"largest dip {100 * largest_dip(sys.argv[1]):.2f} %")
