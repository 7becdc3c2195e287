#!/usr/bin/env bash
# Installs what the win64 binaries and their test under wine need, or says in one line what is missing:
# the Rust target x86_64-pc-windows-gnu (rustup), the linker x86_64-w64-mingw32-gcc (Debian's
# gcc-mingw-w64-x86-64) and wine (Debian's wine, wine64). Needs root (or sudo) for apt-get.
set -euo pipefail
target=x86_64-pc-windows-gnu
if ! rustup target list --installed 2>/dev/null | grep -qx "$target"; then
    rustup target add "$target" >&2
fi
missing=()
command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 || missing+=(gcc-mingw-w64-x86-64)
command -v wine >/dev/null 2>&1 || missing+=(wine wine64)
if [ ${#missing[@]} -gt 0 ]; then
    sudo=""
    [ "$(id -u)" = 0 ] || sudo="sudo -n"
    if command -v apt-get >/dev/null 2>&1 && $sudo true 2>/dev/null; then
        echo "windows_toolchain.sh: installing ${missing[*]} (apt-get)" >&2
        $sudo apt-get update -qq >&2
        DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >&2
    else
        echo "windows_toolchain.sh: missing ${missing[*]}: install them (apt-get install ${missing[*]}) or set POWDERFMU_SKIP_WINDOWS=1" >&2
        exit 1
    fi
fi
