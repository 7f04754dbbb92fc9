#!/usr/bin/env bash
# docs/ARCHITECTURE.md says: "a file that is not on this map (or under a
# folder it describes), or an entry with no file, is a bug", and its walks
# name each function "with the file that holds each one". This test is those
# rules, run over the files git tracks.
#
# Files. A source file is on the map when the map names it: by file name
# (the map writes pairs as `name.{h,cpp}`), by a glob such as
# `src/truth/checks/*.cpp`, or, outside engine/ and harness/ (mapped file by
# file), by a folder of its path written as `folder/` (the reference/ and
# apps/ tables describe whole folders); `<name>` in the map stands for any
# name. A file-like name in backticks must exist.
#
# Names. A backticked token that looks like a function or type is a name:
# PascalCase with a lower-case letter (`Stage`, `Vec3`; not `AVX2`), maybe
# qualified (`ContactSolver::Prepare`, `WorldSettings::threads`), maybe
# followed by arguments, template arguments or braces, which are ignored
# (`Step(dt)`, `Result<T>`, `BodyId{index, generation}`). Tokens with
# spaces (`stepSolver = SoftStep`) and names of tracked files (`Makefile`)
# are not names. A file token stands for every tracked file whose path ends
# with it, and for the other half of its .h/.cpp pair wherever that lives
# (`hull.cpp` also means `talus/hull.h`, the harness's `run/runner.cpp`
# its header under include/). A name occurs in a file when each part of it
# is a whole word there: a use counts as well as the definition, since the
# map says what a file does with a name, not only what it defines.
#   1. Every name occurs in some source file of engine/, harness/,
#      reference/, apps/, bench/, fuzz/ or tests/, so a renamed or deleted
#      function is caught wherever the map mentions it.
#   2. A name in a table row, or in a prose sentence, that also names files
#      occurs in at least one of those files. A row is one line; prose is
#      read by paragraph and list item, cut at ". " (not "e.g. ", "i.e. "),
#      code blocks skipped. This is how a walk's "`Name` ... (`file`)"
#      reads, and what a reader greps for.
#   3. A name directly followed by a file, "`Name` (`file`" or
#      "`Name`, `file`", occurs in that file itself, and so does each name
#      of a list joined to it by ", ", " and " or " or " ("`A`, `B` and
#      `C` (`file`)"). This is the finer check for sentences that name
#      several files.
# So a name met on the way in a sentence about other files (a setting, a
# caller) gets its own file beside it, as the walks promise.
#
# Usage: architecture_map_test.sh REPO_ROOT [MAP]
# MAP (default REPO_ROOT/docs/ARCHITECTURE.md) is checked against the tree
# at REPO_ROOT, so another version of the map can be tried against today's
# code:
#   git show COMMIT:docs/ARCHITECTURE.md >/tmp/map.md
#   tests/docs/architecture_map_test.sh . /tmp/map.md
set -euo pipefail
root=${1:?usage: architecture_map_test.sh REPO_ROOT [MAP]}
map=${2:-$root/docs/ARCHITECTURE.md}
label=${2:-docs/ARCHITECTURE.md}
[[ $map == /* ]] || map=$PWD/$map
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
paths=$(git ls-files)
tracked=$(git ls-files | sed 's|.*/||' | sort -u)
while read -r name; do
  [ -n "$name" ] || continue
  if ! grep -qxF "$name" <<<"$tracked"; then
    echo "named on docs/ARCHITECTURE.md but no such file: $name"
    status=1
  fi
done <<<"$names"

# ---- Names against files (rules 1 to 3 of the header) ----

name_re='^([A-Z][A-Za-z0-9]*[a-z][A-Za-z0-9]*(::[A-Za-z_][A-Za-z0-9_]*)*)(<.*>|\(.*\)|\{.*\})?$'
file_re='\.(h|cpp|in|js|sh|json)$'
angle_re='^(.*)<[^>]*>(.*)$'
brace_re='^(.*)\{([^}]*)\}(.*)$'
# A unit read as: the text before a backticked token, the token, the rest.
# shellcheck disable=SC2016  # the backticks are the map's, not a command
unit_re='^([^`]*)`([^`]*)`(.*)$'

declare -A tracked_base=()
while read -r base; do tracked_base[$base]=1; done <<<"$tracked"

# Rule 1's vocabulary: every word of the sources.
mapfile -t sources < <(git ls-files -- engine harness reference apps bench fuzz tests |
                       grep -E '\.(h|cpp|in|js)$' | grep -v '/node_modules/')
declare -A known=()
while read -r word; do known[$word]=1; done < <(grep -ohE '[A-Za-z_][A-Za-z0-9_]*' "${sources[@]}" | sort -u)

# Sets `parts` to the parts of name $1 (`A::B(x)` gives A and B); fails
# when the token is not a name.
split_name() {
  parts=()
  [[ $1 =~ $name_re ]] || return 1
  [[ -z ${tracked_base[$1]+set} ]] || return 1
  local name=${BASH_REMATCH[1]}
  read -ra parts <<<"${name//::/ }"
}

# Sets `expanded` to the names file token $1 stands for: braces expanded
# (`a.{h,cpp}` gives a.h and a.cpp), `<name>` as the glob *.
expand_token() {
  local token=$1 part pre post
  local -a list
  while [[ $token =~ $angle_re ]]; do token="${BASH_REMATCH[1]}*${BASH_REMATCH[2]}"; done
  expanded=("$token")
  [[ $token =~ $brace_re ]] || return 0
  pre=${BASH_REMATCH[1]} post=${BASH_REMATCH[3]}
  IFS=',' read -ra list <<<"${BASH_REMATCH[2]}"
  expanded=()
  for part in "${list[@]}"; do expanded+=("$pre$part$post"); done
}
is_file_token() {
  local name
  expand_token "$1"
  for name in "${expanded[@]}"; do [[ $name =~ $file_re ]] && return 0; done
  return 1
}

# Sets `found` to the tracked paths file token $1 stands for, one per line:
# its names matched as path endings (a glob's * within one folder), with
# the .h/.cpp partner of each.
declare -A resolved=()
resolve() {
  local token=$1 name pattern alternatives=""
  if [[ -z ${resolved[$token]+set} ]]; then
    expand_token "$token"
    for name in "${expanded[@]}"; do
      pattern=${name//./\\.}
      pattern=${pattern//\*/[^/]*}
      alternatives+="|(^|/)$pattern\$"
      if [[ $name =~ \.(h|cpp|cpp\.in)$ ]]; then
        pattern=${name%.in}
        pattern=${pattern%.*}
        pattern=${pattern//./\\.}
        pattern=${pattern//\*/[^/]*}
        alternatives+="|(^|/)$pattern\\.(h|cpp|cpp\\.in)\$"
      fi
    done
    resolved[$token]=$(grep -E "${alternatives#|}" <<<"$paths" || true)
  fi
  found=${resolved[$token]}
}

# Whether every part of name $1 is a whole word of one of the files $2
# (one per line).
declare -A seen=()
occurs() {
  local part key
  local -a files
  split_name "$1" || return 0
  mapfile -t files < <(grep . <<<"$2")
  [ ${#files[@]} -gt 0 ] || return 1
  for part in "${parts[@]}"; do
    key="$part"$'\t'"$2"
    if [[ -z ${seen[$key]+set} ]]; then
      seen[$key]=0
      grep -qwF -- "$part" "${files[@]}" && seen[$key]=1
    fi
    [ "${seen[$key]}" = 1 ] || return 1
  done
}

# The line of the map, from $2 to $3, that holds token $1.
line_of() {
  local at
  at=$(sed -n "$2,$3p" "$map" | grep -nF -- "\`$1\`" | head -n 1 | sed 's/:.*//')
  echo $(($2 + ${at:-1} - 1))
}

# Checks one unit: one table row or one prose sentence, $3, found between
# lines $1 and $2 of the map.
check_unit() {
  local first=$1 last=$2 rest=$3 i j k token part all="" files
  local -a toks=() gaps=()
  while [[ $rest =~ $unit_re ]]; do
    gaps+=("${BASH_REMATCH[1]}")
    toks+=("${BASH_REMATCH[2]}")
    rest=${BASH_REMATCH[3]}
  done
  for token in "${toks[@]}"; do
    is_file_token "$token" || continue
    resolve "$token"
    all+=$found$'\n'
  done
  for i in "${!toks[@]}"; do
    token=${toks[$i]}
    split_name "$token" || continue
    for part in "${parts[@]}"; do
      if [[ -z ${known[$part]+set} ]]; then
        echo "$label:$(line_of "$token" "$first" "$last"): \`$token\`: no source file has \"$part\""
        status=1
      fi
    done
    if [ -n "${all//$'\n'/}" ] && ! occurs "$token" "$all"; then
      echo "$label:$(line_of "$token" "$first" "$last"): \`$token\` is in none of the files named with it:" \
        "$(grep . <<<"$all" | sort -u | tr '\n' ' ')"
      status=1
    fi
  done
  for k in "${!toks[@]}"; do
    [[ $k -gt 0 && (${gaps[$k]} == ' (' || ${gaps[$k]} == ', ') ]] || continue
    is_file_token "${toks[$k]}" || continue
    resolve "${toks[$k]}"
    files=$found
    [ -n "$files" ] || continue
    j=$((k - 1))
    while [ $j -ge 0 ] && split_name "${toks[$j]}"; do
      if ! occurs "${toks[$j]}" "$files"; then
        echo "$label:$(line_of "${toks[$j]}" "$first" "$last"): \`${toks[$j]}\` is written with" \
          "\`${toks[$k]}\` but is not in it"
        status=1
      fi
      [[ ${gaps[$j]} == ', ' || ${gaps[$j]} == ' and ' || ${gaps[$j]} == ' or ' ]] || break
      j=$((j - 1))
    done
  done
}

# Prose is gathered into paragraphs and list items, then cut into
# sentences; each table row is a unit of its own; code blocks are skipped.
paragraph="" first=0 number=0
flush() {
  local sentence
  if [ -n "$paragraph" ]; then
    # "e.g. " and "i.e. " do not end a sentence.
    while IFS= read -r sentence; do
      check_unit "$first" "$number" "$sentence"
    done < <(sed -e 's/\(e\.g\|i\.e\)\. /\1.\x01/g' -e 's/\. /.\n/g' -e 's/\x01/ /g' <<<"$paragraph")
  fi
  paragraph=""
}
while IFS= read -r line; do
  number=$((number + 1))
  if [[ $line == '|'* ]]; then
    flush
    check_unit "$number" "$number" "$line"
    continue
  fi
  if [[ -z ${line// /} || $line == '#'* ]]; then
    flush
    continue
  fi
  [[ -z $paragraph && $line == '    '* ]] && continue
  [[ $line =~ ^\ *([0-9]+\.|-)\  ]] && flush
  [ -n "$paragraph" ] || first=$number
  paragraph+="${paragraph:+ }${line#"${line%%[! ]*}"}"
done <"$map"
number=$((number + 1))
flush

if [ $status -eq 0 ]; then
  echo "every source file is on the map, every file it names exists, and every name is in its files"
fi
exit $status
