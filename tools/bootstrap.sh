#!/usr/bin/env bash
# Create (once) and print the path of a Python 3.11 venv holding bpy==$1 and the dev tools.
# Venvs live outside the clone, keyed by the bpy version and a hash of requirements-dev.txt,
# so repeated runs reuse the ~1 GB install and a changed pin gets a fresh venv.
set -euo pipefail
bpy_version="${1:?usage: bootstrap.sh BPY_VERSION}"
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
req="$root/requirements-dev.txt"
cache="${BALLMORPH_ENV_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/ballmorph-inbetween}"
key="$(sha256sum "$req" | cut -c1-12)"
venv="$cache/py3.11-bpy$bpy_version-$key"
if [ ! -f "$venv/.complete" ]; then
    python="${PYTHON311:-$(command -v python3.11 || command -v python3)}"
    "$python" -c 'import sys; assert sys.version_info[:2] == (3, 11), "bpy wheels need Python 3.11, got " + sys.version' >&2
    rm -rf "$venv"
    mkdir -p "$cache"
    echo "bootstrap: creating $venv (bpy==$bpy_version, ~1 GB, one time)" >&2
    "$python" -m venv "$venv"
    "$venv/bin/python" -m pip install --quiet --upgrade pip >&2
    "$venv/bin/python" -m pip install --quiet "bpy==$bpy_version" -r "$req" >&2
    touch "$venv/.complete"
fi
echo "$venv/bin/python"
