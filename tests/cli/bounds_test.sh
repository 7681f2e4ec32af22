#!/usr/bin/env bash
# Issue 32: every size a user can set is bounded, and names itself when refused. The two audit
# reproductions (a 100000 px thumbnail; a thumb-seq sequence of 2^31 - 1 frames) and a thumbnail
# larger than the dataset's camera image end at once with `error:` naming the parameter and a
# non-zero exit; a JUnit file of a method named with control and Latin-1 bytes is well-formed XML.
set -euo pipefail
hoilcd=$1
scene=$2
python=${3:-python3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$hoilcd" render "$scene" -o "$work/ds" --outputs thermal,persons > "$work/out" 2>&1 \
  || fail "render failed: $(cat "$work/out")"

# refused PARAM MESSAGE FLAGS...: bench with FLAGS exits non-zero within 20 s, printing `error:`,
# PARAM and MESSAGE, and writes no report.
refused() {
  local param=$1 message=$2
  shift 2
  local status=0
  timeout 20 "$hoilcd" bench "$work/ds" -o "$work/report" "$@" > "$work/out" 2>&1 || status=$?
  [ "$status" -ne 0 ] || fail "accepted: $*"
  [ "$status" -ne 124 ] || fail "still running after 20 s: $*"
  grep -q "^error: .*$param" "$work/out" || fail "$param not named in an error: $(cat "$work/out")"
  grep -qF -- "$message" "$work/out" || fail "'$message' not said: $(cat "$work/out")"
  [ ! -e "$work/report/report.json" ] || fail "a refused bench wrote a report: $*"
}
refused thumbnails.width_px "must be in [1, 8192]" \
  --methods thumb --param thumbnails.width_px=100000 --param thumbnails.height_px=100000
refused thumb-seq.sequence_length "must be in [1, 1000000]" \
  --methods thumb-seq --param thumb-seq.sequence_length=2147483647
refused thumbnails.width_px "must be at most the image width" --methods thumb --param thumbnails.width_px=1000

# render --frames beyond any sequence is refused before a frame is drawn.
if "$hoilcd" render "$scene" -o "$work/long" --frames 2000000 > "$work/out" 2>&1; then fail "render --frames 2000000 ran"; fi
grep -q "^error: .*frames: must be in \[0, 1000000\]" "$work/out" || fail "--frames bound not said: $(cat "$work/out")"
[ ! -e "$work/long/manifest.json" ] || fail "a refused render wrote a dataset"

# A camera of 4096 x 4096 px at 256 threads would hold ~275 GB of frames in flight: refused by name.
if "$hoilcd" render "$scene" -o "$work/big" --threads 256 --set camera.width_px=4096 --set camera.height_px=4096 \
  > "$work/out" 2>&1; then fail "a 4096 px camera rendered at 256 threads"; fi
grep -q "^error: --threads: rendering 256 threads' frames in flight .* needs .* GB; this process may allocate" "$work/out" \
  || fail "frames in flight not refused by name: $(cat "$work/out")"
[ ! -e "$work/big/manifest.json" ] || fail "a refused render wrote a dataset"

# A sequence length within its range but longer than this dataset counts as all of it.
timeout 120 "$hoilcd" bench "$work/ds" -o "$work/seq" --methods thumb-seq \
  --param thumb-seq.sequence_length=1000000 > "$work/out" 2>&1 || fail "a long sequence_length failed: $(cat "$work/out")"

# JUnit XML of a method named with a control character and a Latin-1 byte.
"$hoilcd" bench "$work/ds" -o "$work/scored" --methods thumb --dump-scores "$work/scores" > "$work/out" 2>&1 \
  || fail "bench --dump-scores failed: $(cat "$work/out")"
scores=$(ls "$work"/scores/*.csv | head -1)
"$hoilcd" evaluate "$work/ds" --scores "$scores" --name $'m\x01caf\xe9' -o "$work/evaluated" \
  --junit "$work/junit.xml" > "$work/out" 2>&1 || fail "evaluate --junit failed: $(cat "$work/out")"
"$python" -c 'import sys, xml.dom.minidom; xml.dom.minidom.parse(sys.argv[1])' "$work/junit.xml" \
  || fail "junit.xml is not well-formed: $(cat "$work/junit.xml")"
grep -qF 'name="m\x01caf\xe9"' "$work/junit.xml" || fail "the name's bytes are not shown: $(cat "$work/junit.xml")"
echo ok
