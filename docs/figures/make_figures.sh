#!/usr/bin/env bash
# Builds the command-line tool and redraws docs/figures/*.png in the project's Python environment.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --locked --bin powderfmu
"$(bash tools/venv.sh)" docs/figures/make_figures.py
