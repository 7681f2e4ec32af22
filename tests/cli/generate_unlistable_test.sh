#!/usr/bin/env bash
# Issue 45, defect 1: `hoilcd generate -o DIR`, by a user who cannot list DIR (mode 333) holding
# that user's scene_0000_lounge.json, exited 0 and overwrote the file. It must refuse, naming the
# folder, and leave the file. Runs as user nobody when run as root (root lists any folder); exits
# 77 (skipped) only when root cannot give up its privileges here.
set -euo pipefail
hoilcd=$1
work=$(mktemp -d)
trap 'chmod 755 "$work/out" 2> /dev/null || true; rm -rf "$work"' EXIT
chmod 755 "$work"
mkdir "$work/out"
echo '{"mine": 1}' > "$work/out/scene_0000_lounge.json"
chmod 666 "$work/out/scene_0000_lounge.json"
chmod 333 "$work/out"
as_user=()
if [ "$(id -u)" -eq 0 ]; then
  as_user=(setpriv --reuid=65534 --regid=65534 --clear-groups)
  "${as_user[@]}" true 2> /dev/null || { echo "cannot run as user nobody here: skipped" >&2; exit 77; }
fi
if "${as_user[@]}" "$hoilcd" -q generate --layout lounge --count 1 --seed 1 -o "$work/out" 2> "$work/err.txt"; then
  echo "generate wrote into a folder it cannot list" >&2
  exit 1
fi
grep -q "$work/out: cannot list the folder (Permission denied)" "$work/err.txt" ||
  { echo "refused without naming the folder: $(cat "$work/err.txt")" >&2; exit 1; }
chmod 755 "$work/out"
[ "$(cat "$work/out/scene_0000_lounge.json")" = '{"mine": 1}' ] || { echo "the user's scene was overwritten" >&2; exit 1; }
echo "1 passed, 0 failed"
