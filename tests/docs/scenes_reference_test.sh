#!/usr/bin/env bash
# docs/guide/scenes.md is what `hoilcd reference scene` prints today (it is generated from the
# option tables; an edited table or schema must regenerate it). Usage: scenes_reference_test.sh HOILCD REPO_ROOT
set -euo pipefail
hoilcd="$1"
root="$2"
if ! diff -u "$root/docs/guide/scenes.md" <("$hoilcd" reference scene); then
  echo "docs/guide/scenes.md is stale; regenerate it: build/bin/hoilcd reference scene > docs/guide/scenes.md"
  exit 1
fi
echo "docs/guide/scenes.md is current"
