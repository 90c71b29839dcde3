#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""ironing.py: the ironing benchmark (cases/ironing.toml): the die's reaction
against its travel, and how smooth it is on NURBS surfaces against faceted
(C0) ones of the same element counts.

    /usr/bin/python3 bench/ironing.py [--igac build/igac] [--slide-steps 40] [--quick]

Runs cases/ironing.toml with the slide cut in --slide-steps equal steps
(`[loading] max_increment`; a step Newton fails is cut back, so a run may
take more), as shipped (p = 2, the die's arc in 16 spans) and at p = 3
(the same knot spans), then with C0 die surfaces of the same element
counts: the die's arc replaced by the polygon through its points at the
mesh's knots (a degree-1 geometry file, raised to p = 2 by igac with its
kinks kept: the facets of a linear finite-element die; it is the master
surface the slab's points slide along), with 16 facets and with 8 (against
the NURBS die with 8 spans).  The slab, the slave, stays C1 in all runs:
igac's multipliers need a slave face of continuity p - 1 (a C0 slave is
refused), so a wholly faceted pair is not run.  For each run, on the
sliding plateau (travel in [--from, --to] x the slide), Fx / Fy and two
measures of the force curve's oscillation: the largest deviation of Fx
from its least-squares quadratic in the travel, and the total variation
of Fx's first differences (sum |dFx_i+1 - dFx_i|), both over the mean
Fx.  Writes bench/results/ironing.csv (per run and step: travel, Fx,
Fy), bench/results/ironing_summary.csv (per run: the measures) and
bench/results/ironing.png (about 10 CPU-minutes; --quick: 20 slide
steps, no p = 3).
"""
import argparse
import copy
import csv
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from case_toml import write_case  # noqa: E402
from friction_iterations import read_shipped_case  # noqa: E402
from results_io import pyplot, write_rows  # noqa: E402

DIE = "die:0:north"
F = 0.3


def gismo_patch(degrees, knots, points, weights=None):
    """One G+Smo XML patch (2D): knot vectors per direction, points (u fastest), optional weights."""
    kind = "TensorNurbs2" if weights is not None else "TensorBSpline2"
    basis = "".join(f'    <Basis type="BSplineBasis" index="{d}">\n     <KnotVector degree="{degrees[d]}">'
                    f'{" ".join(repr(k) for k in knots[d])}</KnotVector>\n    </Basis>\n' for d in range(2))
    if weights is not None:
        basis = (f'   <Basis type="TensorBSplineBasis2">\n{basis}   </Basis>\n'
                 f'   <weights>{" ".join(repr(w) for w in weights)}</weights>\n')
    coefs = "".join(f"{x!r} {y!r}\n" for x, y in points)
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<xml>\n <Geometry type="{kind}" id="0">\n'
            f'  <Basis type="{"TensorNurbsBasis2" if weights is not None else "TensorBSplineBasis2"}">\n'
            f'{basis}  </Basis>\n  <coefs geoDim="2">\n{coefs}</coefs>\n </Geometry>\n</xml>\n')


def read_die(path):
    """The shipped die's control points and weights (3 x 2, u fastest): its one quadratic NURBS patch."""
    import xml.etree.ElementTree as ET
    g = ET.parse(path).getroot().find("Geometry")
    w = [float(x) for x in g.find(".//weights").text.split()]
    p = [tuple(float(x) for x in line.split()) for line in g.find("coefs").text.strip().splitlines()]
    return np.array(p), np.array(w)


def rational_quadratic(points, weights, u):
    b = np.array([(1 - u) ** 2, 2 * u * (1 - u), u * u]) * weights
    return b @ points / b.sum()


def faceted_die(shipped, n):
    """The polygon through the shipped die's arc at u = k / n (and its top at the same u): degree 1, n spans."""
    p, w = read_die(shipped)
    us = [k / n for k in range(n + 1)]
    bottom = [tuple(rational_quadratic(p[:3], w[:3], u)) for u in us]
    top = [tuple(rational_quadratic(p[3:], w[3:], u)) for u in us]
    return gismo_patch([1, 1], [[0.0] + us + [1.0], [0.0, 0.0, 1.0, 1.0]], bottom + top)


def body(case, name):
    return next(b for b in case["body"] if b["name"] == name)


def run(igac, case, folder, tag):
    path = folder / f"{tag}.toml"
    write_case(case, path, f"cases/ironing.toml, variant {tag} (bench/ironing.py)")
    out = folder / tag
    subprocess.run([igac, "run", str(path), "--out", str(out), "--quiet"], check=True)
    rows = list(csv.DictReader(open(out / "load_curve.csv")))
    travel = case_travel(case)
    series = []
    for r in rows:
        t = float(r["time"])
        series.append((travel * max(0.0, t - 1.0), float(r[f"reaction_{DIE}_x"]), -float(r[f"reaction_{DIE}_y"])))
    return series


def case_travel(case):
    return next(d["value"] for d in case["dirichlet"] if d["faces"] == [DIE] and d["component"] == "x")


def plateau_measures(series, travel, lo, hi):
    """Fx / Fy and the oscillation measures over the sliding plateau travel in [lo, hi] x travel."""
    pts = np.array([s for s in series if lo * travel - 1e-12 <= s[0] <= hi * travel + 1e-12])
    x, fx, fy = pts[:, 0], pts[:, 1], pts[:, 2]
    mean = fx.mean()
    fit = np.polyval(np.polyfit(x, fx, 2), x)
    d = np.diff(fx)
    return {"points": len(x), "mean_fx": mean, "mean_fy": fy.mean(), "ratio": (fx / fy).mean(),
            "ratio_min": (fx / fy).min(), "ratio_max": (fx / fy).max(),
            "deviation_from_quadratic": np.abs(fx - fit).max() / mean,
            "variation_of_differences": np.abs(np.diff(d)).sum() / mean}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--igac", default=str(HERE.parent / "build" / "igac"))
    ap.add_argument("--slide-steps", type=int, default=40)
    ap.add_argument("--from", dest="lo", type=float, default=0.3, help="plateau start, fraction of the slide")
    ap.add_argument("--to", dest="hi", type=float, default=0.9, help="plateau end, fraction of the slide")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    if args.quick:
        args.slide_steps = 20
    path, shipped = read_shipped_case("ironing")
    die_file = Path(body(shipped, "die")["geometry"]["file"])
    n_die = body(shipped, "die")["mesh"]["elements"][0]
    shipped.setdefault("output", {})["vtk"] = False
    shipped["loading"]["max_increment"] = 1.0 / args.slide_steps
    shipped["loading"]["steps"] = args.slide_steps
    travel = case_travel(shipped)
    runs = {}
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        variants = [("nurbs_p2", shipped)]
        if not args.quick:
            p3 = copy.deepcopy(shipped)
            for b in p3["body"]:
                b["mesh"]["degree"] = 3
            variants.append(("nurbs_p3", p3))
        for n in (n_die, n_die // 2):
            suffix = "" if n == n_die else f"_die{n}"
            if n != n_die:
                coarse = copy.deepcopy(shipped)
                body(coarse, "die")["mesh"]["elements"][0] = n
                variants.append((f"nurbs_p2{suffix}", coarse))
            (folder / f"die_faceted{n}.xml").write_text(faceted_die(die_file, n))
            facets = copy.deepcopy(shipped)
            body(facets, "die")["geometry"] = {"file": str(folder / f"die_faceted{n}.xml")}
            body(facets, "die")["mesh"]["elements"][0] = n
            variants.append((f"faceted{suffix}", facets))
        for tag, case in variants:
            print(f"running {tag} ...", flush=True)
            runs[tag] = run(args.igac, case, folder, tag)
    rows = [{"run": tag, "travel": round(x, 12), "fx": fx, "fy": fy} for tag, s in runs.items() for x, fx, fy in s]
    write_rows(HERE / "results" / "ironing.csv", rows)
    summary = []
    for tag, s in runs.items():
        m = plateau_measures(s, travel, args.lo, args.hi)
        summary.append({"run": tag, **{k: (round(v, 6) if isinstance(v, float) else v) for k, v in m.items()}})
        print(f"{tag:22s} plateau ({m['points']} steps): Fx {m['mean_fx']:.5f}  Fy {m['mean_fy']:.5f}  Fx/Fy "
              f"{m['ratio']:.4f} [{m['ratio_min']:.4f}, {m['ratio_max']:.4f}]  max |Fx - quadratic| / Fx "
              f"{m['deviation_from_quadratic']:.2e}  sum |d2 Fx| / Fx {m['variation_of_differences']:.2e}")
    by_run = {r["run"]: r for r in summary}
    for r in summary:
        base = by_run["nurbs_p2" + r["run"][len("faceted"):]] if r["run"].startswith("faceted") else by_run["nurbs_p2"]
        if r is base:
            continue
        print(f"{r['run']} over {base['run']}: deviation x "
              f"{r['deviation_from_quadratic'] / base['deviation_from_quadratic']:.2f}, variation x "
              f"{r['variation_of_differences'] / base['variation_of_differences']:.2f}")
    write_rows(HERE / "results" / "ironing_summary.csv", summary)
    plot(runs, travel, args)


def plot(runs, travel, args):
    plt = pyplot()
    if plt is None:
        return
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    for tag, s in runs.items():
        x = [p[0] for p in s if p[0] > 0]
        ax[0].plot(x, [p[1] for p in s if p[0] > 0], ".-", label=f"{tag} Fx")
        ax[0].plot(x, [p[2] for p in s if p[0] > 0], ".--", label=f"{tag} Fy")
        ax[1].plot(x, [p[1] / p[2] for p in s if p[0] > 0], ".-", label=tag)
    ax[1].axhline(F, color="k", lw=0.8, label="f = 0.3")
    for a in ax:
        a.axvspan(args.lo * travel, args.hi * travel, color="0.9")
        a.set_xlabel("die travel along x")
        a.legend(fontsize=7)
    ax[0].set_ylabel("die reaction (per unit thickness)")
    ax[1].set_ylabel("Fx / Fy")
    ax[0].set_title("cases/ironing.toml: the die's reaction while it slides (shaded: plateau)")
    fig.tight_layout()
    fig.savefig(HERE / "results" / "ironing.png", dpi=120)
    print("wrote bench/results/ironing.png")


if __name__ == "__main__":
    main()
