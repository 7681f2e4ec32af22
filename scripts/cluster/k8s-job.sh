#!/bin/bash
# Prints the Kubernetes manifest of a sharded hoilcd sweep, suite or render: the template
# scripts/cluster/KIND-job.yaml.in with its ${...} parameters filled in from the environment (the
# names and defaults of the Slurm scripts where they mean the same; docs/guide/cli.md lists them).
# Every value is checked first, so a bad one is refused here by name rather than by kubectl or a
# pod. Nothing is applied:
#
#   SHARDS=5 CPUS=2 MEM=3Gi bash scripts/cluster/k8s-job.sh sweep > sweep-job.yaml
#   kubectl apply -f sweep-job.yaml -l hoilcd-step=shards     # then, once they completed, merge
#
# Parameters (environment, with defaults):
#   every kind: IMAGE=hoilcd:latest; SHARDS (sweep 7, suite 13, render 4); CPUS=4 cores and MEM
#     (sweep and suite 6Gi, render 4Gi) per shard pod; MERGE_CPUS=1 and MERGE_MEM=2Gi for the merge
#     pod; STORAGE (sweep 50Gi, suite 100Gi, render 20Gi) for the shared volume; OUT, the results'
#     folder on the volume (sweep /sweeps/$SWEEP, suite /suites/<suite file's name>, render
#     /renders/<scene file's name>)
#   sweep: SWEEP=crowd (people_per_table 0..6 on scenes/crowded_room.json) or occlusion (walkers
#     0,2,4,6,8 on scenes/paper_room.json), VALUES, SCENE, SEEDS=3, METHODS=paper, FRAMES (the scene's)
#   suite: SUITE=suites/standard.json, SPLIT=all, METHODS=paper
#   render: SCENE=scenes/paper_room.json, FRAMES, SEED, OUTPUTS (the scene's), SET (space-separated
#     KEY=VALUE --set overrides)
# SCENE and SUITE are paths inside the image, relative to /hoilcd.
set -euo pipefail

kind=${1:-}
here=$(dirname "$0")
fail() { echo "$*" >&2; exit 2; }
# Words the pods' shell takes as they are (no spaces, quotes, globs or $): they are written into
# its command line.
safe='^[A-Za-z0-9._/,=:+-]*$'

IMAGE=${IMAGE:-hoilcd:latest}
CPUS=${CPUS:-4}
MERGE_CPUS=${MERGE_CPUS:-1}
MERGE_MEM=${MERGE_MEM:-2Gi}
METHODS=${METHODS:-paper}
FRAMES=${FRAMES:-}
FLAGS=()
case "$kind" in
  sweep)
    SWEEP=${SWEEP:-crowd}
    case "$SWEEP" in
      crowd) key=crowd.people_per_table; VALUES=${VALUES:-0,1,2,3,4,5,6}; SCENE=${SCENE:-scenes/crowded_room.json} ;;
      occlusion) key=crowd.walkers; VALUES=${VALUES:-0,2,4,6,8}; SCENE=${SCENE:-scenes/paper_room.json} ;;
      *) fail "SWEEP must be crowd or occlusion, not '$SWEEP'" ;;
    esac
    SHARDS=${SHARDS:-7} MEM=${MEM:-6Gi} STORAGE=${STORAGE:-50Gi} OUT=${OUT:-/sweeps/$SWEEP} SEEDS=${SEEDS:-3}
    mount=/sweeps
    FLAGS=(--set "$key=$VALUES" --seeds "$SEEDS" --methods "$METHODS")
    if [ -n "$FRAMES" ]; then FLAGS+=(--set "frames=$FRAMES"); fi
    words=(SCENE VALUES METHODS)
    numbers=(SEEDS)
    ;;
  suite)
    SUITE=${SUITE:-suites/standard.json} SPLIT=${SPLIT:-all}
    SHARDS=${SHARDS:-13} MEM=${MEM:-6Gi} STORAGE=${STORAGE:-100Gi} OUT=${OUT:-/suites/$(basename "$SUITE" .json)}
    mount=/suites
    case "$SPLIT" in dev|test|all) ;; *) fail "SPLIT must be dev, test or all, not '$SPLIT'" ;; esac
    FLAGS=(--split "$SPLIT" --methods "$METHODS")
    words=(SUITE METHODS)
    numbers=()
    ;;
  render)
    SCENE=${SCENE:-scenes/paper_room.json} SEED=${SEED:-} OUTPUTS=${OUTPUTS:-} SET=${SET:-}
    SHARDS=${SHARDS:-4} MEM=${MEM:-4Gi} STORAGE=${STORAGE:-20Gi} OUT=${OUT:-/renders/$(basename "$SCENE" .json)}
    mount=/renders
    if [ -n "$FRAMES" ]; then FLAGS+=(--frames "$FRAMES"); fi
    if [ -n "$SEED" ]; then FLAGS+=(--seed "$SEED"); fi
    if [ -n "$OUTPUTS" ]; then FLAGS+=(--outputs "$OUTPUTS"); fi
    for kv in $SET; do
      [[ "$kv" == ?*=?* ]] || fail "SET: each override must look like KEY=VALUE, not '$kv'"
      [[ "$kv" =~ $safe ]] || fail "SET: '$kv' may hold only letters, digits and . _ / , = : + -"
      FLAGS+=(--set "$kv")
    done
    words=(SCENE OUTPUTS)
    numbers=()
    if [ -n "$SEED" ]; then numbers+=(SEED); fi
    ;;
  *) fail "usage: bash scripts/cluster/k8s-job.sh sweep|suite|render (parameters from the environment; docs/guide/cli.md)" ;;
esac
if [ -n "$FRAMES" ]; then numbers+=(FRAMES); fi

# Whole numbers, Kubernetes quantities, an image reference and safe words.
for name in SHARDS CPUS MERGE_CPUS "${numbers[@]}"; do
  [[ "${!name}" =~ ^[1-9][0-9]*$ ]] || fail "$name must be a positive whole number, not '${!name}'"
done
for name in MEM MERGE_MEM STORAGE; do
  [[ "${!name}" =~ ^[1-9][0-9]*(Ki|Mi|Gi|Ti|k|M|G|T)?$ ]] || fail "$name must be a Kubernetes quantity like 6Gi or 6000Mi, not '${!name}'"
done
[[ "$IMAGE" =~ ^[A-Za-z0-9][A-Za-z0-9._/:@-]*$ ]] || fail "IMAGE must be an image reference like registry.example/hoilcd:1.0, not '$IMAGE'"
for name in "${words[@]}"; do
  [[ "${!name}" =~ $safe ]] || fail "$name may hold only letters, digits and . _ / , = : + -, not '${!name}'"
done
if ! [[ "$OUT" =~ ^$mount(/[A-Za-z0-9._-]+)+$ ]] || [[ "$OUT" == *..* ]]; then
  fail "OUT must be a folder on the shared volume, under $mount/ (e.g. $mount/mine), not '$OUT'"
fi

template="$here/$kind-job.yaml.in"
[ -r "$template" ] || fail "cannot read the template '$template'"
text=$(< "$template")
# fill NAME VALUE: every ${NAME} of the template becomes VALUE.
fill() {
  local placeholder="\${$1}"
  text=${text//"$placeholder"/"$2"}
}
for name in IMAGE SHARDS CPUS MEM MERGE_CPUS MERGE_MEM STORAGE OUT SCENE SUITE; do fill "$name" "${!name:-}"; done
fill FLAGS "${FLAGS[*]}"
# shellcheck disable=SC2016  # the pattern is a literal ${NAME}
leftover=$(grep -o '\${[A-Za-z_]*}' <<< "$text" | sort -u | paste -sd' ' || true)
[ -z "$leftover" ] || fail "$template: no value for $leftover"
printf '%s\n' "$text"
