#!/usr/bin/env bash
# Three shards of one render (`hoilcd render --shard I/3`) in parallel processes, one of them
# killed (SIGKILL) past its first manifest checkpoint and then run again alone, merge (`hoilcd
# merge`) to the same bytes as the unsharded render, every file and the manifest included; a bad
# --shard is refused by name. Extra arguments (e.g. --set camera.video.enabled=true) go to every render.
set -euo pipefail
hoilcd=$1
scene=$2
shift 2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
frames=90  # shards of 30 frames: a checkpoint (every 25 frames) lands inside each

"$hoilcd" -q render "$scene" -o "$work/whole" --frames $frames "$@"

for bad in 0/0 3/2 x ''; do  # issue 45, defect 13: '' rendered the whole sequence
  if "$hoilcd" -q render "$scene" -o "$work/bad" --frames $frames --shard "$bad" "$@" 2> "$work/err.txt"; then
    echo "--shard $bad was accepted" >&2
    exit 1
  fi
  grep -q -- "--shard" "$work/err.txt" || { echo "--shard $bad refused without naming it: $(cat "$work/err.txt")" >&2; exit 1; }
  [ ! -e "$work/bad" ] || { echo "--shard $bad wrote $work/bad" >&2; exit 1; }
done

pids=()
for i in 0 1 2; do
  "$hoilcd" -q render "$scene" -o "$work/shard-$i" --frames $frames --shard $i/3 --threads 1 "$@" > /dev/null &
  pids+=($!)
done
# Shard 1 (frames 30-59) is killed once a checkpoint lists frame 45.
for _ in $(seq 1 3000); do
  grep -q '"thermal/000045.png"' "$work/shard-1/manifest.json" 2>/dev/null && break
  sleep 0.02
done
kill -s KILL "${pids[1]}" 2> /dev/null || true  # a fast machine may have finished already
for pid in "${pids[@]}"; do wait "$pid" || true; done
if "$hoilcd" -q merge "$work"/shard-{0,1,2} -o "$work/early" 2> "$work/err.txt"; then
  grep -q '"complete": true' "$work/shard-1/manifest.json" || { echo "merged an incomplete shard" >&2; exit 1; }
else
  grep -q "shard-1: shard 1/3 is incomplete" "$work/err.txt" || { echo "unexpected refusal: $(cat "$work/err.txt")" >&2; exit 1; }
  [ ! -e "$work/early" ] || { echo "a refused merge wrote $work/early" >&2; exit 1; }
fi
"$hoilcd" -q render "$scene" -o "$work/shard-1" --frames $frames --shard 1/3 --threads 2 "$@" > /dev/null
"$hoilcd" -q merge "$work"/shard-{2,0,1} -o "$work/merged" > /dev/null
if ! diff <(cd "$work/whole" && find . -type f | sort | xargs md5sum) \
          <(cd "$work/merged" && find . -type f | sort | xargs md5sum); then
  echo "the merged shards differ from the unsharded render" >&2
  exit 1
fi
echo "1 passed, 0 failed"
