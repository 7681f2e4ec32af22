# shellcheck shell=bash
# The login-node half of scripts/cluster/*.sbatch, sourced by each: check a request against the
# nodes, then submit the script as a job array (one task per shard) and as a merge job that starts
# only when every array task succeeded (afterok on the array job id waits for all its tasks) and
# is cancelled by Slurm if one failed (--kill-on-invalid-dep=yes), instead of pending forever.
# Not sourced inside the jobs: Slurm runs a copy of the batch script from its spool folder.
#
# The caller sets SHARDS, CPUS, MEM, TIME and OUT (and optionally PARTITION and ONLY, the array
# task ids to submit, e.g. ONLY=3,5 to run failed shards again), exports what its jobs read, and
# calls submit_shards_and_merge "$0" NAME. Inside the merge job HOILCD_STEP=merge.

# "8G" / "8000M" / "8000" (MB, Slurm's unit) -> MB.
mem_mb() {
  case "$1" in
    *[Tt]) echo $(( ${1%?} * 1024 * 1024 )) ;;
    *[Gg]) echo $(( ${1%?} * 1024 )) ;;
    *[Mm]) echo "${1%?}" ;;
    *) echo "$1" ;;
  esac
}

# Exits 2 unless every named variable holds a positive whole number.
require_positive() {
  local name
  for name in "$@"; do
    case "${!name}" in ''|*[!0-9]*|0) echo "$name must be a positive whole number, not '${!name}'" >&2; exit 2 ;; esac
  done
}

# submit_shards_and_merge SCRIPT NAME: refuses (exit 1), with the numbers and the largest node, a
# request no node of PARTITION can hold; else submits SCRIPT as the array hoilcd-NAME and the merge
# hoilcd-NAME-merge, logs in $OUT/logs/, and says what it submitted.
submit_shards_and_merge() {
  local script=$1 name=$2
  require_positive SHARDS CPUS
  [[ "$MEM" =~ ^[1-9][0-9]*[MmGgTt]?$ ]] || { echo "MEM must look like 8G, 8000M or 8000 (MB), not '$MEM'" >&2; exit 2; }
  local tasks="0-$((SHARDS - 1))" task
  if [ -n "${ONLY:-}" ]; then
    [[ "$ONLY" =~ ^[0-9]+(,[0-9]+)*$ ]] || { echo "ONLY must list shard numbers like 3 or 3,5, not '$ONLY'" >&2; exit 2; }
    for task in ${ONLY//,/ }; do
      [ "$task" -lt "$SHARDS" ] || { echo "ONLY: shard $task does not exist: shards are 0..$((SHARDS - 1))" >&2; exit 2; }
    done
    tasks=$ONLY
  fi
  local partition=()
  if [ -n "${PARTITION:-}" ]; then partition=(--partition "$PARTITION"); fi
  # Nodes (of the partition) with at least CPUS cores and MEM memory; sinfo gives memory in MB.
  local need_mb nodes fits largest
  need_mb=$(mem_mb "$MEM")
  nodes=$(sinfo -h -N "${partition[@]}" -o '%c %m')
  fits=$(awk -v c="$CPUS" -v m="$need_mb" '$1 >= c && $2 + 0 >= m { n++ } END { print n + 0 }' <<< "$nodes")
  if [ "$fits" -eq 0 ]; then
    largest=$(awk '{ if ($1 > c) c = $1; if ($2 + 0 > m) m = $2 + 0 } END { print c + 0 " cores, " m + 0 " MB" }' <<< "$nodes")
    echo "refusing to submit: each shard asks CPUS=$CPUS cores and MEM=$MEM ($need_mb MB), but no node" \
         "${PARTITION:+of partition $PARTITION }has that much (largest: $largest); set CPUS and MEM lower" >&2
    exit 1
  fi
  mkdir -p "$OUT/logs"
  local common=(--parsable --export=ALL --time="$TIME" "${partition[@]}") array_id merge_id
  array_id=$(sbatch "${common[@]}" --array="$tasks" --cpus-per-task="$CPUS" --mem="$MEM" \
    --job-name="hoilcd-$name" --output="$OUT/logs/shard-%A_%a.out" "$script")
  array_id=${array_id%%;*}  # --parsable prints "id" or "id;cluster"
  merge_id=$(sbatch "${common[@]}" --dependency=afterok:"$array_id" --kill-on-invalid-dep=yes \
    --export=ALL,HOILCD_STEP=merge --cpus-per-task=1 --mem=2G --job-name="hoilcd-$name-merge" \
    --output="$OUT/logs/merge-%j.out" "$script")
  merge_id=${merge_id%%;*}
  echo "shards: job array $array_id ($tasks of 0-$((SHARDS - 1))), $CPUS cores and $MEM each; merge: job $merge_id after"
  echo "all shards succeed (Slurm cancels it if one fails: see sacct -j $array_id). Logs: $OUT/logs/"
}
