#!/usr/bin/env bash
# tools/thermal_table: the docs' table of the room's thermal solution on paper_room holds every room
# surface and the radiator held at its water's temperature, leaves out the wall behind the window
# (the north wall stays above the glass's temperature), and refuses a bad step by name.
set -euo pipefail
tool=$1
scene=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/hoilcd_thermal_table_test.$$.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$tool" "$scene" 40 > "$work/table.md" 2> "$work/stderr.txt" || fail "thermal_table failed: $(cat "$work/stderr.txt")"
for row in "| floor | floor |" "| ceiling | ceiling |" "| north wall | wall |" "| south wall (y = 0) | wall |" \
           "| mean over the material | window |" "| radiator (1) | radiator | held at 42.0 |" "| monitor (1) | monitor_back |"; do
  grep -qF "$row" "$work/table.md" || fail "no row '$row' in: $(cat "$work/table.md")"
done
# The north wall's coldest visible point is 21.1 °C; it read 19.7 while the patches behind the glass
# (16.7 °C) were in the network and blended into the wall above the window.
coldest=$(grep -F "| north wall | wall |" "$work/table.md" | awk -F'|' '{split($4, r, " "); print r[1]}')
awk -v c="$coldest" 'BEGIN { exit !(c > 20.5) }' || fail "the north wall's coldest point is $coldest °C"
if "$tool" "$scene" -5 > /dev/null 2> "$work/bad.txt"; then fail "a step of -5 s was accepted"; fi
grep -q "STEP_S '-5': expected seconds, a number above 0" "$work/bad.txt" || fail "unclear message: $(cat "$work/bad.txt")"
echo "thermal_table_test: ok"
