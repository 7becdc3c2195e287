"""Is the steady state's Mohr circle tangent to the yield locus? The figure of the shears near sigma_pre.

Jenike's construction (004 Sec. 2.2, Fig. 2.7) draws the steady-state circle through the preshear point
tangent to the yield locus, so the locus is assumed to end at the preshear point. This draws, for one
preshear, the shear points of a run at 003's fractions (the locus the tool fits through them, extended)
beside the points of a run sheared close to sigma_pre from the same preshear, and the curves of the
latter against tau_pre. Nothing is fitted here: the numbers are the command's (`powderfmu bed shear`).
The two runs must share their preshear (the same bed, one thread, or `--from-preshear`): the script
refuses two different preshear readings.

Usage: .venv/bin/python benches/shear_tangency.py OUT.png LOW.txt NEAR.txt NEAR.csv "TITLE" [MORE.txt]

MORE.txt, a third reading of the same preshear, is where the steady preshear read as a shear point is
taken from when neither LOW nor NEAR prints it (runs of a binary before that line).
"""

import csv
import math
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

NUM = r"([-+0-9.e]+)"


def reading(log):
    text = open(log).read()
    points = [tuple(float(x) for x in m)
              for m in re.findall(rf"on the plane sigma {NUM} \+- {NUM} Pa, tau_peak {NUM} \+- {NUM} Pa", text)]
    head = re.search(rf"preshear at {NUM} Pa", text)
    targets = [float(t) for t in re.findall(rf"shear cell: sigma_n {NUM} Pa:", text)]
    pre = re.search(rf"preshear steady state on the plane sigma {NUM} \+- {NUM} Pa, tau {NUM} \+- {NUM} Pa", text)
    like = re.search(rf"read as the shears read tau_peak [^:]*: {NUM} \+- {NUM} Pa", text)
    locus = re.search(rf"c = {NUM} \+- {NUM} Pa, phi_i = {NUM} \+- {NUM} deg", text)
    if not pre or not points or not head:
        sys.exit(f"{log}: no preshear reading or no shear points (the text `powderfmu bed shear` prints)")
    return {
        "points": points,
        "fractions": [t / float(head.group(1)) for t in targets],
        "preshear": tuple(float(pre.group(k)) for k in (1, 2, 3, 4)),
        "like": (float(like.group(1)), float(like.group(2))) if like else None,
        "locus": (float(locus.group(1)), math.radians(float(locus.group(3)))) if locus else None,
    }


def main():
    if len(sys.argv) not in (6, 7):
        sys.exit(__doc__)
    out, low_log, near_log, near_csv, title = sys.argv[1:6]
    low, near = reading(low_log), reading(near_log)
    more = reading(sys.argv[6]) if len(sys.argv) == 7 else near
    for other in (near, more):
        if low["preshear"] != other["preshear"]:
            sys.exit(f"the runs have different preshears: {low['preshear']} and {other['preshear']}")
    s_pre, s_pre_e, t_pre, t_pre_e = low["preshear"]
    kpa = 1e-3
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.4))
    span = lambda r: f"shears at {min(r['fractions']):.2f}-{max(r['fractions']):.2f} sigma_pre"  # noqa: E731
    for pts, style, label in [(low["points"], "o", span(low)), (near["points"], "s", span(near))]:
        left.errorbar([p[0] * kpa for p in pts], [p[2] * kpa for p in pts], xerr=[p[1] * kpa for p in pts],
                      yerr=[p[3] * kpa for p in pts], fmt=style, capsize=3, label=label)
    left.errorbar([s_pre * kpa], [t_pre * kpa], xerr=[s_pre_e * kpa], yerr=[t_pre_e * kpa], fmt="*", ms=14,
                  color="k", capsize=3, label="preshear (steady flow): sigma_pre, tau_pre")
    like = near["like"] or low["like"] or more["like"]
    if like:
        left.errorbar([s_pre * kpa], [like[0] * kpa], yerr=[like[1] * kpa], fmt="*", ms=14, mfc="none", color="k",
                      capsize=3, label="the steady preshear read as a shear point (largest window mean per shear's travel)")
    if low["locus"]:
        c, phi = low["locus"]
        xs = [0.0, 1.1 * s_pre]
        left.plot([x * kpa for x in xs], [(c + x * math.tan(phi)) * kpa for x in xs], "--", color="C0",
                  label=f"locus through the {span(low)}: c {c * kpa:.2f} kPa, phi_i {math.degrees(phi):.1f} deg")
    left.set_xlim(0, 1.15 * s_pre * kpa)
    left.set_ylim(0, None)
    left.set_xlabel("normal stress on the shear plane sigma [kPa]")
    left.set_ylabel("shear stress on the plane tau [kPa]")
    left.set_title("points on the plane (Bagi's slab), +- one standard error")
    left.legend(fontsize=8, loc="lower right")
    left.grid(alpha=0.3)

    rows = list(csv.DictReader(open(near_csv)))
    pre = [r for r in rows if r["phase"] == "preshear"]
    targets = sorted({r["normal_stress_target_Pa"] for r in rows if r["phase"] == "shear"}, key=float)
    for k, t in enumerate(targets):
        s = [r for r in rows if r["phase"] == "shear" and r["normal_stress_target_Pa"] == t]
        right.plot([float(r["displacement_m"]) * 1e3 for r in s], [float(r["shear_stress_Pa"]) * kpa for r in s],
                   lw=0.9, color=f"C{k + 1}", label=f"shear at sigma_n {float(t) * kpa:.1f} kPa ({float(t) / float(pre[0]['normal_stress_target_Pa']):.2f} sigma_pre)")
    right.axhspan((t_pre - 2 * t_pre_e) * kpa, (t_pre + 2 * t_pre_e) * kpa, color="k", alpha=0.15,
                  label=f"tau_pre +- 2 standard errors ({t_pre * kpa:.2f} kPa)")
    right.set_xlabel("travel of the upper ring in the shear [mm]")
    right.set_ylabel("tau on the plane [kPa]")
    right.set_title("the shears near sigma_pre against the steady flow's tau_pre")
    right.legend(fontsize=8, loc="lower right")
    right.grid(alpha=0.3)
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
