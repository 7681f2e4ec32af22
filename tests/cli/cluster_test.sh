#!/usr/bin/env bash
# scripts/cluster/sweep.sbatch against stand-ins for sinfo and sbatch (no Slurm here): a request no
# node can hold is refused before anything is submitted; a request that fits submits the shard
# array and a merge that Slurm cancels if a shard fails, with logs under the sweep's folder;
# each step passes the swept values, frames and cores from the environment to hoilcd.
set -euo pipefail
script=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir "$work/bin"
cat > "$work/bin/sinfo" <<'SH'
#!/bin/sh
printf '4 7800\n2 3900\n'
SH
cat > "$work/bin/sbatch" <<'SH'
#!/bin/sh
echo "$*" >> "$SBATCH_LOG"
echo "4242$(wc -l < "$SBATCH_LOG" | tr -d ' ');cluster"
SH
cat > "$work/bin/fake-hoilcd" <<'SH'
#!/bin/sh
echo "$*" > "$HOILCD_LOG"
SH
chmod +x "$work/bin/"*
export PATH="$work/bin:$PATH" SBATCH_LOG="$work/sbatch.log" HOILCD_LOG="$work/hoilcd.log"

# The shipped default (8 cores) cannot fit a 4-core node: refused, nothing submitted.
if OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "an oversized request was submitted"; fi
grep -q "refusing to submit: each shard asks CPUS=8" "$work/out.txt" || fail "no refusal: $(cat "$work/out.txt")"
grep -q "largest: 4 cores, 7800 MB" "$work/out.txt" || fail "largest node not named: $(cat "$work/out.txt")"
[ ! -e "$SBATCH_LOG" ] || fail "sbatch was called for a refused request"
if CPUS=4 MEM=16G OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "too much memory submitted"; fi
for bad in 8GG G 0 8.5G -8G; do
  if CPUS=4 MEM="$bad" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "MEM=$bad submitted"; fi
  grep -q "MEM must look like" "$work/out.txt" || fail "MEM=$bad not explained: $(cat "$work/out.txt")"
done

# A request that fits: the array and the merge, logs under OUT/logs, merge cancelled on failure.
CPUS=4 MEM=7G SHARDS=3 FRAMES=400 VALUES=0,2 OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1 \
  || fail "a fitting request was refused: $(cat "$work/out.txt")"
[ "$(wc -l < "$SBATCH_LOG")" -eq 2 ] || fail "expected two sbatch calls: $(cat "$SBATCH_LOG")"
shards=$(sed -n 1p "$SBATCH_LOG"); merge=$(sed -n 2p "$SBATCH_LOG")
for want in "--array=0-2" "--cpus-per-task=4" "--mem=7G" "--output=$work/out/logs/shard-%A_%a.out"; do
  case "$shards" in *"$want"*) ;; *) fail "shard submission lacks $want: $shards" ;; esac
done
for want in "--dependency=afterok:42421" "--kill-on-invalid-dep=yes" "--output=$work/out/logs/merge-%j.out"; do
  case "$merge" in *"$want"*) ;; *) fail "merge submission lacks $want: $merge" ;; esac
done
[ -d "$work/out/logs" ] || fail "no log folder"

# Inside the jobs: a shard and the merge call hoilcd with the values, frames and cores.
SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=4 SHARDS=3 FRAMES=400 VALUES=0,2 \
  OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
for want in "--set crowd.people_per_table=0,2" "--set frames=400" "--shard 1/3" "--threads 4"; do
  grep -q -- "$want" "$HOILCD_LOG" || fail "shard runs hoilcd without $want: $(cat "$HOILCD_LOG")"
done
SLURM_JOB_ID=2 SWEEP_STEP=merge SHARDS=3 FRAMES=400 VALUES=0,2 OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
grep -q -- "--merge $work/out/shard-0 $work/out/shard-1 $work/out/shard-2 -o $work/out" "$HOILCD_LOG" \
  || fail "merge does not list the shards: $(cat "$HOILCD_LOG")"
echo "1 passed, 0 failed"
