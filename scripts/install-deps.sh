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
  libccd-dev                        # collision truth (GJK/MPR)
  libqhull-dev                      # hull truth (tests, benchmarks)
  nlohmann-json3-dev                # scenario files and reports
  libcli11-dev                      # command lines
  libgtest-dev libgmock-dev         # tests
  libbenchmark-dev                  # micro benchmarks
  clang-format                      # style check
)

if [ "${TALUS_SKIP_DEPS:-0}" = 1 ]; then exit 0; fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

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
