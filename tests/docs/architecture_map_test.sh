#!/usr/bin/env bash
# docs/ARCHITECTURE.md says: "a file that is not on this map (or under a
# folder it describes), or an entry with no file, is a bug". This test is
# that rule, run over the source files git tracks.
#
# A source file is on the map when the map names it: by file name (the map
# writes pairs as `name.{h,cpp}`), by a glob such as `src/truth/checks/*.cpp`,
# or, outside engine/ and harness/ (mapped file by file), by a folder of its
# path written as `folder/` (the reference/ and apps/ tables describe whole
# folders); `<name>` in the map stands for any name. A file-like name in
# backticks must exist.
#
# Usage: architecture_map_test.sh REPO_ROOT
set -euo pipefail
root=${1:?usage: architecture_map_test.sh REPO_ROOT}
map="$root/docs/ARCHITECTURE.md"
cd "$root"

# Every backticked token of the map, brace pairs expanded (`a.{h,cpp}` gives
# a.h and a.cpp), one per line.
tokens=$(grep -o '`[^`]*`' "$map" | tr -d '`' | sed 's/<[^>]*>/*/g' | tr ' ,' '\n\n' | sed -n '/./p' |
  while read -r token; do
    if [[ $token =~ ^(.*)\{([^}]*)\}(.*)$ ]]; then
      IFS=',' read -ra parts <<<"${BASH_REMATCH[2]}"
      for part in "${parts[@]}"; do echo "${BASH_REMATCH[1]}${part}${BASH_REMATCH[3]}"; done
      # `a.{h,cpp}` is split at the comma above; rebuild the halves.
    else
      echo "$token"
    fi
  done)
# The comma split breaks `a.{h,cpp}` into `a.{h` and `cpp}`: expand those.
tokens+=$'\n'$(grep -o '`[^`]*{[^}]*}[^`]*`' "$map" | tr -d '`' | sed 's/<[^>]*>/*/g' | while read -r token; do
  [[ $token =~ ^(.*)\{([^}]*)\}(.*)$ ]] || continue
  IFS=',' read -ra parts <<<"${BASH_REMATCH[2]}"
  for part in "${parts[@]}"; do echo "${BASH_REMATCH[1]}${part}${BASH_REMATCH[3]}"; done
done)

names=$(printf '%s\n' "$tokens" | grep -E '\.(h|cpp|in|js|sh|json)$' | grep -vF '*' | sed 's|.*/||' | sort -u)
globs=$(printf '%s\n' "$tokens" | grep -F '*' | sort -u)
folders=$(printf '%s\n' "$tokens" | grep -E '^[A-Za-z0-9_./-]+/$' | sort -u)

covered() {
  local file=$1 base dir glob folder
  base=${file##*/}
  grep -qxF "$base" <<<"$names" && return 0
  while read -r glob; do
    [ -n "$glob" ] || continue
    # shellcheck disable=SC2053  # the glob is meant to match
    [[ $file == $glob || $file == */$glob ]] && return 0
  done <<<"$globs"
  # The engine and the harness are mapped file by file; the other areas'
  # tables describe whole folders.
  [[ $file == engine/* || $file == harness/* ]] && return 1
  dir=${file%/*}
  while [[ $dir == */* ]]; do
    while read -r folder; do
      [ -n "$folder" ] || continue
      [[ "$dir/" == "$folder" || "$dir/" == */"$folder" ]] && return 0
    done <<<"$folders"
    dir=${dir%/*}
  done
  return 1
}

status=0
# Source files of the products: the engine, the testbed and the programs.
while read -r file; do
  if ! covered "$file"; then
    echo "not on docs/ARCHITECTURE.md: $file"
    status=1
  fi
done < <(git ls-files -- engine harness reference apps bench fuzz |
         grep -E '\.(h|cpp|in|js)$' | grep -v '/node_modules/')

# Every file the map names must exist somewhere in the tree.
tracked=$(git ls-files | sed 's|.*/||' | sort -u)
while read -r name; do
  [ -n "$name" ] || continue
  if ! grep -qxF "$name" <<<"$tracked"; then
    echo "named on docs/ARCHITECTURE.md but no such file: $name"
    status=1
  fi
done <<<"$names"

if [ $status -eq 0 ]; then echo "every source file is on the map, and every file it names exists"; fi
exit $status
