"""The powderfmu demonstration: the ParticleWallImpact FMU on the default scene (000 Table 5, an ammonium
fluorescein sphere of radius 2.45 um on silicon, Nan's law, undamped), run through fmpy as a user would.

Prints the rebound of one impact against the energy balance, the sticking velocity found by bisection on
the FMU against 000 Table 6, and a restitution curve; then runs the BallIndentation FMU's default test
(004 Sec. 2.3.5 on the seed's bed of 004 Ch. 6) with no arguments and prints its hardness against the
full-fidelity run at the seed's own speed, and the UnconfinedCompression FMU's (004 Sec. 2.1 on a
specimen of the same material) with its sigma_c, ff_c and H / sigma_c; runs the units inside a system
model (the ultrasonic sieve of docs/system.md); writes the plots to
out/demo/ (PNG).

Usage: python tools/demo.py [--fmu-dir target/fmu] [--cli target/release/powderfmu] [--out out/demo]
"""

import argparse
import json
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from fmpy import read_model_description, simulate_fmu  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENE = os.path.join(ROOT, "scenes", "ammonium_fluorescein_on_silicon.json")


def impact(fmu, v, fmi_type="CoSimulation", interval=2e-10, stop=3e-7, **start):
    """One impact at approach speed v [m/s]; returns fmpy's result array."""
    start_values = {"initial_velocity": v, **start}
    return simulate_fmu(
        fmu,
        fmi_type=fmi_type,
        stop_time=stop,
        output_interval=interval,
        start_values=start_values,
        relative_tolerance=1e-8 if fmi_type == "ModelExchange" else None,
        output=["force", "overlap", "contact_state", "sphere_velocity", "max_overlap", "dissipated_energy", "plastic_overlap"],
    )


def rebounds(fmu, v, stop=4e-7):
    """True when the sphere leaves the wall, False when it falls back (sticks). A sphere just above the
    sticking velocity leaves slowly, so an undecided run is repeated four times longer."""
    while True:
        r = impact(fmu, v, interval=2e-9, stop=stop)
        u = r["sphere_velocity"]
        moving_away = np.nonzero(u > 0)[0]
        if len(moving_away) and np.any(u[moving_away[0]:] < 0):
            return False  # turned back toward the wall in the adhesive well
        if u[-1] > 0 and r["overlap"][-1] < 0 and r["contact_state"][-1] == 0:
            return True
        stop *= 4


def sticking_velocity(fmu, lo=0.5, hi=5.0, rel=1e-4):
    """Bisection on initial_velocity between a sticking and a rebounding impact."""
    assert not rebounds(fmu, lo) and rebounds(fmu, hi)
    while hi - lo > rel * hi:
        mid = 0.5 * (lo + hi)
        if rebounds(fmu, mid):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


def energy_balance(cli, v):
    out = subprocess.run([cli, "analyze", "--json", SCENE, "--velocity", str(v)], check=True, capture_output=True, text=True).stdout
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fmu-dir", default=os.path.join(ROOT, "target", "fmu"))
    ap.add_argument("--cli", default=os.path.join(ROOT, "target", "release", "powderfmu"))
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "demo"))
    a = ap.parse_args()
    fmu = os.path.join(a.fmu_dir, "ParticleWallImpact.fmu")
    os.makedirs(a.out, exist_ok=True)
    print(f"powderfmu demonstration: {fmu}")
    print("scene: 000 Table 5, ammonium fluorescein (R = 2.45 um) on silicon, nan law, p_y = 30 MPa, Gamma = 0.24 J/m^2, undamped")

    v = 3.0
    t0 = time.perf_counter()
    cs = impact(fmu, v)
    t_cs = time.perf_counter() - t0
    t0 = time.perf_counter()
    me = impact(fmu, v, fmi_type="ModelExchange")
    t_me = time.perf_counter() - t0
    ref = energy_balance(a.cli, v)
    e_cs = cs["sphere_velocity"][-1] / v
    e_me = me["sphere_velocity"][-1] / v
    m = ref["effective_mass"]
    print(f"\nimpact at {v} m/s")
    print(f"  restitution  CS (exact) {e_cs:.7f}  ME (CVode, rtol 1e-8) {e_me:.7f}  energy balance {ref['restitution']:.7f}")
    print(f"  max overlap  {cs['max_overlap'][-1] * 1e9:.3f} nm (energy balance {ref['max_overlap'] * 1e9:.3f} nm), plastic overlap {cs['plastic_overlap'][-1] * 1e9:.3f} nm")
    print(f"  dissipated   {cs['dissipated_energy'][-1]:.4e} J = 1/2 m (v_in^2 - v_out^2) = {0.5 * m * (v * v - cs['sphere_velocity'][-1] ** 2):.4e} J")
    print(f"  wall time    CS {t_cs * 1e3:.0f} ms, ME {t_me * 1e3:.0f} ms (fmpy.simulate_fmu, 1500 output points)")

    t0 = time.perf_counter()
    v_ys = sticking_velocity(fmu)
    print(f"\nsticking velocity (bisection on the FMU, {time.perf_counter() - t0:.1f} s): {v_ys:.4f} m/s;"
          f" closed form (000 Eqs. 78-79) {ref['sticking_velocity']:.4f} m/s; 000 Table 6 prints 1.86 m/s")

    fmi3_demo(a.fmu_dir, v, cs)

    speeds = np.concatenate([np.linspace(0.5, 1.8, 5), np.linspace(1.87, 8.0, 14)])
    e = []
    for s in speeds:
        r = impact(fmu, s, interval=1e-8, stop=4e-7)
        e.append(max(r["sphere_velocity"][-1], 0.0) / s if r["overlap"][-1] < 0 else 0.0)
    print("\nrestitution through the FMU (impact velocity [m/s]: coefficient of restitution [-], 0 where the sphere sticks):")
    print("  " + "  ".join(f"{s:.2f}:{x:.3f}" for s, x in zip(speeds, e)))

    fig, ax = plt.subplots(1, 3, figsize=(15, 4.4))
    ax[0].plot(cs["overlap"] * 1e9, cs["force"] * 1e6, lw=1.5)
    ax[0].axhline(0, color="0.6", lw=0.6)
    ax[0].set(xlabel="overlap [nm]", ylabel="force [uN]", title=f"force-overlap loop, impact at {v} m/s")
    ax[0].set_xlim(-30, cs["max_overlap"][-1] * 1e9 * 1.05)
    ax[1].plot(cs["time"] * 1e9, cs["overlap"] * 1e9, label="overlap [nm]")
    ax[1].plot(cs["time"] * 1e9, cs["force"] * 1e6, label="force [uN]")
    ax[1].plot(cs["time"] * 1e9, cs["contact_state"] * 10, label="contact_state x 10", lw=0.8)
    ax[1].set(xlabel="time [ns]", title="CS run of ParticleWallImpact")
    ax[1].legend(fontsize=8)
    ax[2].plot(speeds, e, "o-", label="FMU (CS)")
    ax[2].axvline(v_ys, color="C3", ls="--", label=f"sticking velocity {v_ys:.3f} m/s")
    ax[2].set(xlabel="impact velocity [m/s]", ylabel="restitution [-]", title="restitution, undamped Nan law")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(a.out, "impact.png")
    fig.savefig(path, dpi=110)
    paths = [path, sieve_demo(a.fmu_dir, a.out)]
    indentation_plot, plateau, plateau_se = indentation(os.path.join(a.fmu_dir, "BallIndentation.fmu"), a.out)
    paths += [indentation_plot, compression(os.path.join(a.fmu_dir, "UnconfinedCompression.fmu"), a.out, plateau, plateau_se)]
    print("\nplots: " + ", ".join(paths))
    return 0


def fmi3_demo(fmu_dir, v, cs2):
    """The same impact through the FMI 3.0 unit, stepped by a master at 1 ms with early return: each
    change of contact_state ends the step there (docs/fmi3.md)."""
    fmu3 = os.path.join(fmu_dir, "fmi3", "ParticleWallImpact.fmu")
    r = simulate_fmu(fmu3, start_values={"initial_velocity": v}, stop_time=2e-3, output_interval=1e-3,
                          early_return_allowed=True, use_event_mode=True,
                          output=["contact_state", "sphere_velocity", "max_overlap"])
    # Where the fine FMI 2.0 run (0.2 ns output) saw each change of contact_state.
    fine = cs2["time"][1:][np.diff(cs2["contact_state"]) != 0]
    events = [(t, s) for t, s in zip(r["time"], r["contact_state"]) if 0 < t < 1e-3]
    seen, last = [], None
    for t, s in events:
        if s != last:
            seen.append((t, s))
            last = s
    print(f"\nFMI 3.0 ({fmu3}), the impact at {v} m/s stepped at 1 ms with early return:")
    gap = float(next(x.start for x in read_model_description(fmu3).modelVariables if x.name == "initial_gap"))
    print("  step ends inside the first 1 ms step: " + ", ".join(f"{t * 1e9:.4f} ns -> state {s}" for t, s in seen)
          + f"\n  (contact at gap / v = {gap / v * 1e9:.4f} ns in closed form: {abs(seen[0][0] - gap / v) / (gap / v):.1e} relative)")
    print("  the FMI 2.0 run at 0.2 ns output saw the changes within: " + ", ".join(f"{t * 1e9:.1f} ns" for t in fine))
    print(f"  rebound {r['sphere_velocity'][-1]:.10f} m/s (FMI 2.0 CS {cs2['sphere_velocity'][-1]:.10f} m/s),"
          f" max overlap {r['max_overlap'][-1] * 1e9:.4f} nm; the grid goes on at 1 ms: t = {r['time'][-1]:g} s")


def sieve_demo(fmu_dir, out):
    """The units in a system model: the ultrasonic sieve of powderfmu.sieve (docs/system.md) at 35 kHz and
    1.5e6 m/s2, 40 particles of the default powder, and the same at half the step."""
    os.environ.setdefault("POWDERFMU_FMU_DIR", fmu_dir)
    from powderfmu import sieve

    r = sieve.run({"acceleration": 1.5e6})
    fine = sieve.run({"acceleration": 1.5e6, "steps_per_period": 200})
    s = r.system
    print(f"\nultrasonic sieve (python -m powderfmu.sieve): plate {s['plate_mass']:g} kg at {s['frequency']:g} Hz, peak acceleration {s['acceleration']:.3g} m/s2, "
          f"{s['particles']} particles (median R {s['particle_radius'] * 1e6:g} um), {r.wall_time:.2f} s")
    print(f"  detached {int(r.detached.sum())} of {len(r.radius)} (mass fraction {r.detached_mass_fraction:.3f}; quasi-statically expected "
          f"{int((r.quasi_static_threshold < s['acceleration']).sum())}), first at {np.nanmin(r.detach_time) * 1e6:.2f} us; "
          f"smallest detached radius {r.radius[r.detached].min() * 1e6:.2f} um")
    both = r.detached & fine.detached
    print(f"  half the step: {int((r.detached != fine.detached).sum())} particles change side, detachment times move by at most "
          f"{np.abs(r.detach_time[both] - fine.detach_time[both]).max() * 1e9:.0f} ns (one step {1e9 / s['frequency'] / s['steps_per_period']:.0f} ns)")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(12, 4.2))
    a1.plot(r.time * 1e6, r.plate_position * 1e6)
    a1.set(xlabel="time after the drive started [us]", ylabel="plate position [um]", title="the plate (ramped drive, 35 kHz)")
    for t in r.detach_time[r.detached]:
        a1.axvline(t * 1e6, color="C3", lw=0.5, alpha=0.6)
    a2.semilogx(r.radius * 1e6, r.quasi_static_threshold, "o", mfc="none", label="quasi-static threshold F_po/m + g of each particle")
    a2.semilogx(r.radius[r.detached] * 1e6, r.quasi_static_threshold[r.detached], "v", color="C3", label="detached")
    a2.axhline(s["acceleration"], color="k", lw=0.8, label="the drive's peak acceleration")
    a2.set(xlabel="particle radius [um]", ylabel="acceleration [m/s2]", yscale="log", title="who leaves")
    a2.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "sieve.png")
    fig.savefig(path, dpi=110)
    return path


DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs", "data")
# One whole bed at the seed's speed, for the curves; the number compared with is the reference of record.
REFERENCE = os.path.join(DATA, "ch6_indentation", "window", "whole1_g0.01.csv")


def reference_of_record():
    """(mean, its standard error over beds) of the seed's speed on three whole beds, and the quarter beds'
    bed-to-bed scatter s_bed, from docs/data (docs/indentation.md, "What a 5 % interval costs")."""
    import csv

    with open(os.path.join(DATA, "reference_of_record.csv")) as f:
        mean = next(r for r in csv.DictReader(f) if r["bed_fill_seed"] == "mean")
    with open(os.path.join(DATA, "indentation_halfwidth.csv")) as f:
        default = next(r for r in csv.DictReader(f) if "(the default)" in r["setting"])
    return float(mean["plateau_Pa"]), float(mean["own_standard_error_Pa"]), float(default["s_bed_Pa"])


def indentation(fmu, out):
    """The BallIndentation FMU's default test through fmpy with no arguments; prints and plots it against
    the full-fidelity run at the seed's speed (gamma* = 0.01, docs/indentation.md)."""
    from fmpy import read_model_description

    md = read_model_description(fmu)
    start = {v.name: v.start for v in md.modelVariables if v.causality == "parameter"}
    d, h_max, v = float(start["indenter_diameter"]), float(start["max_penetration"]), float(start["indentation_speed"])
    print(f"\nball indentation: {fmu}")
    bed = ("a quarter of the seed's bed (resources/bed_quarter.pfbed: 7250 spheres between two mirror planes, 29000 in the whole die, 004 Ch. 6)"
           if start["fidelity"] == "quarter" else "the seed's bed (resources/bed.pfbed: 29000 spheres, 004 Ch. 6)")
    print(f"  {bed}, indenter d = {d * 1e3:.1f} mm to h = {h_max * 1e3:.2f} mm "
          f"(h/r = {2 * h_max / d:.2f}) at {v} m/s, time step {float(start['time_step']):.2e} s, fidelity {start['fidelity']}, "
          f"{start['threads']} threads; running (about 110 s on two cores with AVX2)")
    t0 = time.perf_counter()
    r = simulate_fmu(fmu)
    wall = time.perf_counter() - t0
    last = r[-1]
    print(f"  wall time {wall:.1f} s, {len(r)} output points; test_state at the end {last['test_state']} (2 = done)")
    p0, p1 = float(start["plateau_start"]), float(start["plateau_end"])
    se = last["plateau_hardness_standard_error"]
    s_bed = reference_of_record()[2]
    print(f"  plateau hardness (mean F/A(h) while loading at {p0} <= h/r <= {p1}, the seed's window: 004 Figs. 5.3-5.4, 5.19): {last['plateau_hardness']:.4g} "
          f"+- {se:.2g} Pa (standard error from this run's fluctuations, {last['plateau_samples']} samples; quarter beds differ by a further {s_bed:.0f} Pa: "
          f"docs/data/indentation_halfwidth.csv; replicas = 3 measures it), "
          f"unconfined yield strength plateau / C {last['plateau_hardness'] / float(start['constraint_factor']):.4g} +- {se / float(start['constraint_factor']):.2g} Pa "
          f"(C = {start['constraint_factor']}, taken as exact)")
    how = "from the tangent to the unloading curve" if last["contact_depth_from_tangent"] else "= h_max: the bed let go of the indenter too fast for a tangent"
    print(f"  after unloading: F_max {last['force_at_turn']:.4f} N (the loading curve at the turn; largest output sample "
          f"{r['indenter_force'].max():.4f} N), h_c {last['contact_depth'] * 1e3:.4f} mm ({how}), hardness F_max/A(h_c) {last['hardness']:.4g} +- {last['hardness_standard_error']:.2g} Pa "
          f"(a local reading at h_max, the window's deep end: docs/indentation.md)")
    hyd, dev = last["plateau_hydrostatic_stress"], last["plateau_deviatoric_stress"]
    print(f"  dynamic bin (5.2 x 5.2 x 4.2 mm under the indenter, 004 Sec. 5.3, Eqs. 5.2-5.3) over the same window: hydrostatic {hyd:.4g} "
          f"+- {last['plateau_hydrostatic_stress_standard_error']:.2g} Pa, deviatoric {dev:.4g} +- {last['plateau_deviatoric_stress_standard_error']:.2g} Pa "
          f"(standard errors of this run; the quarter beds differ by about 20 % in these: docs/data/bin_stresses_ch6.csv); "
          f"plateau hardness / hydrostatic {last['plateau_hardness'] / hyd:.3g}")
    reference = None
    if os.path.isfile(REFERENCE):
        reference = np.genfromtxt(REFERENCE, delimiter=",", names=True)
        ref, ref_se, s_bed = reference_of_record()
        half = 1.96 * float(np.hypot(se, s_bed))
        inside = abs(last["plateau_hardness"] - ref) <= half
        print(f"  reference of record (the seed's speed gamma* = 0.01 on three whole beds, the same window, docs/data/reference_of_record.csv): "
              f"{ref:.4g} +- {ref_se:.2g} Pa; the default is {100 * (last['plateau_hardness'] - ref) / ref:+.1f} % off, and its 95 % interval "
              f"(its own error and the quarter beds' scatter {s_bed:.0f} Pa) is +-{half:.3g} Pa ({100 * half / ref:.0f} %): it "
              f"{'contains' if inside else 'does not contain'} the reference")
    fig, ax = plt.subplots(1, 2, figsize=(10, 4.2))
    inside = r["penetration_depth"] >= 0
    ax[0].plot(r["penetration_depth"][inside] * 1e3, r["indenter_force"][inside], lw=1.2, label="the FMU's default test")
    ok = (r["test_state"] == 0) & (r["dimensionless_penetration"] > 0.02)
    ax[1].plot(r["dimensionless_penetration"][ok], r["hardness"][ok] / 1e3, lw=1.2, label="F / A(h), the FMU's default test")
    if reference is not None:
        ax[0].plot(reference["depth_m"] * 1e3, reference["force_N"], lw=0.8, color="0.5", label="one whole bed, full fidelity, gamma* = 0.01")
        slow = (reference["state"] == 0) & (reference["depth_over_r"] > 0.02)
        ax[1].plot(reference["depth_over_r"][slow], reference["hardness_Pa"][slow] / 1e3, lw=0.8, color="0.5", label="F / A(h), one whole bed, gamma* = 0.01")
    ax[0].set(xlabel="penetration depth h [mm]", ylabel="indenter force [N]", title="force-depth curve")
    ax[0].legend(fontsize=8)
    ax[1].plot(r["dimensionless_penetration"][ok], r["hydrostatic_stress"][ok] / 1e3, lw=0.8, label="hydrostatic stress, dynamic bin")
    ax[1].hlines(last["plateau_hardness"] / 1e3, p0, p1, color="C3", lw=2, label="plateau hardness")
    ax[1].hlines(hyd / 1e3, p0, p1, color="C1", lw=2, label="plateau hydrostatic stress")
    ax[1].fill_between([p0, p1], (last["plateau_hardness"] - 2 * se) / 1e3, (last["plateau_hardness"] + 2 * se) / 1e3, color="C3", alpha=0.2, lw=0,
                       label="+- 2 standard errors")
    ax[1].set(xlabel="h / r [-]", ylabel="[kPa]", title="hardness against dimensionless penetration")
    ax[1].legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "indentation.png")
    fig.savefig(path, dpi=110)
    return path, float(last["plateau_hardness"]), float(last["plateau_hardness_standard_error"])


def measured_constraint_factor(sigma_1):
    """C and its standard error at sigma_1 from docs/data/constraint_factor_ch6_seed_window.csv (None where the table
    has no row at that stress)."""
    import csv

    with open(os.path.join(ROOT, "docs", "data", "constraint_factor_ch6_seed_window.csv")) as f:
        for row in csv.DictReader(line for line in f if not line.startswith("#")):
            if float(row["consolidation_stress_Pa"]) == sigma_1:
                return float(row["constraint_factor"]), float(row["constraint_factor_standard_error"])
    return None, None


def compression(fmu, out, plateau, plateau_se):
    """The UnconfinedCompression FMU's default test through fmpy with no arguments: the stress-strain curve,
    sigma_c with its standard error, ff_c; and H / sigma_c with the indentation's plateau on the same material."""
    print(f"\nunconfined compression: {fmu}")
    print("  the shipped specimen (resources/specimen.pfbed: 004 Ch. 6's material, 4000 spheres in a 15 mm die, consolidated to 10 kPa), "
          "the die removed, the platen at 1/s until the specimen fails (or 10 % strain), two threads; running (seconds)")
    t0 = time.perf_counter()
    r = simulate_fmu(fmu, output_interval=1e-5)
    wall = time.perf_counter() - t0
    last = r[-1]
    sigma_c, se = last["unconfined_yield_strength"], last["unconfined_yield_strength_standard_error"]
    print(f"  wall time {wall:.1f} s; specimen H_0 = {last['specimen_height'] * 1e3:.2f} mm, solid fraction {last['solid_fraction']:.4f}, "
          f"its own weight {last['self_weight_stress']:.0f} Pa on its base; consolidated to sigma_1 = {last['consolidation_stress']:.0f} Pa")
    state = "failed" if last["failed"] else "not failed by max_strain: a lower bound"
    print(f"  sigma_c (the largest mean stress over 0.05 % strain, read from 0.05 % on, past the platen's arrival) {sigma_c:.4g} +- {se:.2g} Pa "
          f"(standard error of this run; the scatter from fill to fill is larger: the three fills below; quasi-static rates, 0.03-0.3/s, read 7 % lower: docs/units/UnconfinedCompression.md) "
          f"at strain {last['strain_at_failure']:.4f}, {state}; ff_c = sigma_1 / sigma_c = {last['flow_function']:.3g} "
          f"+- {last['flow_function'] * se / sigma_c:.1g} (sigma_c's standard error; sigma_1 is set) "
          f"(004 Table 2.1: free flowing above 10)")
    print("  the same test on the FMU's three fills of the specimen's scene (replicas = 3), for the scatter one specimen cannot show; running (seconds)")
    t0 = time.perf_counter()
    three = simulate_fmu(fmu, start_values={"replicas": 3})[-1]
    wall3 = time.perf_counter() - t0
    s3, own3, over3 = three["unconfined_yield_strength"], three["unconfined_yield_strength_standard_error"], three["unconfined_yield_strength_standard_error_over_specimens"]
    print(f"  wall time {wall3:.1f} s; sigma_c over three fills {s3:.4g} +- {over3:.2g} Pa (standard error from their spread; "
          f"+- {own3:.2g} Pa from their own fluctuations), ff_c = {three['flow_function']:.3g} +- {three['flow_function'] * over3 / s3:.1g}")
    ratio = plateau / sigma_c
    # Both runs' own standard errors in quadrature (independent runs); the beds' scatter is not in it.
    ratio_se = ratio * ((plateau_se / plateau) ** 2 + (se / sigma_c) ** 2) ** 0.5
    if not last["failed"]:
        print(f"  with the indentation's plateau above on the same material: H / sigma_c = {ratio:.3g} +- {ratio_se:.2g}, an upper bound of the constraint "
              f"factor C (004 Eq. 2.10; BallIndentation divides by C = 3): sigma_c here is a lower bound, and the two beds and rates differ")
    else:
        print(f"  with the indentation's plateau above on the same material: H / sigma_c = {ratio:.3g} +- {ratio_se:.2g} (the two runs' standard errors; 004 Eq. 2.10's C; BallIndentation divides by C = 3)")
    c, c_se = measured_constraint_factor(last["consolidation_stress"])
    if c is not None:
        print(f"  the constraint factor measured over several beds and specimens at this stress: C = {c:.3g} +- {c_se:.2g} "
              f"(docs/data/constraint_factor_ch6_seed_window.csv, the default test read over h/r 0.35-0.5; BallIndentation divides by it with constraint_factor_source = measured)")
    fig, ax = plt.subplots(figsize=(6.5, 4.2))
    loaded = r["axial_strain"] > 0
    ax.plot(r["axial_strain"][loaded] * 100, r["axial_stress"][loaded], lw=0.8, label="axial stress (mean over 100 engine steps)")
    read = loaded & (r["unconfined_yield_strength"] > 0)  # 0 until a window of samples exists
    ax.plot(r["axial_strain"][read] * 100, r["unconfined_yield_strength"][read], lw=1.5, color="C3", label="sigma_c so far (largest 0.05 % window mean)")
    ax.axvline(0.05, color="0.5", ls="--", lw=0.8, label="reading_start: the platen's arrival (an impact) before it")
    ax.axhline(last["self_weight_stress"], color="0.5", ls=":", lw=1, label="the specimen's own weight on its base")
    ax.set(xlabel="axial strain [%]", ylabel="stress [Pa]", ylim=(0, 2.5 * sigma_c),
           title=f"unconfined compression at 1/s: sigma_c {sigma_c:.0f} +- {se:.0f} Pa ({'failed' if last['failed'] else 'lower bound'})")
    ax.legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(out, "compression.png")
    fig.savefig(path, dpi=110)
    return path


if __name__ == "__main__":
    sys.exit(main())
