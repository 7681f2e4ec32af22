#!/usr/bin/env bash
# examples/cpp_method builds against an installed (and moved) prefix, registers its own
# LoopClosureMethod, and benchmarks it beside SLCD: both get figures and the report describes
# the new method from its object (issue 12).
# Arguments: CMAKE BUILD_DIR EXAMPLE_SOURCE_DIR SCENE (a short two-lap scene: tests/data/tiny_room.json)
set -euo pipefail
cmake=$1
build=$2
example=$3
scene=$4
source "$(dirname "${BASH_SOURCE[0]}")/moved_prefix.sh"
moved_prefix "$cmake" "$build" install_cpp_method
"$cmake" -S "$example" -B "$work/example-build" -DCMAKE_PREFIX_PATH="$moved" > "$work/example.log" 2>&1 \
  || { cat "$work/example.log"; fail "configuring the example"; }
"$cmake" --build "$work/example-build" >> "$work/example.log" 2>&1 || { cat "$work/example.log"; fail "building the example"; }

# 300 frames of tiny_room reach into its second lap, so the laps protocol has queries.
"$moved/bin/hoilcd" -q render "$scene" -o "$work/dataset" --frames 300 --threads 2 > /dev/null
"$work/example-build/column_profile_bench" "$work/dataset" "$work/report" > "$work/out" 2>&1 \
  || { cat "$work/out"; fail "the example failed"; }
grep -Eq '^column-profile: MRR 0\.[0-9]{4}, R@1 [01]\.[0-9]{4} over [1-9][0-9]* queries$' "$work/out" \
  || fail "no column-profile figures: $(cat "$work/out")"
grep -Eq '^slcd: MRR ' "$work/out" || fail "no slcd figures: $(cat "$work/out")"
grep -q "negative L1 distance of per-column mean intensity" "$work/report/report.md" \
  || fail "the report does not describe the example method"
if "$work/example-build/column_profile_bench" "$work/nowhere" > "$work/bad" 2>&1; then fail "a missing dataset ran"; fi
grep -q "^error: .*nowhere" "$work/bad" || fail "missing dataset: $(cat "$work/bad")"
echo "install_cpp_method: ok"
