#!/usr/bin/env bash
# Drives ParticleWallImpact from a measured wall signal with fmpy's command line, then plots the result.
# Run from the repository root after the main command (bash tools/demo.sh) has built the FMUs:
#   bash examples/measured_wall/run.sh
set -euo pipefail
cd "$(dirname "$0")"
python=../../.venv/bin/python
fmpy=../../.venv/bin/fmpy
"$python" make_signal.py
# A 1 mm glass bead (JKR, interface energy 0.05 J/m^2) resting on the tray. --validate makes fmpy refuse a
# misspelt start value name instead of ignoring it.
"$fmpy" simulate ../../target/fmu/ParticleWallImpact.fmu --validate \
    --input-file wall.csv --stop-time 0.2 --output-interval 1e-5 \
    --start-values contact_model jkr particle_radius 0.5e-3 particle_density 2500 \
        particle_youngs_modulus 63e9 particle_poisson_ratio 0.2 surface_energy 0.05 \
        wall_youngs_modulus 200e9 restitution_coefficient 0.5 initial_gap 0 initial_velocity 0 gravity 9.81 solver adaptive \
    --output-variables force overlap contact_state sphere_position sphere_velocity \
    --output-file result.csv
"$python" plot.py
