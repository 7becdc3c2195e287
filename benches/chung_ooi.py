"""Chung and Ooi's Test 4 (Granular Matter 13 (2011) 643-656): an aluminium oxide sphere hits a rigid plane
at 3.9 m/s and incident angles 1-89 deg (Hertz-Mindlin, mu = 0.092, elastic). For each angle: the
tangential restitution v_t2/v_t1, the spin after, the rebound angle of the centre and, normalised as
Maw, Barber and Fawcett do, the contact point's rebound Psi_2 against the incidence Psi_1 (Psi =
2 (1 - nu) / (mu (2 - nu)) times the contact point's tangential over the incident normal velocity).
Ours with both levers (`powderfmu oblique --lever mid-overlap|radius`), LAMMPS's `fix wall/gran granular
hertz/material ... tangential mindlin/force` every 5 deg where `lmp` is installed, and the closed form of
gross sliding (Delta v_t = mu (1 + e) v_n, omega R = 5/2 Delta v_t, Psi_2 = Psi_1 - 4 chi).

    python benches/chung_ooi.py [--plot docs/figures/chung_ooi_test4.png] [--csv docs/data/chung_ooi_test4.csv]
"""

import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.join(HERE, "..")
sys.path.insert(0, os.path.join(REPO, "tests", "python"))
CLI = os.environ.get("POWDERFMU_CLI", os.path.join(REPO, "target", "release", "powderfmu"))
SCENE = os.path.join(REPO, "scenes", "chung_ooi_alumina.json")
SPEED, RADIUS, MU, NU = 3.9, 2.5e-3, 0.092, 0.23
NORM = 2 * (1 - NU) / (MU * (2 - NU))
CHI = (1 - NU) / (2 - NU) * (1 + 1 / 0.4)


def ours(angles, lever):
    out = subprocess.run([CLI, "oblique", SCENE, "--speed", str(SPEED), "--angles", ",".join(map(str, angles)), "--lever", lever],
                         capture_output=True, text=True, check=True).stdout
    return list(csv.DictReader(out.splitlines()))


def lammps(theta):
    from test_peers import lammps_oblique  # noqa: E402 (the same input and mapping as the peer test)

    return lammps_oblique(theta, "mindlin/force")


def psi(v_t, omega, v_n1):
    return NORM * (v_t - RADIUS * omega) / v_n1


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plot")
    p.add_argument("--csv")
    a = p.parse_args()
    angles = list(range(1, 90))
    rows = []
    for lever in ("mid-overlap", "radius"):
        for r in ours(angles, lever):
            theta = float(r["incident_angle_deg"])
            v_n1, v_t1 = float(r["normal_velocity_in_m_per_s"]), float(r["tangential_velocity_in_m_per_s"])
            v_t2, w2 = float(r["tangential_velocity_out_m_per_s"]), float(r["angular_velocity_out_rad_per_s"])
            rows.append({"code": f"powderfmu ({lever})", "incident_angle_deg": theta, "tangential_restitution": v_t2 / v_t1,
                         "angular_velocity_rad_per_s": w2, "rebound_angle_deg": float(r["rebound_angle_deg"]),
                         "psi1": psi(v_t1, 0.0, v_n1), "psi2": psi(v_t2, w2, v_n1)})
    if shutil.which("lmp"):
        for theta in range(5, 90, 5):
            vx, vz, wy = lammps(float(theta))
            v_n1, v_t1 = SPEED * math.cos(math.radians(theta)), SPEED * math.sin(math.radians(theta))
            rows.append({"code": "LAMMPS mindlin/force", "incident_angle_deg": theta, "tangential_restitution": vx / v_t1,
                         "angular_velocity_rad_per_s": wy, "rebound_angle_deg": math.degrees(math.atan2(vx, vz)),
                         "psi1": psi(v_t1, 0.0, v_n1), "psi2": psi(vx, wy, v_n1)})
    else:
        print("lmp not found: LAMMPS's points left out", file=sys.stderr)
    if a.csv:
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(rows[0]))
            w.writeheader()
            for r in rows:
                w.writerow({k: (f"{v:.10g}" if isinstance(v, float) else v) for k, v in r.items()})
    # The largest gaps between our radius lever and LAMMPS, per regime.
    by = {(r["code"], r["incident_angle_deg"]): r for r in rows}
    for theta in range(5, 90, 5):
        l, o = by.get(("LAMMPS mindlin/force", theta)), by.get(("powderfmu (radius)", float(theta)))
        if l and o:
            print(f"{theta:2d} deg: e_t {o['tangential_restitution']:.6f} vs LAMMPS {l['tangential_restitution']:.6f}, "
                  f"omega {o['angular_velocity_rad_per_s']:.3f} vs {l['angular_velocity_rad_per_s']:.3f} rad/s")
    if a.plot:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, ax = plt.subplots(2, 2, figsize=(11, 8))
        th = [t / 10 for t in range(10, 900)]
        sliding = [t for t in th if NORM * math.tan(math.radians(t)) >= 4 * CHI - 1]
        v_n = [SPEED * math.cos(math.radians(t)) for t in sliding]
        closed_et = [1 - MU * 2 / math.tan(math.radians(t)) for t in sliding]
        closed_w = [2.5 * MU * 2 * vn / RADIUS for vn in v_n]
        styles = {"powderfmu (mid-overlap)": dict(color="C0", lw=2), "powderfmu (radius)": dict(color="C1", lw=1, ls="--"),
                  "LAMMPS mindlin/force": dict(color="k", marker="o", ls="none", ms=4)}
        for code, st in styles.items():
            rs = [r for r in rows if r["code"] == code]
            if not rs:
                continue
            x = [r["incident_angle_deg"] for r in rs]
            ax[0, 0].plot(x, [r["tangential_restitution"] for r in rs], label=code, **st)
            ax[0, 1].plot(x, [r["angular_velocity_rad_per_s"] for r in rs], label=code, **st)
            ax[1, 0].plot(x, [r["rebound_angle_deg"] for r in rs], label=code, **st)
            ax[1, 1].plot([r["psi1"] for r in rs], [r["psi2"] for r in rs], label=code, **st)
        ax[0, 0].plot(sliding, closed_et, color="C3", lw=1, ls=":", label="gross sliding, closed form")
        ax[0, 1].plot(sliding, closed_w, color="C3", lw=1, ls=":", label="gross sliding, closed form")
        p1 = [4 * CHI - 1 + 0.1 * k for k in range(0, 250)]
        ax[1, 1].plot(p1, [x - 4 * CHI for x in p1], color="C3", lw=1, ls=":", label="gross sliding: Psi_2 = Psi_1 - 4 chi")
        for axis in ax.flat:
            axis.axvline(math.degrees(math.atan((4 * CHI - 1) / NORM)) if axis is not ax[1, 1] else 4 * CHI - 1, color="0.7", lw=0.8)
            axis.grid(alpha=0.3)
        ax[0, 0].set(xlabel="incident angle [deg]", ylabel="tangential restitution v_t2 / v_t1 [-]")
        ax[0, 1].set(xlabel="incident angle [deg]", ylabel="spin after [rad/s]")
        ax[1, 0].set(xlabel="incident angle [deg]", ylabel="rebound angle of the centre [deg]")
        ax[1, 1].set(xlabel="Psi_1 (normalised incidence) [-]", ylabel="Psi_2 (normalised rebound of the contact point) [-]", xlim=(0, 12), ylim=(-6, 8))
        ax[0, 0].legend(fontsize=8)
        fig.suptitle("Chung and Ooi Test 4: alumina on a rigid plane at 3.9 m/s, Hertz-Mindlin, mu = 0.092\n(grey line: gross sliding from here, Psi_1 = 4 chi - 1, 28.3 deg)")
        fig.tight_layout()
        fig.savefig(a.plot, dpi=110)
        print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
