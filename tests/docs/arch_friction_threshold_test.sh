#!/usr/bin/env bash
# The arch's friction threshold (docs/scenarios.md, "The arch's friction
# threshold") is what scripts/arch_friction_threshold.py computes from the
# shipped arch files, so the documented figure cannot go stale; and the
# script's limit analysis gives the answers known by hand on small scenes
# (tests/data/limit_analysis/, each file's description derives its answer).
#
# Usage: arch_friction_threshold_test.sh REPO_ROOT
set -euo pipefail
root=${1:?usage: arch_friction_threshold_test.sh REPO_ROOT}
cd "$root"
script=scripts/arch_friction_threshold.py
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

# The threshold the script prints for FILE ("none" when no friction holds it).
threshold() {
  local out
  out=$("$script" "$1") || { echo "error"; return; }
  if grep -q "no equilibrium at any friction" <<<"$out"; then echo none; return; fi
  sed -n 's/^friction threshold mu\* = \([0-9.]*\)$/\1/p' <<<"$out"
}

# Known answers. The printed 4 decimals must agree with the closed form to
# half a unit in the last place plus the bisection's 1e-7 resolution.
expect_near() {  # FILE EXPECTED
  local got
  got=$(threshold "$1")
  if ! awk -v g="$got" -v e="$2" 'BEGIN { d = g - e; if (d < 0) d = -d; exit !(g != "" && d <= 0.5e-4 + 1e-7) }'; then
    fail "$1: threshold $got, expected $2"
  fi
}
data=tests/data/limit_analysis
expect_near $data/incline_cube.json 0.36397023426620234   # tan 20 degrees: friction alone
expect_near $data/incline_stack.json 0.36397023426620234  # tan 20 degrees at both interfaces
expect_near $data/a_frame.json 0.42456140350877193        # 0.968 / 2.28: moments and a block-block joint
got=$(threshold $data/incline_tall_box.json)              # past its tipping angle: the moment equation
[[ $got == none ]] || fail "$data/incline_tall_box.json: threshold $got, expected none (it tips)"

# The shipped arch files: one geometry, one threshold, the documented one.
stands=$(threshold scenarios/structures/arch_stands.json)
falls=$(threshold scenarios/structures/arch_falls.json)
[[ -n $stands && $stands == "$falls" ]] || fail "arch_stands gives $stands, arch_falls $falls: not one geometry"
documented=$(sed -n 's/.*friction threshold of the arch: mu\* = \([0-9.]*\).*/\1/p' docs/scenarios.md)
[[ $documented == "$stands" ]] || fail "docs/scenarios.md documents mu* = '$documented', the script prints $stands"
for file in scenarios/structures/arch_stands.json scenarios/structures/arch_falls.json; do
  grep -q "mu\* = $stands" "$file" || fail "$file: its description does not give mu* = $stands"
done

# The files' frictions keep their argued 2x margins either side.
ratio() { "$script" "$1" | sed -n 's/^file.s friction .* = \([0-9.]*\) x the threshold$/\1/p'; }
awk -v r="$(ratio scenarios/structures/arch_stands.json)" 'BEGIN { exit !(r >= 2.0) }' ||
  fail "arch_stands.json: friction not at least 2 x the threshold"
awk -v r="$(ratio scenarios/structures/arch_falls.json)" 'BEGIN { exit !(r != "" && r <= 0.5) }' ||
  fail "arch_falls.json: friction not at most 0.5 x the threshold"

if ((failures)); then exit 1; fi
echo "arch friction threshold: mu* = $stands, documented and checked"
