#!/usr/bin/env bash
# A stepping sweep spread over a Slurm cluster: one array task per shard,
# each on its own node, then one merge job once every shard has succeeded
# (docs/sharding.md). Every node must run the same build of talus-testbed on
# the same scenario files; the merge refuses anything else by name.
#
#   scripts/slurm-sweep.sh submit N [sweep options...]
#       submits an array job of N shard tasks and a merge job that waits for
#       all of them (sbatch --dependency=afterok); prints both job ids.
#   scripts/slurm-sweep.sh shard [sweep options...]
#       what each array task runs: shard SLURM_ARRAY_TASK_ID - MIN of
#       SLURM_ARRAY_TASK_COUNT, into $OUT/shards/shard-i-of-n.json.
#   scripts/slurm-sweep.sh merge N
#       what the merge job runs: talus-testbed merge of the N shard files
#       into $OUT (results.json, sweep.json, sweep.md).
#
# Environment: TALUS_TESTBED (default build/apps/testbed/talus-testbed),
# TALUS_SWEEP_OUT (default reports/sweep-<array job id>, which submit fixes
# for both jobs), SBATCH (default sbatch; tests put a fake one here) and
# TALUS_SBATCH_OPTIONS (extra sbatch options, e.g. "--partition=cpu --time=2:00:00").
# Exit status: 0 done; 1 the sweep or the merge failed; 2 bad usage or
# environment (the message says which variable or argument).
set -euo pipefail

script=$(readlink -f "$0")
testbed=${TALUS_TESTBED:-build/apps/testbed/talus-testbed}
sbatch=${SBATCH:-sbatch}

fail() {
  echo "slurm-sweep: $1" >&2
  exit 2
}

whole_number() {
  [[ "$2" =~ ^[0-9]+$ ]] || fail "$1 is \"$2\", not a whole number"
}

out_dir() {
  if [ -n "${TALUS_SWEEP_OUT:-}" ]; then
    echo "$TALUS_SWEEP_OUT"
  elif [ -n "${SLURM_ARRAY_JOB_ID:-}" ]; then
    echo "reports/sweep-$SLURM_ARRAY_JOB_ID"
  else
    fail "set TALUS_SWEEP_OUT (or run inside a Slurm array job)"
  fi
}

command=${1:-}
[ $# -gt 0 ] && shift
case "$command" in
  submit)
    [ $# -ge 1 ] || fail "usage: slurm-sweep.sh submit N [sweep options...]"
    count=$1
    shift
    whole_number N "$count"
    [ "$count" -ge 1 ] || fail "N must be at least 1"
    out=${TALUS_SWEEP_OUT:-reports/sweep-$(date -u +%Y%m%dT%H%M%SZ)}
    mkdir -p "$out/shards" "$out/logs"
    # shellcheck disable=SC2086 # TALUS_SBATCH_OPTIONS is a list of options
    array=$(TALUS_SWEEP_OUT=$out "$sbatch" --parsable ${TALUS_SBATCH_OPTIONS:-} --export=ALL \
      --job-name=talus-sweep --array="0-$((count - 1))" --output="$out/logs/shard-%a.log" \
      "$script" shard "$@")
    array=${array%%;*}
    whole_number "sbatch's job id" "$array"
    # shellcheck disable=SC2086
    merge=$(TALUS_SWEEP_OUT=$out "$sbatch" --parsable ${TALUS_SBATCH_OPTIONS:-} --export=ALL \
      --job-name=talus-merge --dependency="afterok:$array" --output="$out/logs/merge.log" \
      "$script" merge "$count")
    merge=${merge%%;*}
    echo "shards: job $array (array 0-$((count - 1))), merge: job $merge, output: $out"
    ;;
  shard)
    task=${SLURM_ARRAY_TASK_ID:-}
    [ -n "$task" ] || fail "SLURM_ARRAY_TASK_ID is not set: run this inside an array job (submit does)"
    total=${SLURM_ARRAY_TASK_COUNT:-}
    [ -n "$total" ] || fail "SLURM_ARRAY_TASK_COUNT is not set"
    low=${SLURM_ARRAY_TASK_MIN:-0}
    high=${SLURM_ARRAY_TASK_MAX:-$((low + total - 1))}
    for name in SLURM_ARRAY_TASK_ID:$task SLURM_ARRAY_TASK_COUNT:$total SLURM_ARRAY_TASK_MIN:$low \
      SLURM_ARRAY_TASK_MAX:$high; do
      whole_number "${name%%:*}" "${name#*:}"
    done
    # A stepped or sparse array (--array=0-9:2, --array=1,5) would leave
    # shards out: the tasks must be MIN..MAX, every one.
    [ $((high - low + 1)) -eq "$total" ] ||
      fail "the array must be contiguous: tasks $low-$high are not $total tasks"
    if [ "$task" -lt "$low" ] || [ "$task" -gt "$high" ]; then fail "task $task is outside $low-$high"; fi
    out=$(out_dir)
    mkdir -p "$out/shards"
    exec "$testbed" sweep --quiet --shard "$((task - low))/$total" -o "$out/shards" "$@"
    ;;
  merge)
    [ $# -eq 1 ] || fail "usage: slurm-sweep.sh merge N"
    whole_number N "$1"
    out=$(out_dir)
    shards=()
    for ((i = 0; i < $1; i++)); do shards+=("$out/shards/shard-$i-of-$1.json"); done
    # A missing file is named by talus-testbed ("cannot read").
    "$testbed" merge -o "$out" "${shards[@]}" || exit 1
    ;;
  *)
    fail "usage: slurm-sweep.sh submit N [sweep options...] | shard [sweep options...] | merge N"
    ;;
esac
