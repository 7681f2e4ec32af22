#!/bin/bash
# Renders paper_room (all 1996 frames) with sensor effects switched on/off; keeps EXR for extraction.
set -e
export HOILCD_DATA_DIR=/work/main
B=/work/main/build/bin/hoilcd
S=${SCENE:-/work/main/scenes/paper_room.json}
P=${PREFIX:-pr}
FR=${FRAMES:-0}
EFF="optics_blur temporal_noise fixed_pattern drift lens_shading ffc_freeze time_constant quantisation"
render() { # name, sets...
  local name=$1; shift
  [ -f /tmp/slope/$P\_$name/manifest.json ] && grep -q '"complete": true' /tmp/slope/$P\_$name/manifest.json && return 0
  nice -n 10 $B -q render $S -o /tmp/slope/$P\_$name --outputs radiometric,exr --frames $FR --threads 1 "$@"
}
off_all() { for e in $EFF; do echo --set camera.$e=false; done; }
only() { for e in $EFF; do [ "$e" = "$1" ] || [ "$e" = "$2" ] || echo --set camera.$e=false; done; }
for v in "$@"; do
  case $v in
    full) render full ;;
    none) render none $(off_all) ;;
    only_*) e=${v#only_}; if [ $e = lowfreq ]; then render $v $(only drift lens_shading); else render $v $(only $e); fi ;;
    but_*) e=${v#but_}; render $v --set camera.$e=false ;;
  esac
done
