"""The unconfined compression test against its strain rate (the quasi-static threshold, issue 34): the
shipped specimen's curves to 1 % strain at several rates beside sigma_c against the rate, with the
inertial number I = rate d (rho / sigma_c)^(1/2) (d the mean diameter, rho the particles' density) on a
second axis. Reads docs/data/compression/rates_10kPa.csv and the curves it names.

    python benches/compression_rates.py --plot docs/figures/compression_rates.png
"""

import argparse
import csv
import math
from pathlib import Path

DATA = Path(__file__).resolve().parent.parent / "docs" / "data" / "compression"
D, RHO = 1.0e-3, 2500.0  # the Ch. 6 material's mean diameter [m] and density [kg/m^3]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--plot", required=True)
    a = p.parse_args()
    with open(DATA / "rates_10kPa.csv") as f:
        table = list(csv.DictReader(line for line in f if not line.startswith("#")))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(13, 5))
    for k, r in enumerate(table):
        rate = r["strain_rate_per_s"]
        with open(DATA / f"uct_004_ch6_10kPa_rate{rate}_to1pct.csv") as f:
            rows = list(csv.DictReader(f))
        ax[0].plot([100 * float(x["strain"]) for x in rows], [float(x["stress_Pa"]) for x in rows], lw=1, color=f"C{k}",
                   label=f"{rate}/s: sigma_c {float(r['unconfined_yield_strength_Pa']):.0f} Pa{' (failed)' if r['failed'] == 'True' else ''}")
        ax[0].plot([100 * float(r["strain_at_peak"])], [float(r["unconfined_yield_strength_Pa"])], "o", color=f"C{k}")
    ax[0].set(xlabel="axial strain [%]", ylabel="platen stress [Pa]", title="the shipped specimen (10 kPa) to 1 % strain", xlim=(0, 1), ylim=(0, 1400))
    ax[0].legend(fontsize=8)
    rates = [float(r["strain_rate_per_s"]) for r in table]
    sc = [float(r["unconfined_yield_strength_Pa"]) for r in table]
    se = [float(r["standard_error_Pa"]) for r in table]
    ax[1].errorbar(rates, sc, yerr=se, fmt="o-", capsize=3, color="C3")
    ax[1].set(xscale="log", xlabel="strain rate [1/s]", ylabel="sigma_c [Pa]", title="sigma_c against the rate (error bars: standard errors)")
    inertial = lambda x: x * D * math.sqrt(RHO / 900.0)  # noqa: E731 (sigma_c about 900 Pa)
    top = ax[1].secondary_xaxis("top", functions=(inertial, lambda i: i / (D * math.sqrt(RHO / 900.0))))
    top.set_xlabel("inertial number I = rate d (rho / sigma_c)^(1/2)")
    for axis in ax:
        axis.grid(alpha=0.3, which="both")
    fig.suptitle("Unconfined compression of the 004 Ch. 6 material: the rate where the reading stops depending on it")
    fig.tight_layout()
    fig.savefig(a.plot, dpi=110)
    print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
