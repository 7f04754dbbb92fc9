#!/usr/bin/env bash
# Installs every system package Talus needs, from Debian's archive.
# Idempotent: when everything is present it prints nothing and exits 0.
# Run as root (or with sudo available); set TALUS_SKIP_DEPS=1 to skip it.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev                     # engine math
  libbullet-dev libbullet-extras-dev # peer engine (reference/)
  libode-dev                        # peer engine (reference/)
  libmujoco-dev                     # peer engine (reference/mujoco)
  libccd-dev                        # collision truth (GJK/MPR)
  libqhull-dev                      # hull truth (tests, benchmarks)
  nlohmann-json3-dev                # scenario files and reports
  libcli11-dev                      # command lines
  libgtest-dev libgmock-dev         # tests
  libbenchmark-dev                  # micro benchmarks
  python3-scipy                     # LP solver of scripts/arch_friction_threshold.py (ctest docs.arch_friction_threshold)
  clang-format                      # style check
  ccache                            # compiler cache (cmake/TalusBuildSpeed.cmake; a rebuild costs lookups)
  chromium                          # headless browser: the report's render test (ctest label browser)
)

# Optional group, only for `make fuzz` / `make fuzz-ci` (which set
# TALUS_FUZZ_DEPS=1): clang and its runtime, which holds libFuzzer and the
# sanitizers for clang. A plain `make test` neither needs nor installs them.
if [ "${TALUS_FUZZ_DEPS:-0}" = 1 ]; then
  packages+=(
    clang-14 libclang-rt-14-dev     # libFuzzer targets in fuzz/ (docs/fuzzing.md)
  )
fi

# The report inlines Chart.js and three.js, pinned by harness/report/package-lock.json;
# `npm ci` installs exactly that into harness/report/node_modules, quietly,
# and only when it is missing or older than the lock. Only the HTML report
# needs it, so a failure is a warning.
install_chart_library() {
  local dir
  dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/harness/report"
  local stamp="$dir/node_modules/.package-lock.json"
  if [ -f "$stamp" ] && [ ! "$dir/package-lock.json" -nt "$stamp" ]; then return 0; fi
  if ! (cd "$dir" && npm ci --no-audit --no-fund --loglevel=error >/dev/null 2>&1); then
    # Only the HTML report needs it (tests inline a stand-in), so a failure
    # warns instead of stopping the build; `talus-testbed report` says the same.
    echo "install-deps: warning: 'npm ci' in harness/report failed; the HTML report needs it." >&2
    echo "install-deps: check the network and rerun scripts/install-deps.sh." >&2
  fi
}

if [ "${TALUS_SKIP_DEPS:-0}" = 1 ]; then exit 0; fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
# Node and npm fetch the report's charting library. Checked by command, not
# by package: a Node from another source (which bundles npm) conflicts with
# Debian's npm package, and serves as well.
if ! command -v npm >/dev/null 2>&1; then
  missing+=(nodejs npm)
fi
if [ ${#missing[@]} -eq 0 ]; then
  install_chart_library
  exit 0
fi

if ! command -v apt-get >/dev/null 2>&1; then
  echo "install-deps: this is not a Debian-like system (no apt-get)." >&2
  echo "install-deps: install these packages by hand: ${missing[*]}" >&2
  exit 1
fi

sudo=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo=(sudo)
  else
    echo "install-deps: need root to install: ${missing[*]}" >&2
    echo "install-deps: run 'sudo apt-get install ${missing[*]}' and try again." >&2
    exit 1
  fi
fi

echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if ! "${sudo[@]}" apt-get update -qq >/dev/null \
   || ! "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null; then
  echo "install-deps: apt-get could not install: ${missing[*]}" >&2
  echo "install-deps: check the network and the apt sources, then rerun scripts/install-deps.sh." >&2
  exit 1
fi
install_chart_library
