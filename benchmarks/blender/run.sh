#!/usr/bin/env bash
# The Blender comparison: installs Debian 12's blender if missing (scripts/setup's
# hoilcd_install_blender), then renders a hoilcd dataset's room and camera poses with Cycles on the
# CPU (benchmarks/blender/thermal_room.py) and prints frames per second.
# Usage: benchmarks/blender/run.sh DATASET [--frames N (200)] [--threads N (2)] [--still PNG --still-frame F]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
if [ $# -lt 1 ]; then
  echo "usage: $0 DATASET [--frames N] [--threads N] [--warmup N] [--still PNG [--still-frame F]]" >&2
  exit 2
fi
source "$here/../../scripts/setup"
hoilcd_install_blender
# Blender's own log lines (one per tile and frame) go to a file; the figures are printed.
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
if ! blender -b --factory-startup --python-exit-code 2 --python "$here/thermal_room.py" -- "$@" > "$log" 2>&1; then
  grep -v '^Fra:' "$log" >&2
  exit 1
fi
grep -E '^blender .* fps$|^thermal_room.py: ' "$log" || true
