#!/usr/bin/env bash
# The main job (README's `make demo`).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
py=$(tools/bootstrap.sh 5.0.1)
"$py" tools/core_demo.py
