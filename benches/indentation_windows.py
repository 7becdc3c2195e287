#!/usr/bin/env python3
"""Window means of an indentation's hardness over depth, per run, and their mean over runs on several beds.

Reads the CSVs `powderfmu bed indent --every DT --out F` writes (docs/data/ch5_quarter*.csv,
docs/data/ch6_indentation) and prints, per file, the mean hardness F/(pi (2 r h - h^2)) of the rows while
loading (state 0) in each window of h/r (both ends included), then the mean over the files with its
standard error from their spread (the bed-to-bed scatter, n - 1 in the variance). The unit's own plateau
(the log's `plateau hardness`) is read over its every-100-steps samples and differs from the rows' mean
by a few percent; the docs quote both.

LABEL=CSV@OFFSET re-reads a first-touch run from another depth origin: h - OFFSET [m], OFFSET being how far
the origin lies below the first touch (`bed indent BED --depth-origin mean-surface` prints the bed's mean
surface's as "... m below the first touch"); the windows are then taken in (h - OFFSET)/r and the area
is A(h - OFFSET) (docs/indentation.md, "The depth origin").

    python3 benches/indentation_windows.py seed1=docs/data/ch5_quarter45_13mm_edem_friction.csv \
        seed2=docs/data/ch5_quarter45_13mm_edem_friction_seed2.csv

`--quantity hydrostatic` or `--quantity deviatoric` (first) reads the dynamic bin's stresses of the same
rows instead (004 Eqs. 5.2-5.3, Sec. 5.3).
"""

import math
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from indentation_rate import load, summary  # noqa: E402  (the window mean of every indentation bench)

WINDOWS = [(0.1, 0.2), (0.2, 0.35), (0.35, 0.4), (0.4, 0.45), (0.45, 0.5), (0.35, 0.5)]


def from_origin(rows, offset):
    """The same rows read from an origin `offset` [m] below the first touch: depth, h/r and F/A(h)."""
    last = max(rows, key=lambda r: r["depth_m"])
    radius = round(last["depth_m"] / last["depth_over_r"], 4)  # depth_over_r is rounded; radii are whole 0.1 mm
    out = []
    for r in rows:
        h = r["depth_m"] - offset
        if h > 0.0:
            out.append({**r, "depth_over_r": h / radius, "hardness_Pa": r["force_N"] / (math.pi * (2.0 * radius * h - h * h))})
    return out


def window_means(path, offset=0.0, quantity="plateau"):
    """Mean hardness [Pa] (or `quantity` of `summary`) of the loading rows in each of WINDOWS; NaN where a
    window has no row."""
    rows = load(path)
    if not any(r["state"] == 0 for r in rows):
        sys.exit(f"{path}: no loading rows (state 0); is it a `bed indent --out` CSV?")
    if offset != 0.0:
        rows = from_origin(rows, offset)
    return [summary(rows, window)[quantity] for window in WINDOWS]


def main(args):
    quantity, name = "plateau", "hardness"
    if args and args[0] == "--quantity":
        if len(args) < 2 or args[1] not in ("hydrostatic", "deviatoric"):
            sys.exit("--quantity takes hydrostatic or deviatoric")
        quantity = name = args[1]
        args = args[2:]
    if not args or any("=" not in a for a in args):
        sys.exit("usage: indentation_windows.py LABEL=CSV[@OFFSET_M] [LABEL=CSV[@OFFSET_M] ...]")
    labels, table = [], []
    for a in args:
        label, path = a.split("=", 1)
        offset = 0.0
        if "@" in path:
            path, off = path.rsplit("@", 1)
            offset = float(off)
        labels.append(label)
        table.append(window_means(path, offset, quantity))
    head = " | ".join(f"{lo}-{hi}" for lo, hi in WINDOWS)
    print(f"| bed ({name}) | {head} |")
    print("|---" + "|---:" * len(WINDOWS) + "|")
    for label, row in zip(labels, table):
        print(f"| {label} [Pa] | " + " | ".join(f"{v:.0f}" for v in row) + " |")
    if len(table) > 1:
        cells = []
        for j in range(len(WINDOWS)):
            column = [row[j] for row in table]
            se = statistics.stdev(column) / math.sqrt(len(column))
            cells.append(f"{statistics.fmean(column):.0f} +- {se:.0f}")
        print(f"| mean of {len(table)} +- standard error [Pa] | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1:])
