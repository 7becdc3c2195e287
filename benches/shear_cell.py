"""The shear cell's figure: the curves of `powderfmu bed shear` and the yield locus with its Mohr circles.

Reads the CSV (`--out`) and the text the command printed (its stderr, saved beside the CSV) of one run
or more (e.g. two drive speeds on one bed), and draws: the shear stress on the plane against the upper
ring's travel for the preshear and each shear to failure; and the points (sigma, tau_peak) with their
standard errors, the fitted locus, the Mohr circle through the origin tangent to it (sigma_c), the
preshear point and, where it exists, the steady-state circle (sigma_1). Nothing is fitted here: the
numbers are the command's.

Usage: .venv/bin/python benches/shear_cell.py OUT.png RUN.csv:RUN.log[:LABEL] [...]
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
    points = [(float(s), float(se), float(t), float(te))
              for s, se, t, te in re.findall(rf"on the plane sigma {NUM} \+- {NUM} Pa, tau_peak {NUM} \+- {NUM} Pa", text)]
    pre = re.search(rf"on the plane sigma {NUM} \+- {NUM} Pa, tau {NUM} \+- {NUM} Pa", text)
    locus = re.search(rf"c = {NUM} \+- {NUM} Pa, phi_i = {NUM} \+- {NUM} deg", text)
    sc = re.search(rf"sigma_c = {NUM} \+- {NUM} Pa", text)
    s1 = re.search(rf"sigma_1 = {NUM} \+- {NUM} Pa", text)
    return {
        "points": points,
        "preshear": (float(pre.group(1)), float(pre.group(3))) if pre else None,
        "c": float(locus.group(1)) if locus else None,
        "phi": math.radians(float(locus.group(3))) if locus else None,
        "sigma_c": float(sc.group(1)) if sc else None,
        "sigma_1": float(s1.group(1)) if s1 else None,
    }


def circle(ax, centre, radius, **kw):
    t = [math.pi * k / 100 for k in range(101)]
    ax.plot([centre + radius * math.cos(a) for a in t], [radius * math.sin(a) for a in t], **kw)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    out, runs = sys.argv[1], sys.argv[2:]
    fig, (left, right) = plt.subplots(1, 2, figsize=(14, 5.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, run in enumerate(runs):
        parts = run.split(":")
        path, log = parts[0], parts[1]
        label = parts[2] if len(parts) > 2 else path
        rows = list(csv.DictReader(open(path)))
        r = reading(log)
        style = "-" if k == 0 else "--"
        groups = {}
        for row in rows:
            groups.setdefault((row["phase"], row["normal_stress_target_Pa"]), []).append(row)
        for g, ((phase, target), rs) in enumerate(groups.items()):
            # One run: a colour per phase. Several: a colour per run, so the runs can be told apart.
            c = colours[g % len(colours)] if len(runs) == 1 else colours[k % len(colours)]
            if len(runs) > 1:
                name = "preshear and shears"
            else:
                name = f"{phase} {float(target) / 1e3:.1f} kPa"
            left.plot([float(x["displacement_m"]) * 1e3 for x in rs], [float(x["shear_stress_Pa"]) / 1e3 for x in rs], "-", color=c, lw=1,
                      label=f"{name} ({label})" if len(runs) == 1 or g == 0 else None)
        c = colours[k % len(colours)]
        sig = [p[0] / 1e3 for p in r["points"]]
        right.errorbar(sig, [p[2] / 1e3 for p in r["points"]], xerr=[p[1] / 1e3 for p in r["points"]], yerr=[p[3] / 1e3 for p in r["points"]],
                       fmt="o", color=c, label=f"incipient flow ({label})")
        if r["preshear"]:
            right.plot([r["preshear"][0] / 1e3], [r["preshear"][1] / 1e3], "s", color=c, mfc="none", ms=9, label=f"preshear ({label})")
        if r["c"] is not None:
            top = 1.3 * max(sig + [r["preshear"][0] / 1e3 if r["preshear"] else 0.0])
            right.plot([0, top], [r["c"] / 1e3, (r["c"] + math.tan(r["phi"]) * top * 1e3) / 1e3], style, color=c, lw=1,
                       label=f"locus: c = {r['c'] / 1e3:.2f} kPa, phi_i = {math.degrees(r['phi']):.1f} deg")
        if r["sigma_c"]:
            circle(right, r["sigma_c"] / 2e3, r["sigma_c"] / 2e3, color=c, lw=0.8, ls=":", label=f"sigma_c = {r['sigma_c'] / 1e3:.2f} kPa")
        if r["sigma_1"] and r["c"] is not None:
            phi = r["phi"]
            # The steady-state circle: centre p with radius c cos(phi) + p sin(phi) and right end sigma_1.
            p = (r["sigma_1"] - r["c"] * math.cos(phi)) / (1 + math.sin(phi))
            circle(right, p / 1e3, (r["sigma_1"] - p) / 1e3, color=c, lw=0.8, ls="-.", label=f"sigma_1 = {r['sigma_1'] / 1e3:.1f} kPa")
    left.set_xlabel("travel of the upper ring [mm]")
    left.set_ylabel("shear stress on the plane, Bagi's in the slab [kPa]")
    left.set_title("preshear and shears to failure")
    left.legend(fontsize=7)
    right.set_xlabel("normal stress on the plane [kPa]")
    right.set_ylabel("shear stress [kPa]")
    right.set_title("yield locus and Mohr circles (004 Sec. 2.2)")
    right.set_xlim(left=0)
    right.set_ylim(bottom=0)
    right.set_aspect("equal", adjustable="datalim")
    right.legend(fontsize=7, loc="center left", bbox_to_anchor=(1.02, 0.5))
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"written {out}")


if __name__ == "__main__":
    main()
