#!/bin/bash
# Interleaved first runs of `hoilcd run` on a fresh cache, for A/B comparisons of hoilcd binaries
# on a noisy shared host (quote ratios and pairs, not single figures).
#
#   benchmarks/run_pairs.sh ROUNDS LABEL=BINARY [LABEL=BINARY ...]     e.g.
#   benchmarks/run_pairs.sh 4 before=/tmp/hoilcd_before after=build/bin/hoilcd
#
# Each run starts as on a machine that just built hoilcd: earlier runs' folders deleted and synced,
# the page cache dropped when this is root (/proc/sys/vm/drop_caches), the binary and assets read
# once, then 10 s of quiet. The wait matters on ext4 without a journal: for some seconds after a
# delete, every file created scans past the inodes just freed (perf: `recently_deleted`), which
# cost a render ~1.5 s of CPU right after `rm -rf` of the previous run's 4000 files.
# Prints per run: wall, user and system CPU seconds, the `end to end` split, and a checksum of
# both datasets' manifests (equal for binaries that write the same bytes).
set -euo pipefail
rounds=$1
shift
root=$(cd "$(dirname "$0")/.." && pwd)
scene=${SCENE:-$root/scenes/paper_room.json}
work=$(mktemp -d /tmp/hoilcd_pairs.XXXXXX)
trap 'rm -rf "$work"' EXIT
for ((round = 1; round <= rounds; round++)); do
  for spec in "$@"; do
    label=${spec%%=*}
    binary=${spec#*=}
    rm -rf "$work"/run
    sync
    if [ -w /proc/sys/vm/drop_caches ]; then echo 3 >/proc/sys/vm/drop_caches; fi
    "$binary" --version >/dev/null
    cat "$scene" "$root"/assets/* >/dev/null 2>&1 || true
    sleep 10
    out=$(HOILCD_DATA_DIR=$root /usr/bin/time -f "%e s wall, %U s user, %S s sys" \
      "$binary" -q run "$scene" --cache "$work"/run 2>&1)
    split=$(echo "$out" | grep "end to end" | sed -E 's/^end to end: ([0-9.]+) s: render ([0-9.]+) s, then bench ([0-9.]+) s.*beside them, ([0-9.]+) s.*/render \2 s, bench \3 s, calibration \4 s/')
    manifests=$(cat "$work"/run/*/dataset/manifest.json | sha256sum | cut -c1-12)
    echo "$label: $(echo "$out" | tail -1) | $split | manifests $manifests"
  done
done
