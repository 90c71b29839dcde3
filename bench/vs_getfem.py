#!/usr/bin/python3
"""vs_getfem.py [--problems 2d 3d] [--quick] — igac against GetFEM, same machine, same run.

Runs the GetFEM peer scripts (../shared/peers/getfem, Debian's
python3-getfem++, installed here when missing: the bench's, never the
tests') and igac on the same Hertz problems, one after the other, and
reports for each the time to reach a relative L2 pressure error (against
Hertz, over the contact face) and the ratio GetFEM / igac.

  2D Hertz P = 0.003: targets 2 %, 1 %, 0.7 %   (igac: cases/hertz2d.toml with its element counts
                                                 scaled x1 ... x8, p = 2 and 3; GetFEM N = 16, 32, 64)
  3D Hertz P = 1e-4:  target 5 %                (igac: cases/hertz3d.toml; GetFEM N = 4..12)

Times.  GetFEM: mesh + setup + solve of its run (Python import excluded, as
its README measures).  igac: the wall time of the whole process (start, case
file, mesh, solve, report) with --no-output, since GetFEM writes no files;
igac's own "total" is in the CSV too.  Each run is a fresh process.

Writes bench/results/vs_getfem_runs.csv (every run), vs_getfem.csv (time to
each target, ratio) and vs_getfem.png (error against time, both codes).
"""
import argparse
import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
IGAC = os.path.join(ROOT, "build", "igac")
PEERS = os.path.normpath(os.path.join(ROOT, "..", "shared", "peers", "getfem"))
PYTHON = "/usr/bin/python3"  # Debian's: GetFEM lives in its dist-packages

TARGETS = {"2d": [0.02, 0.01, 0.007], "3d": [0.05]}


def ensure_getfem():
    if subprocess.run([PYTHON, "-c", "import getfem"], capture_output=True).returncode == 0:
        return
    print("vs_getfem: installing python3-getfem++ (Debian) for the bench", file=sys.stderr)
    env = dict(os.environ, DEBIAN_FRONTEND="noninteractive")
    subprocess.run(["apt-get", "install", "-y", "-qq", "python3-getfem++"], check=True, env=env)


def run_getfem(problem, quick):
    script = os.path.join(PEERS, "hertz2d.py" if problem == "2d" else "hertz3d.py")
    if problem == "2d":
        args = ["--P", "0.003", "--N"] + (["16", "32"] if quick else ["16", "32", "64"])
    else:
        args = ["--P", "1e-4", "--N"] + (["4", "6"] if quick else ["4", "6", "8", "10", "12"])
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "gf.csv")
        subprocess.run([PYTHON, script] + args + ["--csv", out], check=True, capture_output=True, cwd=PEERS)
        with open(out) as f:
            rows = list(csv.DictReader(f))
    return [{"code": "getfem", "problem": problem, "mesh": f"N={r['N']}", "unknowns": int(r["n_dof_total"]),
             "seconds": float(r["t_mesh_s"]) + float(r["t_setup_plus_solve_s"]), "own_total_s": float(r["t_solve_s"]),
             "l2_rel": float(r["L2_err_rel"])} for r in rows]


def scaled_case(case, factor, tmp):
    """The case with its element counts scaled by factor (finer steps than --refine's doubling)."""
    text = open(case).read()
    m = re.search(r"elements = \[([0-9, ]+)\]", text)
    counts = [max(1, round(int(c) * factor)) for c in m.group(1).split(",")]
    path = os.path.join(tmp, f"case_{factor:g}.toml")
    with open(path, "w") as f:
        f.write(text[:m.start()] + "elements = [" + ", ".join(map(str, counts)) + "]" + text[m.end():])
    return path


def run_igac(problem, quick):
    case = os.path.join(ROOT, "cases", "hertz2d.toml" if problem == "2d" else "hertz3d.toml")
    if problem == "2d":
        meshes = [(2, f) for f in (1, 1.5, 2, 2.5, 3, 4, 6, 8)] + [(3, f) for f in (1, 1.5, 2, 3, 4)]
        if quick:
            meshes = [(2, 1), (2, 2), (3, 1)]
    else:
        meshes = [(2, 1)] if quick else [(2, 1), (2, 1.5), (3, 1)]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for degree, factor in meshes:
            path = scaled_case(case, factor, tmp)
            t0 = time.perf_counter()
            done = subprocess.run([IGAC, "run", path, "--no-output", "--degree", str(degree)], capture_output=True, text=True)
            wall = time.perf_counter() - t0
            if done.returncode != 0:
                print(f"igac {problem} p={degree} x{factor}: {done.stderr.strip()}", file=sys.stderr)
                continue
            sizes = re.search(r"(\d+) dofs, (\d+) multipliers", done.stdout)
            rel = float(re.search(r"pressure L2 +\S+ +\(relative (\S+),", done.stdout).group(1))
            own = float(re.search(r"time +(\S+) s", done.stdout).group(1))
            rows.append({"code": "igac", "problem": problem, "mesh": f"p={degree} elements x{factor:g}",
                         "unknowns": int(sizes.group(1)) + int(sizes.group(2)), "seconds": wall, "own_total_s": own,
                         "l2_rel": rel})
    return rows


def time_to(rows, target):
    ok = [r for r in rows if r["l2_rel"] <= target]
    return min(ok, key=lambda r: r["seconds"]) if ok else None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--problems", nargs="+", default=["2d"], choices=["2d", "3d"])
    ap.add_argument("--quick", action="store_true", help="fewer meshes (a smoke run of the bench)")
    args = ap.parse_args()
    if not os.path.exists(IGAC):
        sys.exit("vs_getfem: build igac first (./test.sh or cmake --build build)")
    ensure_getfem()
    runs, summary = [], []
    for problem in args.problems:
        gf, ig = run_getfem(problem, args.quick), run_igac(problem, args.quick)
        runs += gf + ig
        for target in TARGETS[problem]:
            g, i = time_to(gf, target), time_to(ig, target)
            summary.append({"problem": problem, "target_l2_rel": target,
                            "getfem_s": f"{g['seconds']:.3f}" if g else "", "getfem_mesh": g["mesh"] if g else "not reached",
                            "igac_s": f"{i['seconds']:.3f}" if i else "", "igac_mesh": i["mesh"] if i else "not reached",
                            "ratio_getfem_over_igac": f"{g['seconds'] / i['seconds']:.2f}" if g and i else ""})
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    with open(os.path.join(HERE, "results", "vs_getfem_runs.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(runs[0].keys()))
        w.writeheader()
        w.writerows(runs)
    with open(os.path.join(HERE, "results", "vs_getfem.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(summary[0].keys()))
        w.writeheader()
        w.writerows(summary)
    for r in runs:
        print(f"{r['code']:7} {r['problem']} {r['mesh']:18} {r['unknowns']:>8} unknowns  {r['seconds']:8.3f} s  "
              f"L2 rel {100 * r['l2_rel']:.3f} %")
    for s in summary:
        print(f"{s['problem']} {100 * s['target_l2_rel']:.1f} %: GetFEM {s['getfem_s'] or '-'} s ({s['getfem_mesh']}), "
              f"igac {s['igac_s'] or '-'} s ({s['igac_mesh']}), ratio {s['ratio_getfem_over_igac'] or '-'}")
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, len(args.problems), figsize=(6 * len(args.problems), 4.5), squeeze=False)
        for ax, problem in zip(axes[0], args.problems):
            for code, style in (("getfem", "s-"), ("igac", "o")):
                pts = sorted((r["seconds"], r["l2_rel"]) for r in runs if r["code"] == code and r["problem"] == problem)
                if pts:
                    ax.loglog([p[0] for p in pts], [100 * p[1] for p in pts], style, label=code)
            for t in TARGETS[problem]:
                ax.axhline(100 * t, color="grey", lw=0.5, ls=":")
            ax.set_xlabel("time (s, same machine, same run)")
            ax.set_ylabel("relative L2 pressure error (%)")
            ax.set_title(f"Hertz {problem.upper()}")
            ax.grid(alpha=0.3, which="both")
            ax.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(HERE, "results", "vs_getfem.png"), dpi=110)
    except ImportError:
        print("vs_getfem: no matplotlib, no plot", file=sys.stderr)


if __name__ == "__main__":
    main()
