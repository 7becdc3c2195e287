#!/usr/bin/env python3
"""Two builds of the engine timed in pairs: `powderfmu bed bench` with the same arguments, the builds
taking turns (the order swapped each round), then each build's median, least and largest particle-steps
per second and the ratio NEW / OLD of each round: its median, quartiles, and in how many rounds NEW was
faster. On a shared machine the ratio within a round cancels what drifts between rounds.

    python3 benches/paired.py ROUNDS BED "BENCH ARGS" OLD NEW
    e.g. python3 benches/paired.py 31 beds/bed_004_ch6_quarter.pfbed \\
         "--model pasha_simplified --steps 4000 --threads 2" /tmp/old/powderfmu target/release/powderfmu
"""
import re
import statistics
import subprocess
import sys


def speed(binary, bed, args):
    out = subprocess.run([binary, "bed", "bench", bed, *args.split()], capture_output=True, text=True, check=True).stdout
    m = re.search(r"particle_steps_per_s=([0-9.e+]+)", out)
    if not m:
        sys.exit(f"paired: {binary} printed no particle_steps_per_s")
    return float(m.group(1))


def main():
    if len(sys.argv) != 6:
        sys.exit(__doc__)
    rounds, bed, args, old, new = int(sys.argv[1]), sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5]
    if rounds < 1:
        sys.exit(f"paired: ROUNDS = {rounds} must be at least 1")
    runs = {old: [], new: []}
    for r in range(rounds):
        for b in (old, new) if r % 2 == 0 else (new, old):
            runs[b].append(speed(b, bed, args))
        print(f"\rround {r + 1} of {rounds}", end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    for b, v in runs.items():
        print(f"{b:40s} median {statistics.median(v):.3e}  least {min(v):.3e}  largest {max(v):.3e}  particle-steps/s, n {len(v)}")
    ratios = sorted(n / o for o, n in zip(runs[old], runs[new]))
    q = statistics.quantiles(ratios, n=4) if len(ratios) > 1 else ratios * 3
    print(f"NEW / OLD per round: median {statistics.median(ratios):.3f}, quartiles {q[0]:.3f}-{q[2]:.3f}, NEW faster in {sum(r > 1 for r in ratios)} of {len(ratios)}")


if __name__ == "__main__":
    main()
