#!/usr/bin/env bash
# The main job (README's `make demo`): the add-on in-betweens four shot-like Grease Pencil
# cases inside Blender 5.0 (headless) and writes out/demo.blend and out/demo.png; Blender renders
# every frame of out/demo.blend with Workbench into out/demo.gif; then the picture of the path
# preview drawn from the same shots, out/path_preview.png, the correspondence hints on a real
# scene, out/hints.png, and the core's own picture of a
# ball-morph, out/core_demo.png.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
py=$(tools/bootstrap.sh 5.0.1)
# bpy can hang at exit if an operator stays registered: the timeout turns that into a failure.
timeout 600 "$py" tools/demo.py
timeout 600 "$py" tools/render_demo.py
timeout 600 "$py" tools/path_preview.py
timeout 600 "$py" tools/hints_picture.py
"$py" tools/core_demo.py
