"""The bed engine's builds and skins against LAMMPS, side by side in one run (issue 30, eleventh round).

On the LAMMPS bench bed of benches/vs_lammps.py (prepared once, cached in target/bench/), one core, each
law alternating: an earlier build at its own default skin (--old, which need not know `--skin`), this
build at its default skin and at --skin, and LAMMPS at the default skin (a tenth of the mean diameter; its
speed does not depend on the skin, docs/benchmarks.md). Then the two-thread speed-up of the simplified
Pasha law on the shipped quarter and whole beds for the same three. Medians and min-max of --repeats.

Usage: python3 benches/vs_lammps_skins.py --old BIN [--skin 2.5e-5] [--repeats 5] [--steps 2000]
"""

import argparse
import statistics
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import vs_lammps as v  # noqa: E402

BEDS = [v.ROOT / "beds" / "bed_004_ch6_quarter.pfbed", v.ROOT / "beds" / "bed_004_ch6.pfbed"]


def ours(binary, model, steps, skin=None, threads=1, bed=None):
    """particle-steps/s and the step of one `bed bench` run (the bench bed's mapping unless `bed`)."""
    cmd = [str(binary), "bed", "bench", str(bed or v.BED), "--model", model, "--steps", str(steps), "--threads", str(threads)]
    if skin is not None:
        cmd += ["--skin", str(skin)]
    if bed is None:
        gamma = v.GAMMA if model in v.ADHESIVE else 0.0
        cmd += ["--stiffness", str(v.KN), "--surface-energy", str(gamma), "--rolling-friction", "0"]
    fields = dict(kv.split("=", 1) for kv in v.run(cmd).stdout.split())
    return float(fields["particle_steps_per_s"]), float(fields["dt"])


def spread(xs):
    return f"{statistics.median(xs):.3e} [{min(xs):.2e}-{max(xs):.2e}]"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--old", type=Path, required=True, help="an earlier powderfmu binary, kept aside")
    ap.add_argument("--skin", type=float, default=2.5e-5, help="the second skin of this build [m]")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--steps", type=int, default=2000)
    args = ap.parse_args()
    lmp = v.ensure_lammps()
    v.ensure_bed()
    new = v.BIN
    print(f"old {args.old}, this build {new}, second skin {args.skin:g} m; {args.steps} steps, medians of {args.repeats}")
    for model, peer in [("hooke", "hooke"), ("hertz", "hertz"), ("jkr", "jkr"), ("nan", None), ("pasha_simplified", None)]:
        a, b, d, c = [], [], [], []
        for _ in range(args.repeats):
            a.append(ours(args.old, model, args.steps)[0])
            rate, dt = ours(new, model, args.steps)
            b.append(rate)
            d.append(ours(new, model, args.steps, args.skin)[0])
            if peer:
                c.append(v.lammps(lmp, peer, args.steps, dt, 200)[0])
        A, B, D = (statistics.median(x) for x in (a, b, d))
        line = f"{model}: old {spread(a)}  this {spread(b)}  this@skin {spread(d)}  this/old {B / A:.2f}  this@skin/old {D / A:.2f}"
        if c:
            C = statistics.median(c)
            line += f"  LAMMPS {spread(c)}  old/L {A / C:.2f}  this/L {B / C:.2f}  this@skin/L {D / C:.2f}"
        print(line, flush=True)
    for bed in BEDS:
        for name, binary, skin in [("old", args.old, None), ("this", new, None), ("this@skin", new, args.skin)]:
            one = [ours(binary, "pasha_simplified", args.steps, skin, 1, bed)[0] for _ in range(3)]
            two = [ours(binary, "pasha_simplified", args.steps, skin, 2, bed)[0] for _ in range(3)]
            print(f"{bed.name} {name}: 1 thread {spread(one)}, 2 threads {spread(two)}, speed-up {statistics.median(two) / statistics.median(one):.2f}", flush=True)


if __name__ == "__main__":
    main()
