#!/usr/bin/python3
# SPDX-License-Identifier: BSD-3-Clause
"""The Python module against the command line (docs/python.md).

Run by CTest (tests/CMakeLists.txt) with PYTHONPATH=build/python and
IGAC_BINARY=build/igac:
  - every shipped case (cases/*.toml) gives the summary igac run writes,
    number for number (relative 1e-12; the keys that time the run aside):
    those of a second or less as shipped; the 3D ones and the longer ones
    (LONG_CASES) with [output] vtk = false added to a copy that both run, so
    that the command line does not spend half its time on ParaView files the
    module never writes (no number of summary.json depends on them; their
    von Mises is checked on the golden runs, tests/cli/test_golden_cases.cpp).
    The two study cases run as cases (their level 0): the module has no
    study, and `igac study` is runs of the same code at --refine 0, 1, ...;
  - an override is the same as the case file edited;
  - a case given as a dict is the same as its file;
  - bad input is igac.InputError (a ValueError) with the one-line message;
  - the arrays have the shapes of the model.
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import tomllib
import unittest

import numpy as np

import igac

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CASES = os.path.join(ROOT, "cases")
IGAC = os.environ.get("IGAC_BINARY", os.path.join(ROOT, "build", "igac"))
FAST_CASES = ["hertz2d", "hertz2d_two_patches", "two_blocks", "roller_on_block", "lame_cylinder",
              "cattaneo_mindlin", "oring", "hertz2d_from_file", "hertz2d_high_load", "cattaneo_mindlin_two_bodies",
              "cattaneo_mindlin_cycle", "oring_on_plate", "oring_rubber", "roller_on_block_neohookean",
              "hertz2d_neohookean_pressure", "hertz2d_neohookean_displacement", "oring_two_plates", "oring_unloading",
              "oring_friction", "cook_membrane", "press_fit", "hertz_axisymmetric"]
# Run by the module and the command line at their shipped mesh, 3D and longer
# (8 to 30 s each on a loaded machine), once each.
LONG_CASES = ["hertz3d", "hertz3d_high_load", "hertz3d_p3", "hertz3d_neohookean", "sphere_on_block",
              "indented_block", "hertz2d_neohookean_pressure_study", "hertz3d_study", "ironing", "seal"]
ROUND_OFF = 1e-12
# Keys that measure the machine or name a file, not the numerics.
MACHINE = ("time", "timing", "seconds", "_s", "memory", "resident", "path", "folder", "fnv1a64")


def cli_summary(case_file):
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        subprocess.run([IGAC, "run", case_file, "--out", out, "--quiet"], check=False)
        with open(os.path.join(out, "summary.json")) as f:
            return json.load(f)


def compare(test, a, b, where="summary"):
    if isinstance(a, dict):
        test.assertEqual(sorted(k for k in a if not k.endswith(MACHINE)),
                         sorted(k for k in b if not k.endswith(MACHINE)), where)
        for k in a:
            if not k.endswith(MACHINE):
                compare(test, a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        test.assertEqual(len(a), len(b), where)
        for i, (x, y) in enumerate(zip(a, b)):
            compare(test, x, y, f"{where}[{i}]")
    elif isinstance(a, float) or isinstance(b, float):
        test.assertTrue(math.isclose(a, b, rel_tol=ROUND_OFF, abs_tol=1e-300), f"{where}: {a} != {b}")
    else:
        test.assertEqual(a, b, where)


class ModuleAgainstCommandLine(unittest.TestCase):
    def test_every_fast_shipped_case_gives_the_command_lines_summary(self):
        for name in FAST_CASES:
            with self.subTest(case=name):
                path = os.path.join(CASES, name + ".toml")
                result = igac.run(path)
                compare(self, cli_summary(path), result["summary"])
                self.assertEqual(result["status"], result["summary"]["status"])

    def test_every_long_shipped_case_gives_the_command_lines_summary(self):
        with tempfile.TemporaryDirectory() as tmp:
            for name in os.listdir(CASES):  # the geometry files beside the copies
                if name.endswith(".xml"):
                    shutil.copy(os.path.join(CASES, name), tmp)
            for name in LONG_CASES:
                with self.subTest(case=name):
                    with open(os.path.join(CASES, name + ".toml")) as f:
                        text = f.read()
                    self.assertNotIn("[output]", text)
                    path = os.path.join(tmp, name + ".toml")
                    with open(path, "w") as f:
                        f.write(text + "\n[output]\nvtk = false\n")
                    result = igac.run(path)
                    compare(self, cli_summary(path), result["summary"])
                    self.assertEqual(result["status"], "converged")

    def test_every_shipped_case_is_compared(self):
        shipped = sorted(f[:-5] for f in os.listdir(CASES) if f.endswith(".toml"))
        self.assertEqual(sorted(FAST_CASES + LONG_CASES), shipped)

    def test_an_override_is_the_case_file_edited(self):
        path = os.path.join(CASES, "hertz2d.toml")
        with open(path) as f:
            text = f.read()
        self.assertIn("E = 1.0", text)
        with tempfile.TemporaryDirectory() as tmp:
            edited = os.path.join(tmp, "hertz2d.toml")
            with open(edited, "w") as f:
                f.write(text.replace("E = 1.0", "E = 2.0"))
            expected = cli_summary(edited)
        got = igac.run(path, {"material.E": 2.0})["summary"]
        compare(self, expected, got)
        self.assertNotEqual(got["contact"]["max_pressure"], igac.run(path)["summary"]["contact"]["max_pressure"])

    def test_an_array_of_tables_is_indexed(self):
        path = os.path.join(CASES, "oring.toml")
        with open(path, "rb") as f:
            case = tomllib.load(f)
        contact = case["contact"][0] if isinstance(case["contact"], list) else case["contact"]
        motion = [0.5 * x for x in contact["obstacle"]["motion"]]
        key = "contact.0.obstacle.motion" if isinstance(case["contact"], list) else "contact.obstacle.motion"
        half = igac.run(path, {key: motion})["summary"]
        full = igac.run(path)["summary"]
        self.assertLess(half["contact"]["total_force"], full["contact"]["total_force"])

    def test_a_case_as_a_dict_is_its_file(self):
        path = os.path.join(CASES, "two_blocks.toml")  # with a geometry file beside it
        with open(path, "rb") as f:
            case = tomllib.load(f)
        compare(self, igac.run(path)["summary"], igac.run_dict(case, folder=CASES)["summary"])

    def test_bad_input_is_an_input_error_with_the_one_line_message(self):
        path = os.path.join(CASES, "hertz2d.toml")
        with self.assertRaises(igac.InputError) as e:
            igac.run(path, {"material.nu": 0.5})
        self.assertIn("[material] nu", str(e.exception))
        self.assertTrue(issubclass(igac.InputError, ValueError))
        with self.assertRaises(igac.InputError) as e:
            igac.run(path, {"material.E.x": 1.0})
        self.assertIn("'material.E' is not a table", str(e.exception))
        with self.assertRaises(igac.InputError):
            igac.run(path, {"material.colour": "red"})

    def test_arrays_have_the_models_shapes(self):
        r = igac.run(os.path.join(CASES, "roller_on_block.toml"))
        n = r["summary"]["dofs"]
        self.assertEqual(r["displacement"].shape, r["control_points"].shape)
        self.assertEqual(r["displacement"].shape[1], 2)
        self.assertGreaterEqual(r["displacement"].size, n)
        self.assertEqual(r["multipliers"].shape, (r["summary"]["multipliers"],))
        self.assertEqual(len(r["pressure"]), 1)
        p = r["pressure"][0]
        self.assertEqual(p["face"], "roller:curved")
        self.assertAlmostEqual(float(np.max(p["pressure"])), r["summary"]["contact"]["max_pressure"], delta=1e-15)


    def test_reactions_are_the_summarys_per_face_set_and_per_step(self):
        path = os.path.join(ROOT, "tests", "data", "curve_block_neohookean.toml")
        r = igac.run(path)
        faces = r["summary"]["dirichlet_reactions"]
        self.assertEqual([f["face"] for f in r["reactions"]], [f["face"] for f in faces])
        for mine, theirs in zip(r["reactions"], faces):
            self.assertEqual(mine["force"].tolist(), theirs["force"])
            self.assertEqual(mine["steps"].shape, (len(mine["t"]), 2))
            self.assertEqual(mine["steps"][-1].tolist(), theirs["force"])
            # per step: the summary's load_steps carry the same reactions
            for row, step in zip(mine["steps"][-len(r["summary"]["load_steps"]):], r["summary"]["load_steps"]):
                match = [f for f in step["dirichlet_reactions"] if f["face"] == mine["face"]][0]
                self.assertEqual(row.tolist(), match["force"])
        self.assertGreater(len(r["summary"]["load_steps"]), 4)


class HostileValues(unittest.TestCase):
    """Bad Python input is igac.InputError in one line, never a crash or a hang."""

    HERTZ = os.path.join(CASES, "hertz2d.toml")

    def assertInputError(self, call, *fragments):
        with self.assertRaises(igac.InputError) as e:
            call()
        message = str(e.exception)
        self.assertNotIn("\n", message)
        for f in fragments:
            self.assertIn(f, message)

    def test_a_list_that_holds_itself_and_a_dict_that_holds_itself(self):
        loop = [0.0, -0.1]
        loop.append(loop)
        self.assertInputError(lambda: igac.run(self.HERTZ, {"contact.obstacle.motion": loop}), "holds itself")
        with open(self.HERTZ, "rb") as f:
            case = tomllib.load(f)
        case["material"]["self"] = case["material"]
        self.assertInputError(lambda: igac.run_dict(case, folder=CASES), "holds itself")

    def test_a_value_nested_1e5_deep(self):
        deep = 1.0
        for _ in range(100000):
            deep = [deep]
        self.assertInputError(lambda: igac.run(self.HERTZ, {"material.E": deep}), "nested more than")
        self.assertInputError(lambda: igac.run_dict({"name": "x", "material": {"E": deep}}), "nested more than")

    def test_numpy_scalars_are_the_numbers_they_are(self):
        plain = igac.run(self.HERTZ, {"material.E": 2.0, "mesh.refine": 1})["summary"]
        numpy = igac.run(self.HERTZ, {"material.E": np.float64(2.0), "mesh.refine": np.arange(3)[1]},
                         refine=None, degree=np.int64(2))["summary"]
        compare(self, plain, numpy)

    def test_huge_integers_bad_paths_and_nul_characters(self):
        self.assertInputError(lambda: igac.run(self.HERTZ, {"mesh.refine": 10 ** 30}), "beyond 64 bits")
        self.assertInputError(lambda: igac.run(self.HERTZ, refine=10 ** 30), "refine")
        self.assertInputError(lambda: igac.run(os.path.join(CASES, "no_such_case.toml")), "no such case file")
        self.assertInputError(lambda: igac.run(self.HERTZ + "\0.txt"), "NUL")
        self.assertInputError(lambda: igac.run(3.5), "not a path")
        self.assertInputError(lambda: igac.run(self.HERTZ, {"contact.0.x": 1}), "")
        self.assertInputError(lambda: igac.run(self.HERTZ, {1: 2.0}), "a key of type int")

    def test_special_files_are_refused_without_reading_them(self):
        self.assertInputError(lambda: igac.run("/dev/zero"), "not a regular file")
        with tempfile.TemporaryDirectory() as tmp:
            fifo = os.path.join(tmp, "fifo.toml")
            os.mkfifo(fifo)
            self.assertInputError(lambda: igac.run(fifo), "not a regular file")
            self.assertInputError(lambda: igac.run(tmp), "not a regular file")

    def test_an_overrides_error_names_the_override_not_a_line_of_the_file(self):
        with self.assertRaises(igac.InputError) as e:
            igac.run(self.HERTZ, {"material.nu": 0.7})
        self.assertIn("override 'material.nu'", str(e.exception))


if __name__ == "__main__":
    unittest.main(verbosity=2)
