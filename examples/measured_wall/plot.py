"""Plots result.csv (written by run.sh) against the wall signal: when the bead leaves the tray, and the
contact force."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

wall = np.genfromtxt("wall.csv", delimiter=",", names=True)
r = np.genfromtxt("result.csv", delimiter=",", names=True)
fig, ax = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
ax[0].plot(wall["time"], wall["wall_displacement"] * 1e3, label="wall (measured) [mm]")
ax[0].plot(r["time"], (r["sphere_position"] - 0.5e-3) * 1e3, label="bead bottom [mm]")
ax[0].set_ylabel("height [mm]")
ax[0].legend()
ax[1].plot(r["time"], r["force"] * 1e3)
ax[1].set_ylabel("contact force [mN]")
ax[1].set_xlabel("time [s]")
fig.tight_layout()
fig.savefig("measured_wall.png", dpi=120)
flight = np.mean(r["contact_state"] == 0)
print(f"bead off the tray {100 * flight:.0f} % of the time; largest force {r['force'].max() * 1e3:.3f} mN; plot: measured_wall.png")
