#!/bin/sh
# Bench's measuring code reads only the dataset folder: none of these files includes hoilcd/sim
# (issue 15). Usage: bench_reads_only_dataset_test.sh REPO_ROOT
set -u
root="$1"
cd "$root/bench/src" || exit 2
found=$(grep -n 'hoilcd/sim' runner*.cpp metrics*.cpp protocol*.cpp report*.cpp tracking_metrics*.cpp \
  methods*.cpp figures*.cpp diagnosis*.cpp)
if [ -n "$found" ]; then
  echo "bench measuring code includes hoilcd/sim (read the dataset instead):"
  echo "$found"
  exit 1
fi
echo "no hoilcd/sim include in bench's measuring code"
