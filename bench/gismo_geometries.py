#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Runs igac on every solid geometry file of G+Smo's own collection.

    python3 bench/gismo_geometries.py BUILD/igac GISMO_FILEDATA [--elements N] [--csv FILE]

GISMO_FILEDATA is the filedata/ folder of a G+Smo checkout
(https://github.com/gismo/gismo); its planar/, domain2d/ and volumes/ files
are read (THB files left out: igac reads tensor-product NURBS).  Each file
gets a case of its own: [mesh] degree the file's largest (at least 2),
`elements` N per direction, linear elasticity, one boundary side held and
another pulled by 0.01 along x (the first and last sides of the file's
<boundary>, or of the sides igac finds on the boundary).
One line per file: the exit code, the dofs, the patches igac reoriented and
the sides it joined, or the one-line error.  Nothing is written into the
G+Smo folder.
"""
import argparse
import csv
import json
import os
import re
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

NAMES = ["west", "east", "south", "north", "front", "back"]


def parse(path):
    text = open(path, encoding="utf-8", errors="replace").read()
    text = re.sub(r"<\?xml[^>]*\?>", "", re.sub(r"^\s*<!--.*?-->\s*", "", text, flags=re.S))
    return ET.fromstring(text)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("igac")
    ap.add_argument("filedata")
    ap.add_argument("--elements", type=int, default=4)
    ap.add_argument("--csv")
    a = ap.parse_args()
    files = []
    for sub in ("planar", "domain2d", "volumes"):
        folder = os.path.join(a.filedata, sub)
        if os.path.isdir(folder):
            files += [os.path.join(folder, f) for f in sorted(os.listdir(folder)) if f.endswith(".xml")]
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for path in files:
            name = os.path.relpath(path, a.filedata)
            if "thb" in name.lower():
                continue
            root = parse(path)
            geos = root.findall(".//Geometry")
            degree = max([int(k.get("degree")) for k in root.iter("KnotVector")] + [2])
            dim = len(list(geos[0].iter("KnotVector"))) if geos else 2
            mp = root.find("MultiPatch")
            boundary = []
            if mp is not None and mp.find("boundary") is not None:
                v = [int(x) for x in mp.find("boundary").text.split()]
                ids = [int(g.get("id", i)) for i, g in enumerate(geos)]
                boundary = [(ids.index(v[i]) if v[i] in ids else v[i], v[i + 1]) for i in range(0, len(v), 2)]
            if not boundary:  # the sides igac does not find inside the body
                for p in range(max(len(geos), 1)):
                    for side in range(1, 2 * dim + 1):
                        probe = os.path.join(tmp, "probe.toml")
                        with open(probe, "w") as f:
                            f.write(f'[geometry]\nfile = "{path}"\n[mesh]\ndegree = {degree}\nelements = [{", ".join(["1"] * dim)}]\n'
                                    f'[material]\nE = 1.0\nnu = 0.3\n[faces]\nprobe = ["{p}:{NAMES[side - 1]}"]\n'
                                    f'[[dirichlet]]\nfaces = ["probe"]\ncomponent = "x"\n')
                        r = subprocess.run([a.igac, "run", probe, "--no-output", "--quiet"], capture_output=True,
                                           text=True, timeout=600)
                        if "is the interface" not in r.stderr:
                            boundary.append((p, side))
            tries = [(boundary[0], boundary[-1])] if len(boundary) > 1 else []
            row = None
            for held, pulled in tries:
                case = os.path.join(tmp, "case.toml")
                with open(case, "w") as f:
                    f.write(f'name = "gismo"\n[geometry]\nfile = "{path}"\n[mesh]\ndegree = {degree}\n'
                            f'elements = [{", ".join([str(a.elements)] * dim)}]\n'
                            '[material]\nmodel = "linear_elastic"\nE = 1.0\nnu = 0.3\n')
                    for c in "xyz"[:dim]:
                        f.write(f'[[dirichlet]]\nfaces = ["{held[0]}:{NAMES[held[1] - 1]}"]\ncomponent = "{c}"\n')
                    f.write(f'[[dirichlet]]\nfaces = ["{pulled[0]}:{NAMES[pulled[1] - 1]}"]\ncomponent = "x"\nvalue = 0.01\n')
                out = os.path.join(tmp, "out")
                r = subprocess.run([a.igac, "run", case, "--out", out, "--quiet"], capture_output=True, text=True,
                                   timeout=600)
                message = (r.stderr.strip().splitlines() or [""])[-1]
                if r.returncode == 2 and ("is the interface" in message or "unknown face" in message):
                    continue  # that side is inside the body: try another pair
                row = {"file": name, "exit": r.returncode, "dofs": "", "reoriented": "", "joined": "", "error": ""}
                if r.returncode == 0:
                    s = json.load(open(os.path.join(out, "summary.json")))
                    row["dofs"] = s.get("dofs", "")
                    row["reoriented"] = " ".join(map(str, s.get("reoriented_patches", [])))
                    row["joined"] = " ".join("=".join(p) for p in s.get("joined_sides", []))
                else:
                    row["error"] = message
                break
            if row is None:
                row = {"file": name, "exit": "", "dofs": "", "reoriented": "", "joined": "",
                       "error": "no pair of boundary sides to hold and pull"}
            rows.append(row)
            print(f'{name:40s} exit {row["exit"]}  dofs {row["dofs"]}  reoriented [{row["reoriented"]}]  '
                  f'joined [{row["joined"]}]  {row["error"]}', flush=True)
    ran = sum(1 for r in rows if r["exit"] == 0)
    print(f"{ran} of {len(rows)} files run; the others are refused in one line")
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
            w.writeheader()
            w.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
