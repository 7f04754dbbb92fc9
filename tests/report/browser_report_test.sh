#!/usr/bin/env bash
# The report in a real browser: runs a small replayed scenario through two
# engines, writes report.html, loads it in headless Chromium (software
# WebGL through SwiftShader) and reads back the status the page's scripts
# wrote into #report-status (harness/report/src/status.js). Fails, never
# skips, when Chromium is missing or does not start.
# Usage: browser_report_test.sh TALUS_TESTBED SCENARIO WORK_DIR
set -euo pipefail
testbed="$1"
scenario="$2"
work="$3"

browser=""
for name in chromium chromium-browser google-chrome; do
  if command -v "$name" >/dev/null 2>&1; then browser="$(command -v "$name")"; break; fi
done
if [ -z "$browser" ]; then
  echo "FAIL: no Chromium found (install Debian's chromium: scripts/install-deps.sh)" >&2
  exit 1
fi

rm -rf "$work"
mkdir -p "$work/profile"
"$testbed" run "$scenario" -b talus,bullet --replay all --deterministic -j 1 -q -o "$work" >/dev/null
# The replay drawn below is the display form (thinned series, rounded
# poses and contacts; harness display_trajectory.h), what a default run writes.
if ! head -c 200 "$work/results.trajectories.json" | grep -q '"resolution":"display"'; then
  echo "FAIL: the run's trajectory file is not in the display form" >&2
  exit 1
fi
# A small large-scenes file (the layout talus-scenes --format jsonl writes):
# two scenes, two engines, so the page must draw two scaling charts; and
# pyramid H = 4 again at 3 iterations, so it must draw a speed-against-
# accuracy chart too (its script runs without errors).
cat >"$work/scenes.jsonl" <<'LINES'
{"engine":"talus","scene":"pyramid","parameter":4,"bodies":30,"threads":1,"steps":60,"iterations":0,"substeps":1,"total_ms":72.0,"ms_per_step_mean":1.2,"ms_per_step_max":2.4,"max_contacts":496,"drift_m":0.001}
{"engine":"talus","scene":"pyramid","parameter":4,"bodies":30,"threads":1,"steps":60,"iterations":3,"substeps":1,"total_ms":36.0,"ms_per_step_mean":0.6,"ms_per_step_max":1.2,"max_contacts":480,"drift_m":0.004}
{"engine":"bullet","scene":"pyramid","parameter":4,"bodies":30,"threads":1,"steps":60,"iterations":3,"substeps":1,"total_ms":24.0,"ms_per_step_mean":0.4,"ms_per_step_max":0.8,"max_contacts":470,"drift_m":0.009}
{"engine":"bullet","scene":"pyramid","parameter":4,"bodies":30,"threads":1,"steps":60,"iterations":0,"substeps":1,"total_ms":36.0,"ms_per_step_mean":0.6,"ms_per_step_max":1.2,"max_contacts":486,"drift_m":0.002}
{"engine":"talus","scene":"pyramid","parameter":6,"bodies":91,"threads":1,"steps":60,"iterations":0,"substeps":1,"total_ms":186.0,"ms_per_step_mean":3.1,"ms_per_step_max":6.2,"max_contacts":1500,"drift_m":0.001}
{"engine":"bullet","scene":"pyramid","parameter":6,"bodies":91,"threads":1,"steps":60,"iterations":0,"substeps":1,"total_ms":96.0,"ms_per_step_mean":1.6,"ms_per_step_max":3.2,"max_contacts":1400,"drift_m":0.002}
{"engine":"talus","scene":"hull_pile","parameter":2,"bodies":40,"threads":1,"steps":60,"iterations":0,"substeps":1,"total_ms":12.0,"ms_per_step_mean":0.2,"ms_per_step_max":0.4,"max_contacts":27,"max_penetration_m":0.05,"kinetic_energy_j":3.4e5,"escaped":0}
{"engine":"bullet","scene":"hull_pile","parameter":2,"bodies":40,"threads":1,"steps":60,"iterations":0,"substeps":1,"total_ms":12.0,"ms_per_step_mean":0.2,"ms_per_step_max":0.4,"max_contacts":30,"max_penetration_m":0.03,"kinetic_energy_j":3.3e5,"escaped":0}
LINES
"$testbed" report "$work/results.json" -o "$work" --scenes "$work/scenes.jsonl" >/dev/null

if ! dom="$(timeout 120 "$browser" --headless --no-sandbox --disable-gpu --use-angle=swiftshader \
      --enable-unsafe-swiftshader --disable-background-networking --disable-component-update \
      --disable-sync --no-first-run --user-data-dir="$work/profile" --virtual-time-budget=10000 \
      --dump-dom "file://$work/report.html" 2>"$work/chromium.log")"; then
  echo "FAIL: Chromium ($browser) did not start or did not finish; its log:" >&2
  tail -20 "$work/chromium.log" >&2
  exit 1
fi
printf '%s\n' "$dom" >"$work/dom.html"

status="$(printf '%s' "$dom" | sed -n 's:.*<pre id="report-status"[^>]*>\(.*\)</pre>.*:\1:p' | head -1)"
echo "page status: $status"
fail=0
check() {  # check DESCRIPTION EXTENDED-REGEX
  if printf '%s' "$status" | grep -Eq "$2"; then echo "ok: $1"; else echo "FAIL: $1" >&2; fail=1; fi
}
check "the page's scripts finished (status written on load)" '"errors"'
check "no script errors" '"errors":\[\]'
check "Chart.js charts created" '"charts":([1-9][0-9]*)'
check "a WebGL context" '"webgl":true'
check "one replay view per engine" '"replayViews":2'
check "replay meshes in the scenes" '"replayMeshes":[1-9]'
check "every replay viewport has drawn pixels" '"replayLitPixels":\[[1-9][0-9]*,[1-9][0-9]*\]'
check "Quickhull trace meshes" '"hullTraceMeshes":[1-9]'
check "the Quickhull view has drawn pixels" '"hullTraceLitPixels":[1-9]'
check "a broad-phase funnel chart (talus)" '"funnelCharts":1'
check "one scaling chart per large scene" '"scalingCharts":2'
check "one speed-against-accuracy chart (pyramid H = 4)" '"tradeoffCharts":1'
check "the scorecard's pass-fraction chart" '"scorecardCharts":1'

# Without report-data.js beside it (the plots' series), the page still
# loads, says what is missing, and the replay (its own file) still draws.
load_without() {  # load_without NAME: the status of the page loaded again
  dom="$(timeout 120 "$browser" --headless --no-sandbox --disable-gpu --use-angle=swiftshader \
        --enable-unsafe-swiftshader --disable-background-networking --disable-component-update \
        --disable-sync --no-first-run --user-data-dir="$work/profile" --virtual-time-budget=10000 \
        --dump-dom "file://$work/report.html" 2>>"$work/chromium.log")" || dom=""
  printf '%s\n' "$dom" >"$work/dom-without-$1.html"
  status="$(printf '%s' "$dom" | sed -n 's:.*<pre id="report-status"[^>]*>\(.*\)</pre>.*:\1:p' | head -1)"
  echo "page status without $1: $status"
}
rm "$work/report-data.js"
load_without report-data.js
check "a missing report-data.js is the one error" '"errors":\["report-data.js was not found beside the page"\]'
check "the replay still draws without the plots' file" '"replayLitPixels":\[[1-9][0-9]*,[1-9][0-9]*\]'

# Without report-replay.js too, the replay section names it.
rm "$work/report-replay.js"
load_without report-replay.js
check "a missing report-replay.js is named" '"report-replay.js was not found beside the page"'
if grep -q 'The replay data (report-replay.js' "$work/dom-without-report-replay.js.html"; then
  echo "ok: the replay section names report-replay.js"
else
  echo "FAIL: the replay section does not name report-replay.js" >&2
  fail=1
fi
exit $fail
