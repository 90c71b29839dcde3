#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""vs_getfem.py [--problems 2d 3d follower disp two_bodies two_bodies_largedef friction] [--quick]
igac against GetFEM, same machine, same run.

Runs the GetFEM peer scripts (../shared/peers/getfem and getfem-largedef,
Debian's python3-getfem++, installed here when missing: the bench's, never
the tests') and igac on the same problems, one after the other, and reports
for each accuracy target the time each code needs to reach it and the ratio
GetFEM / igac.

  2d        Hertz P = 0.003, relative L2 pressure error against Hertz: 2 %, 1 %, 0.7 %
            (igac: cases/hertz2d.toml, element counts scaled, p = 2 and 3; GetFEM N = 16, 32, 64)
  3d        Hertz P = 1e-4, the same error: 5 %
            (igac: cases/hertz3d.toml (paper mesh, p = 2) and cases/hertz3d_p3.toml (p = 3, fitted),
             scaled; GetFEM N = 4 .. 14)
  follower  Neo-Hookean, follower pressure P = 0.1; disp: top face moved by u_y = -0.4.  Target:
  disp      GetFEM's converged values (../shared/peers/getfem-largedef/README.md, section 0): contact
            force within 0.5 %, deformed contact half-width within 3 %, nominal peak pressure within
            3 %, all three (igac: the shipped cases scaled; GetFEM N = 8 .. 64).  The issue's yardstick
            is GetFEM's N = 64 run, so that ratio is reported too.

  two_bodies  Hertz between two elastic bodies (issue 22): cases/roller_on_block.toml, the hertz2d roller
            (E = 1) on a block (E = 3), P = 0.003, against Hertz with the combined modulus
            (a = 0.096277, p0 = 0.039674); relative L2 pressure error: 2 %, 1 %, 0.7 %.  GetFEM:
            bench/getfem_two_bodies.py (both meshes graded, P2, integral Alart-Curnier contact between
            the meshes, N = 8 .. 64); igac: the case with both bodies' element counts scaled, its L2
            error from pressure.csv of a second (untimed) run of the same mesh.
  two_bodies_largedef  Two Neo-Hookean bodies in large deformation (issue 22):
            cases/roller_on_block_neohookean.toml, the roller pressed by the follower pressure P = 0.1
            into a block of the same rubber.  No closed form: the target is the applied force (the
            follower load's vertical resultant), the deformed contact half width and the nominal peak
            pressure within 0.5 %, 3 % and 3 % of their converged values (LARGEDEF below: both codes'
            finest meshes), and the same at half those tolerances.  GetFEM:
            bench/getfem_two_bodies_largedef.py (its large-sliding contact brick between the two
            meshes, ray tracing, Q2, N = 8 .. 32); igac: the case with both bodies' element counts
            scaled.
  friction  Cattaneo-Mindlin, f = 0.3 (issue 23): cases/cattaneo_mindlin.toml, a half disc pressed by
            0.02 on a rigid plane, then sheared by 0.008 in 4 steps.  No closed form for the forces of
            this displacement-driven geometry: the target is the normal force N and tangential force Q
            within 1 %, 0.5 %, 0.2 % of their converged values (FRICTION_REF: both codes' finest
            meshes agree within 0.1 % on Q and 0.01 % on N).  The stick half width c against the
            Cattaneo-Mindlin law a sqrt(1 - Q / (f N)) is recorded beside it (it moves by whole
            multipliers, too jumpy to time).  GetFEM: bench/getfem_friction.py (the top sheared
            instead of the plane, P2, integral Alart-Curnier brick with friction, N = 8 .. 64); igac:
            the case scaled, c from pressure.csv of a second (untimed) run.

Times.  GetFEM: mesh + setup + solve of its run (Python import excluded, as
its READMEs measure).  igac: the wall time of the whole process (start, case
file, mesh, solve, report) with --no-output, since GetFEM writes no files.
Each run is a fresh process; the two codes never run at the same time.

Writes bench/results/vs_getfem_runs.csv (every run), vs_getfem.csv (time to
each target, ratio) and vs_getfem.png (error against time, both codes); a
run of another set of problems, or --quick, writes vs_getfem_<problems>[_quick]
*.csv/png instead (e.g. vs_getfem_two_bodies.csv), leaving those alone.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IGAC = os.path.join(ROOT, "build", "igac")
PEERS = os.path.normpath(os.path.join(ROOT, "..", "shared", "peers"))
PYTHON = "/usr/bin/python3"  # Debian's: GetFEM lives in its dist-packages

# GetFEM's converged large-deformation values and the tolerances of issue 11.
LARGEDEF = {
    "follower": {"force": 0.111476, "half_width": 0.4959, "max_pressure": 0.238557},
    "disp": {"force": 0.366592, "half_width": 0.7673, "max_pressure": 0.570388},
    # both codes' finest meshes (docs/benchmarks.md): the force and the peak agree to 1e-5; the
    # half width's estimates move by about 1 % from mesh to mesh in both codes, so its mean
    "two_bodies_largedef": {"force": 0.110734, "half_width": 0.672, "max_pressure": 0.18059},
}
LARGEDEF_TOL = {"force": 0.005, "half_width": 0.03, "max_pressure": 0.03}
TARGETS = {"2d": [0.02, 0.01, 0.007], "3d": [0.05], "follower": [1.0], "disp": [1.0],
           "two_bodies": [0.02, 0.01, 0.007], "two_bodies_largedef": [1.0, 0.5]}
L2_PROBLEMS = ("2d", "3d", "two_bodies")
DEFAULT_PROBLEMS = ["2d", "3d", "follower", "disp"]
TARGETS["friction"] = [0.01, 0.005, 0.002]
FRICTION_REF = {"normal_force": 0.014952, "tangential_force": 0.0027638}  # see docs/benchmarks.md
FRICTION_F = 0.3
ROLLER_HERTZ = (0.096277, 0.039674)  # a, p0: Hertz with the combined modulus, roller_on_block.toml


def ensure_getfem():
    if subprocess.run([PYTHON, "-c", "import getfem"], capture_output=True).returncode == 0:
        return
    print("vs_getfem: installing python3-getfem++ (Debian) for the bench", file=sys.stderr)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.run(["apt-get", "install", "-y", "-qq", "python3-getfem++"], check=True, env=env)


def largedef_error(problem, force, half_width, max_pressure):
    """Largest error relative to its tolerance: <= 1 when all three are within."""
    ref, got = LARGEDEF[problem], {"force": force, "half_width": half_width, "max_pressure": max_pressure}
    return max(abs(got[k] - ref[k]) / ref[k] / LARGEDEF_TOL[k] for k in ref)


def friction_error(run):
    return max(abs(run[k] - v) / v for k, v in FRICTION_REF.items())


def run_getfem(problem, quick):
    if problem == "friction":
        script = os.path.join(HERE, "getfem_friction.py")
        args = ["--N"] + (["8", "16"] if quick else ["8", "16", "32", "64"])
    elif problem == "two_bodies":
        script = os.path.join(HERE, "getfem_two_bodies.py")
        args = ["--N"] + (["8", "16", "32"] if quick else ["8", "16", "24", "32", "48", "64"])
    elif problem == "two_bodies_largedef":
        script = os.path.join(HERE, "getfem_two_bodies_largedef.py")
        args = ["--N"] + (["8", "16"] if quick else ["8", "12", "16", "24", "32"])
    elif problem in ("2d", "3d"):
        script = os.path.join(PEERS, "getfem", "hertz2d.py" if problem == "2d" else "hertz3d.py")
        if problem == "2d":
            args = ["--P", "0.003", "--N"] + (["16", "32"] if quick else ["16", "32", "64"])
        else:
            args = ["--P", "1e-4", "--N"] + (["4", "6", "8"] if quick else ["4", "6", "8", "10", "12", "14"])
    else:
        script = os.path.join(PEERS, "getfem-largedef", "largedef2d.py")
        args = (["--case", "follower", "--P", "0.1"] if problem == "follower" else ["--case", "disp", "--uy", "-0.4"])
        args += ["--steps", "20", "--N"] + (["8", "16"] if quick else ["8", "16", "32", "64"])
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "gf.csv")
        subprocess.run([PYTHON, script] + args + ["--csv", out], check=True, capture_output=True,
                       cwd=os.path.dirname(script))
        with open(out) as f:
            rows = list(csv.DictReader(f))
    runs = []
    for r in rows:
        run = {"code": "getfem", "problem": problem, "mesh": f"N={r['N']}", "unknowns": int(r["n_dof_total"])}
        if problem == "friction":
            run.update(seconds=float(r["t_mesh_s"]) + float(r["t_setup_s"]) + float(r["t_solve_s"]),
                       **{k: float(r[k]) for k in ("normal_force", "tangential_force", "half_width",
                                                   "stick_half_width", "stick_law")})
            run["error"] = friction_error(run)
        elif problem == "two_bodies":
            run.update(seconds=float(r["t_mesh_s"]) + float(r["t_setup_s"]) + float(r["t_solve_s"]),
                       error=float(r["L2_err_rel"]), half_width=float(r["a_h"]), max_pressure=float(r["p0_h"]))
        elif problem == "two_bodies_largedef":
            run.update(seconds=float(r["t_mesh_s"]) + float(r["t_setup_s"]) + float(r["t_solve_s"]),
                       **{k: float(r[k]) for k in ("force", "half_width", "max_pressure")})
            run["error"] = largedef_error(problem, run["force"], run["half_width"], run["max_pressure"])
        elif problem in ("2d", "3d"):
            run.update(seconds=float(r["t_mesh_s"]) + float(r["t_setup_plus_solve_s"]), error=float(r["L2_err_rel"]))
        else:
            run.update(seconds=float(r["t_mesh_s"]) + float(r["t_setup_s"]) + float(r["t_solve_s"]),
                       force=float(r["F_contact"]), half_width=float(r["a_def_active"]),
                       max_pressure=float(r["p_nom_max"]))
            run["error"] = largedef_error(problem, run["force"], run["half_width"], run["max_pressure"])
        runs.append(run)
    return runs


def scaled_case(case, factor, tmp):
    """The case with its element counts scaled by factor (finer steps than --refine's doubling)."""
    text = open(case).read()

    def scale(m):   # every body's elements line (a two-body case has two)
        counts = [max(1, round(int(c) * factor)) for c in m.group(1).split(",")]
        return "elements = [" + ", ".join(map(str, counts)) + "]"
    path = os.path.join(tmp, f"x{factor:g}_{os.path.basename(case)}")
    with open(path, "w") as f:
        text = re.sub(r"elements = \[([0-9, ]+)\]", scale, text)
        # a geometry file named relative to the case stays found from the temporary folder
        text = re.sub(r'^(file *= *")([^"/][^"]*)"', lambda m: m.group(1) + os.path.join(os.path.dirname(
            os.path.abspath(case)), m.group(2)) + '"', text, flags=re.M)
        f.write(text)
    return path


def stick_half_width(path):
    """The stick zone's half width from igac's pressure.csv: to the outer edge of the outermost sticking
    multiplier (r is the distance from the lowest point; the multipliers of both sides share it)."""
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if r["kind"] == "multiplier"]
    rs = sorted({float(r["r"]) for r in rows})
    stuck = [float(r["r"]) for r in rows if r["state"] == "stick"]
    if not stuck:
        return 0.0
    r = max(stuck)
    k = rs.index(r)
    span = (rs[k + 1] - rs[k]) if k + 1 < len(rs) else (rs[k] - rs[k - 1])
    return r + 0.5 * span


def pressure_l2_from_csv(path, a, p0):
    """Relative L2 error against Hertz of igac's multiplier pressure (pressure.csv: constant on each span
    between consecutive p1 points, the S0 multipliers of p = 2), Gauss-integrated span by span."""
    with open(path) as f:
        rows = list(csv.DictReader(f))
    values = [float(r["pressure"]) for r in sorted((r for r in rows if r["kind"] == "multiplier"),
                                                   key=lambda r: float(r["r"]))]
    edges = sorted(float(r["r"]) for r in rows if r["kind"] == "p1")
    gauss = [(-0.9061798459, 0.2369268851), (-0.5384693101, 0.4786286705), (0.0, 0.5688888889),
             (0.5384693101, 0.4786286705), (0.9061798459, 0.2369268851)]
    err = norm = 0.0
    for lo, hi, p in zip(edges[:-1], edges[1:], values):
        for k in range(8):   # 8 sub-spans: the Hertz square root's kink at r = a
            l, h = lo + (hi - lo) * k / 8, lo + (hi - lo) * (k + 1) / 8
            for g, w in gauss:
                x = 0.5 * (h - l) * g + 0.5 * (h + l)
                ph = p0 * math.sqrt(max(0.0, 1.0 - (x / a) ** 2))
                err += 0.5 * (h - l) * w * (p - ph) ** 2
                norm += 0.5 * (h - l) * w * ph ** 2
    return math.sqrt(err / norm)


def igac_meshes(problem, quick):
    """(case file, degree, element factor) of every igac run."""
    if problem == "2d":
        factors = (1, 2) if quick else (0.75, 1, 1.5, 2, 3, 4)
        return [("hertz2d.toml", p, f) for p in (2, 3) for f in factors]
    if problem == "3d":
        if quick:
            return [("hertz3d.toml", 2, 1), ("hertz3d_p3.toml", 3, 0.75), ("hertz3d_p3.toml", 3, 1)]
        return [("hertz3d.toml", 2, 1), ("hertz3d.toml", 2, 1.5)] + [
            ("hertz3d_p3.toml", 3, f) for f in (0.75, 1, 1.25, 1.5)]
    if problem == "friction":
        return [("cattaneo_mindlin.toml", 2, f) for f in ((0.125, 0.25) if quick else (0.125, 0.25, 0.5, 1, 2))]
    if problem == "two_bodies":
        return [("roller_on_block.toml", 2, f) for f in ((0.5, 1) if quick else (0.5, 0.75, 1, 1.5, 2, 3, 4))]
    if problem == "two_bodies_largedef":
        return [("roller_on_block_neohookean.toml", 2, f) for f in ((0.5, 1) if quick else (0.375, 0.5, 0.75, 1, 1.5))]
    case = "hertz2d_neohookean_pressure.toml" if problem == "follower" else "hertz2d_neohookean_displacement.toml"
    return [(case, 2, f) for f in ((0.5, 1) if quick else (0.375, 0.5, 0.75, 1))]


def run_igac(problem, quick):
    rows = []
    tmp = tempfile.TemporaryDirectory()
    for name, degree, factor in igac_meshes(problem, quick):
        path = scaled_case(os.path.join(ROOT, "cases", name), factor, tmp.name)
        t0 = time.perf_counter()
        done = subprocess.run([IGAC, "run", path, "--no-output", "--degree", str(degree)], capture_output=True,
                              text=True)
        wall = time.perf_counter() - t0
        label = f"{name.removesuffix('.toml')} p={degree} x{factor:g}"
        if done.returncode != 0:
            print(f"igac {problem} {label}: {done.stderr.strip()}", file=sys.stderr)
            continue
        out = done.stdout
        sizes = re.search(r"(\d+) dofs, (\d+) multipliers", out)
        run = {"code": "igac", "problem": problem, "mesh": label,
               "unknowns": int(sizes.group(1)) + int(sizes.group(2)), "seconds": wall}
        if problem == "friction":   # the stick zone from the same mesh run again with output (untimed)
            outdir = os.path.join(tmp.name, f"out_x{factor:g}")
            subprocess.run([IGAC, "run", path, "--quiet", "--out", outdir, "--degree", str(degree)], check=True)
            run["normal_force"] = float(re.search(r"total force +(\S+)", out).group(1))
            run["tangential_force"] = float(re.search(r"tangential force +(\S+)", out).group(1))
            run["half_width"] = float(re.search(r"half width +(\S+)", out).group(1))
            run["stick_half_width"] = stick_half_width(os.path.join(outdir, "pressure.csv"))
            run["stick_law"] = run["half_width"] * math.sqrt(
                max(0.0, 1.0 - run["tangential_force"] / (FRICTION_F * run["normal_force"])))
            run["error"] = friction_error(run)
        elif problem == "two_bodies":   # the error from the same mesh run again with output (untimed)
            outdir = os.path.join(tmp.name, f"out_x{factor:g}")
            subprocess.run([IGAC, "run", path, "--quiet", "--out", outdir, "--degree", str(degree)], check=True)
            run["error"] = pressure_l2_from_csv(os.path.join(outdir, "pressure.csv"), *ROLLER_HERTZ)
            run["half_width"] = float(re.search(r"half width +(\S+)", out).group(1))
            run["max_pressure"] = float(re.search(r"max pressure +(\S+)", out).group(1))
        elif problem in ("2d", "3d"):
            run["error"] = float(re.search(r"pressure L2 +\S+ +\(relative (\S+),", out).group(1))
        else:
            run["half_width"] = float(re.search(r"half width +(\S+) deformed", out).group(1))
            run["max_pressure"] = float(re.search(r"max pressure +(\S+) nominal", out).group(1))
            # on a rigid plane the pressure's sum is the applied force; between two bodies the contact
            # face curves, and the force both codes compare is the follower load's vertical resultant
            run["force"] = float(re.search(r"\(applied (\S+)," if problem == "two_bodies_largedef"
                                           else r"total force +(\S+)", out).group(1))
            run["error"] = largedef_error(problem, run["force"], run["half_width"], run["max_pressure"])
        rows.append(run)
    return rows


def time_to(rows, target):
    ok = [r for r in rows if r["error"] <= target]
    return min(ok, key=lambda r: r["seconds"]) if ok else None


def summarise(problem, gf, ig):
    out = []
    for target in TARGETS[problem]:
        g, i = time_to(gf, target), time_to(ig, target)
        row = {"problem": problem,
               "target": f"L2 pressure {100 * target:g} %" if problem in L2_PROBLEMS
               else f"N and Q {100 * target:g} %" if problem == "friction"
               else "force 0.5 %, half width 3 %, peak pressure 3 %" if target == 1.0
               else f"force {0.5 * target:g} %, half width {3 * target:g} %, peak pressure {3 * target:g} %",
               "getfem_s": f"{g['seconds']:.3f}" if g else "", "getfem_mesh": g["mesh"] if g else "not reached",
               "igac_s": f"{i['seconds']:.3f}" if i else "", "igac_mesh": i["mesh"] if i else "not reached",
               "ratio_getfem_over_igac": f"{g['seconds'] / i['seconds']:.1f}" if g and i else "",
               "getfem_N64_s": "", "ratio_getfem_N64_over_igac": ""}
        n64 = [r for r in gf if r["mesh"] == "N=64"]
        if problem in ("follower", "disp") and n64 and i:
            row["getfem_N64_s"] = f"{n64[0]['seconds']:.3f}"
            row["ratio_getfem_N64_over_igac"] = f"{n64[0]['seconds'] / i['seconds']:.1f}"
        out.append(row)
    return out


def plot(runs, problems, tag):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("vs_getfem: no matplotlib, no plot", file=sys.stderr)
        return
    fig, axes = plt.subplots(1, len(problems), figsize=(5 * len(problems), 4.2), squeeze=False)
    for ax, problem in zip(axes[0], problems):
        for code, style in (("getfem", "s-"), ("igac", "o")):
            pts = sorted((r["seconds"], r["error"]) for r in runs if r["code"] == code and r["problem"] == problem)
            if pts:
                ax.loglog([p[0] for p in pts], [p[1] * (1 if problem in LARGEDEF else 100) for p in pts], style,
                          label=code)
        for t in TARGETS[problem]:
            ax.axhline(t * (1 if problem in LARGEDEF else 100), color="grey", lw=0.5, ls=":")
        ax.set_xlabel("time (s, same machine, same run)")
        ax.set_ylabel("relative L2 pressure error (%)" if problem in L2_PROBLEMS
                      else "N, Q: largest error (%)" if problem == "friction" else "largest error / its tolerance")
        ax.set_title({"2d": "Hertz 2D, P = 0.003", "3d": "Hertz 3D, P = 1e-4",
                      "follower": "Neo-Hookean, follower P = 0.1", "disp": "Neo-Hookean, u_y = -0.4",
                      "two_bodies": "roller (E = 1) on block (E = 3), P = 0.003",
                      "two_bodies_largedef": "Neo-Hookean roller on block, follower P = 0.1",
                      "friction": "Cattaneo-Mindlin, f = 0.3"}[problem])
        ax.grid(alpha=0.3, which="both")
        ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "results", f"vs_getfem{tag}.png"), dpi=110)


def write_csv(path, rows):
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--problems", nargs="+", default=DEFAULT_PROBLEMS, choices=list(TARGETS))
    ap.add_argument("--quick", action="store_true", help="fewer meshes (a smoke run of the bench)")
    args = ap.parse_args()
    if not os.path.exists(IGAC):
        sys.exit("vs_getfem: build igac first (./test.sh or cmake --build build)")
    ensure_getfem()
    runs, summary = [], []
    for problem in args.problems:
        gf, ig = run_getfem(problem, args.quick), run_igac(problem, args.quick)
        runs += gf + ig
        summary += summarise(problem, gf, ig)
    # the four original problems keep their file names; any other set (and --quick) gets its own, so a
    # run of one problem never overwrites another's record
    tag = "" if args.problems == DEFAULT_PROBLEMS and not args.quick else \
        "_" + "_".join(args.problems) + ("_quick" if args.quick else "")
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    write_csv(os.path.join(HERE, "results", f"vs_getfem{tag}_runs.csv"), runs)
    write_csv(os.path.join(HERE, "results", f"vs_getfem{tag}.csv"), summary)
    for r in runs:
        if r["problem"] in L2_PROBLEMS:
            err = f"L2 rel {100 * r['error']:.3f} %"
        elif r["problem"] == "friction":
            err = (f"N {r['normal_force']:.7f}, Q {r['tangential_force']:.7f} (error {100 * r['error']:.3f} %), "
                   f"a {r['half_width']:.5f}, stick c {r['stick_half_width']:.5f}, law {r['stick_law']:.5f}")
        else:
            err = (f"force {r['force']:.6f}, a {r['half_width']:.4f}, p {r['max_pressure']:.5f} "
                   f"(error/tol {r['error']:.2f})")
        if r["problem"] == "two_bodies":
            err += f", a {r['half_width']:.5f}, p0 {r['max_pressure']:.5f} (Hertz {ROLLER_HERTZ[0]}, {ROLLER_HERTZ[1]})"
        print(f"{r['code']:7} {r['problem']:8} {r['mesh']:32} {r['unknowns']:>8} unknowns {r['seconds']:9.3f} s  {err}")
    for s in summary:
        extra = f", GetFEM N=64 {s['getfem_N64_s']} s: ratio {s['ratio_getfem_N64_over_igac']}" if s["getfem_N64_s"] else ""
        print(f"{s['problem']} {s['target']}: GetFEM {s['getfem_s'] or '-'} s ({s['getfem_mesh']}), "
              f"igac {s['igac_s'] or '-'} s ({s['igac_mesh']}), ratio {s['ratio_getfem_over_igac'] or '-'}{extra}")
    plot(runs, args.problems, tag)


if __name__ == "__main__":
    main()
