#!/usr/bin/env bash
# Issue 45, the class "folder handling that assumes one process and one render": two processes on
# one folder, TRIALS times (default 50) for KIND = render, merge, suite or sweep. Each process
# finishes, or is refused naming the folder ("DIR: is in use by another hoilcd process (pid N),
# which holds its lock file hoilcd.lock; ..."); the folder then holds exactly the bytes one process
# alone writes, with no temp or lock file left. Suites and sweeps sharing a --cache (each its own
# -o) both finish, the second waiting for the dataset the first renders. KIND = export-mot: two
# datasets exported into one folder at once both reach its seqmap. KIND = shard checks that render,
# suite and sweep refuse --shard '' (issue 45, defect 13).
# Usage: two_processes_test.sh HOILCD SCENE KIND [TRIALS]
set -euo pipefail
hoilcd=$1
scene=$(realpath "$2")
kind=$3
trials=${4:-50}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
refused=0

fail() {
  echo "$*" >&2
  exit 1
}
# Every file under a folder with its checksum, sorted.
tree() { (cd "$1" && find . -type f | sort | xargs -r md5sum); }
same_tree() {
  diff <(tree "$1") <(tree "$2") > /dev/null ||
    fail "$3: $2 is not what one process alone writes: $(diff <(tree "$1") <(tree "$2") | head -5)"
}

# Runs two hoilcd commands at once ($1 and $2, each a string of arguments); each must exit 0, or,
# when $4 is may-refuse, exit 1 refused by name for the folder $3.
pair() {
  local a=$1 b=$2 dir=$3 may=$4 codes=() pids=() i
  # shellcheck disable=SC2086
  "$hoilcd" -q $a > "$work/out0" 2> "$work/err0" &
  pids+=($!)
  # shellcheck disable=SC2086
  "$hoilcd" -q $b > "$work/out1" 2> "$work/err1" &
  pids+=($!)
  for i in 0 1; do
    if wait "${pids[$i]}"; then codes+=(0); else codes+=($?); fi
  done
  for i in 0 1; do
    [ "${codes[$i]}" -eq 0 ] && continue
    if [ "$may" = may-refuse ] && [ "${codes[$i]}" -eq 1 ] &&
      grep -Eq -- "$dir: is in use by another hoilcd process( \(pid [0-9]+\))?, which holds its lock file hoilcd.lock" \
        "$work/err$i"; then
      refused=$((refused + 1))
      continue
    fi
    fail "hoilcd $([ "$i" -eq 0 ] && echo "$a" || echo "$b") exited ${codes[$i]}: $(cat "$work/err$i")"
  done
}

frames=2        # render and merge: the scene cut to 2 frames (its robot's run too)
suite_frames=20 # suite and sweep: enough for the bench to have queries
start=$SECONDS
printf '{"name": "two", "sequences": [{"name": "s", "scene": "%s", "seeds": [1], "set": ["frames=%s"], "split": "dev"}]}\n' \
  "$scene" "$suite_frames" > "$work/suite.json"

case $kind in
render) # the same -o twice
  "$hoilcd" -q render "$scene" -o "$work/render_ref" --set frames=$frames --threads 1 > /dev/null
  for t in $(seq "$trials"); do
    rm -rf "$work/render"
    pair "render $scene -o $work/render --set frames=$frames --threads 1" \
      "render $scene -o $work/render --set frames=$frames --threads 1" "$work/render" may-refuse
    same_tree "$work/render_ref" "$work/render" "render trial $t"
  done
  ;;
merge) # the same -o twice, from two shards
  "$hoilcd" -q render "$scene" -o "$work/render_ref" --set frames=$frames --threads 1 > /dev/null
  for i in 0 1; do
    "$hoilcd" -q render "$scene" -o "$work/shard$i" --set frames=$frames --shard $i/2 --threads 1 > /dev/null
  done
  for t in $(seq "$trials"); do
    rm -rf "$work/merged"
    pair "merge $work/shard0 $work/shard1 -o $work/merged --threads 1" \
      "merge $work/shard1 $work/shard0 -o $work/merged --threads 1" "$work/merged" may-refuse
    same_tree "$work/render_ref" "$work/merged" "merge trial $t"
  done
  ;;
suite | sweep) # odd trials: the same -o (one may be refused); even trials: two -o sharing a --cache
  fast="--methods slcd --no-slam --threads 1"
  if [ "$kind" = suite ]; then
    what="suite $work/suite.json"
    report=suite_report.json
  else
    what="sweep $scene --set frames=$suite_frames --seeds 1"
    report=summary.json
  fi
  # shellcheck disable=SC2086
  "$hoilcd" -q $what -o "$work/${kind}_ref" --cache "$work/${kind}_ref_cache" $fast > /dev/null
  for t in $(seq "$trials"); do
    rm -rf "$work/$kind" "$work/${kind}_a" "$work/${kind}_b" "$work/${kind}_cache"
    if [ $((t % 2)) -eq 1 ]; then
      pair "$what -o $work/$kind --cache $work/${kind}_cache $fast" \
        "$what -o $work/$kind --cache $work/${kind}_cache $fast" "$work/$kind" may-refuse
      outs=("$work/$kind")
    else
      pair "$what -o $work/${kind}_a --cache $work/${kind}_cache $fast" \
        "$what -o $work/${kind}_b --cache $work/${kind}_cache $fast" "$work/${kind}_cache" must-finish
      outs=("$work/${kind}_a" "$work/${kind}_b")
    fi
    for out in "${outs[@]}"; do
      cmp -s "$work/${kind}_ref/$report" "$out/$report" || fail "$kind trial $t: $out/$report differs from one $kind alone"
      left=$(find "$out" "$work/${kind}_cache" -name '*.tmp.*' -o -name hoilcd.lock)
      [ -z "$left" ] || fail "$kind trial $t: left $left"
    done
  done
  ;;
export-mot) # two datasets into one folder at once: the seqmap they share lists both
  for seed in 1 2; do
    "$hoilcd" -q render "$scene" -o "$work/seed$seed" --set frames=$frames --seed $seed --threads 1 > /dev/null
    "$hoilcd" -q export-mot "$work/seed$seed" -o "$work/mot_ref" --threads 1 > /dev/null
  done
  for t in $(seq "$trials"); do
    rm -rf "$work/mot"
    pair "export-mot $work/seed1 -o $work/mot --threads 1" "export-mot $work/seed2 -o $work/mot --threads 1" \
      "$work/mot" must-finish
    same_tree "$work/mot_ref" "$work/mot" "export-mot trial $t"
  done
  ;;
shard) # --shard '' is refused by name, as any bad --shard, and writes nothing
  trials=0
  for command in "render $scene -o $work/bad" "suite $work/suite.json -o $work/bad" "sweep $scene -o $work/bad"; do
    # shellcheck disable=SC2086
    if "$hoilcd" -q $command --shard '' 2> "$work/err"; then fail "$command --shard '' was accepted"; fi
    grep -q -- "--shard: expected I/N" "$work/err" || fail "$command --shard '' refused without naming it: $(cat "$work/err")"
    [ ! -e "$work/bad" ] || fail "$command --shard '' wrote $work/bad"
  done
  ;;
*) fail "unknown KIND $kind: expected render, merge, suite, sweep, export-mot or shard" ;;
esac
echo "$kind: $trials trials, $refused refused by name, $((SECONDS - start)) s; all passed"
