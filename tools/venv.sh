#!/usr/bin/env bash
# Creates (once) the project's Python virtual environment in .venv with the pinned requirements and
# prints its python path. Safe to rerun: it only installs what requirements.txt changed.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv >&2
fi
if ! cmp -s requirements.txt .venv/requirements.installed 2>/dev/null; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -r requirements.txt >&2
    cp requirements.txt .venv/requirements.installed
fi
echo "$PWD/.venv/bin/python"
