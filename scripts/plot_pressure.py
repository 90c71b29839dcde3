#!/usr/bin/python3
"""Contact pressure against Hertz, like Figure 1(b) of Antolin, Buffa & Fabre (2018).

    /usr/bin/python3 scripts/plot_pressure.py OUT/pressure.csv OUT/pressure.png TITLE

pressure.csv (written by `igac run`) has the columns
    kind,r,pressure,r_over_a,p_over_p0,hertz_p_over_p0
with kind 'multiplier' (one row per Lagrange multiplier: its anchor r and
p = -lambda) or 'p1' (the P1 re-interpolation at the contact face's
breakpoints).  With an analytic solution the plot is p/p0 against r/a with
the Hertz curve p/p0 = sqrt(1 - (r/a)^2); without one (r_over_a empty) it is
p against r.

Multipliers of degree 0 (one constant per face element, N2/S0) are drawn as
the constants they are: a horizontal segment over their element (the
element ends are the P1 breakpoints) and a marker at the anchor.

Runs under Debian's /usr/bin/python3 with python3-matplotlib (Agg backend,
no display needed).
"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    rows = {"multiplier": [], "p1": []}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            rows.setdefault(row["kind"], []).append(row)
    return rows


def number(s):
    return float(s) if s not in (None, "") else None


def main(argv):
    if len(argv) != 4:
        sys.exit("usage: plot_pressure.py PRESSURE.csv OUT.png TITLE")
    csv_path, png_path, title = argv[1:]
    rows = read(csv_path)
    mult, p1 = rows["multiplier"], rows["p1"]
    if not mult:
        sys.exit(f"{csv_path}: no multiplier rows")
    analytic = number(mult[0].get("r_over_a")) is not None
    if analytic:
        x_of = lambda r: number(r["r_over_a"])  # noqa: E731
        y_of = lambda r: number(r["p_over_p0"])  # noqa: E731
        xlabel, ylabel = "r / a", "p / p0"
    else:
        x_of = lambda r: number(r["r"])  # noqa: E731
        y_of = lambda r: number(r["pressure"])  # noqa: E731
        xlabel, ylabel = "r (distance from the initial contact point)", "p = -lambda"

    mx = [x_of(r) for r in mult]
    my = [y_of(r) for r in mult]
    px = [x_of(r) for r in p1]
    py = [y_of(r) for r in p1]
    order = sorted(range(len(mx)), key=lambda i: mx[i])
    mx = [mx[i] for i in order]
    my = [my[i] for i in order]

    fig, ax = plt.subplots(figsize=(7.0, 4.6), dpi=130)
    # One constant per element: the breakpoints bound each multiplier's element.
    constants = len(px) == len(mx) + 1
    if constants:
        for i in range(len(mx)):
            ax.plot([px[i], px[i + 1]], [my[i], my[i]], color="tab:blue", lw=1.2, alpha=0.8,
                    label="multipliers (constant per element)" if i == 0 else None)
        ax.plot(mx, my, "o", ms=3.5, color="tab:blue")
    else:
        ax.plot(mx, my, "o", ms=4, color="tab:blue", label="multipliers (at their anchors)")
    if px:
        ax.plot(px, py, "-", color="tab:orange", lw=1.4, marker=".", ms=3, label="P1 re-interpolation")
    if analytic:
        xs = [1.2 * k / 400 for k in range(401)]
        ax.plot(xs, [math.sqrt(1 - x * x) if x < 1 else 0.0 for x in xs], "k--", lw=1.2,
                label="Hertz  p/p0 = sqrt(1 - (r/a)^2)")
        xmax = 1.6
    else:
        # 1.5 times the end of the pressed zone: the far end of the last
        # pressed element (or the next anchor), so the edge of contact shows.
        pressed = [i for i, y in enumerate(my) if y > 0]
        if pressed:
            j = pressed[-1]
            edge = px[j + 1] if constants else mx[min(j + 1, len(mx) - 1)]
            xmax = min(1.5 * edge, max(mx + px))
        else:
            xmax = max(mx + px)
    ax.set_xlim(0, xmax)
    ymax = max([y for x, y in zip(mx, my) if x <= xmax] + [y for x, y in zip(px, py) if x <= xmax] + [1.0 if analytic else 0.0])
    ax.set_ylim(min(0.0, min(my)) - 0.02 * ymax, 1.12 * ymax)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(png_path)


if __name__ == "__main__":
    main(sys.argv)
