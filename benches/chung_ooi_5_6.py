"""Chung and Ooi's Tests 5 and 6 (Granular Matter 13 (2011) 643-656): oblique impacts on a rigid plane at a
constant normal velocity, the tangential velocity (Test 5) or the spin (Test 6) swept. The benchmarks as
Kratos's DEM application runs them (its DEM3D_chung_ooi_tests): Test 5 a 10 um sphere at v_n = 5 m/s,
mu = 0.3, elastic, steel and polyethylene (scenes/chung_ooi_steel.json, chung_ooi_polyethylene.json);
Test 6 a 0.1 m sphere at v_n = 0.2 m/s with spin and no tangential velocity, mu = 0.4, e_n = 0.5,
aluminium alloy and nylon (scenes/chung_ooi_aluminium_alloy.json, chung_ooi_nylon.json).

Test 5 plots the contact point's rebound V_st' / (mu V_cn') and the spin R omega' / (mu V_cn) against
V_st / (mu V_cn); Test 6 the contact point's tangential restitution beta = -V_st' / V_st against
3.5 mu (1 + e_n) V_cn / V_st and the tangent of the recoil angle V_st' / V_cn' against V_st / V_cn. Beside
ours (the adaptive integrator, converged, and velocity Verlet at 0.01 of the Rayleigh step, what DEM codes
run): LAMMPS's `fix wall/gran ... tangential mindlin/force` at 0.001 of the Rayleigh step (Test 5 and
Test 6's elastic twin: LAMMPS's damping models are not ours), the closed form of gross sliding, Chung and
Ooi's curves for Test 5 (docs/data/chung_ooi_test5_paper.csv) and the spin of a sticking contact whose
tangential period equals the normal one (k_t = 2/7 k_n: R omega' = 10/7 V_st).

    python benches/chung_ooi_5_6.py [--plot5 docs/figures/chung_ooi_test5.png] [--plot6 docs/figures/chung_ooi_test6.png]
                                    [--csv docs/data/chung_ooi_tests_5_6.csv]
"""

import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.join(HERE, "..")
sys.path.insert(0, os.path.join(REPO, "tests", "python"))
CLI = os.environ.get("POWDERFMU_CLI", os.path.join(REPO, "target", "release", "powderfmu"))
TEST5 = {"steel": "chung_ooi_steel.json", "polyethylene": "chung_ooi_polyethylene.json"}
TEST6 = {"aluminium alloy": "chung_ooi_aluminium_alloy.json", "nylon": "chung_ooi_nylon.json"}
ANGLES = [float(a) for a in range(2, 89, 2)]


def scene(name: str) -> dict:
    with open(os.path.join(REPO, "scenes", name)) as f:
        return json.load(f)


def ours(scene_file: str, v_n: float, v_t: float, spin: float, solver: str) -> dict:
    """One impact by `powderfmu oblique` (LAMMPS's lever R, as Kratos and the closed forms take it)."""
    speed, angle = math.hypot(v_n, v_t), math.degrees(math.atan2(v_t, v_n))
    out = subprocess.run([CLI, "oblique", os.path.join(REPO, "scenes", scene_file), "--speed", repr(speed), "--angles", repr(angle),
                          "--angular-velocity", repr(spin), "--lever", "radius", "--solver", solver],
                         capture_output=True, text=True, check=True).stdout
    r = next(csv.DictReader(out.splitlines()))
    return {"v_t": float(r["tangential_velocity_out_m_per_s"]), "v_n": float(r["normal_velocity_out_m_per_s"]),
            "omega": float(r["angular_velocity_out_rad_per_s"]), "slid": r["slid_throughout"] == "true"}


def lammps(s: dict, v_n: float, v_t: float, spin: float) -> dict:
    from test_peers import lammps_for_scene  # noqa: E402 (the peer test's input, mapping and step)

    vx, vz, wy = lammps_for_scene(s, v_n, v_t, spin)
    return {"v_t": vx, "v_n": vz, "omega": wy, "slid": None}


def test5_row(material: str, code: str, s: dict, v_n: float, v_t: float, o: dict) -> dict:
    mu, R = s["friction_coefficient"], s["particle_radius"]
    return {"test": 5, "material": material, "code": code, "incident_angle_deg": math.degrees(math.atan2(v_t, v_n)),
            "x": v_t / (mu * v_n), "contact_rebound": (o["v_t"] - R * o["omega"]) / (mu * o["v_n"]),
            "spin_after": -R * o["omega"] / (mu * v_n), "e_n": o["v_n"] / v_n, "slid_throughout": o["slid"]}


def test6_row(material: str, code: str, s: dict, v_n: float, v_st: float, o: dict) -> dict:
    mu, R = s["friction_coefficient"], s["particle_radius"]
    e_n = o["v_n"] / v_n
    contact_after = o["v_t"] - R * o["omega"]
    return {"test": 6, "material": material, "code": code, "incident_angle_deg": math.degrees(math.atan2(v_st, v_n)),
            "x": 3.5 * mu * (1 + e_n) * v_n / v_st, "beta": -contact_after / v_st, "tan_incidence": v_st / v_n,
            "tan_recoil": contact_after / o["v_n"], "e_n": e_n, "slid_throughout": o["slid"]}


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plot5")
    p.add_argument("--plot6")
    p.add_argument("--csv")
    a = p.parse_args()
    have_lammps = shutil.which("lmp") is not None
    if not have_lammps:
        print("lmp not found: LAMMPS's points left out", file=sys.stderr)
    rows = []
    v_n = 5.0
    for material, f in TEST5.items():
        s = scene(f)
        for angle in ANGLES:
            v_t = v_n * math.tan(math.radians(angle))
            for solver in ("adaptive", "verlet"):
                rows.append(test5_row(material, f"powderfmu {solver}", s, v_n, v_t, ours(f, v_n, v_t, 0.0, solver)))
            if have_lammps and angle % 6 == 0:
                rows.append(test5_row(material, "LAMMPS mindlin/force", s, v_n, v_t, lammps(s, v_n, v_t, 0.0)))
        print(f"Test 5 {material}: done", file=sys.stderr)
    v_n = 0.2
    for material, f in TEST6.items():
        s = scene(f)
        R = s["particle_radius"]
        for angle in ANGLES:
            v_st = v_n * math.tan(math.radians(angle))
            # Spin only: the contact point moves at v_t - R omega = V_st with v_t = 0.
            for solver in ("adaptive", "verlet"):
                rows.append(test6_row(material, f"powderfmu {solver}", s, v_n, v_st, ours(f, v_n, 0.0, -v_st / R, solver)))
            if have_lammps and angle % 6 == 0:
                elastic = s | {"restitution_coefficient": 1.0}
                o = lammps(elastic, v_n, 0.0, -v_st / R)
                rows.append(test6_row(material, "LAMMPS mindlin/force, elastic", elastic, v_n, v_st, o))
                path = os.path.join(REPO, "target", f"chung_ooi_elastic_{f}")
                with open(path, "w") as out:
                    json.dump(elastic, out)
                e = subprocess.run([CLI, "oblique", path, "--speed", repr(v_n), "--angles", "0", "--angular-velocity", repr(-v_st / R),
                                    "--lever", "radius", "--solver", "adaptive"], capture_output=True, text=True, check=True).stdout
                r = next(csv.DictReader(e.splitlines()))
                oe = {"v_t": float(r["tangential_velocity_out_m_per_s"]), "v_n": float(r["normal_velocity_out_m_per_s"]),
                      "omega": float(r["angular_velocity_out_rad_per_s"]), "slid": r["slid_throughout"] == "true"}
                rows.append(test6_row(material, "powderfmu adaptive, elastic", elastic, v_n, v_st, oe))
        print(f"Test 6 {material}: done", file=sys.stderr)
    if a.csv:
        # Test 5's columns, then Test 6's: first seen, first written.
        fields = list(dict.fromkeys(k for r in rows for k in r))
        with open(a.csv, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            for r in rows:
                w.writerow({k: (f"{v:.8g}" if isinstance(v, float) else v) for k, v in r.items()})
        print(f"wrote {a.csv}")
    # The gaps that matter, printed: ours (adaptive) against LAMMPS (0.001 Rayleigh), and Verlet against adaptive.
    by = {(r["test"], r["material"], r["code"], round(r["incident_angle_deg"], 6)): r for r in rows}
    for (t, m, code, ang), r in sorted(by.items()):
        if code.startswith("LAMMPS"):
            twin = "powderfmu adaptive" if t == 5 else "powderfmu adaptive, elastic"
            o = by[(t, m, twin, ang)]
            key = "spin_after" if t == 5 else "beta"
            print(f"Test {t} {m:15s} {ang:5.1f} deg: {key} {o[key]: .6f} (ours) {r[key]: .6f} (LAMMPS)")
    for t, key in ((5, "spin_after"), (6, "beta")):
        gaps = [abs(r[key] - by[(t, r["material"], "powderfmu adaptive", round(r["incident_angle_deg"], 6))][key])
                for r in rows if r["test"] == t and r["code"] == "powderfmu verlet"]
        print(f"Test {t}: Verlet at 0.01 Rayleigh against adaptive, largest |gap| in {key}: {max(gaps):.2e}")
    if a.plot5 or a.plot6:
        plot(rows, a.plot5, a.plot6)


def plot(rows, plot5, plot6):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    colours = {"steel": "C0", "polyethylene": "C1", "aluminium alloy": "C0", "nylon": "C1"}
    if plot5:
        fig, ax = plt.subplots(1, 2, figsize=(12, 5))
        for m in TEST5:
            for code, st in (("powderfmu adaptive", dict(lw=2)), ("powderfmu verlet", dict(lw=1, ls="--")),
                             ("LAMMPS mindlin/force", dict(marker="o", ls="none", ms=5, mfc="none"))):
                rs = [r for r in rows if r["test"] == 5 and r["material"] == m and r["code"] == code]
                if rs:
                    kw = dict(color=colours[m], label=f"{m}: {code}") | st
                    ax[0].plot([r["x"] for r in rs], [r["contact_rebound"] for r in rs], **kw)
                    ax[1].plot([r["x"] for r in rs], [r["spin_after"] for r in rs], **kw)
        with open(os.path.join(REPO, "docs", "data", "chung_ooi_test5_paper.csv")) as f:
            paper = list(csv.DictReader(l for l in f if not l.startswith("#")))
        for series, st in (("steel", dict(color="C0", marker="s", ms=4, ls=":")), ("polyethylene", dict(color="C1", marker="^", ms=4, ls=":")),
                           ("FEM", dict(color="k", marker="*", ms=7, ls="none"))):
            ps = [r for r in paper if r["series"] == series]
            ax[1].plot([float(r["incidence"]) for r in ps], [float(r["spin_after"]) for r in ps], label=f"Chung and Ooi: {series}", **st)
        x = [0.05 * k for k in range(0, 401)]
        ax[0].plot(x, [xx - 7 for xx in x], color="C3", lw=1, ls=":", label="gross sliding: x - 7 (e = 1)")
        ax[1].plot(x, [-5.0 for _ in x], color="C3", lw=1, ls=":", label="gross sliding: -5/2 (1 + e)")
        ax[1].plot(x, [max(-10 / 7 * xx, -5.0) for xx in x], color="0.5", lw=1, ls="-.", label="sticking, k_t = 2/7 k_n: -10/7 x")
        ax[0].set(xlabel="V_st / (mu V_cn) [-]", ylabel="V_st' / (mu V_cn') (contact point after) [-]", xlim=(0, 14), ylim=(-4, 8))
        ax[1].set(xlabel="V_st / (mu V_cn) [-]", ylabel="R omega' / (mu V_cn) [-]", xlim=(0, 20), ylim=(-6, 0.5))
        for axis in ax:
            axis.grid(alpha=0.3)
        ax[0].legend(fontsize=7)
        ax[1].legend(fontsize=7, loc="upper right")
        fig.suptitle("Chung and Ooi Test 5: v_n = 5 m/s, tangential velocity swept, Hertz-Mindlin, mu = 0.3, elastic")
        fig.tight_layout()
        fig.savefig(plot5, dpi=110)
        print(f"wrote {plot5}")
    if plot6:
        fig, ax = plt.subplots(1, 2, figsize=(12, 5))
        for m in TEST6:
            for code, st in (("powderfmu adaptive", dict(lw=2)), ("powderfmu verlet", dict(lw=1, ls="--")),
                             ("powderfmu adaptive, elastic", dict(lw=1, ls=":")),
                             ("LAMMPS mindlin/force, elastic", dict(marker="o", ls="none", ms=5, mfc="none"))):
                rs = [r for r in rows if r["test"] == 6 and r["material"] == m and r["code"] == code]
                if rs:
                    kw = dict(color=colours[m], label=f"{m}: {code}") | st
                    ax[0].plot([r["x"] for r in rs], [r["beta"] for r in rs], **kw)
                    ax[1].plot([r["tan_incidence"] for r in rs], [r["tan_recoil"] for r in rs], **kw)
        x = [0.02 * k for k in range(0, 60)]
        ax[0].plot(x, [xx - 1 for xx in x], color="C3", lw=1, ls=":", label="gross sliding: beta = x - 1")
        t = [0.1 * k for k in range(0, 80)]
        ax[1].plot(t, [(tt - 3.5 * 0.4 * 1.5) / 0.5 for tt in t], color="C3", lw=1, ls=":", label="gross sliding, e = 0.5")
        ax[0].set(xlabel="3.5 mu (1 + e_n) V_cn / V_st [-]", ylabel="beta = -V_st' / V_st [-]", xlim=(0, 25), ylim=(-1, 0.8))
        ax[1].set(xlabel="V_st / V_cn (tangent of the incidence) [-]", ylabel="V_st' / V_cn' (tangent of the recoil) [-]", xlim=(0, 7), ylim=(-2, 8))
        for axis in ax:
            axis.grid(alpha=0.3)
        ax[0].legend(fontsize=7)
        fig.suptitle("Chung and Ooi Test 6: v_n = 0.2 m/s, spin swept (no tangential velocity), Hertz-Mindlin, mu = 0.4, e_n = 0.5")
        fig.tight_layout()
        fig.savefig(plot6, dpi=110)
        print(f"wrote {plot6}")


if __name__ == "__main__":
    main()
