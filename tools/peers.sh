#!/usr/bin/env bash
# Installs the peer DEM codes the fmpy suite compares our laws with (tests/python/test_peers.py,
# docs/porting.md): LAMMPS (`lmp`, Debian's lammps) and Yade (`yade`, Debian's yade). Needs root (or
# sudo) for apt-get; where that is not possible it says so in one line and the peer tests skip with the
# reason. About 2.5 minutes on a clean Debian 12 (measured 2026-12-04: 137 s for both, the tests 20 s).
set -euo pipefail
missing=()
command -v lmp >/dev/null 2>&1 || missing+=(lammps)
command -v yade >/dev/null 2>&1 || missing+=(yade)
[ ${#missing[@]} -eq 0 ] && exit 0
sudo=""
[ "$(id -u)" = 0 ] || sudo="sudo -n"
if command -v apt-get >/dev/null 2>&1 && $sudo true 2>/dev/null; then
    echo "peers.sh: installing ${missing[*]} (apt-get)" >&2
    $sudo apt-get update -qq >&2
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >&2
else
    echo "peers.sh: ${missing[*]} not installed and apt-get not usable here: the peer tests will skip (apt-get install ${missing[*]})" >&2
fi
