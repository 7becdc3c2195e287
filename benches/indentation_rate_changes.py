"""The rate question of issue 31 (benches/indentation_rate_changes.sh): one row per run with gamma*, the
inertial number, the change, the plateau hardness with its standard error and the hardness after
unloading; each change beside the unchanged bed at the same gamma*, and the slow end over gamma* = 0.08
for the unchanged bed and each change (what makes the slow end harder); where replicas were run (steps a few
parts in 10^4 apart), the run-to-run scatter at each nominal step.

    python benches/indentation_rate_changes.py OUT_DIR [--csv docs/data/rate_changes.csv]

I = (v / H) d / (P / rho)^(1/2) (GDR MiDi 2004) with H = 18.0 mm, d = 1 mm, rho = 2500 kg/m^3 (the shipped
bed, scenes/bed_004_ch6.json) and P the unchanged bed's plateau at the slowest gamma*.
"""
import argparse
import csv
import math
import pathlib
import re

H, D, RHO, G = 18.0e-3, 1.0e-3, 2500.0, 9.81
NUMBER = r"([-+0-9.e]+)"


def read(path):
    text = path.read_text()
    if not text.startswith("gamma="):
        return None  # the driver's own log
    head = dict(kv.split("=", 1) for kv in text.splitlines()[0].split(" ", 2))
    m = re.search(r"plateau hardness " + NUMBER + r" \+- " + NUMBER + r" Pa", text)
    # "hardness H Pa, plateau" (logs before the hardness had an error) or "hardness H +- E Pa (...), plateau".
    h = re.search(r"hardness " + NUMBER + r"(?: Pa| \+- " + NUMBER + r" Pa \(standard error of the force at the turn\)), plateau", text)
    n = re.search(r"h/r [0-9.-]+, (\d+) samples, correlation time " + NUMBER, text)
    wall = re.search(r"([0-9.]+) s wall time", text)
    if not m:
        return None
    return {
        "run": path.stem,
        "gamma": float(head["gamma"]),
        "time_step_s": float(head["dt"]),
        "change": head["change"],
        "plateau_Pa": float(m.group(1)),
        "plateau_se_Pa": float(m.group(2)),
        "samples": int(n.group(1)) if n else 0,
        "correlation_time": float(n.group(2)) if n else float("nan"),
        "hardness_after_unloading_Pa": float(h.group(1)) if h else float("nan"),
        "wall_time_s": float(wall.group(1)) if wall else float("nan"),
    }


def nominal_step(dt):
    """The step a run stands for: 2.5e-7 s or its half; a step a few parts in 10^4 off is a replica."""
    return min((2.5e-7, 1.25e-7), key=lambda n: abs(dt - n))


def label(row):
    dt = row["time_step_s"]
    if dt != nominal_step(dt):
        return f"replica: time step {dt:g} s"
    if dt != 2.5e-7:
        return f"time step {dt:g} s"
    names = {
        "none": "none",
        '{"rolling_friction": 0}': "no rolling friction",
        '{"particle_particle": {"surface_energy": 0}}': "no cohesion",
        '{"particle_particle": {"damping_factor_elastic": 0.1, "damping_factor_plastic": 0.1}}': "damping x 0.1",
    }
    return names.get(row["change"], row["change"])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--csv", type=pathlib.Path)
    a = ap.parse_args()
    rows = [r for r in (read(p) for p in sorted(a.out.glob("*.log"))) if r]
    if not rows:
        raise SystemExit(f"no finished runs in {a.out}")
    base = {r["gamma"]: r for r in rows if r["change"] == "none" and r["time_step_s"] == 2.5e-7}
    slowest = base[min(base)]["plateau_Pa"]
    for r in rows:
        v = r["gamma"] * math.sqrt(G / D) * H
        r["speed_m_per_s"] = v
        r["inertial_number"] = (v / H) * D / math.sqrt(slowest / RHO)
        b = base.get(r["gamma"])
        r["over_unchanged"] = r["plateau_Pa"] / b["plateau_Pa"] if b else float("nan")
    rows.sort(key=lambda r: (r["change"] != "none" or r["time_step_s"] != 2.5e-7, label(r), r["gamma"]))
    print("| change | gamma* | I | speed [m/s] | plateau hardness [Pa] | standard error [Pa] | / unchanged at this gamma* | hardness after unloading [Pa] | wall time [s] |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {label(r)} | {r['gamma']:g} | {r['inertial_number']:.2g} | {r['speed_m_per_s']:.4g} | {r['plateau_Pa']:.0f} | {r['plateau_se_Pa']:.0f} | "
              f"{r['over_unchanged']:.3f} | {r['hardness_after_unloading_Pa']:.0f} | {r['wall_time_s']:.0f} |")
    print()
    print("| change | plateau at gamma* 0.0115 over gamma* 0.08 | combined standard error |")
    print("|---|---:|---:|")
    by = {}
    for r in rows:
        by.setdefault(label(r), {})[r["gamma"]] = r
    for name, runs in by.items():
        if 0.0115 in runs and 0.08 in runs:
            s, f = runs[0.0115], runs[0.08]
            ratio = s["plateau_Pa"] / f["plateau_Pa"]
            err = ratio * math.hypot(s["plateau_se_Pa"] / s["plateau_Pa"], f["plateau_se_Pa"] / f["plateau_Pa"])
            print(f"| {name} | {ratio:.3f} | {err:.3f} |")
    replicas = {}
    for r in rows:
        if r["change"] == "none":
            replicas.setdefault((r["gamma"], nominal_step(r["time_step_s"])), []).append(r["plateau_Pa"])
    if any(len(v) > 1 for v in replicas.values()):
        print()
        print("Run-to-run scatter (the unchanged bed at one nominal step, steps a few parts in 10^4 apart):")
        print()
        print("| gamma* | nominal time step [s] | runs | plateau hardness [Pa] | mean [Pa] | standard deviation [Pa] |")
        print("|---:|---:|---:|---|---:|---:|")
        for (g, dt), v in sorted(replicas.items()):
            if len(v) > 1:
                m = sum(v) / len(v)
                sd = math.sqrt(sum((x - m) ** 2 for x in v) / (len(v) - 1))
                print(f"| {g:g} | {dt:g} | {len(v)} | {', '.join(f'{x:.0f}' for x in v)} | {m:.0f} | {sd:.0f} ({100 * sd / m:.1f} %) |")
    if a.csv:
        keys = ["run", "change", "gamma", "inertial_number", "speed_m_per_s", "time_step_s", "plateau_Pa", "plateau_se_Pa", "samples",
                "correlation_time", "over_unchanged", "hardness_after_unloading_Pa", "wall_time_s"]
        with a.csv.open("w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
            w.writeheader()
            for r in rows:
                w.writerow({k: (f"{r[k]:.6g}" if isinstance(r[k], float) else r[k]) for k in keys})
        print(f"\n{len(rows)} runs -> {a.csv}")


if __name__ == "__main__":
    main()
