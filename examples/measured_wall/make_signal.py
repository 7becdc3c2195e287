"""Writes wall.csv: the wall of ParticleWallImpact as a data logger would record a vibrating feeder tray.

A tray at rest for 20 ms, then driven at 50 Hz (with its second harmonic) whose amplitude ramps up over
100 ms as the drive starts, sampled at 20 kHz, with sensor noise on the displacement;
the velocity column is what the logger's differentiator gives (a smoothed central difference of the
noisy samples), so the two columns are only roughly consistent, as measured signals are. Columns: time [s],
wall_displacement [m], wall_velocity [m/s] (fmpy's --input-file format: a header of variable names).
"""

import numpy as np

rate = 20_000.0  # samples per second
t = np.arange(0.0, 0.2 + 0.5 / rate, 1.0 / rate)
f = 50.0  # Hz
ramp = np.clip((t - 0.02) / 0.1, 0.0, 1.0)
a1, a2 = 1.5e-3, 0.2e-3  # m
z = ramp * (a1 * np.sin(2 * np.pi * f * (t - 0.02)) + a2 * np.sin(4 * np.pi * f * (t - 0.02)))
z += np.random.default_rng(1).normal(0.0, 0.5e-6, t.size)  # 0.5 um sensor noise
# The logger's velocity: the derivative of the displacement smoothed over 5 samples (0.25 ms). Unsmoothed,
# the noise alone would make the tray "move" at cm/s and kick the bead off a tray at rest.
v = np.gradient(np.convolve(z, np.ones(5) / 5, mode="same"), t)
peak = (a1 * (2 * np.pi * f) ** 2 + a2 * (4 * np.pi * f) ** 2) / 9.81
np.savetxt("wall.csv", np.column_stack([t, z, v]), delimiter=",", header="time,wall_displacement,wall_velocity", comments="", fmt="%.9e")
print(f"wall.csv: {t.size} samples over {t[-1]:.3f} s, drive acceleration up to {peak:.0f} g")
