#!/usr/bin/env python3
"""Reads criterion's medians for the force_evaluation group and prints the markdown table of
docs/benchmarks.md: ns per evaluation, evaluations per second, and the cost relative to the Nan law.
Run after `cargo bench --bench laws`."""
import json
import pathlib
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent / "target" / "criterion" / "force_evaluation"
STATES = 256

rows = []
for d in sorted(ROOT.iterdir()) if ROOT.exists() else []:
    est = d / "new" / "estimates.json"
    if not est.exists():
        continue
    e = json.loads(est.read_text())
    med = e["median"]["point_estimate"] / STATES
    lo = e["median"]["confidence_interval"]["lower_bound"] / STATES
    hi = e["median"]["confidence_interval"]["upper_bound"] / STATES
    rows.append((d.name, med, lo, hi))
if not rows:
    sys.exit("no criterion results: run `cargo bench --bench laws` first")
nan = dict((r[0], r[1]) for r in rows).get("nan")
print("| law | median ns / evaluation | 95 % CI of the median [ns] | evaluations / s | cost / Nan |")
print("|---|---:|---:|---:|---:|")
for name, med, lo, hi in sorted(rows, key=lambda r: r[1]):
    ratio = f"{med / nan:.2f}" if nan else "-"
    print(f"| {name} | {med:.2f} | {lo:.2f} - {hi:.2f} | {1e9 / med:.3g} | {ratio} |")
