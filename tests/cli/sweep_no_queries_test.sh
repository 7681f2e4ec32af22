#!/usr/bin/env bash
# Issue 48: a sweep whose runs end before the first lap does (so no query has a true match) says so
# on stderr and in summary.md, still exits 0 with its summary, and its runs' report.md hold no NaN
# (no paired comparison "  > : Δ nan", no "nan m" figure) but say why every metric is "-".
set -euo pipefail
hoilcd=$1
scene=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/hoilcd_sweep_no_queries_test.$$.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# tiny_room's first lap takes ~200 frames at 10 Hz: 40 and 60 frames never reach a revisit.
"$hoilcd" sweep "$scene" --set frames=40,60 --seeds 1 --methods paper --threads 2 \
  --cache "$work/cache" -o "$work/sweep" > "$work/stdout.txt" 2> "$work/stderr.txt" \
  || fail "the sweep failed: $(cat "$work/stderr.txt")"
grep -q "^warning: 2 of 2 runs scored no query" "$work/stderr.txt" || fail "no warning on stderr: $(cat "$work/stderr.txt")"
grep -q "frames=40,seed=1, frames=60,seed=1" "$work/stderr.txt" || fail "the warning does not name the runs: $(cat "$work/stderr.txt")"
grep -q "set more frames" "$work/stderr.txt" || fail "the warning does not say what to do: $(cat "$work/stderr.txt")"
grep -q '^\*\*Warning:\*\* 2 of 2 runs scored no query' "$work/sweep/summary.md" \
  || fail "summary.md has no warning: $(cat "$work/sweep/summary.md")"
grep -q '"runs_without_queries"' "$work/sweep/summary.json" || fail "summary.json does not list the runs without queries"
reports=("$work"/sweep/runs/*/report.md)
[ "${#reports[@]}" -eq 2 ] || fail "expected 2 reports, found ${#reports[@]}"
for report in "${reports[@]}"; do
  if grep -n -i -w "nan" "$report"; then fail "$report prints NaN (lines above)"; fi
  if grep -n -- " > : " "$report"; then fail "$report compares methods without queries (lines above)"; fi
  grep -q '^\*\*No query was scored\*\*' "$report" || fail "$report does not say that no query was scored"
done
echo "1 passed, 0 failed"
