#!/bin/bash
# A sequence rendered whole against the same sequence rendered as SHARDS shards in parallel
# processes and merged (`hoilcd render --shard I/N`, `hoilcd merge`), in turns, on one machine:
# the wall and CPU time of each, their ratios, and a check that the merged dataset is the whole
# render's bytes. On one machine the shards share its cores, so this measures what sharding costs
# (every shard plans the whole run and crowd; the video is encoded after the shards, not beside
# the rendering); on N machines the shards' wall time is about 1/N of it.
#
#   benchmarks/shard_render.sh [ROUNDS]      (SCENE=scenes/paper_room.json SHARDS=3 THREADS=2;
#                                             each shard renders on THREADS/SHARDS threads, at least 1)
set -euo pipefail
rounds=${1:-1}
root=$(cd "$(dirname "$0")/.." && pwd)
hoilcd=${HOILCD:-$root/build/bin/hoilcd}
scene=${SCENE:-$root/scenes/paper_room.json}
shards=${SHARDS:-3}
threads=${THREADS:-2}
shard_threads=$(( threads / shards > 0 ? threads / shards : 1 ))
work=$(mktemp -d /tmp/hoilcd_shards.XXXXXX)
trap 'rm -rf "$work"' EXIT
source "$root/benchmarks/seconds.sh"
for ((round = 1; round <= rounds; round++)); do
  rm -rf "$work"/*
  sync
  whole=$(seconds "$hoilcd" -q render "$scene" -o "$work/whole" --threads "$threads")
  sync
  sharded=$(seconds bash -c "for ((i = 0; i < $shards; i++)); do
      '$hoilcd' -q render '$scene' --shard \$i/$shards -o '$work/shard-'\$i --threads $shard_threads & done; wait")
  merged=$(seconds "$hoilcd" -q merge "$work"/shard-* -o "$work/merged" --threads "$threads")
  same=$(diff -q <(cd "$work/whole" && find . -type f | sort | xargs md5sum) \
                 <(cd "$work/merged" && find . -type f | sort | xargs md5sum) > /dev/null && echo identical || echo DIFFERENT)
  read -r ww wu ws <<< "$whole"; read -r sw su ss <<< "$sharded"; read -r mw mu ms <<< "$merged"
  awk -v ww="$ww" -v wu="$wu" -v ws="$ws" -v sw="$sw" -v su="$su" -v ss="$ss" -v mw="$mw" -v mu="$mu" \
      -v ms="$ms" -v same="$same" -v load="$(cut -d' ' -f1 /proc/loadavg)" -v n="$shards" -v t="$threads" 'BEGIN {
    wc = wu + ws; sc = su + ss; mc = mu + ms
    printf "round: whole %.1f s wall (%.1f s CPU, %d threads); %d shards %.1f s wall (%.1f s CPU); merge %.1f s wall (%.1f s CPU); merged dataset %s; load %s\n",
           ww, wc, t, n, sw, sc, mw, mc, same, load
    printf "  ratios to whole: shards %.2fx wall, shards + merge %.2fx wall, %.2fx CPU\n", sw / ww, (sw + mw) / ww, (sc + mc) / wc
  }'
done
