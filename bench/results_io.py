# SPDX-License-Identifier: BSD-3-Clause
"""results_io.py: what the bench scripts write: rows as CSV, and matplotlib
(headless) when it is installed."""
import csv
from pathlib import Path


def write_rows(path, rows):
    """rows (dicts with the same keys) as CSV at path, its folder made."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    with open(path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def pyplot():
    """matplotlib.pyplot on the Agg backend, or None (said) without matplotlib."""
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("matplotlib missing: no plot")
        return None
    return plt
