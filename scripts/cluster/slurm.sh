# shellcheck shell=bash
# The login-node half of scripts/cluster/*.sbatch, sourced by each: check a request against the
# partitions and nodes, then submit the script as a job array (one task per shard) and as a merge
# job that starts only when every array task succeeded (afterok on the array job id waits for all
# its tasks) and is cancelled by Slurm if one failed (--kill-on-invalid-dep=yes), instead of
# pending forever. Not sourced inside the jobs: Slurm runs a copy of the batch script from its
# spool folder.
#
# The caller sets SHARDS, CPUS, MEM, TIME, OUT and HOILCD (and optionally PARTITION; ONLY, the
# array task ids to submit, e.g. ONLY=3,5 to run failed shards again; MERGE_CPUS and MERGE_MEM,
# the merge job's, 1 and 2G by default), checks its own files with require_file, exports what its
# jobs read, and calls submit_shards_and_merge "$0" NAME. Inside the merge job HOILCD_STEP=merge.

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

# Exits 2 unless every named variable holds a memory size as sbatch --mem takes it.
require_mem() {
  local name
  for name in "$@"; do
    [[ "${!name}" =~ ^[1-9][0-9]*[MmGgTt]?$ ]] || { echo "$name must look like 8G, 8000M or 8000 (MB), not '${!name}'" >&2; exit 2; }
  done
}

# require_file NAME WHAT: exits 2 unless the file in variable NAME can be read from here (the jobs
# start in this folder too), saying what to give instead.
require_file() {
  [ -r "${!1}" ] || { echo "$1: cannot read '${!1}' from $PWD, where the jobs start (give $2)" >&2; exit 2; }
}

# Exits 2 unless HOILCD names a program the jobs can run: a path (relative ones from this folder,
# where the jobs start) to an executable file, or a command on PATH. Checked here, since a job
# that cannot start it fails with exit 127 and takes the merge with it.
require_program() {
  if [[ "$HOILCD" == */* ]]; then
    [ -f "$HOILCD" ] && [ -x "$HOILCD" ] && return 0
    echo "HOILCD: no executable program at '$HOILCD' (from $PWD, where the jobs start): build hoilcd," \
         "submit from the repository root, or set HOILCD to the program's path" >&2
  else
    command -v "$HOILCD" > /dev/null && return 0
    echo "HOILCD: '$HOILCD' is no command on PATH: set HOILCD to the program's path (e.g. build/bin/hoilcd)" >&2
  fi
  exit 2
}

# Exits 2 unless every partition PARTITION names (one, or a comma-separated list as sbatch takes)
# is one sinfo knows, hidden ones included; a name sinfo does not list has no nodes to check.
require_partition() {
  [ -n "${PARTITION:-}" ] || return 0
  local known p
  known=$(sinfo -a -h -o '%R' | sort -u)
  for p in ${PARTITION//,/ }; do
    grep -qxF -- "$p" <<< "$known" && continue
    known=$(paste -sd, <<< "$known" | sed 's/,/, /g')
    echo "PARTITION: partition '$p' does not exist (sinfo lists: ${known:-no partition}); leave PARTITION unset for Slurm's default" >&2
    exit 2
  done
}

# require_fits WHAT CPUS_NAME MEM_NAME NODES: exits 1, with the numbers and the largest node,
# unless one of NODES (sinfo's "cores MB" lines) holds the cores and memory in the named variables.
require_fits() {
  local what=$1 cpus_name=$2 mem_name=$3 nodes=$4 need_mb fits largest
  need_mb=$(mem_mb "${!mem_name}")
  fits=$(awk -v c="${!cpus_name}" -v m="$need_mb" '$1 >= c && $2 + 0 >= m { n++ } END { print n + 0 }' <<< "$nodes")
  [ "$fits" -eq 0 ] || return 0
  largest=$(awk '{ if ($1 > c) c = $1; if ($2 + 0 > m) m = $2 + 0 } END { print c + 0 " cores, " m + 0 " MB" }' <<< "$nodes")
  echo "refusing to submit: $what asks $cpus_name=${!cpus_name} cores and $mem_name=${!mem_name} ($need_mb MB), but no" \
       "node ${PARTITION:+of partition $PARTITION }has that much (largest: $largest); set $cpus_name and $mem_name lower" >&2
  exit 1
}

# submit_shards_and_merge SCRIPT NAME: refuses a request with a bad setting, a missing program or
# partition, or shards or a merge no node can hold; else submits SCRIPT as the array hoilcd-NAME
# and the merge hoilcd-NAME-merge, logs in $OUT/logs/, and says what it submitted.
submit_shards_and_merge() {
  local script=$1 name=$2
  MERGE_CPUS=${MERGE_CPUS:-1}
  MERGE_MEM=${MERGE_MEM:-2G}
  require_positive SHARDS CPUS MERGE_CPUS
  require_mem MEM MERGE_MEM
  local tasks="0-$((SHARDS - 1))" task
  if [ -n "${ONLY:-}" ]; then
    [[ "$ONLY" =~ ^[0-9]+(,[0-9]+)*$ ]] || { echo "ONLY must list shard numbers like 3 or 3,5, not '$ONLY'" >&2; exit 2; }
    for task in ${ONLY//,/ }; do
      [ "$task" -lt "$SHARDS" ] || { echo "ONLY: shard $task does not exist: shards are 0..$((SHARDS - 1))" >&2; exit 2; }
    done
    tasks=$ONLY
  fi
  require_program
  local tool
  for tool in sinfo sbatch; do
    command -v "$tool" > /dev/null || { echo "refusing to submit: $tool is not on PATH (run this on a Slurm login node)" >&2; exit 2; }
  done
  require_partition
  local partition=()
  if [ -n "${PARTITION:-}" ]; then partition=(--partition "$PARTITION"); fi
  # The nodes (of the partition), one "cores MB" line each: sinfo gives memory in MB.
  local nodes
  nodes=$(sinfo -h -N "${partition[@]}" -o '%c %m')
  if [ -z "$nodes" ]; then
    echo "refusing to submit: sinfo lists no node${PARTITION:+ in partition $PARTITION}" >&2
    exit 1
  fi
  require_fits "each shard" CPUS MEM "$nodes"
  require_fits "the merge" MERGE_CPUS MERGE_MEM "$nodes"
  mkdir -p "$OUT/logs"
  local common=(--parsable --export=ALL --time="$TIME" "${partition[@]}") array_id merge_id
  array_id=$(sbatch "${common[@]}" --array="$tasks" --cpus-per-task="$CPUS" --mem="$MEM" \
    --job-name="hoilcd-$name" --output="$OUT/logs/shard-%A_%a.out" "$script")
  array_id=${array_id%%;*}  # --parsable prints "id" or "id;cluster"
  merge_id=$(sbatch "${common[@]}" --dependency=afterok:"$array_id" --kill-on-invalid-dep=yes \
    --export=ALL,HOILCD_STEP=merge --cpus-per-task="$MERGE_CPUS" --mem="$MERGE_MEM" --job-name="hoilcd-$name-merge" \
    --output="$OUT/logs/merge-%j.out" "$script")
  merge_id=${merge_id%%;*}
  echo "shards: job array $array_id ($tasks of 0-$((SHARDS - 1))), $CPUS cores and $MEM each; merge: job $merge_id"
  echo "($MERGE_CPUS cores, $MERGE_MEM) after all shards succeed (Slurm cancels it if one fails: see sacct -j $array_id)."
  echo "Logs: $OUT/logs/"
}
