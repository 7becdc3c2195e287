"""Throughput of the bed engine against LAMMPS, side by side in one run (issue 6).

One settled bed of 10^4 spheres (benches/bench_bed.json, prepared once with `powderfmu bed prepare
--until settle` and cached in target/bench/) is exported to a LAMMPS data file, and both codes step it
with the same time step, skin and equivalent contact models on one core each:

    linear spring + tangential history   powderfmu `linear`    LAMMPS granular hooke + linear_history
                                                               (and the classic gran/hooke/history)
    Hertz-Mindlin                        powderfmu `hertz`     LAMMPS granular hertz/material + mindlin
    JKR + Mindlin                        powderfmu `jkr`       LAMMPS granular jkr + mindlin
    Nan (000), no LAMMPS equivalent      powderfmu `nan`       compared with powderfmu's Hertz-Mindlin
    simplified Pasha (004), the same     powderfmu             compared with powderfmu's Hertz-Mindlin
                                         `pasha_simplified`    (BallIndentation's default law)

Each measurement is repeated (--repeats, default 3), alternating the two codes, and the medians are
compared. Also printed: the 2-thread speed-up of powderfmu and the memory per particle of both.
Results go to docs/figures/vs_lammps.csv; docs/benchmarks.md quotes them.

--compare BIN times a second powderfmu binary (an earlier build, kept aside) in the same alternation, on
the same bed, so a change of the engine is measured against the code it replaces and against LAMMPS in
one run; its rates go to the CSV's `compared_particle_steps_per_s` column. A build older than the bed's
scene keys reads the same bed rewritten without them (--compare-bed, made by
benches/bed_for_older_build.py); a build without `bed bench --skin` runs at its built-in skin, a tenth
of the mean diameter (1e-4 m here), and is refused with any other --skin.

Usage: bash benches/vs_lammps.sh [--steps N] [--repeats K] [--compare BIN [--compare-bed BED]] [--skin M] [--out CSV]
"""

import argparse
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIN = ROOT / "target" / "release" / "powderfmu"
WORK = ROOT / "target" / "bench"
SCENE = ROOT / "benches" / "bench_bed.json"
BED = WORK / "settled.bed"
DATA = WORK / "bed.data"
LAMMPS_INPUT = ROOT / "benches" / "lammps" / "bed.in"

# The bench bed's material (benches/bench_bed.json: 004 Tables 5.2-5.3 with E = 55 MPa).
E, NU, DENSITY, GAMMA, E_PP, MU = 55e6, 0.25, 2456.0, 0.5, 0.5, 0.15
E_PW = 0.3
# LAMMPS' wall models take one set of material values for both bodies. Debian's LAMMPS (the 2021-2022
# builds this benchmark runs) forms the wall's E* as E / (2 (1 - nu)), not E / (2 (1 - nu^2)) as its
# pair styles do (checked contact by contact in an independent LAMMPS run; docs/porting.md): this E gives
# the E* powderfmu's particle-wall laws have against the steel die (1/E* = (1-nu^2)/E + (1-nu_w^2)/E_w).
# The mapping of the first runs used (1 - nu^2) and made the walls 1.25 times too stiff.
E_STAR_WALL = 1.0 / ((1 - NU**2) / E + (1 - 0.3**2) / 182e9)
E_WALL, NU_WALL = 2 * (1 - NU) * E_STAR_WALL, NU
KN = 1000.0  # linear spring [N/m]: about the Hertz stiffness of these contacts, so the step is the same
KT = KN * 2 * (1 - NU) / (2 - NU)  # powderfmu's k_t = 4 G*/E* k_n for two equal spheres (000 Eq. 22)
# Both codes' Verlet skin: a tenth of the mean diameter, powderfmu's default. --skin sets another (issue
# 30's eleventh round: 2.5e-5 made powderfmu 1.05-1.13 times faster, LAMMPS not; docs/benchmarks.md).
SKIN = 1e-4
DIE_RADIUS = 0.0195


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def ensure_lammps():
    lmp = shutil.which("lmp")
    if lmp is None:
        print("LAMMPS not found: installing Debian's package `lammps` ...", flush=True)
        sudo = [] if os.geteuid() == 0 else ["sudo"]
        subprocess.run(sudo + ["apt-get", "install", "-y", "lammps"], check=True, stdout=subprocess.DEVNULL)
        lmp = shutil.which("lmp")
    if lmp is None:
        sys.exit("vs_lammps: `lmp` is still missing after installing lammps")
    return lmp


def ensure_bed():
    WORK.mkdir(parents=True, exist_ok=True)
    if not BED.exists():
        print(f"preparing the bench bed once ({SCENE.name}, 10^4 spheres, fill + settle; a few minutes) ...", flush=True)
        subprocess.run([str(BIN), "bed", "prepare", str(SCENE), "-o", str(BED), "--until", "settle"], check=True)
    run([str(BIN), "bed", "export-lammps", str(BED), str(DATA)])


ADHESIVE = {"jkr", "jkr_modified", "nan", "pasha_simplified"}
CONTACTS = {}  # force-carrying particle contacts per particle at the end of the last run of each model


def powderfmu(model, steps, threads=1, binary=BIN, bed=None, skin=True):
    gamma = GAMMA if model in ADHESIVE else 0.0
    cmd = [str(binary), "bed", "bench", str(bed or BED), "--model", model, "--steps", str(steps), "--threads", str(threads),
           "--stiffness", str(KN), "--surface-energy", str(gamma), "--rolling-friction", "0"]
    out = run(cmd + (["--skin", str(SKIN)] if skin else [])).stdout
    fields = dict(kv.split("=", 1) for kv in out.split())
    CONTACTS[model] = float(fields["contacts_per_particle"])
    return float(fields["particle_steps_per_s"]), float(fields["dt"]), float(fields["bytes_per_particle"]), int(fields["particles"])


def lammps(lmp, model, steps, dt, warmup):
    variables = {
        "data": DATA, "model": model, "steps": steps, "warmup": warmup, "dt": dt, "skin": SKIN,
        # LAMMPS's jkr gamma is the energy per surface, half our interface energy (its pull-off 3 pi gamma R*).
        "kn": KN, "kt": KT, "xt": 1.0, "E": E, "nu": NU, "gamma": GAMMA / 2, "e": E_PP, "mu": MU,
        "Ew": E_WALL, "nuw": NU_WALL, "ew": E_PW, "die_radius": DIE_RADIUS,
        # gran/hooke/history damps with gamma_n m_eff: 2 gamma(e) sqrt(k/m) at the mean pair mass.
        "gamman": 2 * 0.2155 * (KN / (0.5 * DENSITY * 3.14159 / 6 * 1e-9)) ** 0.5, "gammat": 0.0,
    }
    cmd = [lmp, "-in", str(LAMMPS_INPUT), "-log", "none", "-screen", "none"]
    for k, v in variables.items():
        cmd += ["-var", k, str(v)]
    log = WORK / f"lammps_{model}.log"
    cmd[cmd.index("-log") + 1] = str(log)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    run(cmd, env=env, cwd=WORK)
    text = log.read_text()
    loops = re.findall(r"Loop time of ([0-9.eE+-]+) on 1 procs for (\d+) steps with (\d+) atoms", text)
    if not loops:
        sys.exit(f"vs_lammps: no timing in {log}")
    seconds, nsteps, atoms = loops[-1]
    memory = re.findall(r"Per MPI rank memory allocation \(min/avg/max\) = [0-9.]+ \| ([0-9.]+) \| [0-9.]+ Mbytes", text)
    mbytes = float(memory[-1]) if memory else float("nan")
    return int(atoms) * int(nsteps) / float(seconds), mbytes * 1e6 / int(atoms), int(atoms)


def main():
    global SKIN
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=2000)
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--compare", type=Path, help="a second powderfmu binary, timed alongside this build")
    ap.add_argument("--compare-bed", type=Path, help="the bed the --compare build reads (default: the same bed)")
    ap.add_argument("--skin", type=float, default=SKIN, help="the Verlet skin of both codes [m] (default 1e-4, a tenth of the mean diameter)")
    ap.add_argument("--out", type=Path, default=ROOT / "docs" / "figures" / "vs_lammps.csv", help="the CSV to write")
    args = ap.parse_args()
    SKIN = args.skin
    if args.compare is not None and not os.access(args.compare, os.X_OK):
        sys.exit(f"vs_lammps: --compare {args.compare}: not an executable file")
    compare_skin = args.compare is not None and "--skin" in run([str(args.compare), "bed", "bench", "--help"]).stdout
    if args.compare is not None and not compare_skin and SKIN != 1e-4:
        sys.exit(f"vs_lammps: --compare {args.compare} has no `bed bench --skin` (it runs at 1e-4 m); --skin {SKIN:g} cannot be compared")
    lmp = ensure_lammps()
    ensure_bed()
    version = run([lmp, "-h"]).stdout.splitlines()[1].strip() if run([lmp, "-h"]).stdout else "?"
    print(f"bed: {BED.relative_to(ROOT)}; {args.steps} steps per run, medians of {args.repeats}; skin {SKIN:g} m; LAMMPS: {version}")
    rows = []
    results = {}
    for name, ours, theirs in [("linear spring + tangential history", "hooke", ["hooke", "hooke_classic"]),
                               ("Hertz-Mindlin", "hertz", ["hertz"]),
                               ("JKR + Mindlin", "jkr", ["jkr"]),
                               ("Nan", "nan", []),
                               ("simplified Pasha", "pasha_simplified", [])]:
        mine, peer, other = [], {t: [] for t in theirs}, []
        for _ in range(args.repeats):
            rate, dt, bytes_ours, n = powderfmu(ours, args.steps)
            mine.append(rate)
            if args.compare is not None:
                other.append(powderfmu(ours, args.steps, binary=args.compare, bed=args.compare_bed, skin=compare_skin)[0])
            for t in theirs:
                rate_l, bytes_lammps, atoms = lammps(lmp, t, args.steps, dt, 200)
                assert atoms == n, f"LAMMPS read {atoms} atoms, the bed has {n}"
                peer[t].append(rate_l)
        x = statistics.median(mine)
        results[ours] = x
        compared = f"{statistics.median(other):.4e}" if other else ""
        if other:
            print(f"{ours}: this build {x:.3e}, --compare build {statistics.median(other):.3e} particle-steps/s, ratio {x / statistics.median(other):.3f}")
        if theirs:
            best = max(theirs, key=lambda t: statistics.median(peer[t]))
            y = statistics.median(peer[best])
            print(f"{ours}: powderfmu {x:.3e}, LAMMPS {y:.3e} particle-steps/s, ratio {x / y:.2f}"
                  f"   ({name}; {CONTACTS[ours]:.2f} contacts per particle; LAMMPS {best}"
                  f"{'; ' + ', '.join(f'{t} {statistics.median(peer[t]):.3e}' for t in theirs) if len(theirs) > 1 else ''})")
            rows.append([ours, name, f"{x:.4e}", f"{y:.4e}", f"{x / y:.3f}", best, f"{bytes_ours:.0f}", f"{bytes_lammps:.0f}", f"{dt:.4e}", f"{CONTACTS[ours]:.3f}", compared])
        else:
            h = results["hertz"]
            per_contact = (x * CONTACTS[ours]) / (h * CONTACTS["hertz"])
            print(f"{ours}: powderfmu {x:.3e} particle-steps/s, powderfmu Hertz-Mindlin {h:.3e}, ratio {x / h:.2f}   ({name}, no LAMMPS equivalent;"
                  f" {CONTACTS[ours]:.2f} contacts per particle against Hertz's {CONTACTS['hertz']:.2f}: contact-steps per second, ratio {per_contact:.2f})")
            rows.append([ours, name, f"{x:.4e}", f"{h:.4e}", f"{x / h:.3f}", "powderfmu hertz", f"{bytes_ours:.0f}", "", f"{dt:.4e}", f"{CONTACTS[ours]:.3f}", compared])
    for model in ["jkr_modified", "hertz"]:
        one, two = [], []
        for _ in range(args.repeats):
            one.append(powderfmu(model, args.steps, 1)[0])
            two.append(powderfmu(model, args.steps, 2)[0])
        speedup = statistics.median(two) / statistics.median(one)
        print(f"2-thread speed-up ({model}): {speedup:.2f} ({statistics.median(one):.3e} -> {statistics.median(two):.3e} particle-steps/s)")
        rows.append([f"{model}_2_threads", "2-thread speed-up", f"{statistics.median(two):.4e}", f"{statistics.median(one):.4e}", f"{speedup:.3f}", "powderfmu 1 thread", "", "", "", "", ""])
    print(f"memory: powderfmu {rows[1][6]} bytes per particle (engine arrays, Hertz-Mindlin, 1 thread), LAMMPS {rows[1][7]} bytes per particle (its per-rank allocation)")
    out = args.out
    with open(out, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["model", "name", "powderfmu_particle_steps_per_s", "reference_particle_steps_per_s", "ratio", "reference",
                    "powderfmu_bytes_per_particle", "lammps_bytes_per_particle", "dt_s", "contacts_per_particle", "compared_particle_steps_per_s"])
        w.writerows(rows)
    print(f"written {out}")


if __name__ == "__main__":
    main()
