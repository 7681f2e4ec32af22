#!/usr/bin/env bash
# hoilcd export-mcap end to end: the tiny room rendered with --outputs ...,mcap, exported again
# (zstd and uncompressed), each bag read by the independent reader (tests/mcap/read_bag.cjs:
# @mcap/core and @foxglove/rosmsg2-serialization under node) against the dataset; the render's bag
# and a second export are the same bytes; bad input fails naming the file.
# Usage: export_mcap_test.sh HOILCD TINY_ROOM_JSON NODE_MODULES READ_BAG_CJS
set -euo pipefail
hoilcd="$1" scene="$2" node_modules="$3" read_bag="$4"
if [ ! -d "$node_modules/@mcap/core" ] || [ ! -d "$node_modules/@foxglove/rosmsg2-serialization" ]; then
  echo "FAIL: the MCAP reader's npm packages are not installed in $node_modules:" \
       "run 'source scripts/setup && hoilcd_prepare_mcap_reader' (scripts/test does)" >&2
  exit 1
fi
command -v node > /dev/null || { echo "FAIL: node is not on PATH" >&2; exit 1; }
tmp="$(mktemp -d "${TMPDIR:-/tmp}/hoilcd_export_mcap.XXXXXX")"
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$hoilcd" -q render "$scene" -o "$tmp/ds" --outputs thermal,radiometric,exr,persons,mcap > "$tmp/render.txt"
[ -f "$tmp/ds/ros2.mcap" ] || fail "render --outputs ...,mcap wrote no ros2.mcap"
grep -q "/thermal/image_raw" "$tmp/render.txt" || fail "render printed no topic counts"
"$hoilcd" -q render "$scene" -o "$tmp/ds" --outputs thermal,radiometric,exr,persons,mcap > /dev/null \
  || fail "rendering the same dataset again refused the folder holding ros2.mcap"

"$hoilcd" -q export-mcap "$tmp/ds" -o "$tmp/a.mcap" > "$tmp/export.txt"
"$hoilcd" -q export-mcap "$tmp/ds" -o "$tmp/b.mcap" --threads 1 > /dev/null
cmp "$tmp/a.mcap" "$tmp/b.mcap" || fail "a second export differs"
cmp "$tmp/a.mcap" "$tmp/ds/ros2.mcap" || fail "the render's bag differs from export-mcap's"
"$hoilcd" -q export-mcap "$tmp/ds" -o "$tmp/none.mcap" --compression none > /dev/null

NODE_PATH="$node_modules" node "$read_bag" "$tmp/ds" "$tmp/a.mcap"
NODE_PATH="$node_modules" node "$read_bag" "$tmp/ds" "$tmp/none.mcap"

# A changed pixel: the reader must notice (the check is not vacuous).
cp -r "$tmp/ds" "$tmp/changed"
rm "$tmp/changed/radiometric/000007.png"
cp "$tmp/ds/radiometric/000008.png" "$tmp/changed/radiometric/000007.png"
if NODE_PATH="$node_modules" node "$read_bag" "$tmp/changed" "$tmp/a.mcap" 2> "$tmp/reader.txt"; then
  fail "the reader accepted a bag whose frame 7 differs from the PNG"
fi
grep -q "/thermal/image_raw frame" "$tmp/reader.txt" || { cat "$tmp/reader.txt"; fail "the reader's message names no frame"; }

# Bad input: each refused with exit 1, naming what is wrong; nothing written.
expect_error() {  # expect_error TEXT ARGS...
  local text="$1"; shift
  if "$hoilcd" -q "$@" > /dev/null 2> "$tmp/err.txt"; then fail "hoilcd $* succeeded"; fi
  grep -qF -- "$text" "$tmp/err.txt" || { cat "$tmp/err.txt"; fail "hoilcd $*: no '$text' in the error"; }
}
expect_error "$tmp/missing" export-mcap "$tmp/missing" -o "$tmp/c.mcap"
expect_error "radiometric/000007.png" export-mcap "$tmp/changed" -o "$tmp/c.mcap"
expect_error "--compression" export-mcap "$tmp/ds" -o "$tmp/c.mcap" --compression lz4
expect_error "is a folder" export-mcap "$tmp/ds" -o "$tmp/ds"
expect_error "mcap needs the whole sequence" render "$scene" -o "$tmp/shard" --shard 0/2 --outputs mcap
[ ! -e "$tmp/c.mcap" ] || fail "a failed export left c.mcap"
echo "export-mcap: bags read back by @mcap/core, byte-identical exports, bad input refused"
