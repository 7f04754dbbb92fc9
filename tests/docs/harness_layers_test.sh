#!/usr/bin/env bash
# docs/ARCHITECTURE.md says the harness's folders are layers along a
# scenario's path and that includes only go down them. This test is that
# rule, run over the harness files git tracks: every file sits in one of the
# layer folders, and no #include names a folder of a higher layer.
#
# Usage: harness_layers_test.sh REPO_ROOT
set -euo pipefail
root=${1:?usage: harness_layers_test.sh REPO_ROOT}
cd "$root"

# Lowest first; the same order as the map's table.
layers=(support analytic scenario backend truth run sweep stress scenes report)
rank() {
  local i
  for i in "${!layers[@]}"; do [[ ${layers[$i]} == "$1" ]] && { echo "$i"; return; }; done
  echo -1
}

failures=0
while read -r file; do
  case $file in
    harness/src/*) rest=${file#harness/src/} ;;
    harness/include/talus/harness/*) rest=${file#harness/include/talus/harness/} ;;
    *) continue ;;
  esac
  layer=${rest%%/*}
  own=$(rank "$layer")
  if [[ $rest != */* || $own -lt 0 ]]; then
    echo "not in a layer folder: $file"
    failures=$((failures + 1))
    continue
  fi
  while read -r included; do
    case $included in
      talus/harness/*) target=${included#talus/harness/} ;;
      talus/*) continue ;;  # the engine's public API: below every layer
      *) target=$included ;;
    esac
    target=${target%%/*}
    theirs=$(rank "$target")
    if [[ $theirs -lt 0 ]]; then
      echo "$file: #include \"$included\" names no layer folder"
      failures=$((failures + 1))
    elif [[ $theirs -gt $own ]]; then
      echo "$file ($layer): #include \"$included\" runs up to $target"
      failures=$((failures + 1))
    fi
  done < <(sed -n 's/^#include "\([^"]*\)".*/\1/p' "$file")
done < <(git ls-files harness/src harness/include | grep -E '\.(h|cpp|cpp\.in)$')

if [[ $failures -gt 0 ]]; then
  echo "$failures include(s) break the harness layers (${layers[*]})"
  exit 1
fi
echo "every harness include goes down the layers (${layers[*]})"
