"""The table of benches/ch5_soft_proxy.sh: one row per run, then per candidate the mean over fill seeds
against the base rows (the seed's Table 5.3 as printed) and against 004 Sec. 5.2's about 8 kPa.

    python benches/ch5_soft_proxy.py OUT_DIR [--csv docs/data/ch5_soft_proxy.csv]
"""
import argparse
import csv
import re
import statistics
import sys
from pathlib import Path

SEED_KPA = 8.0  # 004 Sec. 5.2: "the hardness stabilises around 8 kPa" (13 mm indenter, Fig. 5.3)
RESULT = re.compile(
    r"plateau hardness (?P<plateau>[-+.\deE]+) \+- (?P<se>[-+.\deE]+) Pa .*?"
    r"correlation time (?P<tau>[.\d]+) samples.*?(?P<wall>[.\d]+) s wall time")


def read_runs(out: Path):
    rows = []
    for log in sorted(out.glob("*.log")):
        if log.name.endswith(".prepare.log"):
            continue
        text = log.read_text()
        m = RESULT.search(text)
        if not m:
            continue
        head = text.splitlines()[0]
        name = log.stem
        candidate, _, seed = name.rpartition("_s")
        rows.append({
            "run": name,
            "candidate": candidate,
            "fill_seed": int(seed),
            "bed": head.split()[0].removeprefix("bed="),
            "plateau_Pa": float(m["plateau"]),
            "plateau_se_Pa": float(m["se"]),
            "correlation_time_samples": float(m["tau"]),
            "wall_time_s": float(m["wall"]),
            "args": head.partition("args=")[2],
        })
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", type=Path)
    ap.add_argument("--csv", type=Path)
    a = ap.parse_args()
    rows = read_runs(a.out)
    if not rows:
        sys.exit(f"no finished runs in {a.out}")
    print(f"{'run':<22} {'plateau [Pa]':>14} {'wall [s]':>9}")
    for r in rows:
        print(f"{r['run']:<22} {r['plateau_Pa']:>8.0f} +- {r['plateau_se_Pa']:<4.0f} {r['wall_time_s']:>9.1f}")
    by = {}
    for r in rows:
        by.setdefault(r["candidate"], []).append(r["plateau_Pa"])
    base = by.get("base")
    base_mean = statistics.mean(base) if base else float("nan")
    print(f"\n{'candidate':<16} {'seeds':>5} {'mean [Pa]':>10} {'spread [Pa]':>11} {'over base':>9} {'over 8 kPa':>10}")
    for c, v in by.items():
        m = statistics.mean(v)
        spread = (max(v) - min(v)) / 2 if len(v) > 1 else float("nan")
        print(f"{c:<16} {len(v):>5} {m:>10.0f} {spread:>11.0f} {m / base_mean:>9.3f} {m / (SEED_KPA * 1e3):>10.3f}")
    if a.csv:
        with a.csv.open("w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
        print(f"\nwrote {a.csv}")


if __name__ == "__main__":
    main()
