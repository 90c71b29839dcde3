#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Stress tests of igac's numerical stability.

bench/stress_test.py [--quick] [--igac PATH] [--timeout S] [--keep DIR]

Generates case variants from the shipped cases (coarse [32, 8] meshes, no
ParaView output), runs each with `igac run`, and tabulates per run: status,
exit code, load steps, Newton (or active-set) iterations, cut-backs, max
pressure, total force against applied force, time, and a scan of every file
the run wrote (summary.json, the CSV files and the SVG plots) for NaN / inf
(and for the JSON `null` that summary.json writes in place of a value that
is not finite).

Writes bench/results/stress_tests.csv and bench/results/stress_tests.md.
Exit status: 0 when every run either converged or stopped with exit code 1
and a clear status, and no output holds a non-finite value; 1 when a run
crashed (exit code not in {0, 1}, killed by a signal, or over --timeout) or
wrote a NaN.  --quick runs a subset (under 3 minutes on 2 cores).
"""

import argparse
import csv
import json
import math
import os
import re
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RESULTS = ROOT / "bench" / "results"
COARSE_2D = [32, 8]


# ---------------------------------------------------------------- TOML out
from case_toml import write_case  # noqa: E402  (bench/ is on sys.path when run as a script)


def load_case(name):
    with open(ROOT / "cases" / name, "rb") as f:
        return tomllib.load(f)


# ---------------------------------------------------------------- variants
def base_linear():
    c = load_case("hertz2d.toml")
    c["mesh"]["elements"] = list(COARSE_2D)
    return c


def base_neohookean(P):
    c = load_case("hertz2d_neohookean_pressure.toml")
    c["mesh"]["elements"] = list(COARSE_2D)
    c["pressure"][0]["value"] = P
    return c


def set_plane_y(c, y):
    c["contact"]["obstacle"]["point"][1] = y
    return c


def set_grading(c, span, rng):
    g = c["mesh"]["grading"]
    if isinstance(g, list):  # [[mesh.grading]] tables: the first grades the contact face
        g = g[0]
    g["span_fraction"] = span
    g["range_fraction"] = rng
    return c


def set_nu(c, nu):
    c["material"]["nu"] = nu
    return c


def set_steps(c, steps):
    c["loading"]["steps"] = steps
    return c


def variants():
    """(name, group, what changed, case dict, extra command-line options, in --quick)."""
    v = []
    for P in (1e-6, 1e-4, 3e-3, 1e-2, 0.1, 0.2, 0.3):
        v.append((f"nh_P{P:g}", "load", f"Neo-Hookean, follower P = {P:g}, default steps",
                  base_neohookean(P), [], P in (1e-6, 0.1, 0.3)))
    for p in (2, 3, 4, 5):
        v.append((f"lin_p{p}", "degree", f"linear hertz2d, degree {p}", base_linear(), ["--degree", str(p)],
                  p in (2, 5)))
    for p in (2, 3, 4, 5):
        v.append((f"nh_P0.01_p{p}", "degree", f"Neo-Hookean P = 0.01, degree {p}", base_neohookean(0.01),
                  ["--degree", str(p)], p == 5))
    v.append(("lin_grading99", "grading", "linear, 99 % of the spans in 1 % of the range",
              set_grading(base_linear(), 0.99, 0.01), [], True))
    v.append(("nh_P0.01_grading99", "grading", "Neo-Hookean P = 0.01, 99 % of the spans in 1 % of the range",
              set_grading(base_neohookean(0.01), 0.99, 0.01), [], True))
    c = set_grading(base_linear(), 0.99, 0.01)
    c["pressure"][0]["value"] = 5e-5
    v.append(("lin_grading99_P5e-5", "grading", "linear P = 5e-5 (Hertz a = 0.0108 inside the 1 % fine zone), "
              "99 % of the spans in 1 % of the range", c, [], False))
    v.append(("nh_P0.1_grading99", "grading", "Neo-Hookean P = 0.1, 99 % of the spans in 1 % of the range",
              set_grading(base_neohookean(0.1), 0.99, 0.01), [], False))
    for nu in (0.45, 0.49):
        v.append((f"lin_nu{nu:g}", "nu", f"linear, nu = {nu:g}", set_nu(base_linear(), nu), [], nu == 0.49))
        v.append((f"nh_P0.01_nu{nu:g}", "nu", f"Neo-Hookean P = 0.01, nu = {nu:g}",
                  set_nu(base_neohookean(0.01), nu), [], nu == 0.49))
    v.append(("nh_P0.1_steps100", "steps", "Neo-Hookean P = 0.1, steps = 100",
              set_steps(base_neohookean(0.1), 100), [], False))
    v.append(("nh_P0.1_steps1", "steps", "Neo-Hookean P = 0.1, one single step (steps = 1)",
              set_steps(base_neohookean(0.1), 1), [], True))
    v.append(("nh_P0.3_steps1", "steps", "Neo-Hookean P = 0.3, one single step (steps = 1)",
              set_steps(base_neohookean(0.3), 1), [], False))
    for y, where in ((-1.001, "away"), (-0.999, "inside")):
        gap = "0.001 away from" if where == "away" else "0.001 inside"
        v.append((f"lin_{where}", "offset", f"linear, body starting {gap} the plane (plane y = {y:g})",
                  set_plane_y(base_linear(), y), [], True))
        v.append((f"nh_P0.01_{where}", "offset", f"Neo-Hookean P = 0.01, body starting {gap} the plane (y = {y:g})",
                  set_plane_y(base_neohookean(0.01), y), [], True))
    v += newer_variants()
    disp = load_case("hertz2d_neohookean_displacement.toml")
    disp["mesh"]["elements"] = list(COARSE_2D)
    v.append(("nh_displacement", "displacement", "Neo-Hookean, top face displaced u_y = -0.4",
              disp, [], True))
    return v


def shipped(name, **mesh):
    """A shipped case with its geometry file's path made absolute."""
    c = load_case(name)
    for g in [c.get("geometry", {})] + [b.get("geometry", {}) for b in c.get("body", [])]:
        if "file" in g:
            g["file"] = str(ROOT / "cases" / g["file"])
    return c


def oring_coarse(name):
    c = shipped(name)
    c["mesh"]["elements"] = [16, 8]
    return c


def floating_ring(friction):
    """The whole O-ring section without supports in a groove of four planes."""
    def plane(point, normal, motion=None):
        o = {"type": "plane", "point": point, "normal": normal}
        if motion:
            o["motion"] = motion
        return {"face": "arcs", "friction": friction, "obstacle": o}
    c = oring_coarse("oring.toml")
    c["geometry"]["file"] = str(ROOT / "cases" / "oring_full.xml")
    c["faces"] = {"arcs": ["0:south", "1:south", "2:south", "3:south"]}
    c["mesh"]["elements"] = [8, 4]
    c.pop("dirichlet", None)
    c["loading"] = {"steps": 10, "max_increment": 0.1, "max_newton_iterations": 25}
    c["contact"] = [plane([0.0, -2.665], [0.0, 1.0], [0.0, 0.66625]), plane([0.0, 2.665], [0.0, -1.0], [0.0, -0.66625]),
                    plane([-3.2, 0.0], [1.0, 0.0]), plane([3.2, 0.0], [-1.0, 0.0])]
    return c


def newer_variants():
    """The features added after the Hertz variants: friction, real rubber, bodies held by contact alone,
    two deformable bodies, interference fits."""
    v = []
    for f in (0.1, 0.5, 1.0):
        c = oring_coarse("oring_friction.toml")
        c["contact"]["friction"] = f
        c["loading"].update({"steps": 10, "max_increment": 0.1})
        v.append((f"oring_friction{f:g}", "friction", f"O-ring squeezed 25 %, friction {f:g}, ten fixed steps", c, [],
                  f == 1.0))
    c = oring_coarse("oring_rubber.toml")
    c["contact"]["obstacle"]["motion"] = [0.0, 1.066]
    v.append(("oring_rubber_squeeze40", "rubber", "O-ring, K/G = 2000, mixed, squeezed 40 %", c, [], True))
    for f in (0.0, 0.3):
        v.append((f"floating_ring_f{f:g}", "held by contact", f"whole O-ring, no support, groove of four planes, "
                  f"friction {f:g}", floating_ring(f), [], f == 0.0))
    c = shipped("roller_on_block_neohookean.toml")
    c["pressure"][0]["value"] = 0.3
    v.append(("roller_on_block_P0.3", "two bodies", "Neo-Hookean roller on a Neo-Hookean block, P = 0.3", c, [], False))
    for interference in (0.01, 0.05):
        c = shipped("press_fit.toml")
        c["body"][0]["geometry"]["radius"] = 1.0 + interference
        v.append((f"press_fit_{interference:g}", "interference", f"disc on a shaft, plane stress, "
                  f"{100 * interference:g} % interference", c, [], interference == 0.05))
        c = shipped("press_fit.toml")
        c["body"][0]["geometry"]["radius"] = 1.0 + interference
        for b in c["body"]:
            b["material"] = {"model": "neo_hookean", "E": 1.0, "nu": 0.3}
        c["loading"] = {"steps": 5}
        v.append((f"press_fit_{interference:g}_neohookean", "interference", f"disc on a shaft, plane stress, "
                  f"Neo-Hookean, {100 * interference:g} % interference", c, [], False))
    return v


# ---------------------------------------------------------------- scanning
NONFINITE = re.compile(r"(?<![A-Za-z_])[-+]?(nan|inf|infinity)(?![A-Za-z_])", re.IGNORECASE)


def scan_nonfinite(folder):
    """Non-finite tokens per written text file, and JSON nulls in summary.json."""
    nonfinite, nulls, files = 0, 0, []
    for f in sorted(Path(folder).glob("*")):
        if f.suffix not in (".json", ".csv", ".svg"):
            continue
        files.append(f.name)
        text = f.read_text(errors="replace")
        if f.suffix == ".json":
            # keys and the status string are free text: scan values only
            def walk(x):
                nonlocal nonfinite, nulls
                if x is None:
                    nulls += 1
                elif isinstance(x, float) and not math.isfinite(x):
                    nonfinite += 1
                elif isinstance(x, dict):
                    for k, y in x.items():
                        if k not in ("status", "case", "description", "model_part", "obstacle"):
                            walk(y)
                elif isinstance(x, list):
                    for y in x:
                        walk(y)
                elif isinstance(x, str) and NONFINITE.search(x):
                    nonfinite += 1
            try:
                walk(json.loads(text))
            except json.JSONDecodeError:
                nonfinite += len(NONFINITE.findall(text)) or 1  # NaN/Infinity literals break strict JSON
        else:
            nonfinite += len(NONFINITE.findall(text))
    return nonfinite, nulls, files


def material_model(case):
    """The law's name ("a / b" for several bodies of different laws)."""
    models = [case["material"].get("model", "linear_elastic")] if "material" in case else \
        [b.get("material", {}).get("model", "linear_elastic") for b in case.get("body", [])]
    return " / ".join(dict.fromkeys(models))


def fmt(x, spec=".4g"):
    if x is None or x == "":
        return ""
    if isinstance(x, float):
        return format(x, spec)
    return str(x)


def run_one(igac, tmp, name, group, what, case, extra, timeout):
    case_path = Path(tmp) / f"{name}.toml"
    case = json.loads(json.dumps(case))  # deep copy
    case["name"] = name
    case["output"] = {"vtk": False}
    write_case(case, case_path, f"stress variant {name}: {what}\n(generated by bench/stress_test.py)")
    out = Path(tmp) / name
    cmd = [igac, "run", str(case_path), "--out", str(out), "--quiet"] + extra
    t0 = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        rc, stderr = p.returncode, p.stderr
    except subprocess.TimeoutExpired as e:
        rc, stderr = "timeout", (e.stderr or b"").decode(errors="replace") if isinstance(e.stderr, bytes) else (e.stderr or "")
    wall = time.perf_counter() - t0
    row = {"name": name, "group": group, "variant": what, "options": " ".join(extra), "exit_code": rc,
           "wall_s": round(wall, 3)}
    summary = {}
    if (out / "summary.json").exists():
        try:
            summary = json.loads((out / "summary.json").read_text())
        except json.JSONDecodeError:
            summary = {}
    nonfinite, nulls, files = scan_nonfinite(out) if out.exists() else (0, 0, [])
    steps = summary.get("load_steps", [])
    contact = summary.get("contact", {})
    large = "newton_seconds" in summary or any(s.get("newton_iterations", 0) for s in steps) or \
        material_model(case) != "linear_elastic"
    if large:
        iterations = sum(s.get("newton_iterations", 0) for s in steps)
    else:
        iterations = contact.get("active_set_iterations", sum(len(s.get("active_set_sizes", [])) for s in steps))
    total, applied = contact.get("total_force"), contact.get("applied_force")
    if isinstance(contact.get("resultant_along_normal"), (int, float)):
        # against a deformed or curved partner the pressure turns with its normal: the
        # resultant, not the integral of p, balances the load
        total = contact["resultant_along_normal"]
    rel = abs(total - applied) / abs(applied) if isinstance(total, (int, float)) and \
        isinstance(applied, (int, float)) and applied else None
    status = summary.get("status", "")
    if not status:
        status = (stderr.strip().splitlines() or ["(no summary.json)"])[-1]
    row.update({
        "model": material_model(case),
        "degree": summary.get("degree", ""),
        "dofs": summary.get("dofs", ""),
        "multipliers": summary.get("multipliers", ""),
        "status": status,
        "steps": len(steps) if large else "",
        "final_load_factor": steps[-1].get("load_factor") if steps else "",
        "iterations": iterations,
        "iteration_kind": "newton" if large else "active-set",
        "cut_backs": sum(s.get("cut_backs", 0) for s in steps),
        "active": contact.get("active", ""),
        "max_pressure": contact.get("max_pressure", ""),
        "half_width": contact.get("half_width", ""),
        "max_pressure_hertz": summary.get("analytic", {}).get("max_pressure", ""),
        "pressure_l2_rel": summary.get("errors", {}).get("pressure_l2_rel", ""),
        "total_force": total if total is not None else "",
        "applied_force": applied if applied is not None else "",
        "force_rel_diff": rel if rel is not None else "",
        "solver_s": summary.get("timing_s", {}).get("total", ""),
        "nonfinite_values": nonfinite,
        "json_nulls": nulls,
        "files_checked": " ".join(files),
    })
    crashed = rc not in (0, 1)
    row["verdict"] = ("CRASH" if crashed else "NaN" if nonfinite or nulls else
                      "converged" if rc == 0 else "stopped (clear status)")
    return row


COLUMNS = ["name", "group", "variant", "options", "model", "degree", "dofs", "multipliers", "exit_code", "status",
           "verdict", "steps", "final_load_factor", "iterations", "iteration_kind", "cut_backs", "active",
           "max_pressure", "max_pressure_hertz", "pressure_l2_rel", "half_width", "total_force", "applied_force", "force_rel_diff", "solver_s", "wall_s",
           "nonfinite_values", "json_nulls", "files_checked"]


def vs_hertz(r):
    p, h = r.get("max_pressure"), r.get("max_pressure_hertz")
    if isinstance(p, (int, float)) and isinstance(h, (int, float)) and h:
        return f"{100 * (p / h - 1):+.1f} %"
    return ""


def write_markdown(rows, path, quick, elapsed, igac):
    n = len(rows)
    conv = sum(r["verdict"] == "converged" for r in rows)
    stopped = sum(r["verdict"].startswith("stopped") for r in rows)
    bad = [r for r in rows if r["verdict"] in ("CRASH", "NaN")]
    lines = [
        "# Stress tests of numerical stability",
        "",
        f"`bench/stress_test.py{' --quick' if quick else ''}` ({Path(igac).name}, 2D meshes [32, 8] unless the "
        f"degree is raised, ParaView output off); {n} runs in {elapsed:.0f} s: {conv} converged, {stopped} stopped "
        f"with exit code 1 and a status, {len(bad)} crashed or wrote a non-finite value.",
        "",
        "Iterations: Newton iterations summed over the load steps (Neo-Hookean), active-set iterations (linear). "
        "Force: |total contact force - applied force| / applied force (the follower load's resultant on the "
        "deformed face; against a deformable partner the contact force's resultant along the normal; for the "
        "displacement-driven case there is no applied force). vs Hertz: max pressure against Hertz's p0 for the same P and nu (linear cases; Hertz assumes a half space, the coarse [32, 8] mesh sits about 0.5 % below). Solve: `timing_s.total` of summary.json; wall: the whole process, with writing the CSV files and the SVG plots. NaN: non-finite tokens in "
        "summary.json, pressure.csv, load_curve.csv and the SVG plots, plus `null` values in summary.json.",
        "",
        "| run | variant | p | dofs | exit | status | steps | iterations | cut-backs | max pressure | vs Hertz | force rel. diff | solve (s) | wall (s) | NaN |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        status = str(r["status"]).replace("|", "\\|")
        if len(status) > 90:
            status = status[:87] + "..."
        lines.append(
            f"| {r['name']} | {r['variant']} | {r['degree']} | {r['dofs']} | {r['exit_code']} | {status} | "
            f"{r['steps']} | {r['iterations']}{'' if r['iteration_kind'] == 'newton' else ' (AS)'} | "
            f"{r['cut_backs']} | {fmt(r['max_pressure'])} | {vs_hertz(r)} | {fmt(r['force_rel_diff'], '.1e')} | "
            f"{fmt(r['solver_s'], '.2f')} | {fmt(r['wall_s'], '.1f')} | {'yes' if r['nonfinite_values'] or r['json_nulls'] else 'no'} |")
    lines.append("")
    if bad:
        lines.append("Runs that crashed or wrote a non-finite value:")
        lines.append("")
        for r in bad:
            lines.append(f"- {r['name']} ({r['variant']}): exit {r['exit_code']}, {r['status']}")
    else:
        lines.append("No run crashed, none wrote a NaN / inf / null.")
    lines.append("")
    Path(path).write_text("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[1])
    ap.add_argument("--quick", action="store_true", help="a subset (< 3 minutes)")
    ap.add_argument("--igac", default=str(ROOT / "build" / "igac"), help="igac binary (default build/igac)")
    ap.add_argument("--timeout", type=float, default=600, help="seconds before a run counts as hung (crash)")
    ap.add_argument("--keep", help="keep the runs' folders here instead of a temporary folder")
    ap.add_argument("--results", default=str(RESULTS), help="where the tables go (default bench/results)")
    args = ap.parse_args()
    igac = str(Path(args.igac).resolve())
    if not os.access(igac, os.X_OK):
        sys.exit(f"stress_test: no igac binary at {igac} (build it or pass --igac)")
    todo = [v for v in variants() if v[5] or not args.quick]
    t_start = time.perf_counter()
    rows = []
    with tempfile.TemporaryDirectory(prefix="igac-stress-") as tmp:
        work = args.keep or tmp
        Path(work).mkdir(parents=True, exist_ok=True)
        for name, group, what, case, extra, _ in todo:
            r = run_one(igac, work, name, group, what, case, extra, args.timeout)
            rows.append(r)
            print(f"{name:22s} exit {str(r['exit_code']):7s} {r['verdict']:22s} steps {str(r['steps']):3s} "
                  f"it {str(r['iterations']):4s} cut {r['cut_backs']:2d} p_max {fmt(r['max_pressure']):10s} "
                  f"dF {fmt(r['force_rel_diff'], '.1e'):8s} {r['wall_s']:6.1f} s  {str(r['status'])[:70]}",
                  flush=True)
    elapsed = time.perf_counter() - t_start
    results = Path(args.results)
    results.mkdir(parents=True, exist_ok=True)
    with open(results / "stress_tests.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=COLUMNS)
        w.writeheader()
        for r in rows:
            w.writerow({k: r.get(k, "") for k in COLUMNS})
    write_markdown(rows, results / "stress_tests.md", args.quick, elapsed, igac)
    bad = [r for r in rows if r["verdict"] in ("CRASH", "NaN")]
    print(f"{len(rows)} runs in {elapsed:.0f} s; wrote {results / 'stress_tests.csv'} and stress_tests.md")
    if bad:
        for r in bad:
            print(f"FAILED: {r['name']}: exit {r['exit_code']}, {r['verdict']}, {r['status']}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
