#!/usr/bin/env bash
# A page generated from the code is what `hoilcd reference TOPIC` prints today (an edited option
# table, schema or camera profile must regenerate it).
# Usage: scenes_reference_test.sh HOILCD REPO_ROOT [TOPIC PAGE] (default: scene docs/guide/scenes.md)
set -euo pipefail
hoilcd="$1"
root="$2"
topic="${3:-scene}"
page="${4:-docs/guide/scenes.md}"
if ! diff -u "$root/$page" <("$hoilcd" reference "$topic"); then
  echo "$page is stale; regenerate it: build/bin/hoilcd reference $topic > $page"
  exit 1
fi
echo "$page is current"
