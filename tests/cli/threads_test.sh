#!/usr/bin/env bash
# `--threads 0` means the CPUs this process may use: under `taskset -c <one cpu>` a render runs on
# one thread (not on every core of the machine), and an explicit --threads is kept.
set -euo pipefail
hoilcd=$1
scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v taskset > /dev/null || fail "taskset (util-linux) is missing"
cpu=$(taskset -pc $$ | sed 's/.*: *//; s/[-,].*//')
taskset -c "$cpu" "$hoilcd" render "$scene" -o "$work/one" --frames 3 --threads 0 > "$work/out" 2>&1 \
  || fail "render under taskset failed: $(cat "$work/out")"
grep -q "frames/s, 1 thread)" "$work/out" || fail "--threads 0 under taskset -c $cpu did not use one thread: $(cat "$work/out")"
taskset -c "$cpu" "$hoilcd" render "$scene" -o "$work/three" --frames 3 --threads 3 > "$work/out" 2>&1 \
  || fail "render --threads 3 failed: $(cat "$work/out")"
grep -q "frames/s, 3 threads)" "$work/out" || fail "--threads 3 was not kept: $(cat "$work/out")"
echo ok
