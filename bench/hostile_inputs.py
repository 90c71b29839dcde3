#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""Hostile and clumsy inputs: does igac keep its promise on bad input?

bench/hostile_inputs.py [--igac PATH] [--timeout S] [--keep DIR] [--only SUBSTRING]

Generates case files, geometry files and command lines a new user could
produce, mutated from the shipped cases in cases/ (coarse meshes), runs
each with a timeout and classifies the outcome:

  OK   bad input: exit 2 and exactly one line `igac: error: ...` (warnings
       before it are one line each); a failed run: exit 1 with one error
       line or a summary.json whose status says it failed; a run that
       converged: exit 0, no nan/inf in any file written;
  BAD  anything else: a signal, exit 3 (internal error), another exit
       code, a hang over --timeout, text of an uncaught exception, a line
       on stderr that is not igac's, an input the case file promises to
       refuse that ran anyway, --out DIR left behind (or changed) by a run
       that did not converge, files other than DIR left beside it, nan/inf
       in an output.

Writes bench/results/hostile_inputs.csv (one row per input: id, group,
what, expected, exit code, seconds, verdict, reason, first line of the
output) and prints a summary line.  Exit status 0 when every input is OK.
Stdlib only.
"""

import argparse
import copy
import csv
import json
import math
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
IGAC = str(ROOT / "build" / "igac")
# Permissions do not stop root: those inputs are then only checked for crashes.
AS_ROOT = " (as root: permissions do not apply)" if os.geteuid() == 0 else ""
PERMS = "any" if AS_ROOT else "error"
RESULTS = ROOT / "bench" / "results"

# ---------------------------------------------------------------- TOML out
# bench/case_toml.py refuses non-finite numbers; hostile inputs want them.


def tv(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(tv(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {tv(x)}" for k, x in v.items()) + "}"
    raise TypeError(v)


def _table(d, prefix, out):
    for k, v in d.items():
        if not isinstance(v, dict) and not (isinstance(v, list) and v and all(isinstance(x, dict) for x in v)):
            out.append(f"{json.dumps(k) if not re.fullmatch(r'[A-Za-z0-9_-]+', k) else k} = {tv(v)}")
    for k, v in d.items():
        name = f"{prefix}.{k}" if prefix else k
        if isinstance(v, dict):
            out.append(f"\n[{name}]")
            _table(v, name, out)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for item in v:
                out.append(f"\n[[{name}]]")
                _table(item, name, out)


def toml_text(d):
    out = []
    _table(d, "", out)
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- base cases
def load(name):
    with open(ROOT / "cases" / name, "rb") as f:
        return tomllib.load(f)


def base(key):
    """The shipped case `key` on a coarse mesh (a fresh copy)."""
    if key == "h2":
        c = load("hertz2d.toml")
        c["mesh"]["elements"] = [16, 4]
    elif key == "h2f":
        c = load("hertz2d_from_file.toml")
        c["mesh"]["elements"] = [16, 4]
    elif key == "h2tp":
        c = load("hertz2d_two_patches.toml")
        c["mesh"]["elements"] = [8, 4]
    elif key == "h3":
        c = load("hertz3d.toml")
        c["mesh"]["elements"] = [4, 2, 4]
    elif key == "nh":
        c = load("hertz2d_neohookean_pressure.toml")
        c["mesh"]["elements"] = [16, 4]
        c["loading"]["steps"] = 4
    elif key == "oring":
        c = load("oring.toml")
        c["mesh"]["elements"] = [16, 8]
    elif key == "tb":
        c = load("two_blocks.toml")
    elif key == "lame":
        c = load("lame_cylinder.toml")
    elif key == "ib":
        c = load("indented_block.toml")
        c["mesh"]["elements"] = [4, 4, 2]
    else:
        raise KeyError(key)
    c.setdefault("output", {})["vtk"] = True
    return c


def geometry_file(key):
    return {"h2f": "quarter_disc.xml", "h2tp": "quarter_disc_two_patches.xml", "oring": "oring_quarter.xml",
            "tb": "two_blocks.xml", "ib": "indented_block.xml"}.get(key)


# ---------------------------------------------------------------- inputs
class Input:
    """One hostile input: files to write, the igac arguments, what to expect."""

    def __init__(self, group, what, expect="error", files=None, args=None, out="out", setup=None, kill_after=None):
        self.group = group
        self.what = what
        self.expect = expect  # "error": exit 2 required; "any": 0, 1 or 2 (checked for what each promises)
        self.files = files or {}  # name -> str | bytes
        self.args = args  # None: run case.toml --out out
        self.out = out  # the --out folder (relative to the run folder), None: none given
        self.setup = setup  # callable(run_dir) before the run
        self.kill_after = kill_after  # seconds, then SIGTERM


INPUTS = []


def add(*a, **k):
    INPUTS.append(Input(*a, **k))


def case_input(group, what, case, basekey=None, expect="error", extra=None, raw=None):
    files = {"case.toml": raw if raw is not None else toml_text(case)}
    g = geometry_file(basekey) if basekey else None
    if g and (extra is None or "geom.xml" not in extra):
        files[g] = (ROOT / "cases" / g).read_text()
    if extra:
        files.update(extra)
    add(group, what, expect=expect, files=files)


def mutated(basekey, fn):
    c = base(basekey)
    fn(c)
    return c


def leaves(d, path=()):
    """(path, value) of every leaf of a case dict; arrays of tables by index."""
    for k, v in d.items():
        p = path + (k,)
        if isinstance(v, dict):
            yield from leaves(v, p)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for i, x in enumerate(v):
                yield from leaves(x, p + (i,))
        else:
            yield p, v


def set_path(d, path, value):
    for k in path[:-1]:
        d = d[k]
    d[path[-1]] = value


def del_path(d, path):
    for k in path[:-1]:
        d = d[k]
    del d[path[-1]]


def pname(path):
    return ".".join(str(p) for p in path)


# Keys whose removal leaves a valid case (they have defaults).
OPTIONAL = {"name", "description", "refine", "toward", "model", "value", "vtk", "solution", "steps", "line_search",
            "pressure", "max_newton_iterations", "radius"}


def gen_case_keys():
    # every leaf of three bases: wrong types, missing
    for key in ["h2", "nh", "tb"]:
        for path, v in leaves(base(key)):
            last = path[-1]
            # wrong type: a table where a value belongs, a string where a number or array belongs
            wrong = {"type": {"x": 1}} if not isinstance(v, dict) else "x"
            c = base(key)
            set_path(c, path, {"a": 1})
            case_input("wrong_type", f"{key}: {pname(path)} = {{a = 1}}", c, key)
            c = base(key)
            if isinstance(v, str):
                set_path(c, path, 7)
                case_input("wrong_type", f"{key}: {pname(path)} = 7 (a number for a string)", c, key)
            elif isinstance(v, bool):
                set_path(c, path, "yes")
                case_input("wrong_type", f'{key}: {pname(path)} = "yes"', c, key)
            elif isinstance(v, (int, float)):
                set_path(c, path, "1.0")
                case_input("wrong_type", f'{key}: {pname(path)} = "1.0" (a string for a number)', c, key)
            elif isinstance(v, list):
                set_path(c, path, 1.0 if not (v and isinstance(v[0], str)) else "0:west,0:north")
                case_input("wrong_type", f"{key}: {pname(path)} is a scalar, not an array", c, key,
                           expect="any" if v and isinstance(v[0], str) else "error")
            # missing
            if key != "h2" or last in OPTIONAL:
                pass
            c = base(key)
            del_path(c, path)
            case_input("missing", f"{key}: no {pname(path)}", c, key,
                       expect="any" if last in OPTIONAL else "error")
    del wrong


def gen_numbers():
    numeric = [("mesh.degree", ("mesh", "degree")), ("mesh.refine", ("mesh", "refine")),
               ("material.E", ("material", "E")), ("material.nu", ("material", "nu")),
               ("pressure.value", ("pressure", 0, "value")), ("dirichlet.value", ("dirichlet", 0, "value")),
               ("geometry.radius", ("geometry", "radius")),
               ("grading.span_fraction", ("mesh", "grading", 0, "span_fraction")),
               ("grading.range_fraction", ("mesh", "grading", 0, "range_fraction")),
               ("obstacle.point[1]", ("contact", "obstacle", "point", 1)),
               ("obstacle.normal[1]", ("contact", "obstacle", "normal", 1))]
    specials = {"-1": -1.0, "0": 0.0, "1e300": 1e300, "nan": math.nan, "inf": math.inf, "-inf": -math.inf}
    for label, path in numeric:
        for sname, s in specials.items():
            c = base("h2")
            d = c
            for k in path[:-1]:
                d = d[k]
            old = d[path[-1]] if isinstance(d, list) else d.get(path[-1], 0.0)
            v = s
            if isinstance(old, int) and not isinstance(old, bool) and math.isfinite(s) and abs(s) < 1e18:
                v = int(s)
            d[path[-1]] = v
            expect = "error"
            if sname in ("-1", "0") and label in ("pressure.value", "dirichlet.value", "obstacle.point[1]",
                                                  "mesh.refine", "obstacle.normal[1]"):
                expect = "any"
            if sname == "1e300" and label in ("pressure.value", "dirichlet.value"):
                expect = "any"
            if label == "material.nu" and sname == "0":
                expect = "any"
            if label == "mesh.refine" and sname == "0":
                expect = "any"
            if label == "mesh.refine" and sname == "-1":
                expect = "error"
            case_input("number", f"h2: {label} = {sname}", c, "h2", expect=expect)


def gen_structure():
    # unknown keys
    for table in [None, "geometry", "mesh", "material", "contact", "contact.obstacle", "reference", "output"]:
        c = base("h2")
        d = c
        if table:
            for k in table.split("."):
                d = d[k]
        d["colour"] = "red"
        case_input("unknown_key", f"h2: [{table or 'top'}] colour = \"red\"", c, "h2")
    c = base("h2")
    c["Material"] = c.pop("material")
    case_input("unknown_key", "h2: [Material] (capitalised)", c, "h2")
    c = base("h2")
    c["mesh"]["elemets"] = c["mesh"].pop("elements")
    case_input("unknown_key", "h2: mesh.elemets (misspelled)", c, "h2")
    # empty tables
    for t in ["geometry", "mesh", "material", "contact", "reference", "output", "faces", "loading", "solver"]:
        key = "nh" if t == "loading" else ("h2f" if t == "faces" else "h2")
        c = base(key)
        c[t] = {}
        ok = t in ("reference", "output", "faces", "solver", "loading")
        case_input("empty_table", f"{key}: [{t}] empty", c, key, expect="any" if ok else "error")
    c = base("h2")
    c["contact"]["obstacle"] = {}
    case_input("empty_table", "h2: [contact.obstacle] empty", c, "h2")
    c = base("h2")
    c["mesh"]["grading"] = [{}]
    case_input("empty_table", "h2: [[mesh.grading]] empty", c, "h2")
    # the whole file empty / only comments / not TOML / binary / BOM / invalid UTF-8
    add("file", "case file empty", files={"case.toml": ""})
    add("file", "case file only a comment", files={"case.toml": "# nothing\n"})
    add("file", "case file is binary", files={"case.toml": bytes(range(256)) * 8})
    add("file", "case file with a UTF-8 BOM", expect="any",
        files={"case.toml": "\ufeff" + toml_text(base("h2"))})
    add("file", "case file with invalid UTF-8 in a string", files={
        "case.toml": toml_text(base("h2")).encode().replace(b'"hertz2d"', b'"hertz\xff\xfe2d"', 1)})
    add("file", "case file is JSON", files={"case.toml": json.dumps(base("h2"))})
    add("file", "case file unterminated string", files={"case.toml": 'name = "oops\n' + toml_text(base("h2"))})
    add("file", "case file: an array nested 100000 deep", files={"case.toml": "x = " + "[" * 100000 + "]" * 100000 + "\n"})
    add("file", "case file: an inline table nested 100000 deep",
        files={"case.toml": "x = " + "{a = " * 100000 + "1" + "}" * 100000 + "\n"})
    add("file", "case file: a dotted key 100000 parts long", files={"case.toml": "a" + ".a" * 100000 + " = 1\n"})
    add("file", "case file: integer beyond 64 bits", files={"case.toml": toml_text(base("h2")).replace(
        "degree = 2", "degree = 99999999999999999999999")})
    add("file", "case file: a 5 MB description", expect="any",
        files={"case.toml": toml_text(mutated("h2", lambda c: c.__setitem__("description", "x" * 5_000_000)))})
    add("file", "case file missing", args=["run", "nothere.toml"])
    add("file", "case file is a named pipe (FIFO) nobody writes", args=["run", "fifo.toml", "--out", "out"],
        setup=lambda d: os.mkfifo(d / "fifo.toml"))
    add("file", "case file a symlink loop", args=["run", "loop.toml", "--out", "out"],
        setup=lambda d: (os.symlink("loop2.toml", d / "loop.toml"), os.symlink("loop.toml", d / "loop2.toml")))
    add("file", "case file is a folder", args=["run", "adir"], setup=lambda d: (d / "adir").mkdir())
    add("file", "case file unreadable" + AS_ROOT, expect=PERMS, args=["run", "case.toml"], files={"case.toml": toml_text(base("h2"))},
        setup=lambda d: os.chmod(d / "case.toml", 0))
    # duplicated tables (raw text)
    text = toml_text(base("h2"))
    add("duplicate", "h2: [material] twice", files={"case.toml": text + "\n[material]\nE = 2.0\nnu = 0.3\n"})
    add("duplicate", "h2: [geometry] twice", files={"case.toml": text + "\n[geometry]\nshape = \"rectangle\"\n"})
    add("duplicate", "h2: key twice", files={"case.toml": text.replace("E = 1.0", "E = 1.0\nE = 2.0")})
    add("duplicate", "h2: [contact] then [[contact]]",
        files={"case.toml": text + "\n[[contact]]\nface = \"curved\"\n"})
    c = base("h2")
    c["contact"] = [c["contact"], copy.deepcopy(c["contact"])]
    case_input("duplicate", "h2: the same [[contact]] twice", c, "h2", expect="any")
    c = base("h2")
    c["mesh"]["grading"].append(copy.deepcopy(c["mesh"]["grading"][0]))
    case_input("duplicate", "h2: [[mesh.grading]] direction u twice", c, "h2")
    c = base("h2")
    c["dirichlet"].append(copy.deepcopy(c["dirichlet"][0]))
    case_input("duplicate", "h2: the same [[dirichlet]] twice", c, "h2", expect="any")
    c = base("h2")
    c["dirichlet"].append({"faces": ["left"], "component": "x", "value": 0.1})
    case_input("duplicate", "h2: left x fixed to 0 and to 0.1 (a warning: the last applies)", c, "h2", expect="any")
    # array lengths
    for label, path, v in [("mesh.elements = [16]", ("mesh", "elements"), [16]),
                           ("mesh.elements = [16, 4, 4]", ("mesh", "elements"), [16, 4, 4]),
                           ("mesh.elements = []", ("mesh", "elements"), []),
                           ("obstacle.point = [0]", ("contact", "obstacle", "point"), [0.0]),
                           ("obstacle.point = [0, -1, 0]", ("contact", "obstacle", "point"), [0.0, -1.0, 0.0]),
                           ("obstacle.normal = []", ("contact", "obstacle", "normal"), []),
                           ("obstacle.normal = [0, 0]", ("contact", "obstacle", "normal"), [0.0, 0.0]),
                           ("obstacle.motion = [0]", ("contact", "obstacle", "motion"), [0.0]),
                           ("dirichlet.faces = []", ("dirichlet", 0, "faces"), []),
                           ("pressure.faces = []", ("pressure", 0, "faces"), []),
                           ("mesh.elements = [[16], [4]]", ("mesh", "elements"), [[16], [4]]),
                           ("mesh.elements mixed types", ("mesh", "elements"), [16, "4"])]:
        c = base("h2")
        set_path(c, path, v)
        case_input("array_length", f"h2: {label}", c, "h2")
    c = base("h2")
    c["body_force"] = {"value": [0.0]}
    case_input("array_length", "h2: body_force.value = [0]", c, "h2")
    c = base("h2")
    c["body_force"] = {"value": [0.0, math.nan]}
    case_input("array_length", "h2: body_force.value = [0, nan]", c, "h2")
    c = base("h3")
    c["mesh"]["elements"] = [4, 2]
    case_input("array_length", "h3: mesh.elements with 2 entries in 3D", c, "h3")
    c = base("h3")
    c["contact"]["obstacle"]["normal"] = [0.0, 1.0]
    case_input("array_length", "h3: obstacle.normal with 2 entries in 3D", c, "h3")


def gen_faces():
    for face in ["nowhere", "", "0:west", "CURVED", "curved ", "u0", "u0 u1", "left,top"]:
        c = base("h2")
        c["contact"]["face"] = face
        case_input("face", f"h2: contact.face = {face!r}", c, "h2", expect="any" if face in ("u0",) else "error")
    for face in ["5:south", "0:middle", "0:", ":south", "-1:south", "0:front", "0:w1", "99999999999999999999:south",
                 "0:south:x", "0 : south"]:
        c = base("h2f")
        c["faces"]["contact"] = [face]
        case_input("face", f"h2f: contact face {face!r}", c, "h2f")
    # interface sides of the two-patch disc: 0:east joined to 1:west
    for what, fn in [("contact face", lambda c: c["faces"].__setitem__("contact", ["0:east"])),
                     ("pressure face", lambda c: c["faces"].__setitem__("loaded", ["1:west"])),
                     ("dirichlet face", lambda c: c["faces"].__setitem__("symmetry", ["0:east"]))]:
        c = base("h2tp")
        fn(c)
        case_input("face", f"h2tp: an interface side as the {what}", c, "h2tp")
    c = base("h2f")
    c["faces"]["contact"] = []
    case_input("face", "h2f: [faces] contact = []", c, "h2f")
    c = base("h2f")
    c["faces"]["contact"] = ["contact"]
    case_input("face", "h2f: [faces] contact names itself", c, "h2f")
    c = base("h2f")
    c["faces"]["loop_a"] = ["loop_b"]
    c["faces"]["loop_b"] = ["loop_a"]
    c["contact"]["face"] = "loop_a"
    case_input("face", "h2f: two [faces] sets naming each other", c, "h2f")
    c = base("h2")
    c["faces"] = {"curved": ["top"]}
    case_input("face", "h2: [faces] redefines a shape's face name", c, "h2", expect="any")
    c = base("h2f")
    c["faces"]["contact"] = "0:south"
    case_input("face", "h2f: [faces] set a string, not an array", c, "h2f", expect="any")
    c = base("h2f")
    c["faces"]["contact"] = ["0:south", "0:south"]
    case_input("face", "h2f: a face listed twice in a set", c, "h2f")
    c = base("h2")
    c["pressure"][0]["faces"] = ["top", "top"]
    case_input("face", "h2: pressure faces = [top, top]", c, "h2")
    c = base("h2f")
    c["faces"]["loaded"] = ["0:east"]
    c["pressure"][0]["faces"] = ["loaded", "0:east"]
    case_input("face", "h2f: pressure on a set and on a side it holds", c, "h2f")
    c = base("h2")
    c["contact"]["face"] = "top"
    c["pressure"][0]["faces"] = ["curved"]
    case_input("face", "h2: contact on the loaded face and load on the contact face", c, "h2", expect="any")
    c = base("h2")
    c["dirichlet"][0]["component"] = "z"
    case_input("face", "h2: dirichlet component z in 2D", c, "h2")
    c = base("h2")
    c["dirichlet"][0]["component"] = "X"
    case_input("face", "h2: dirichlet component X", c, "h2")


def gen_contact():
    c = base("tb")
    c["contact"][0]["obstacle"] = {"type": "plane", "point": [0.0, 1.0], "normal": [0.0, 1.0]}
    case_input("contact", "tb: contact with both obstacle and master", c, "tb")
    c = base("tb")
    del c["contact"][0]["master"]
    case_input("contact", "tb: contact with neither obstacle nor master", c, "tb")
    for m, what in [("1:south", "the slave face itself"), ("1:north", "a face of the slave's own body"),
                    ("0:south", "a fixed face of the master body"), ("nowhere", "a face that does not exist"),
                    ("2:north", "a patch that does not exist"), ("", "empty")]:
        c = base("tb")
        c["contact"][0]["master"] = m
        case_input("contact", f"tb: master = {m!r} ({what})", c, "tb", expect="error" if m not in ("0:south",) else "any")
    c = base("tb")
    c["contact"][0]["master"] = ["0:north"]
    case_input("contact", "tb: master is an array", c, "tb")
    c = base("h2tp")
    c["contact"]["master"] = "1:west"
    del c["contact"]["obstacle"]
    case_input("contact", "h2tp: master = an interface side (one body)", c, "h2tp")
    c = base("h2")
    c["contact"]["master"] = "top"
    del c["contact"]["obstacle"]
    case_input("contact", "h2: master on a one-body shape", c, "h2")
    c = base("tb")
    c["material"] = {"model": "neo_hookean", "E": 1.0, "nu": 0.3}
    c["loading"] = {"steps": 2}
    case_input("contact", "tb: master with a hyperelastic law (two bodies in large deformation: it runs)", c, "tb",
               expect="any")
    c = base("tb")
    c["contact"].append(copy.deepcopy(c["contact"][0]))
    case_input("contact", "tb: the same master contact twice", c, "tb")
    c = base("h2")
    c.pop("reference")
    c["contact"] = [c["contact"], copy.deepcopy(c["contact"])]
    case_input("contact", "h2 (no reference): the same obstacle contact twice", c, "h2")
    c = base("h2")
    c.pop("reference")
    c["contact"] = [c["contact"], copy.deepcopy(c["contact"])]
    c["contact"][1]["obstacle"]["point"] = [0.0, -1.001]
    case_input("contact", "h2 (no reference): one face on two parallel planes", c, "h2", expect="any")
    for t in ["cone", "", "PLANE", "cylinder"]:
        c = base("h2")
        c["contact"]["obstacle"]["type"] = t
        case_input("contact", f"h2: obstacle.type = {t!r}", c, "h2")
    c = base("h2")
    c["contact"]["obstacle"] = {"type": "sphere", "centre": [0.0, 0.0], "radius": 0.5}
    case_input("contact", "h2: sphere obstacle inside the body", c, "h2", expect="any")
    c = base("h2")
    c["contact"]["obstacle"] = {"type": "sphere", "centre": [0.0, -2.0], "radius": 0.0}
    case_input("contact", "h2: sphere obstacle radius 0", c, "h2")
    c = base("h2")
    c["contact"]["obstacle"]["motion"] = [0.0, 1e300]
    case_input("contact", "h2: obstacle motion 1e300", c, "h2", expect="any")
    c = base("h2")
    c["contact"]["obstacle"]["motion"] = [0.0, 0.5]
    case_input("contact", "h2: obstacle moved half a radius into the body (linear)", c, "h2", expect="any")
    c = base("h2")
    c["contact"]["obstacle"]["normal"] = [1e-300, 1e-300]
    case_input("contact", "h2: obstacle normal [1e-300, 1e-300]", c, "h2", expect="any")
    for p in [1, 0]:
        c = base("h2")
        c["mesh"]["degree"] = p
        case_input("contact", f"h2: degree {p} with contact", c, "h2")
    c = base("h2f")
    c["mesh"]["degree"] = 1
    case_input("contact", "h2f: degree 1 with contact (quadratic file)", c, "h2f")
    c = base("tb")
    c["mesh"]["degree"] = 1
    case_input("contact", "tb: degree 1 with a master contact", c, "tb")


def gen_mesh():
    for el in [[0, 4], [16, 0], [-1, 4], [2.5, 4], [10**7, 4], [10**6, 10**6], [2**31, 4], [2**63 - 1, 4]]:
        c = base("h2")
        c["mesh"]["elements"] = el
        case_input("mesh", f"h2: elements = {el}", c, "h2")
    for d in [11, 100, -3, 2.0, 2.5]:
        c = base("h2")
        c["mesh"]["degree"] = d
        case_input("mesh", f"h2: degree = {d}", c, "h2")
    for r in [40, 2**31]:
        c = base("h2")
        c["mesh"]["refine"] = r
        case_input("mesh", f"h2: refine = {r}", c, "h2")
    for span, rng in [(0.0, 0.1), (1.0, 0.1), (0.8, 0.0), (0.8, 1.0), (0.999999, 1e-12), (1e-12, 0.999999)]:
        c = base("h2")
        c["mesh"]["grading"][0]["span_fraction"] = span
        c["mesh"]["grading"][0]["range_fraction"] = rng
        case_input("grading", f"h2: span_fraction {span}, range_fraction {rng}", c, "h2",
                   expect="error" if span in (0.0, 1.0) or rng in (0.0, 1.0) else "any")
    for d in ["w", "x", "", "U"]:
        c = base("h2")
        c["mesh"]["grading"][0]["direction"] = d
        case_input("grading", f"h2: grading direction {d!r}", c, "h2")
    c = base("h2")
    c["mesh"]["grading"][0]["toward"] = "middle"
    case_input("grading", "h2: grading toward middle", c, "h2")
    c = base("h2")
    c["mesh"]["grading"][0]["coarse"] = "random"
    case_input("grading", "h2: grading coarse random", c, "h2")
    c = base("h2")
    c["mesh"]["elements"] = [1, 4]
    case_input("grading", "h2: grading u with 1 span", c, "h2")
    c = base("h2")
    c["mesh"]["grading"][0]["coarse"] = "geometric"
    c["mesh"]["grading"][0]["span_fraction"] = 0.01
    c["mesh"]["grading"][0]["range_fraction"] = 0.99
    case_input("grading", "h2: geometric coarse spans, fine spans cover 99 %", c, "h2", expect="any")


def gen_material_loading():
    for k, v in [("model", "steel"), ("model", "Linear_Elastic"), ("nu", 0.5), ("nu", -1.0), ("nu", 0.4999999999),
                 ("E", 1e101), ("E", 1e-101)]:
        c = base("h2")
        c["material"][k] = v
        case_input("material", f"h2: material.{k} = {v!r}", c, "h2", expect="any" if v == 0.4999999999 else "error")
    c = base("h2")
    c["material"]["nu"] = 0.0
    case_input("material", "h2: material.nu = 0 (valid)", c, "h2", expect="any")
    c = base("oring")
    c["material"]["C10"] = -0.11
    case_input("material", "oring: C10 = -C01", c, "oring")
    c = base("oring")
    c["material"]["E"] = 1.0
    case_input("material", "oring: E given to mooney_rivlin", c, "oring")
    for k, v in [("steps", 0), ("steps", 10**6), ("first_increment", 0.0), ("first_increment", 2.0),
                 ("min_increment", 0.5), ("max_increment", 1e-9), ("max_newton_iterations", 0),
                 ("line_search", "yes"), ("predictor", "secant"), ("pressure", "floating"), ("min_increment", math.nan)]:
        c = base("nh")
        c["loading"][k] = v
        case_input("loading", f"nh: loading.{k} = {v!r}", c, "nh",
                   expect="any" if (k, v) in (("min_increment", 0.5),) else "error")
    c = base("h2")
    c["loading"] = {"steps": 5}
    case_input("loading", "h2: [loading] with linear_elastic (small-deformation load steps: it runs)", c, "h2",
               expect="any")
    c = base("nh")
    c["pressure"][0]["value"] = 100.0
    case_input("loading", "nh: follower pressure 1000x (the body collapses)", c, "nh", expect="any")
    c = base("nh")
    c["loading"]["min_increment"] = 0.5
    c["loading"]["max_increment"] = 0.5
    c["pressure"][0]["value"] = 10.0
    case_input("loading", "nh: pressure 100x with no room to cut back", c, "nh", expect="any")
    for s, ref in [("lame", "h2"), ("hertz", "lame"), ("exact", "h2")]:
        c = base(ref)
        c["reference"] = {"solution": s}
        case_input("reference", f"{ref}: reference.solution = {s}", c, ref)
    c = base("h2")
    c["contact"] = [c["contact"], {"face": "top", "obstacle": {"type": "plane", "point": [0.0, 0.5],
                                                                 "normal": [0.0, -1.0]}}]
    case_input("reference", "h2: hertz reference with two contacts", c, "h2")
    for k, v in [("type", "gpu"), ("options", "-ksp_type cg"), ("preconditioner", "spline_multigrid"),
                 ("type", "petsc")]:
        c = base("h2")
        c["solver"] = {k: v}
        case_input("solver", f"h2: solver.{k} = {v!r}", c, "h2", expect="any" if v == "petsc" else "error")
    c = base("h2")
    c["solver"] = {"type": "petsc", "options": "-log_view :/tmp/x"}
    case_input("solver", "h2: petsc option that writes a file", c, "h2")
    for n in ["a/b", "", ".", "..", "x" * 300, "naïve ☃", "tab\tname", "new\nline", "-rf"]:
        c = base("h2")
        c["name"] = n
        short = n if len(n) < 20 else n[:10] + "..."
        add("name", f"h2: name = {short!r} (default --out)", files={"case.toml": toml_text(c)}, out=None,
            expect="error" if n in ("a/b", "", ".", "..", "new\nline") or len(n) > 255 else "any")
    c = base("h2")
    c["description"] = "line one\nline two"
    case_input("name", "h2: description over two lines", c, "h2", expect="any")


# ---------------------------------------------------------------- newer keys
# Keys added after the three cases above were mutated key by key: part of a
# side, the edge obstacle, a fluid's entry, the 2D model kinds, the shape
# transforms, interference.
def part_of_a_side(rng):
    c = base("oring")
    c["faces"]["band"] = {"side": "0:south", "range": rng}
    c["contact"]["face"] = "band"
    return c


for what, rng in [("outside [0, 1]", [0.5, 1.5]), ("reversed", [0.8, 0.2]), ("of zero width", [0.5, 0.5]),
                  ("two pairs in 2D", [[0.0, 0.5], [0.0, 1.0]]), ("nan", [float("nan"), 0.5]),
                  ("one number", [0.5])]:
    case_input("newer", f"oring: part of a side, range {what}", part_of_a_side(rng), "oring")
case_input("newer", "oring: part of a side, range [0, 0.6] (valid: it runs)", part_of_a_side([0.0, 0.6]), "oring",
           expect="any")
c = base("oring")
c["faces"]["band"] = {"side": "0:nowhere", "range": [0.0, 0.5]}
case_input("newer", "oring: part of a side that does not exist", c, "oring")
c = base("oring")
c["faces"]["band"] = {"range": [0.0, 0.5]}
case_input("newer", "oring: part of a side without its side", c, "oring")


def edge_obstacle(**changes):
    c = base("oring")
    c["contact"]["obstacle"] = {"type": "edge", "point": [2.0, -2.665], "normal": [0.0, 1.0],
                                "second_normal": [1.0, 0.0], "radius": 0.2, "motion": [0.0, 0.66625]}
    for k, v in changes.items():
        if v is None:
            c["contact"]["obstacle"].pop(k)
        else:
            c["contact"]["obstacle"][k] = v
    return c


for what, changes in [("parallel normals", {"second_normal": [0.0, 2.0]}), ("radius 0", {"radius": 0.0}),
                      ("radius -1", {"radius": -1.0}), ("no second_normal", {"second_normal": None}),
                      ("second_normal of 3 entries in 2D", {"second_normal": [1.0, 0.0, 0.0]}),
                      ("normal zero", {"normal": [0.0, 0.0]}), ("radius inf", {"radius": float("inf")})]:
    case_input("newer", f"oring: edge obstacle, {what}", edge_obstacle(**changes), "oring")
case_input("newer", "oring: edge obstacle (valid: it runs)", edge_obstacle(), "oring", expect="any")


def fluid(entry):
    c = base("oring")
    c["pressure"] = [{"faces": ["0:south"], "value": 0.1, "fluid_entry": entry}]
    return c


for what, entry in [("3 coordinates in 2D", [0.0, -2.665, 0.0]), ("nan", [float("nan"), 0.0]),
                    ("a string", "left")]:
    case_input("newer", f"oring: fluid_entry {what}", fluid(entry), "oring")
for what, kind in [("misspelt", "axisymmetrical"), ("a number", 3), ("empty", "")]:
    c = base("oring")
    c["model"] = {"kind": kind}
    case_input("newer", f"oring: [model] kind {what}", c, "oring")
c = base("h3")
c["model"] = {"kind": "plane_stress"}
case_input("newer", "h3: plane stress in 3D", c, "h3")
c = base("oring")
c["model"] = {"kind": "axisymmetric"}
c["geometry"]["translate"] = [-1.0, 0.0]
case_input("newer", "oring: axisymmetric body across the axis", c, "oring")
for what, key, value in [("scale 0", "scale", 0.0), ("scale -2", "scale", -2.0), ("scale nan", "scale", float("nan")),
                         ("rotate of 3 angles in 2D", "rotate", [1.0, 2.0, 3.0]), ("mirror \"q\"", "mirror", "q"),
                         ("mirror \"z\" in 2D", "mirror", "z"), ("translate of 3 in 2D", "translate", [0.0, 0.0, 1.0])]:
    c = base("oring")
    c["geometry"][key] = value
    case_input("newer", f"oring: geometry {what}", c, "oring")
c = base("oring")
c["contact"]["interference"] = "yes"
case_input("newer", "oring: interference = \"yes\"", c, "oring")


# ---------------------------------------------------------------- geometry files
QD = (ROOT / "cases" / "quarter_disc.xml").read_text()
TP = (ROOT / "cases" / "quarter_disc_two_patches.xml").read_text()


def geom_input(what, xml, expect="error", basekey="h2f", fn=None):
    c = base(basekey)
    c["geometry"]["file"] = "geom.xml"
    if fn:
        fn(c)
    case_input("geometry", what, c, basekey, expect=expect, extra={"geom.xml": xml})


def ring_xml(closed=True):
    s = math.sqrt(0.5)
    pts = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
    w = [1, s, 1, s, 1, s, 1, s, 1]
    rows = []
    for r in (1.0, 2.0):
        for (x, y) in pts:
            rows.append(f"{r * x} {r * y}")
    if not closed:  # the last column of control points lifted by 0.01: the seam no longer closes
        rows = [r if k % 9 != 8 else f"{float(r.split()[0])} 0.01" for k, r in enumerate(rows)]
    return f"""<?xml version="1.0"?>
<xml>
 <Geometry type="TensorNurbs2" id="0">
  <Basis type="TensorNurbsBasis2">
   <Basis type="TensorBSplineBasis2">
    <Basis type="BSplineBasis" index="0"><KnotVector degree="2">0 0 0 0.25 0.25 0.5 0.5 0.75 0.75 1 1 1</KnotVector></Basis>
    <Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>
   </Basis>
   <weights>{' '.join(str(x) for x in w * 2)}</weights>
  </Basis>
  <coefs geoDim="2">
{chr(10).join(rows)}
</coefs>
 </Geometry>
</xml>
"""


def ring_case(c):
    c["faces"] = {"inner": ["0:south"], "outer": ["0:north"]}
    c["mesh"]["elements"] = [16, 2]
    c["mesh"].pop("grading", None)
    c["dirichlet"] = [{"faces": ["inner"], "component": "x"}, {"faces": ["inner"], "component": "y"}]
    c["pressure"] = [{"faces": ["outer"], "value": 0.01}]
    c.pop("contact", None)
    c.pop("reference", None)


def coefs_block(xml):
    m = re.search(r"(<coefs[^>]*>)(.*?)(</coefs>)", xml, re.S)
    return m


def map_coefs(xml, fn):
    m = coefs_block(xml)
    rows = [r.split() for r in m.group(2).strip().splitlines()]
    rows = fn(rows)
    return xml[:m.start(2)] + "\n" + "\n".join(" ".join(r) for r in rows) + "\n" + xml[m.end(2):]


def gen_geometry():
    geom_input("geometry file empty", "")
    geom_input("geometry file truncated at half", QD[: len(QD) // 2])
    geom_input("geometry file truncated inside <coefs>", QD[: QD.index("0.6 -0.6")])
    geom_input("geometry file binary", bytes(range(256)) * 20)
    geom_input("geometry file is the case file", toml_text(base("h2")))
    geom_input("geometry file of whitespace", "   \n\n  ")
    geom_input("geometry <xml> with no <Geometry>", "<?xml version=\"1.0\"?>\n<xml>\n</xml>\n")
    c = base("h2f")
    c["geometry"]["file"] = "missing.xml"
    case_input("geometry", "geometry file missing", c, "h2f")
    c = base("h2f")
    c["geometry"]["file"] = "."
    case_input("geometry", "geometry file is a folder", c, "h2f")
    c = base("h2f")
    c["geometry"]["file"] = "/dev/zero"
    case_input("geometry", "geometry file /dev/zero (endless)", c, "h2f")
    c = base("h2f")
    c["geometry"]["file"] = "fifo.xml"
    add("geometry", "geometry file is a named pipe (FIFO) nobody writes",
        files={"case.toml": toml_text(c)}, setup=lambda d: os.mkfifo(d / "fifo.xml"))
    c = base("h2f")
    c["geometry"]["shape"] = "quarter_disc"
    case_input("geometry", "geometry with both shape and file", c, "h2f")
    lol = '<!ENTITY lol "lol">' + "".join(
        f'<!ENTITY lol{k} "{("&lol" + (str(k - 1) if k > 1 else "") + ";") * 10}">' for k in range(1, 10))
    geom_input("billion laughs (entities nested 9 deep)", '<?xml version="1.0"?>\n<!DOCTYPE lolz [' + lol + ']>\n'
               + QD.split("?>", 1)[1].replace("<xml>", "<xml>&lol9;", 1), expect="any")
    geom_input("entity expansion (1000 characters)", expect="any", xml= '<?xml version="1.0"?>\n<!DOCTYPE lolz [<!ENTITY lol "lol">'
               '<!ENTITY lol2 "&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;&lol;">'
               '<!ENTITY lol3 "&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;&lol2;">]>\n'
               + QD.split("?>", 1)[1].replace("<xml>", "<xml>&lol3;", 1))
    geom_input("XML elements nested 200000 deep", QD.replace("<xml>", "<xml>" + "<a>" * 200000 + "</a>" * 200000, 1),
               expect="any")
    geom_input("XML attribute 10 MB long", QD.replace('id="0"', 'id="0" junk="' + "j" * 10_000_000 + '"', 1),
               expect="any")
    grid = []
    n = 40
    for i in range(n):
        for j in range(n):
            x0, y0, h = i / n, j / n, 1 / n
            grid.append(f'<Geometry type="TensorBSpline2" id="{i * n + j}"><Basis type="TensorBSplineBasis2">'
                        '<Basis type="BSplineBasis" index="0"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>'
                        '<Basis type="BSplineBasis" index="1"><KnotVector degree="1">0 0 1 1</KnotVector></Basis>'
                        f'</Basis><coefs geoDim="2">{x0} {y0}\n{x0 + h} {y0}\n{x0} {y0 + h}\n{x0 + h} {y0 + h}</coefs></Geometry>')
    geom_input(f"{n * n} <Geometry> squares, no <MultiPatch> (all joined by igac)", "<xml>\n" + "\n".join(grid) + "\n</xml>\n",
               expect="any", fn=lambda c: (c.pop("contact"), c.pop("reference"), c["mesh"].pop("grading"),
                                          c["mesh"].__setitem__("elements", [1, 1]),
                                          c.__setitem__("faces", {"symmetry": ["0:west"], "loaded": ["0:south"]}),
                                          c["dirichlet"].append({"faces": ["0:south"], "component": "y"})))
    geom_input("file degree 0", QD.replace('degree="2"', 'degree="0"', 1))
    IB3 = (ROOT / "cases" / "indented_block.xml").read_text()
    geom_input("3D file for a 2D case", IB3)
    # knots
    geom_input("huge knot count (200000 interior knots)",
               QD.replace('<KnotVector degree="2">0 0 0 1 1 1</KnotVector>',
                          '<KnotVector degree="2">0 0 0 ' + " ".join(f"{i / 200001:.9f}" for i in range(1, 200001))
                          + ' 1 1 1</KnotVector>', 1))
    geom_input("decreasing knots", QD.replace("0 0 0 1 1 1", "0 0 0 0.7 0.3 1 1 1", 1))
    geom_input("knots all equal", QD.replace("0 0 0 1 1 1", "1 1 1 1 1 1", 1))
    geom_input("knot nan", QD.replace("0 0 0 1 1 1", "0 0 0 nan 1 1 1", 1))
    geom_input("knot text", QD.replace("0 0 0 1 1 1", "0 0 0 half 1 1 1", 1))
    geom_input("knot 1e400", QD.replace("0 0 0 1 1 1", "0 0 0 1e400 1e400 1e400", 1))
    geom_input("degree -1", QD.replace('degree="2"', 'degree="-1"', 1))
    geom_input("degree 99", QD.replace('degree="2"', 'degree="99"', 1))
    geom_input("degree missing", QD.replace(' degree="2"', '', 1))
    geom_input("degree 2x", QD.replace('degree="2"', 'degree="2x"', 1))
    geom_input("degree 99999999999", QD.replace('degree="2"', 'degree="99999999999"', 1))
    # weights
    geom_input("negative weight", QD.replace("0.7071067811865476", "-0.7071067811865476"))
    geom_input("weight nan", QD.replace("0.7071067811865476", "nan"))
    geom_input("weight 1e308", QD.replace("0.7071067811865476", "1e308"), expect="any")
    geom_input("too few weights", QD.replace("<weights>1 0.7071067811865476 1 1 1 1 1 1 1", "<weights>1 1 1"))
    geom_input("too many weights", QD.replace("<weights>1 0.7071067811865476 1 1 1 1 1 1 1",
                                              "<weights>1 0.7071067811865476 1 1 1 1 1 1 1 1 1"))
    # coordinates
    geom_input("NaN coordinate", QD.replace("0.6 -0.6", "nan -0.6"))
    geom_input("inf coordinate", QD.replace("0.6 -0.6", "inf -0.6"))
    geom_input("coordinate 1e200", QD.replace("0.6 -0.6", "1e200 -0.6"))
    geom_input("all control points equal", map_coefs(QD, lambda rows: [["0.5", "0.5"] for _ in rows]))
    geom_input("a row with 3 numbers", QD.replace("0.6 -0.6", "0.6 -0.6 0.0"))
    geom_input("one control point too few", map_coefs(QD, lambda rows: rows[:-1]))
    geom_input("one control point too many", map_coefs(QD, lambda rows: rows + [["0", "0"]]))
    geom_input("geoDim 3 for a 2D body", QD.replace('geoDim="2"', 'geoDim="3"'))
    geom_input("geoDim 0", QD.replace('geoDim="2"', 'geoDim="0"'))
    geom_input("geoDim -2", QD.replace('geoDim="2"', 'geoDim="-2"'))
    geom_input("type TensorNurbs4", QD.replace('type="TensorNurbs2"', 'type="TensorNurbs4"', 1))
    geom_input("type missing", QD.replace(' type="TensorNurbs2"', '', 1))
    geom_input("coordinate 1,5 (decimal comma)", QD.replace("0.6 -0.6", "0,6 -0,6"))
    # folded, left-handed, collapsed
    geom_input("folded patch (interior control point pushed outside)", QD.replace("0.6 -0.6", "-0.9 0.9"))
    geom_input("self-intersecting patch (two rows swapped)",
               map_coefs(QD, lambda rows: rows[3:6] + rows[0:3] + rows[6:]))
    geom_input("left-handed patch (u reversed)", map_coefs(
        QD, lambda rows: [r for k in range(3) for r in rows[3 * k:3 * k + 3][::-1]]).replace(
        "1 0.7071067811865476 1", "1 0.7071067811865476 1", 1), expect="any",
        fn=lambda c: c["faces"].update({"symmetry": ["0:east", "0:north"], "loaded": ["0:west"]}))
    geom_input("collapsed patch (v = 1 and v = 0 the same)", map_coefs(QD, lambda rows: rows[:3] + rows[:3] + rows[:3]))
    geom_input("closed ring (seam joined)", ring_xml(True), expect="any", fn=ring_case)
    geom_input("ring open by 0.01 (not a seam)", ring_xml(False), expect="any", fn=ring_case)
    # several patches
    g0 = re.search(r"<Geometry.*?</Geometry>", TP, re.S).group(0)
    geoms = re.findall(r"<Geometry.*?</Geometry>", TP, re.S)
    geom_input("two <Geometry>, no <MultiPatch>", "<xml>\n" + "\n".join(geoms) + "\n</xml>\n", expect="any",
               basekey="h2tp")
    geom_input("two <Geometry> with the same id", "<xml>\n" + geoms[0] + "\n" + geoms[1].replace('id="1"', 'id="0"')
               + "\n</xml>\n", expect="any", basekey="h2tp")
    geom_input("the same <Geometry> twice, no <MultiPatch> (overlapping bodies)",
               "<xml>\n" + g0 + "\n" + g0.replace('id="0"', 'id="1"') + "\n</xml>\n", basekey="h2tp")
    geom_input("<MultiPatch> names a patch that does not exist",
               TP.replace('<patches type="id_range">0 1</patches>', '<patches type="id_range">0 2</patches>'),
               basekey="h2tp")
    geom_input("<MultiPatch> id_range backwards",
               TP.replace('<patches type="id_range">0 1</patches>', '<patches type="id_range">1 0</patches>'),
               basekey="h2tp")
    geom_input("<MultiPatch> patches type unknown",
               TP.replace('<patches type="id_range">', '<patches type="id_list">'), basekey="h2tp")
    geom_input("two <MultiPatch>", TP.replace("</xml>", re.search(r"<MultiPatch.*?</MultiPatch>", TP, re.S).group(0)
                                              + "\n</xml>"), basekey="h2tp")
    geom_input("<MultiPatch> without <interfaces>", re.sub(r"<interfaces>.*?</interfaces>", "", TP, flags=re.S),
               expect="any", basekey="h2tp")
    for form, what, exp in [("0 2 1 1 1", "old 5-number form", "any"), ("0 2 1 1", "4 numbers", "any"),
                            ("0 2 1", "3 numbers", "error"), ("0 2 1 1 0 1 1", "7 numbers", "error"),
                            ("0 2 1 1 0 1 1 1 0", "9 numbers", "error"), ("0 2 7 1 0 1 1 1", "patch 7", "error"),
                            ("0 9 1 1 0 1 1 1", "side 9", "error"), ("0 2 0 1 0 1 1 1", "a patch to itself", "error"),
                            ("0 2 1 2 0 1 1 1", "sides that do not coincide", "error"),
                            ("a b c d e", "words", "error"), ("0 2 1 1 0 1 1 1\n0 2 1 1 0 1 1 1", "twice", "any"),
                            ("-1 2 1 1 0 1 1 1", "patch -1", "error"), ("0 2.5 1 1 0 1 1 1", "side 2.5", "error")]:
        geom_input(f"interface {what}: {form!r}",
                   re.sub(r"<interfaces>.*?</interfaces>", f"<interfaces>\n{form}\n</interfaces>", TP, flags=re.S),
                   expect=exp, basekey="h2tp")
    geom_input("boundary lists the interface side", TP.replace("<boundary>\n", "<boundary>\n0 2\n", 1),
               expect="any", basekey="h2tp")
    geom_input("boundary side 9", TP.replace("<boundary>\n", "<boundary>\n0 9\n", 1), basekey="h2tp")
    geom_input("patches of different types (Nurbs and BSpline)",
               TP.replace('type="TensorNurbs2" id="1"', 'type="TensorBSpline2" id="1"'), basekey="h2tp")
    # 3D
    IB = (ROOT / "cases" / "indented_block.xml").read_text()
    geom_input("3D: interface in the old 6-number form",
               re.sub(r"<interfaces>\s*(\S+ \S+ \S+ \S+).*?</interfaces>", r"<interfaces>\n\1 1 1\n</interfaces>",
                      IB, flags=re.S), expect="any", basekey="ib")
    geom_input("3D: NaN coordinate", map_coefs(IB, lambda rows: [["nan"] + rows[0][1:]] + rows[1:]), basekey="ib")
    geom_input("3D: 2D patch for a 3D case", QD, basekey="ib")
    geom_input("3D: folded patch (first and last control points swapped)",
               map_coefs(IB, lambda rows: [rows[-1]] + rows[1:-1] + [rows[0]]), basekey="ib")
    c = base("h3")
    c["mesh"]["elements"] = [2000, 2000, 2000]
    case_input("mesh", "h3: elements [2000, 2000, 2000] (memory guard)", c, "h3")


# ---------------------------------------------------------------- command line, --out, signals
def gen_cli():
    h2 = toml_text(base("h2"))
    f = {"case.toml": h2}
    add("out", "--out is a file", files=dict(f, results="keep me\n"), out="results")
    add("out", "--out in a read-only folder" + AS_ROOT, expect=PERMS, files=dict(f), out="ro/out",
        setup=lambda d: ((d / "ro").mkdir(), os.chmod(d / "ro", 0o555)))
    add("out", "--out is a read-only folder of an earlier run" + AS_ROOT, expect=PERMS, files=dict(f), out="ro2",
        setup=lambda d: ((d / "ro2").mkdir(), (d / "ro2" / "summary.json").write_text("{}\n"),
                         os.chmod(d / "ro2", 0o555)))
    add("out", "--out a folder of someone else's files", files=dict(f), out="home",
        setup=lambda d: ((d / "home").mkdir(), (d / "home" / "thesis.tex").write_text("precious\n")))
    add("out", "--out ''", files=dict(f), args=["run", "case.toml", "--out", ""])
    add("out", "--out /", files=dict(f), args=["run", "case.toml", "--out", "/"])
    add("out", "--out .", files=dict(f), args=["run", "case.toml", "--out", "."])
    add("out", "--out under a file", files=dict(f, afile="x"), out="afile/out")
    add("out", "--out a symlink to /etc", files=dict(f), out="link",
        setup=lambda d: os.symlink("/etc", d / "link"))
    add("out", "--out a dangling symlink", files=dict(f), out="dangling",
        setup=lambda d: os.symlink(d / "nowhere", d / "dangling"))
    add("out", "--out is the case file", files=dict(f), out="case.toml")
    earlier = lambda d: ((d / "earlier.toml").write_text(toml_text(base("h2"))),
                         subprocess.run([IGAC, "run", "earlier.toml", "--quiet", "--out", "out"], cwd=d, check=True))
    add("out", "bad input over an earlier output", files={"case.toml": h2.replace("E = 1.0", "E = -1.0")},
        setup=earlier)
    add("out", "a failed run over an earlier output", expect="any",
        files={"case.toml": toml_text(mutated("nh", lambda c: (c["pressure"][0].__setitem__("value", 10.0),
                                                               c["loading"].__setitem__("min_increment", 0.5))))},
        setup=earlier)
    add("cli", "no arguments", args=[])
    add("cli", "unknown subcommand", args=["solve", "case.toml"], files=dict(f))
    add("cli", "run without a case", args=["run"])
    add("cli", "unknown option", args=["run", "case.toml", "--fast"], files=dict(f))
    for opt, v, exp in [("--refine", "-1", "error"), ("--refine", "x", "error"), ("--refine", "40", "error"),
                        ("--refine", "99999999999", "error"), ("--degree", "0", "error"), ("--degree", "1", "error"),
                        ("--degree", "11", "error"), ("--degree", "2.5", "error"), ("--solver", "gpu", "error"),
                        ("--preconditioner", "magic", "error"), ("--petsc-options", "-ksp_type cg", "error"),
                        ("--out", None, "error")]:
        args = ["run", "case.toml", "--out", "out", opt] + ([v] if v is not None else [])
        add("cli", f"{opt} {v}", args=args, files=dict(f), expect=exp)
    add("cli", "case given twice", args=["run", "case.toml", "case.toml", "--out", "out"], files=dict(f))
    add("cli", "study of a case with an unknown key", args=["study", "case.toml", "--levels", "2", "--out", "out"],
        files={"case.toml": h2 + "\ncolour = 1\n"})
    add("cli", "study --levels 2 of a case whose level 1 is refused (elements 600000)",
        args=["study", "case.toml", "--levels", "2", "--out", "out"],
        files={"case.toml": toml_text(mutated("h2", lambda c: c["mesh"].__setitem__("elements", [600000, 4])))})
    add("cli", "study --levels 2 (fine)", expect="any", args=["study", "case.toml", "--levels", "2", "--out", "out"],
        files=dict(f))
    add("cli", "study --levels 0", args=["study", "case.toml", "--levels", "0", "--out", "out"], files=dict(f))
    add("cli", "study --levels -2", args=["study", "case.toml", "--levels", "-2", "--out", "out"], files=dict(f))
    add("cli", "study --levels 40", args=["study", "case.toml", "--levels", "40", "--out", "out"], files=dict(f))
    add("cli", "geometry --out onto the case file", args=["geometry", "case.toml", "--out", "case.toml"],
        files=dict(f), out="case.toml")
    add("cli", "geometry --out into a missing folder", args=["geometry", "case.toml", "--out", "no/such/x.xml"],
        files=dict(f), out="no")
    add("cli", "geometry of a broken case", args=["geometry", "case.toml", "--out", "g.xml"],
        files={"case.toml": h2.replace("quarter_disc", "half_disc")}, out="g.xml")
    add("cli", "geometry --out a folder", args=["geometry", "case.toml", "--out", "adir"], files=dict(f),
        out="adir", setup=lambda d: (d / "adir").mkdir())
    # signals
    big = base("nh")
    big["mesh"]["elements"] = [128, 32]
    big["loading"]["steps"] = 40
    add("signal", "SIGTERM 1.5 s into a run, fresh --out", files={"case.toml": toml_text(big)}, kill_after=1.5,
        expect="killed")
    add("signal", "SIGTERM 1.5 s into a run over an earlier output", files={"case.toml": toml_text(big)},
        kill_after=1.5, expect="killed",
        setup=lambda d: (d / "earlier.toml").write_text(toml_text(base("h2"))) and
        subprocess.run([IGAC, "run", "earlier.toml", "--quiet", "--out", "out"], cwd=d, check=True))
    add("signal", "SIGTERM 0.05 s into a run", files={"case.toml": toml_text(big)}, kill_after=0.05, expect="killed")


# ---------------------------------------------------------------- running and judging
NONFINITE = re.compile(rb"(?<![A-Za-z_])(-?nan|-?inf|-?infinity)(?![A-Za-z_])", re.I)
# igac's progress on stderr (model/progress.hpp): the load steps' lines
# ("step   3: load factor ...", "         load factor ... cut back", or
# "time" with load curves), a phase as it begins ("assembling 193 equations
# (0.0 s)") and the heartbeat of a long one ("  ... still factorising K (5 s)").
PROGRESS = re.compile(r"^(step\s+\d+:|\s+(load factor|time) |.* \(\d+(\.\d+)? s\)$)")
# A run's staging folder beside --out (app/output_folder.hpp: ".NAME.igac-tmp-PID").
STAGING = re.compile(r"^\..*\.igac-tmp-\d+$")
CONSOLE_NONFINITE = re.compile(r"(?<![A-Za-z_'\"])(-?nan|-?inf|-?infinity)(?![A-Za-z_'\"])", re.I)
CRASH_TEXT = re.compile(r"terminate called|what\(\):|Segmentation|Aborted|core dumped|Traceback|std::|"
                        r"Assertion|stack smashing|double free|AddressSanitizer", re.I)


def snapshot(path):
    """A comparable picture of a folder tree (names, sizes, contents' hash)."""
    if not os.path.lexists(path):
        return None
    if os.path.islink(path) or not os.path.isdir(path):
        try:
            return ("file", Path(path).read_bytes() if os.path.isfile(path) else os.readlink(path))
        except OSError:
            return ("unreadable",)
    out = {}
    for dirpath, dirs, files in os.walk(path):
        for n in files:
            p = os.path.join(dirpath, n)
            try:
                out[os.path.relpath(p, path)] = Path(p).read_bytes()
            except OSError:
                out[os.path.relpath(p, path)] = None
    return out


def nonfinite_in(folder):
    bad = []
    for dirpath, _, files in os.walk(folder):
        for n in files:
            p = Path(dirpath) / n
            try:
                data = p.read_bytes()
            except OSError:
                continue
            if n.endswith(".json"):
                try:
                    j = json.loads(data)
                except ValueError:
                    bad.append(f"{n} is not JSON")
                    continue
                if has_null(j):
                    bad.append(f"{n} holds null")
            if n.endswith(".vtu") and b"<AppendedData" in data:
                data = data[:data.index(b"<AppendedData")]  # the header: ranges of every array
            m = NONFINITE.search(data)
            if m:
                bad.append(f"{n}: {m.group(0).decode(errors='replace')}")
    return bad


def has_null(j):
    if j is None:
        return True
    if isinstance(j, dict):
        return any(has_null(v) for v in j.values())
    if isinstance(j, list):
        return any(has_null(v) for v in j)
    return False


def run_one(inp, igac, workdir, timeout):
    d = workdir
    d.mkdir(parents=True)
    for name, content in inp.files.items():
        p = d / name
        if isinstance(content, bytes):
            p.write_bytes(content)
        else:
            p.write_text(content)
    if inp.setup:
        inp.setup(d)
    if inp.args is not None:
        args = inp.args
    else:
        args = ["run", "case.toml"] + (["--out", inp.out] if inp.out else [])
    out_path = d / inp.out if inp.out else None
    before_out = snapshot(out_path) if out_path else None
    before_dir = set(os.listdir(d))
    t0 = time.monotonic()
    proc = subprocess.Popen([igac] + args, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            start_new_session=True)
    killed = False
    try:
        if inp.kill_after is not None:
            try:
                so, se = proc.communicate(timeout=inp.kill_after)
            except subprocess.TimeoutExpired:
                proc.send_signal(signal.SIGTERM)
                killed = True
                so, se = proc.communicate(timeout=timeout)
        else:
            so, se = proc.communicate(timeout=timeout)
        code = proc.returncode
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        so, se = proc.communicate()
        return dict(code="timeout", secs=time.monotonic() - t0, verdict="BAD",
                    reason=f"no answer within {timeout} s", first=(se or so).decode(errors="replace")[:200])
    secs = time.monotonic() - t0
    so_t, se_t = so.decode(errors="replace"), se.decode(errors="replace")
    reasons = []
    err_lines = [l for l in se_t.splitlines()]
    # the output folder igac was given and what it left there / beside it
    after_dir = set(os.listdir(d))
    new = sorted(after_dir - before_dir)
    # the default out/<name> is a new folder "out" in d
    expected_new = set()
    target = out_path
    if out_path is None and inp.args is None:
        target = d / "out"
    if target is not None:
        rel = os.path.relpath(target, d).split(os.sep)[0]
        expected_new.add(rel)
    stray = [n for n in new if n not in expected_new]
    after_out = snapshot(target) if target is not None else None

    if code < 0:
        reasons.append(f"killed by signal {-code}")
    if code == 3 or "internal error" in se_t:
        reasons.append("internal error")
    if CRASH_TEXT.search(se_t) or CRASH_TEXT.search(so_t):
        reasons.append("crash/exception text: " + CRASH_TEXT.search(se_t + so_t).group(0))
    # igac's own lines: errors, warnings and "stopped by", and the progress
    # of the load steps ("step   3: load factor ...", "         load factor ... cut back")
    foreign = [l for l in err_lines if l and not l.startswith("igac: ") and not PROGRESS.match(l)]
    if foreign:
        reasons.append(f"stderr line not igac's: {foreign[0][:80]!r}")
    errors = [l for l in err_lines if l.startswith("igac: error")]
    changed = target is not None and after_out != before_out

    if inp.expect == "killed":
        if not killed:
            reasons.append(f"ended (exit {code}) before SIGTERM")
        elif code not in (143, -15):
            reasons.append(f"exit {code} after SIGTERM, not 143")
        if changed and before_out is not None:
            reasons.append("the earlier output changed")
        if changed and before_out is None and after_out is not None:
            reasons.append("--out appeared after SIGTERM")
        # A stopped run's staging folder stays once it holds a step's state (to
        # continue with --restart), never with a summary; the next run removes it.
        stray = [n for n in stray if not (STAGING.match(n) and not (d / n / "summary.json").exists())]
        if killed and code in (143, -15):
            reasons = [r for r in reasons if not r.startswith("killed by signal")]
    elif code == 2:
        if len(errors) != 1:
            reasons.append(f"exit 2 with {len(errors)} error lines")
        elif err_lines and not err_lines[-1].startswith("igac: error"):
            reasons.append("lines after the error")
        if so_t.strip():
            reasons.append("stdout not empty on an input error")
        if changed:
            reasons.append("--out changed by an input error" if before_out is not None else "--out created by an input error")
        if errors and len(errors[0]) > 1000:
            reasons.append("error line over 1000 characters")
    elif code == 1:
        if inp.expect == "error":
            reasons.append("bad input ended as a failed run (exit 1), not an input error (exit 2)")
        if target is not None and after_out is not None and changed:
            try:
                s = json.loads((target / "summary.json").read_text())
                if s.get("status") == "converged":
                    reasons.append("exit 1 but summary.json says converged")
                else:
                    bad = nonfinite_in(target)
                    if bad:
                        reasons.append("non-finite in a failed run's output: " + bad[0])
            except (OSError, ValueError):
                reasons.append("exit 1 left --out without a readable summary.json")
        if not errors and not re.search(r"status|failed|stopped", so_t + se_t, re.I):
            reasons.append("exit 1 without saying why")
    elif code == 0:
        if inp.expect == "error":
            reasons.append("bad input accepted (exit 0)")
        if target is not None and os.path.isdir(target):
            bad = nonfinite_in(target)
            if bad:
                reasons.append("non-finite in output: " + bad[0])
        if errors:
            reasons.append("exit 0 with an error line")
    elif not any(r.startswith("killed") or r == "internal error" for r in reasons):
        reasons.append(f"exit code {code}")
    m = CONSOLE_NONFINITE.search(so_t + se_t)
    if m and code != 2:  # an input error may quote the value it refuses
        reasons.append(f"non-finite on the console: {m.group(0)!r}")
    if stray:
        reasons.append(f"left beside --out: {stray[:3]}")
    first = (se_t.strip().splitlines() or so_t.strip().splitlines() or [""])[-1 if code == 2 else 0]
    if code == 2 and errors:
        first = errors[0]
    return dict(code=code, secs=secs, verdict="BAD" if reasons else "OK", reason="; ".join(reasons), first=first[:300])


def make_writable(p):
    for dirpath, dirs, files in os.walk(p):
        for n in dirs + files:
            try:
                os.chmod(os.path.join(dirpath, n), 0o755, follow_symlinks=False)
            except (OSError, NotImplementedError):
                pass


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--igac", default=str(ROOT / "build" / "igac"))
    ap.add_argument("--timeout", type=float, default=20.0)
    ap.add_argument("--keep", help="keep the run folders here")
    ap.add_argument("--only", help="run the inputs whose description contains this")
    ap.add_argument("--csv", default=str(RESULTS / "hostile_inputs.csv"))
    a = ap.parse_args()
    global IGAC
    IGAC = a.igac
    gen_case_keys()
    gen_numbers()
    gen_structure()
    gen_faces()
    gen_contact()
    gen_mesh()
    gen_material_loading()
    gen_geometry()
    gen_cli()
    inputs = [i for i in INPUTS if not a.only or a.only in i.what or a.only in i.group]
    work = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="igac_hostile_"))
    if a.keep and work.exists():
        make_writable(work)
        shutil.rmtree(work)
    work.mkdir(parents=True, exist_ok=True)
    rows = []
    for k, inp in enumerate(inputs):
        r = run_one(inp, a.igac, work / f"{k:03d}", a.timeout)
        rows.append(dict(id=k, group=inp.group, what=inp.what, expected=inp.expect, **r))
        mark = "  " if r["verdict"] == "OK" else "!!"
        print(f"{mark} {k:3d} {inp.group:12s} {inp.what[:60]:60s} exit {r['code']!s:7s} {r['secs']:5.1f}s "
              f"{r['reason'] or r['first'][:80]}", flush=True)
    if not a.keep:
        make_writable(work)
        shutil.rmtree(work, ignore_errors=True)
    Path(a.csv).parent.mkdir(parents=True, exist_ok=True)
    with open(a.csv, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=["id", "group", "what", "expected", "code", "secs", "verdict", "reason", "first"])
        w.writeheader()
        for r in rows:
            r = dict(r, secs=f"{r['secs']:.2f}")
            w.writerow(r)
    nbad = sum(r["verdict"] == "BAD" for r in rows)
    print(f"hostile_inputs: {len(rows)} inputs, {len(rows) - nbad} OK, {nbad} BAD -> {os.path.relpath(a.csv, ROOT)}")
    return 1 if nbad else 0


if __name__ == "__main__":
    sys.exit(main())
