# SPDX-License-Identifier: BSD-3-Clause
"""case_toml.py: write igac case files (TOML) from dicts, for the bench scripts.

Python's tomllib reads TOML but does not write it; this is the small writer
both bench/stress_test.py and bench/work_precision.py use for their variants.
"""
import json
import math
from pathlib import Path


def _toml_value(v):
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError("non-finite value in a case file")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {v!r} as TOML")


def _toml_table(d, prefix, out):
    for k, v in d.items():
        if not isinstance(v, dict) and not (isinstance(v, list) and v and isinstance(v[0], dict)):
            out.append(f"{k} = {_toml_value(v)}")
    for k, v in d.items():
        name = f"{prefix}.{k}" if prefix else k
        if isinstance(v, dict):
            out.append("")
            out.append(f"[{name}]")
            _toml_table(v, name, out)
        elif isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                out.append("")
                out.append(f"[[{name}]]")
                _toml_table(item, name, out)


def write_case(d, path, header):
    lines = [f"# {line}" for line in header.splitlines()]
    _toml_table(d, "", lines)
    Path(path).write_text("\n".join(lines) + "\n")


def contacts_of(case):
    """The [[contact]] tables of a parsed case (one [contact] table is a list of one)."""
    return case["contact"] if isinstance(case["contact"], list) else [case["contact"]]
