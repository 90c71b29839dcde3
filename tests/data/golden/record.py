#!/usr/bin/env python3
"""Records the golden values of the shipped cases (tests/cli/test_golden_cases.cpp).

    python3 tests/data/golden/record.py BUILD/igac RUN_FOLDER CASE [CASE ...]

For each CASE (a cases/CASE.toml, or study:CASE for `igac study CASE
--levels 4`) runs igac into RUN_FOLDER/CASE and writes
tests/data/golden/CASE.json (study_CASE.json): the summary.json (study.json)
without the keys that measure the machine rather than the numerics (timings,
seconds, memory; see EXCLUDED), plus the rows of pressure.csv (or of each
pressure_<face>.csv of a case with several contacts) and load_curve.csv
when the run writes them (an empty cell as null).  The
numbers are written as Python's repr, which reads back to the same
double.  Re-record only on purpose: the point of the files is to hold the
values from before a change.
"""
import csv
import json
import os
import re
import subprocess
import sys

# Keys whose values depend on the machine, the load or the folder, not on the
# numerics: timing_s, newton_seconds, memory_gib (estimated and peak
# resident), any *_seconds / *_s / time / path / folder, and the condition
# estimate (the golden test reads it from the run to set its tolerance:
# tests/support/solve_tolerance.hpp).
EXCLUDED = re.compile(r"(time|timing|seconds|_s$|memory|resident|path|folder|^out$|condition_estimate)")


def strip(node):
    if isinstance(node, dict):
        return {k: strip(v) for k, v in node.items() if not EXCLUDED.search(k)}
    if isinstance(node, list):
        return [strip(v) for v in node]
    return node


def cell(text):
    """A CSV cell as a number, a string (pressure.csv's kind) or None (empty)."""
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        return text


def main():
    igac, runs, cases = sys.argv[1], sys.argv[2], sys.argv[3:]
    here = os.path.dirname(os.path.abspath(__file__))
    source = os.path.abspath(os.path.join(here, "..", "..", ".."))
    for case in cases:
        study = case.startswith("study:")
        name = case.split(":")[-1]
        tag = ("study_" if study else "") + name
        out = os.path.join(runs, tag)
        toml = os.path.join(source, "cases", name + ".toml")
        cmd = [igac, "study", toml, "--levels", "4"] if study else [igac, "run", toml]
        # One thread, so that a record does not depend on the load of the
        # machine that wrote it (the test holds any thread count to the
        # round-off its conditioning allows).
        env = dict(os.environ, OMP_NUM_THREADS="1")
        subprocess.run(cmd + ["--out", out, "--quiet"], check=True, stdout=subprocess.DEVNULL, env=env)
        with open(os.path.join(out, "study.json" if study else "summary.json")) as f:
            record = {"command": " ".join(["igac"] + cmd[1:2] + ["cases/" + name + ".toml"] + cmd[3:]),
                      "summary": strip(json.load(f))}
        # pressure.csv, or pressure_<face>.csv per contact when there are several
        pressure = sorted(f for f in os.listdir(out) if re.fullmatch(r"pressure(_.+)?\.csv", f))
        for csv_name in pressure + ["load_curve.csv"]:
            path = os.path.join(out, csv_name)
            if study or not os.path.exists(path):
                continue
            with open(path) as f:
                rows = list(csv.reader(f))
            record[csv_name[:-4] + "_csv"] = {"header": rows[0], "rows": [[cell(x) for x in r] for r in rows[1:]]}
        with open(os.path.join(here, tag + ".json"), "w") as f:
            json.dump(record, f, indent=1)
            f.write("\n")
        print("recorded", tag)


if __name__ == "__main__":
    main()
