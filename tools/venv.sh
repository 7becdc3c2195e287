#!/usr/bin/env bash
# Creates (once) the project's Python virtual environment in .venv with the pinned requirements and the
# project's Python package (python/, editable: `import powderfmu` is this checkout) and prints its python
# path. Safe to rerun: it only installs what requirements.txt or python/pyproject.toml changed.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv >&2
fi
if ! cmp -s requirements.txt .venv/requirements.installed 2>/dev/null; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -r requirements.txt >&2
    cp requirements.txt .venv/requirements.installed
fi
if ! cmp -s python/pyproject.toml .venv/pyproject.installed 2>/dev/null; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check --no-deps --no-build-isolation -e ./python >&2
    cp python/pyproject.toml .venv/pyproject.installed
fi
echo "$PWD/.venv/bin/python"
