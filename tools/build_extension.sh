#!/usr/bin/env bash
# Validate the manifest and build the extension zip into dist/ with Blender's own extension
# tool (it ships inside the bpy wheel and runs with plain Python).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
py=$(tools/bootstrap.sh "${BPY_BUILD_VERSION:-5.0.1}")
# The wheel keeps Blender's scripts at site-packages/bpy/<major.minor>/scripts.
scripts=$("$py" -c 'import glob, sysconfig; print(glob.glob(sysconfig.get_paths()["purelib"] + "/bpy/[0-9]*/scripts")[0])')
ext_tool="$scripts/addons_core/bl_pkg/cli/blender_ext.py"
tags="$scripts/modules/_bpy_internal/extensions/tags.py"
"$py" "$ext_tool" validate . --valid-tags "$tags"
mkdir -p dist
rm -f dist/*.zip
"$py" "$ext_tool" build --source-dir . --output-dir dist --valid-tags "$tags"
ls dist/*.zip
