#!/usr/bin/env bash
# `hoilcd validate` accepts every shipped scene and reports every problem of a bad one with its
# file and JSON pointer, exiting non-zero; a missing file and bad flags are clear errors too.
set -euo pipefail
hoilcd=$1
source_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

for scene in "$source_dir"/scenes/*.json; do
  case "$scene" in *scene.schema.json) continue ;; esac
  "$hoilcd" validate "$scene" > /dev/null || fail "shipped scene $scene does not validate"
done

cat > "$work/bad.json" <<'JSON'
{ "frames": 0, "crowd": { "people_per_tabel": 3 }, "camera": { "netd_k": "low" } }
JSON
if "$hoilcd" validate "$work/bad.json" > "$work/out" 2>&1; then fail "a bad scene validated"; fi
grep -q "$work/bad.json: /frames" "$work/out" || fail "no /frames problem: $(cat "$work/out")"
grep -q "$work/bad.json: /crowd: unknown key 'people_per_tabel'" "$work/out" || fail "no unknown-key problem: $(cat "$work/out")"
grep -q "$work/bad.json: /camera/netd_k" "$work/out" || fail "no /camera/netd_k problem: $(cat "$work/out")"

if "$hoilcd" validate "$work/missing.json" > "$work/out" 2>&1; then fail "a missing scene validated"; fi
grep -q "missing.json" "$work/out" || fail "missing file not named"

if "$hoilcd" render "$source_dir/scenes/paper_room.json" -o "$work/x" --set crowd.people_per_table=9 > "$work/out" 2>&1; then
  fail "an out-of-range --set rendered"
fi
grep -q "/crowd/people_per_table" "$work/out" || fail "bad --set not reported at its path: $(cat "$work/out")"
[ ! -e "$work/x/manifest.json" ] || fail "a rejected render wrote a dataset"

for flags in "render $source_dir/scenes/paper_room.json -o $work/t" "bench $work/t" "run" "sweep $source_dir/scenes/paper_room.json -o $work/t"; do
  # shellcheck disable=SC2086  # flags are split on purpose
  if "$hoilcd" $flags --threads 134217728 > "$work/out" 2>&1; then fail "--threads 134217728 accepted by ${flags%% *}"; fi
  grep -q -- "--threads" "$work/out" || fail "--threads not named: $(cat "$work/out")"
  grep -q "1024" "$work/out" || fail "allowed --threads range not given: $(cat "$work/out")"
done
[ ! -e "$work/t" ] || fail "a rejected --threads wrote something"
# thermal.mp4 cannot carry every frame rate: validate and render both say so at its JSON path.
echo '{ "frame_rate_hz": 25.123456 }' > "$work/rate.json"
if "$hoilcd" validate "$work/rate.json" > "$work/out" 2>&1; then fail "an unsupported frame rate validated"; fi
grep -q "$work/rate.json: /frame_rate_hz: thermal.mp4 needs a frame rate" "$work/out" || fail "no /frame_rate_hz problem: $(cat "$work/out")"
if "$hoilcd" render "$work/rate.json" -o "$work/y" --frames 1 > "$work/out" 2>&1; then fail "an unsupported frame rate rendered"; fi
grep -q "/frame_rate_hz" "$work/out" || fail "render did not name /frame_rate_hz: $(cat "$work/out")"
[ ! -e "$work/y/manifest.json" ] || fail "a rejected render wrote a dataset"
if "$hoilcd" validate "$source_dir/scenes/paper_room.json" --set camera.video.crf=52 > "$work/out" 2>&1; then
  fail "an out-of-range CRF validated"
fi
grep -q "/camera/video/crf" "$work/out" || fail "bad CRF not reported at its path: $(cat "$work/out")"

if "$hoilcd" bench "$work/nothing" > "$work/out" 2>&1; then fail "bench of a missing dataset succeeded"; fi
grep -q "nothing" "$work/out" || fail "missing dataset not named: $(cat "$work/out")"
# SLAM flags: a back end that does not exist is refused by the parser; a threshold that is not finite is
# bad input, refused before anything is rendered.
rc=0
"$hoilcd" run "$source_dir/tests/data/tiny_room.json" --cache "$work/runs" --slam-backend gauss > "$work/out" 2>&1 || rc=$?
[ "$rc" -ne 0 ] || fail "an unknown --slam-backend ran: $(cat "$work/out")"
grep -q "slam-backend" "$work/out" || fail "bad --slam-backend not named: $(cat "$work/out")"
if "$hoilcd" run "$source_dir/tests/data/tiny_room.json" --cache "$work/runs" --loop-threshold inf > "$work/out" 2>&1; then
  fail "an infinite --loop-threshold ran"
fi
grep -q "loop_threshold: must be a finite number" "$work/out" || fail "infinite --loop-threshold not explained: $(cat "$work/out")"
[ ! -e "$work/runs" ] || fail "a refused run rendered"
echo "1 passed, 0 failed"
