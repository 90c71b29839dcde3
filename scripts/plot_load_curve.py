#!/usr/bin/python3
"""plot_load_curve.py CSV PNG TITLE — the load curve of a large-deformation run.

Reads load_curve.csv (load_factor, contact_force, face_displacement,
obstacle_displacement) and draws the contact force against the load factor
and against the loaded face's displacement (or, when an obstacle moves, against
how far it has moved).
Runs under Debian's /usr/bin/python3 with python3-matplotlib (Agg backend).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    if len(sys.argv) != 4:
        sys.exit("usage: plot_load_curve.py CSV PNG TITLE")
    src, png, title = sys.argv[1:]
    t, force, disp, moved = [0.0], [0.0], [0.0], [0.0]
    with open(src) as f:
        for row in csv.DictReader(f):
            t.append(float(row["load_factor"]))
            force.append(float(row["contact_force"]))
            disp.append(float(row["face_displacement"]))
            moved.append(float(row.get("obstacle_displacement") or 0.0))
    # A moving obstacle drives the run: force against how far it has moved.
    driven = max(abs(m) for m in moved) > 0
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].plot(t, force, "o-")
    ax[0].set_xlabel("load factor")
    ax[0].set_ylabel("total contact force (modelled part)")
    ax[1].plot(moved if driven else disp, force, "o-")
    ax[1].set_xlabel("obstacle displacement (squeeze)" if driven else "loaded face displacement (last axis)")
    ax[1].set_ylabel("total contact force")
    for a in ax:
        a.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(png, dpi=120)


if __name__ == "__main__":
    main()
