#!/usr/bin/env bash
# scripts/slurm-sweep.sh on a tiny sweep without a cluster: a fake sbatch
# records the two submissions, the array tasks run here one after the other
# with the variables Slurm sets, and the merged results must be byte for
# byte those of the unsharded sweep (--deterministic). Then the refusals:
# a missing shard, a sparse array, shards from other settings and a
# scenario file edited between shards.
#
# Usage: slurm_recipe_test.sh TALUS_TESTBED REPO_ROOT
set -euo pipefail
testbed=$(readlink -f "${1:?usage: slurm_recipe_test.sh TALUS_TESTBED REPO_ROOT}")
root=$(readlink -f "${2:?usage: slurm_recipe_test.sh TALUS_TESTBED REPO_ROOT}")
script="$root/scripts/slurm-sweep.sh"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
cp "$root/tests/data/shards/tiny_fall.json" scenario.json
sweep=(scenario.json -b talus --time-step "0.01,0.02,0.05" --iterations 10 --deterministic)
export TALUS_TESTBED=$testbed

failures=0
check() {  # check DESCRIPTION COMMAND...: the command must succeed
  if ! "${@:2}"; then
    echo "FAILED: $1" >&2
    failures=$((failures + 1))
  fi
}
refused() {  # refused DESCRIPTION EXPECTED_STATUS EXPECTED_TEXT COMMAND...
  local status=0
  "${@:4}" >out.txt 2>err.txt || status=$?
  if [ "$status" -ne "$2" ] || ! grep -qF -- "$3" err.txt; then
    echo "FAILED: $1: exit $status (want $2), stderr: $(cat err.txt)" >&2
    failures=$((failures + 1))
  fi
}
tasks() {  # tasks N: run every array task of N as Slurm would
  for ((i = 0; i < $1; i++)); do
    SLURM_ARRAY_JOB_ID=4242 SLURM_ARRAY_TASK_ID=$i SLURM_ARRAY_TASK_COUNT=$1 SLURM_ARRAY_TASK_MIN=0 \
      SLURM_ARRAY_TASK_MAX=$(($1 - 1)) "$script" shard "${sweep[@]}" >/dev/null
  done
}

# 1. submit: two sbatch calls, the merge after the array.
cat >fake-sbatch <<'FAKE'
#!/usr/bin/env bash
echo "$*" >>sbatch.log
if [[ "$*" == *--array=* ]]; then echo "4242;cluster"; else echo "4243"; fi
FAKE
chmod +x fake-sbatch
SBATCH=./fake-sbatch TALUS_SWEEP_OUT=out "$script" submit 2 "${sweep[@]}" >submit.txt
check "submit prints both jobs" grep -qF "shards: job 4242 (array 0-1), merge: job 4243, output: out" submit.txt
check "the array job has two tasks" grep -qE -- "--array=0-1 .*slurm-sweep.sh shard scenario.json -b talus" sbatch.log
check "the merge waits for the array" grep -qE -- "--dependency=afterok:4242 .*slurm-sweep.sh merge 2$" sbatch.log

# 2. the array tasks and the merge job, then the unsharded sweep.
export TALUS_SWEEP_OUT=out
tasks 2
check "shard 0 written" test -s out/shards/shard-0-of-2.json
check "shard 1 written" test -s out/shards/shard-1-of-2.json
"$script" merge 2 >/dev/null
"$testbed" sweep --quiet "${sweep[@]}" -o whole >/dev/null
check "merged results equal the unsharded sweep's" cmp out/results.json whole/results.json
check "merged analysis equals the unsharded sweep's" cmp out/sweep.json whole/sweep.json

# 3. refusals.
rm out/shards/shard-1-of-2.json
refused "a missing shard" 1 "shard-1-of-2.json: cannot read" "$script" merge 2
refused "a sparse array" 2 "the array must be contiguous" env SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=2 \
  SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=2 "$script" shard "${sweep[@]}"
refused "no array task" 2 "SLURM_ARRAY_TASK_ID is not set" env -u SLURM_ARRAY_TASK_ID "$script" shard
refused "a bad N" 2 "N is \"two\"" "$script" merge two
SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 "$script" shard scenario.json -b talus \
  --time-step "0.01,0.02" --iterations 10 --deterministic >/dev/null
refused "other time steps" 1 "has time steps \"0.01,0.02\" but shard 0/2 has \"0.01,0.02,0.05\"" \
  "$script" merge 2
tasks 2  # a complete partition again, then shard 1 rerun after an edit
sed -i 's/"density": 1000/"density": 999/' scenario.json
SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 "$script" shard "${sweep[@]}" >/dev/null
refused "a scenario edited between shards" 1 "ran the same scenario names with different contents" \
  "$script" merge 2

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed" >&2
  exit 1
fi
echo "slurm recipe: all checks passed"
