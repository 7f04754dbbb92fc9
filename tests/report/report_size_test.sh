#!/usr/bin/env bash
# The default report's size budget (docs/testbed-report.md "Sizes"): every
# file `make report` writes under 5 MB.
# It runs the default job itself (every scenario through every default
# engine, the Makefile's REPLAY recorded; about 20 s on two idle cores):
# a part of the suite does not weigh what the whole does per result
# (scenarios/stacking, the most bodies per run, is twice the average, and
# report.html carries a fixed 0.8 MB of libraries), so only the whole
# gives the figures the budget is about.
#   - files that grow with the runs (results.json, the trajectory file,
#     report-data.js, report.html, summary.md, results.csv) must be under
#     the budget (the room for growth that half the budget gave was spent
#     when the suite grew from 19 to 36 files; results.json came under it
#     when its settings and metric definitions went into tables written
#     once, docs/testbed-report.md "Sizes");
#   - files that grow with the replayed runs (results.replays.json,
#     report-replay.js; fixed by REPLAY) must be under the budget.
# Usage: report_size_test.sh TALUS_TESTBED SCENARIO_DIR MAKEFILE WORK_DIR
set -euo pipefail
testbed="$1"
scenarios="$2"
makefile="$3"
work="$4"
budget=$((5 * 1000 * 1000))

replay="$(sed -n 's/^REPLAY ?= *//p' "$makefile")"
if [ -z "$replay" ]; then
  echo "FAIL: no 'REPLAY ?=' line in $makefile" >&2
  exit 1
fi

rm -rf "$work"
mkdir -p "$work"
# A FAIL verdict exits 1 and still writes the files; only bad input (2) stops.
status=0
"$testbed" run "$scenarios" --replay "$replay" --deterministic -j 2 -q -o "$work" >/dev/null || status=$?
if [ "$status" -gt 1 ]; then echo "FAIL: talus-testbed run exited $status" >&2; exit 1; fi
"$testbed" report "$work/results.json" >/dev/null

results="$(sed -n 's/^  "trajectories": \([0-9]*\),$/\1/p' "$work/results.json")"
replayed="$(grep -c '^{"result":' "$work/results.replays.json" || true)"
echo "$results results, $replayed replayed"
if [ -z "$results" ] || [ "$results" -lt 100 ] || [ "$replayed" -lt 4 ]; then
  echo "FAIL: expected at least 100 results and 4 replayed ones" >&2
  exit 1
fi

fail=0
for name in results.json results.trajectories.json report-data.js report.html summary.md results.csv; do
  bytes="$(stat -c %s "$work/$name")"
  if [ "$bytes" -lt "$budget" ]; then verdict=ok; else verdict=FAIL; fail=1; fi
  echo "$verdict: $name $bytes bytes, $((bytes / results)) per result (budget $budget)"
done
for name in results.replays.json report-replay.js; do
  bytes="$(stat -c %s "$work/$name")"
  if [ "$bytes" -lt "$budget" ]; then verdict=ok; else verdict=FAIL; fail=1; fi
  echo "$verdict: $name $bytes bytes for $replayed replayed results (budget $budget)"
done
exit $fail
