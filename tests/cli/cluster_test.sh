#!/usr/bin/env bash
# scripts/cluster/{sweep,suite,render}.sbatch (the one given) against stand-ins for sinfo and sbatch (no
# Slurm here): a request no node can hold, a partition sinfo does not list, a program that is not
# there or a bad merge setting is refused before anything is submitted; a request that fits submits
# the shard array and a merge (its cores and memory from MERGE_CPUS and MERGE_MEM) that Slurm cancels
# if a shard fails, with logs under the output folder; ONLY resubmits chosen shards; each step passes
# its settings from the environment to hoilcd (a sweep's values and frames, a suite's file, split and
# methods, a render's scene, frames and --set) with the cores Slurm gave the job as --threads.
set -euo pipefail
script=$1
kind=$(basename "$script" .sbatch)
work=$(mktemp -d "${TMPDIR:-/tmp}/hoilcd_cluster_test_$kind.$$.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL ($kind): $*" >&2; exit 1; }
# Whatever the caller's shell holds: the scripts read these.
unset SLURM_JOB_ID SLURM_ARRAY_TASK_ID SLURM_CPUS_PER_TASK SLURM_CPUS_ON_NODE HOILCD_STEP PARTITION ONLY \
      MERGE_CPUS MERGE_MEM CPUS MEM SHARDS OUT SCENE SUITE
mkdir "$work/bin"
# Partitions debug (nodes of 4 cores/7800 MB and 2 cores/3900 MB) and compute (the same); no other.
cat > "$work/bin/sinfo" <<'SH'
#!/bin/sh
case "$*" in
  *%R*) printf 'debug\ncompute\ndebug\n' ;;
  *"--partition bogus"*) ;;
  *) printf '4 7800\n2 3900\n' ;;
esac
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
echo '{}' > "$work/my_suite.json"
echo '{}' > "$work/my_scene.json"
export PATH="$work/bin:$PATH" SBATCH_LOG="$work/sbatch.log" HOILCD_LOG="$work/hoilcd.log" HOILCD="$work/bin/fake-hoilcd"
# The settings of each kind's steps, and what its shard and merge must pass to hoilcd.
case "$kind" in
  sweep)
    export SCENE="$work/my_scene.json" FRAMES=1300 VALUES=0,2
    shard_wants=("sweep $work/my_scene.json" "--set crowd.people_per_table=0,2" "--set frames=1300"
                 "--cache $work/out/cache" "-o $work/out/shard-1")
    merge_wants=("sweep $work/my_scene.json --set crowd.people_per_table=0,2 --seeds 3 --methods paper --set frames=1300"
                 "--merge $work/out/shard-0 $work/out/shard-1 $work/out/shard-2 -o $work/out")
    plain_out="$work/out"
    ;;
  suite)
    export SUITE="$work/my_suite.json" SPLIT=test METHODS=slcd,dlcd
    shard_wants=("suite $work/my_suite.json --split test --methods slcd,dlcd" "--cache $work/out/cache"
                 "-o $work/out/shard-1")
    merge_wants=("suite $work/my_suite.json --split test --methods slcd,dlcd"
                 "--merge $work/out/shard-0 $work/out/shard-1 $work/out/shard-2 -o $work/out")
    plain_out="$work/out"
    ;;
  render)
    export SCENE="$work/my_scene.json" FRAMES=300 SET="crowd.walkers=4 camera.video.enabled=true"
    shard_wants=("render $work/my_scene.json --frames 300 --set crowd.walkers=4 --set camera.video.enabled=true"
                 "-o $work/out/shard-1")
    merge_wants=("merge $work/out/shard-0 $work/out/shard-1 $work/out/shard-2 --threads 2 -o $work/out/dataset")
    plain_out="$work/out/dataset"
    ;;
  *) fail "unknown script $script" ;;
esac

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
for bad in x 1,,2 3; do
  if CPUS=4 MEM=7G SHARDS=3 ONLY="$bad" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "ONLY=$bad submitted"; fi
  grep -q "ONLY" "$work/out.txt" || fail "ONLY=$bad not explained: $(cat "$work/out.txt")"
done
# Issue 48: a partition sinfo does not list is named as missing, not as short of cores.
for bad in bogus debug,bogus; do
  if CPUS=4 MEM=7G PARTITION="$bad" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "PARTITION=$bad submitted"; fi
  grep -q "PARTITION: partition 'bogus' does not exist (sinfo lists: compute, debug)" "$work/out.txt" \
    || fail "PARTITION=$bad not named as missing: $(cat "$work/out.txt")"
  if grep -q "cores" "$work/out.txt"; then fail "PARTITION=$bad reported as a lack of cores: $(cat "$work/out.txt")"; fi
done
# A program that is not there (or not executable, or no command) is refused before submitting.
touch "$work/not-executable"
for bad in "$work/nowhere/hoilcd" "$work/not-executable" no-such-hoilcd-command; do
  if CPUS=4 MEM=7G HOILCD="$bad" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "HOILCD=$bad submitted"; fi
  grep -q "HOILCD: .*'$bad'" "$work/out.txt" || fail "HOILCD=$bad not named: $(cat "$work/out.txt")"
done
# The merge's cores and memory are checked like the shards'.
if CPUS=4 MEM=7G MERGE_CPUS=8 OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "MERGE_CPUS=8 submitted"; fi
grep -q "refusing to submit: the merge asks MERGE_CPUS=8 cores and MERGE_MEM=2G (2048 MB), but no node has that much (largest: 4 cores, 7800 MB); set MERGE_CPUS and MERGE_MEM lower" \
  "$work/out.txt" || fail "an oversized merge not refused by name: $(cat "$work/out.txt")"
if CPUS=4 MEM=7G MERGE_MEM=9G OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "MERGE_MEM=9G submitted"; fi
grep -q "the merge asks MERGE_CPUS=1 cores and MERGE_MEM=9G" "$work/out.txt" || fail "MERGE_MEM=9G not refused: $(cat "$work/out.txt")"
for bad in 0 x 1.5; do
  if CPUS=4 MEM=7G MERGE_CPUS="$bad" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "MERGE_CPUS=$bad submitted"; fi
  grep -q "MERGE_CPUS must be a positive whole number, not '$bad'" "$work/out.txt" || fail "MERGE_CPUS=$bad not explained: $(cat "$work/out.txt")"
done
if CPUS=4 MEM=7G MERGE_MEM=2X OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then fail "MERGE_MEM=2X submitted"; fi
grep -q "MERGE_MEM must look like 8G, 8000M or 8000 (MB), not '2X'" "$work/out.txt" || fail "MERGE_MEM=2X not explained: $(cat "$work/out.txt")"
if [ "$kind" = sweep ]; then
  if CPUS=4 MEM=7G SCENE="$work/nowhere.json" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then
    fail "a missing scene file was submitted"
  fi
  grep -q "SCENE: cannot read '$work/nowhere.json'" "$work/out.txt" || fail "missing scene not named: $(cat "$work/out.txt")"
fi
if [ "$kind" = suite ]; then
  if CPUS=4 MEM=7G SUITE="$work/nowhere.json" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then
    fail "a missing suite file was submitted"
  fi
  grep -q "SUITE: cannot read '$work/nowhere.json'" "$work/out.txt" || fail "missing suite not named: $(cat "$work/out.txt")"
fi
if [ "$kind" = render ]; then
  if CPUS=4 MEM=7G SCENE="$work/nowhere.json" OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1; then
    fail "a missing scene file was submitted"
  fi
  grep -q "SCENE: cannot read '$work/nowhere.json'" "$work/out.txt" || fail "missing scene not named: $(cat "$work/out.txt")"
fi
[ ! -e "$SBATCH_LOG" ] || fail "sbatch was called for a refused request"

# A request that fits: the array and the merge, logs under OUT/logs, merge cancelled on failure.
CPUS=4 MEM=7G SHARDS=3 OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1 \
  || fail "a fitting request was refused: $(cat "$work/out.txt")"
[ "$(wc -l < "$SBATCH_LOG")" -eq 2 ] || fail "expected two sbatch calls: $(cat "$SBATCH_LOG")"
shards=$(sed -n 1p "$SBATCH_LOG"); merge=$(sed -n 2p "$SBATCH_LOG")
for want in "--array=0-2" "--cpus-per-task=4" "--mem=7G" "--job-name=hoilcd-$kind" "--output=$work/out/logs/shard-%A_%a.out"; do
  case "$shards" in *"$want"*) ;; *) fail "shard submission lacks $want: $shards" ;; esac
done
for want in "--dependency=afterok:42421" "--kill-on-invalid-dep=yes" "HOILCD_STEP=merge" "--job-name=hoilcd-$kind-merge" \
            "--output=$work/out/logs/merge-%j.out" "--cpus-per-task=1 " "--mem=2G "; do
  case "$merge" in *"$want"*) ;; *) fail "merge submission lacks $want: $merge" ;; esac
done
[ -d "$work/out/logs" ] || fail "no log folder"
# Failed shards again: only they are submitted, and a merge after them.
CPUS=4 MEM=7G SHARDS=3 ONLY=0,2 OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1 \
  || fail "ONLY=0,2 was refused: $(cat "$work/out.txt")"
case "$(sed -n 3p "$SBATCH_LOG")" in *"--array=0,2 "*) ;; *) fail "ONLY=0,2 submitted $(sed -n 3p "$SBATCH_LOG")" ;; esac
case "$(sed -n 4p "$SBATCH_LOG")" in *"--dependency=afterok:42423 "*) ;; *) fail "no merge after ONLY: $(cat "$SBATCH_LOG")" ;; esac
# The merge's resources from MERGE_CPUS and MERGE_MEM; an existing partition is passed to both jobs.
CPUS=4 MEM=7G SHARDS=3 MERGE_CPUS=2 MERGE_MEM=3900M PARTITION=debug OUT="$work/out" bash "$script" > "$work/out.txt" 2>&1 \
  || fail "MERGE_CPUS=2 MERGE_MEM=3900M PARTITION=debug was refused: $(cat "$work/out.txt")"
case "$(sed -n 5p "$SBATCH_LOG")" in *"--partition debug "*"--cpus-per-task=4 --mem=7G "*) ;; *) fail "shards not on debug: $(sed -n 5p "$SBATCH_LOG")" ;; esac
case "$(sed -n 6p "$SBATCH_LOG")" in
  *"--partition debug "*"--cpus-per-task=2 --mem=3900M "*) ;;
  *) fail "merge without MERGE_CPUS, MERGE_MEM or PARTITION: $(sed -n 6p "$SBATCH_LOG")" ;;
esac
grep -q "merge: job 42426" "$work/out.txt" || fail "the submission does not name the merge job: $(cat "$work/out.txt")"
grep -q "(2 cores, 3900M)" "$work/out.txt" || fail "the submission does not say what the merge got: $(cat "$work/out.txt")"

# Inside the jobs: a shard and the merge call hoilcd with the settings and cores.
SLURM_JOB_ID=1 SLURM_ARRAY_TASK_ID=1 SLURM_CPUS_PER_TASK=4 SHARDS=3 OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
for want in "${shard_wants[@]}" "--shard 1/3" "--threads 4"; do
  grep -q -- "$want" "$HOILCD_LOG" || fail "shard runs hoilcd without $want: $(cat "$HOILCD_LOG")"
done
SLURM_JOB_ID=2 SLURM_CPUS_PER_TASK=2 HOILCD_STEP=merge SHARDS=3 OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
for want in "${merge_wants[@]}"; do
  grep -q -- "$want" "$HOILCD_LOG" || fail "merge runs hoilcd without $want: $(cat "$HOILCD_LOG")"
done
# A plain sbatch of the file (no array): the whole job in one, its output straight into OUT.
SLURM_JOB_ID=3 SLURM_CPUS_PER_TASK=4 OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
grep -q -- "-o $plain_out\$" "$HOILCD_LOG" || fail "a plain job does not write into OUT: $(cat "$HOILCD_LOG")"
if grep -q -- "--shard" "$HOILCD_LOG"; then fail "a plain job runs a shard: $(cat "$HOILCD_LOG")"; fi
grep -q -- "--threads 4 " "$HOILCD_LOG" || fail "a plain job with 4 CPUs per task does not run 4 threads: $(cat "$HOILCD_LOG")"
# Issue 48: a plain sbatch without --cpus-per-task runs on the CPUs Slurm allocated (SLURM_CPUS_ON_NODE,
# else one), never on every core (--threads 0).
SLURM_JOB_ID=4 SLURM_CPUS_ON_NODE=2 OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
grep -q -- "--threads 2 " "$HOILCD_LOG" || fail "a plain job on 2 allocated CPUs does not run 2 threads: $(cat "$HOILCD_LOG")"
SLURM_JOB_ID=5 OUT="$work/out" HOILCD=fake-hoilcd bash "$script"
grep -q -- "--threads 1 " "$HOILCD_LOG" || fail "a plain job without an allocation count does not run 1 thread: $(cat "$HOILCD_LOG")"
echo "1 passed, 0 failed"
