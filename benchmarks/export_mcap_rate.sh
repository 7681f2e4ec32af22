#!/bin/bash
# hoilcd export-mcap's frame rate against the render's own, in one run: the scene rendered with
# every output, then exported with every topic (zstd), each timed (wall, user + system); the rates
# in frames/s of wall time and of CPU time, and their ratios. A second export checks the bag's bytes.
#
#   benchmarks/export_mcap_rate.sh [ROUNDS]      (SCENE=scenes/paper_room.json THREADS=2)
set -euo pipefail
rounds=${1:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
hoilcd=${HOILCD:-$root/build/bin/hoilcd}
scene=${SCENE:-$root/scenes/paper_room.json}
threads=${THREADS:-2}
work=$(mktemp -d /tmp/hoilcd_mcap_rate.XXXXXX)
trap 'rm -rf "$work"' EXIT
source "$root/benchmarks/seconds.sh"
for ((round = 1; round <= rounds; round++)); do
  rm -rf "$work"/*
  sync
  render=$(seconds "$hoilcd" -q render "$scene" -o "$work/dataset" --threads "$threads")
  sync
  export=$(seconds "$hoilcd" -q export-mcap "$work/dataset" -o "$work/a.mcap" --threads "$threads")
  "$hoilcd" -q export-mcap "$work/dataset" -o "$work/b.mcap" --threads "$threads" > /dev/null
  same=$(cmp -s "$work/a.mcap" "$work/b.mcap" && echo identical || echo DIFFERENT)
  frames=$(grep -o '"frame_count": *[0-9]*' "$work/dataset/manifest.json" | grep -o '[0-9]*$')
  read -r rw ru rs <<< "$render"; read -r ew eu es <<< "$export"
  awk -v f="$frames" -v rw="$rw" -v ru="$ru" -v rs="$rs" -v ew="$ew" -v eu="$eu" -v es="$es" \
      -v t="$threads" -v mb="$(du -m "$work/a.mcap" | cut -f1)" -v same="$same" \
      -v load="$(cut -d' ' -f1 /proc/loadavg)" 'BEGIN {
    rc = ru + rs; ec = eu + es
    printf "round: %d frames, %d threads, load %s\n", f, t, load
    printf "  render      %6.1f s wall, %6.1f s CPU: %6.1f frames/s wall, %6.1f frames/s per core of CPU\n", rw, rc, f / rw, f / rc
    printf "  export-mcap %6.1f s wall, %6.1f s CPU: %6.1f frames/s wall, %6.1f frames/s per core of CPU; %d MB, second export %s\n",
           ew, ec, f / ew, f / ec, mb, same
    printf "  export-mcap / render: %.1fx the wall rate, %.1fx the CPU rate\n", rw / ew, rc / ec
  }'
done
