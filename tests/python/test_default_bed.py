"""The shipped BallIndentation as a user meets it: fmpy's simulate_fmu with no arguments runs the
default test on the quarter of the seed's bed (7250 spheres between two mirror planes,
`beds/bed_004_ch6_quarter.pfbed`; gamma* 0.04 to h/r 0.5, read in the seed's window h/r 0.35-0.5; about
110 s on two cores), and the whole bed (29000 spheres, `beds/bed_004_ch6.pfbed`) runs with `fidelity`
fast. The runs they are compared with are `powderfmu bed indent` records in docs/data/ch6_indentation
(window/README.md and fmu_check/README.md say how each was recorded; docs/indentation.md, "The seed's
window on the seed's bed", reads them)."""

import csv
import math

import pytest
from fmpy import simulate_fmu

from fmu_support import REPO

DONE = 2
DATA = REPO / "docs" / "data" / "ch6_indentation"
# The default's own settings through the command-line tool (the quarter bed, the 16 mm indenter at gamma*
# = 0.04 to h/r 0.5, 2.5e-7 s, every sphere moving, two threads).
SAME_SETTINGS = DATA / "window" / "quarter1_g0.04.csv"
WINDOW = (0.35, 0.5)


def rows(path):
    with open(path) as f:
        return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(f)]


def plateau_of(path):
    """Mean F/A(h) while loading in the seed's window of a `powderfmu bed indent` CSV."""
    h = [r["hardness_Pa"] for r in rows(path) if r["state"] == 0 and WINDOW[0] <= r["depth_over_r"] <= WINDOW[1]]
    assert len(h) > 20, f"{path}: {len(h)} rows on the plateau"
    return sum(h) / len(h)


@pytest.fixture(scope="module")
def default_run(shipped_indentation):
    r = simulate_fmu(str(shipped_indentation.path))
    print(
        f"\ndefault test: plateau hardness {r[-1]['plateau_hardness']:.0f} +- {r[-1]['plateau_hardness_standard_error']:.0f} Pa "
        f"({r[-1]['plateau_samples']} samples), F_max/A(h_c) {r[-1]['hardness']:.0f} +- {r[-1]['hardness_standard_error']:.0f} Pa (h_c = {r[-1]['contact_depth']:.4e} m, "
        f"from the tangent: {bool(r[-1]['contact_depth_from_tangent'])}); the command line's run of the same settings: {plateau_of(SAME_SETTINGS):.0f} Pa"
    )
    return r


def test_simulate_fmu_with_no_arguments_runs_the_whole_default_test(shipped_indentation, default_run):
    last = default_run[-1]
    assert last["test_state"] == DONE, "the indenter has left the bed by the default stop time"
    # Turned at max_penetration: the deepest output is within one output interval's travel of it.
    step = float(shipped_indentation.md.defaultExperiment.stepSize) * shipped_indentation.start("indentation_speed")
    assert max(default_run["penetration_depth"]) >= shipped_indentation.start("max_penetration") - step
    assert last["indenter_contacts"] == 0
    assert last["plateau_hardness"] > 0 and last["hardness"] > 0


def test_the_default_outputs_are_a_measurement(default_run):
    """The plateau comes with a standard error of a few per cent; the contact depth is never a silent 0
    (the tangent's h_c, or h_max said so); the hardness after unloading is F_max / A(h_c) with F_max the
    loading curve's force at the turn, within its measured spread of the plateau (over the 14 recorded
    runs to h/r 0.5 of docs/data/ch6_indentation/window the local reading at h_max, the window's deep end,
    lay 2.7 % above the plateau with a standard deviation of 6.7 %: benches/reference_of_record.py)."""
    last = default_run[-1]
    p, se = last["plateau_hardness"], last["plateau_hardness_standard_error"]
    assert last["plateau_samples"] > 500, "gamma* = 0.04, h/r 0.35-0.5: about 670 samples in the window"
    # The window holds only a few correlation times of the force, so one run's error is itself uncertain
    # (docs/indentation.md: ten runs' spread against their errors); it is a fraction of the mean.
    assert 0.01 * p < se < 0.25 * p, (p, se)
    hc = last["contact_depth"]
    assert hc > 0
    h_max = 0.004  # max_penetration's default: the indenter turns at the engine step that reaches it
    if last["contact_depth_from_tangent"]:
        assert 0 < hc < h_max * 1.001
    else:
        assert h_max <= hc < h_max * 1.001
    d = 0.016
    assert last["hardness"] == pytest.approx(last["force_at_turn"] / (math.pi * (d * hc - hc * hc)), rel=1e-12)
    assert abs(last["hardness"] - p) < 3 * math.hypot(se, 0.067 * p), (last["hardness"], p, se)
    # The hardness comes with its own standard error, from the fluctuations of the force behind F_max
    # (the last tenth of the loading depth, about 220 samples, about one correlation time, so with
    # the variance and correlation time of the loading's deeper half), scaled to h_c; the yield
    # strength's is C times smaller.
    hse = last["hardness_standard_error"]
    assert 0.005 * last["hardness"] < hse < 0.5 * last["hardness"], (last["hardness"], hse)
    assert last["unconfined_yield_strength_standard_error"] == pytest.approx(hse / 3.0, rel=1e-12)


def test_the_window_stresses_are_the_dynamic_bins_mean_with_its_error(default_run):
    """plateau_hydrostatic_stress and plateau_deviatoric_stress are the dynamic bin's stresses (004 Eqs.
    5.2-5.3, Fig. 5.19) averaged over the samples of the plateau window; the unit's rows every 1e-4 s (every
    fourth sample, the same states) average to the same level within its standard error; and the bin's
    stresses are positive, the hydrostatic below the hardness (the indenter's load spreads under it)."""
    last = default_run[-1]
    r = 0.008
    loading = default_run[(default_run["test_state"] == 0) & (default_run["penetration_depth"] / r >= WINDOW[0]) & (default_run["penetration_depth"] / r <= WINDOW[1])]
    assert len(loading) > 100
    for name, column in [("plateau_hydrostatic_stress", "hydrostatic_stress"), ("plateau_deviatoric_stress", "deviatoric_stress")]:
        level, se = last[name], last[name + "_standard_error"]
        assert 0.01 * level < se < 0.5 * level, (name, level, se)
        assert abs(loading[column].mean() - level) < se, (name, loading[column].mean(), level, se)
    assert 0 < last["plateau_deviatoric_stress"] and 0 < last["plateau_hydrostatic_stress"] < last["plateau_hardness"]


def test_the_default_test_is_the_command_line_run_of_the_same_settings(default_run):
    """The FMU and `powderfmu bed indent` step the same engine: their force records agree to the CSV's
    seven digits at every loading row, and so does the final hardness."""
    cli = [r for r in rows(SAME_SETTINGS)]
    by_time = {round(t / 1e-4): k for k, t in enumerate(default_run["time"])}
    loading = [r for r in cli if r["state"] == 0]
    assert len(loading) > 100
    for r in loading:
        k = by_time[round(r["time_s"] / 1e-4)]
        assert default_run["indenter_force"][k] == pytest.approx(r["force_N"], rel=1e-6, abs=1e-9), r["time_s"]
    # The force at the turn is A(h_max) times the mean F/A over the last tenth of the loading: the unit
    # samples every 100 engine steps, the command line's rows every 1e-4 s (four times fewer).
    h_max = max(r["depth_m"] for r in loading)
    tail = [r["hardness_Pa"] for r in loading if r["depth_m"] >= 0.9 * h_max]
    area = math.pi * (0.016 * h_max - h_max * h_max)
    assert default_run[-1]["force_at_turn"] == pytest.approx(area * sum(tail) / len(tail), rel=0.03)


# The whole bed with fidelity fast at gamma* = 0.08 through the command-line tool (2.5e-7 s, two threads):
# the default before the quarter bed, still the fastest run of the whole bed within 2 minutes.
WHOLE_FAST = DATA / "fmu_check" / "gamma0.08_fast_dt2.5e-7.csv"


def test_the_whole_bed_runs_with_fidelity_fast_as_the_command_line_does(shipped_indentation):
    """`fidelity = fast` loads the FMU's whole bed (29000 spheres) and holds the far spheres: the
    command-line run of the same bed and settings, to seven digits, over the first 2 ms of loading (the
    indenter touches from the first row on: 20 rows of force over 8000 engine steps. The whole test takes
    83 s on the Xeon of docs/indentation.md, about 50 s on an AMD Zen 5; its hardness against the
    quarter's is in docs/indentation.md)."""
    stop = 0.002
    # The record's depth: fidelity fast's mobile zone grows with the contact radius at max_penetration.
    settings = {"fidelity": "fast", "indentation_speed": 0.1429, "max_penetration": 0.0016, "plateau_start": 0.1, "plateau_end": 0.2}
    r = simulate_fmu(str(shipped_indentation.path), start_values=settings, stop_time=stop)
    cli = rows(WHOLE_FAST)
    by_time = {round(t / 1e-4): k for k, t in enumerate(r["time"])}
    loading = [row for row in cli if row["state"] == 0 and row["time_s"] <= stop + 1e-9]
    assert len(loading) >= 19 and all(row["force_N"] > 0 for row in loading)
    assert max(r["penetration_depth"]) > 0.1 * settings["max_penetration"]
    for row in loading:
        k = by_time[round(row["time_s"] / 1e-4)]
        assert r["indenter_force"][k] == pytest.approx(row["force_N"], rel=1e-6, abs=1e-9), row["time_s"]


def test_the_quarter_reports_the_whole_die(default_run):
    """Each sphere of the quarter stands for itself and its three mirror images."""
    touching = [c for c in default_run["indenter_contacts"] if c > 0]
    assert touching and all(c % 4 == 0 for c in touching)


# The default's setting in the table of benches/indentation_halfwidth.py: the quarter beds' scatter from bed
# to bed and the reference of record it is judged against, both in the seed's window, from the recorded runs.
HALFWIDTH = REPO / "docs" / "data" / "indentation_halfwidth.csv"


def default_setting():
    with open(HALFWIDTH) as f:
        return {k: (v if k == "setting" else float(v)) for k, v in next(r for r in csv.DictReader(f) if "(the default)" in r["setting"]).items()}


def test_the_default_interval_contains_the_reference_of_record(default_run):
    """Issue 31's interval: the plateau with its own standard error and the bed-to-bed scatter of the quarter
    beds (s_bed, three beds), at 95 %, contains the reference of record (the seed's speed on three whole
    beds, the same window). Met by the default run (docs/indentation.md, "The default in the seed's
    window", counts how many of the five recorded runs' intervals do)."""
    last, d = default_run[-1], default_setting()
    half_width = 1.96 * math.hypot(last["plateau_hardness_standard_error"], d["s_bed_Pa"])
    assert abs(last["plateau_hardness"] - d["reference_Pa"]) <= half_width, (last["plateau_hardness"], half_width, d)


def recorded_default_runs():
    """The five recorded runs of the default (docs/data/default_replicas.csv): (plateau, own standard error)."""
    with open(REPO / "docs" / "data" / "default_replicas.csv") as f:
        return [(float(r["plateau_hardness"]), float(r["plateau_hardness_standard_error"])) for r in csv.DictReader(f)]


def test_the_default_interval_is_as_wide_as_the_recorded_runs_say(default_run):
    """What the default meets of issue 31's interval, in place of the 5 % it does not: the half-width of its
    95 % interval (its own standard error and the quarter beds' s_bed) is no wider than the widest of the
    five recorded runs' (the first of which is this run: the same engine steps, its error written to six
    digits), and no narrower than 1.96 s_bed, which no single test on one bed can go below. What 5 % takes:
    docs/indentation.md, "The default in the seed's window"."""
    last, d = default_run[-1], default_setting()
    half_width = 1.96 * math.hypot(last["plateau_hardness_standard_error"], d["s_bed_Pa"])
    widest = max(1.96 * math.hypot(se, d["s_bed_Pa"]) for _, se in recorded_default_runs())
    assert 1.96 * d["s_bed_Pa"] < half_width <= widest * (1 + 1e-5), (half_width, widest, d)
