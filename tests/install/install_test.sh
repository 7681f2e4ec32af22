#!/usr/bin/env bash
# `cmake --install` gives a relocatable prefix (issue 12). Installed, then MOVED, the prefix
#  - serves find_package(hoilcd) to a fresh out-of-tree project that links hoilcd::core;
#  - runs its hoilcd from another folder, with HOILCD_DATA_DIR unset, rendering its own
#    share/hoilcd/scenes/paper_room.json, and the dataset names no source or build path;
#  - imports its Python module, which finds the same data folder and reads that dataset.
# A lone copy of the binary, with no share/hoilcd above it, fails naming HOILCD_DATA_DIR, and
# works once HOILCD_DATA_DIR points at the moved data.
# Arguments: CMAKE BUILD_DIR CONSUMER_SOURCE_DIR SOURCE_DIR [PYTHON3 (empty: no Python module)]
set -euo pipefail
cmake=$1
build=$2
consumer=$3
source_dir=$4
python=${5:-}
source "$(dirname "${BASH_SOURCE[0]}")/moved_prefix.sh"
moved_prefix "$cmake" "$build" install_relocatable
for f in bin/hoilcd lib/cmake/hoilcd/hoilcdConfig.cmake lib/cmake/hoilcd/hoilcdConfigVersion.cmake \
         lib/cmake/hoilcd/hoilcdTargets.cmake include/hoilcd/core/dataset/dataset.h include/hoilcd/sim/scene/scene.h \
         include/hoilcd/bench/runner/runner.h share/hoilcd/scenes/paper_room.json share/hoilcd/scenes/scene.schema.json \
         share/hoilcd/assets/chair.gltf; do
  [ -f "$moved/$f" ] || fail "the prefix lacks $f"
done

# A fresh project against the moved prefix.
"$cmake" -S "$consumer" -B "$work/consumer-build" -DCMAKE_PREFIX_PATH="$moved" -DCMAKE_BUILD_TYPE=Release \
  > "$work/consumer.log" 2>&1 || { cat "$work/consumer.log"; fail "configuring the consumer"; }
"$cmake" --build "$work/consumer-build" >> "$work/consumer.log" 2>&1 || { cat "$work/consumer.log"; fail "building the consumer"; }
out=$("$work/consumer-build/consumer")
case "$out" in "hoilcd "*" fused 1.50 1.50 xxh3-128:"*) ;; *) fail "consumer printed: $out" ;; esac

# The moved hoilcd renders the installed paper_room from another folder.
mkdir -p "$work/elsewhere"
cd "$work/elsewhere"
"$moved/bin/hoilcd" validate "$moved/share/hoilcd/scenes/paper_room.json" > /dev/null || fail "validate"
"$moved/bin/hoilcd" -q render "$moved/share/hoilcd/scenes/paper_room.json" -o "$work/dataset" --frames 3 \
  > "$work/render.log" 2>&1 || { cat "$work/render.log"; fail "the installed hoilcd did not render"; }
[ -f "$work/dataset/thermal/000002.png" ] || fail "no third frame"
for path in "$source_dir" "$build"; do
  if grep -rqF "$path" "$work/dataset" --include='*.json'; then fail "the dataset names $path"; fi
done

# A lone binary has no data folder above it: a clear error, fixed by HOILCD_DATA_DIR.
mkdir -p "$work/lone"
cp "$moved/bin/hoilcd" "$work/lone/hoilcd"
if "$work/lone/hoilcd" validate "$moved/share/hoilcd/scenes/paper_room.json" > "$work/lone.log" 2>&1; then
  fail "a lone binary found a data folder"
fi
grep -q "HOILCD_DATA_DIR: hoilcd's data folder (share/hoilcd with scenes/ and assets/) was not found above $work/lone/hoilcd" \
  "$work/lone.log" || fail "lone binary said: $(cat "$work/lone.log")"
HOILCD_DATA_DIR="$moved/share/hoilcd" "$work/lone/hoilcd" validate "$moved/share/hoilcd/scenes/paper_room.json" \
  > /dev/null || fail "HOILCD_DATA_DIR was not honoured"

if [ -n "$python" ]; then
  PYTHONPATH="$moved/lib/python3/dist-packages" "$python" - "$moved" "$work/dataset" <<'PY' || fail "the installed Python module"
import os, sys
import hoilcd
prefix, dataset = sys.argv[1], sys.argv[2]
assert hoilcd.__file__.startswith(prefix), hoilcd.__file__
assert hoilcd.data_dir() == os.path.join(prefix, "share", "hoilcd"), hoilcd.data_dir()
d = hoilcd.Dataset(dataset)
assert len(d) == 3 and d.thermal(2).shape == (192, 256), (len(d), d.thermal(2).shape)
PY
fi
echo "install_relocatable: ok"
