#!/usr/bin/env bash
# The project's one test command (README's `make test`, and .ci/run): lint, the core tests and the
# add-on's bpy-free decision tests in plain CPython, the extension's validate + build with Blender's
# own tool, then the Blender tests inside bpy 4.5 LTS and 5.0. Bootstraps its own cached environments.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
BPY_VERSIONS="${BPY_VERSIONS:-4.5.15 5.0.1}"
py=$(tools/bootstrap.sh 5.0.1)
bin=$(dirname "$py")

echo "== lint (ruff)"
"$bin/ruff" check .
"$bin/ruff" format --check .

echo "== core and add-on decision tests (plain CPython, no bpy imported), with the fuzz target's short profile"
timeout 1200 "$py" -m pytest -q tests/core tests/scenarios tests/tools tests/addon tests/fuzz

echo "== extension: validate and build with Blender's own tool"
tools/build_extension.sh

for version in $BPY_VERSIONS; do
    echo "== Blender tests in bpy $version"
    bpy_py=$(tools/bootstrap.sh "$version")
    # bpy can hang at exit if something stays registered: the timeout turns that into a failure.
    timeout 1500 "$bpy_py" -m pytest -q -p no:cacheprovider -p tests.root_dir_plugin --import-mode=importlib \
        -o testpaths=tests/blender -o addopts= tests/blender
done
echo "== all tests passed"
