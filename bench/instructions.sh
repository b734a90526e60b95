#!/usr/bin/env bash
# bench/instructions.sh: the instructions `twinpost post` executes on the generated jobs, per
# thread, counted by valgrind's callgrind. Unlike a wall-clock time this count does not move
# with the machine's load (other builds on a shared machine), so two builds compare exactly;
# the wall-clock table of bench/run.sh says what two cores make of it. See docs/benchmark.md.
#
#   bench/instructions.sh [--records N] [--kinds "lathe2 mill3 mill5-tcp mill5-ik"] BIN[:MILL] ...
#
# BIN: a twinpost binary; MILL (optional): the machine file it reads for the mill3 job (an older
# build may need bench/bench-mill.toml as it was then). Prints, per kind and binary, millions of
# instructions in all and per thread (thread 1 the post's own: routing and writing; with more
# than one thread, 2 the CL reader and 3 the self-check) and the ratio to the first binary.
set -euo pipefail

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
records=100000
kinds="lathe2 mill3 mill5-tcp mill5-ik"
cache=${TWINPOST_BENCH_CACHE:-/tmp/twinpost-bench}
gen_version=v4  # as in bench/run.sh
bins=()
while [[ $# -gt 0 ]]; do
  case $1 in
    --records) records=$2; shift 2 ;;
    --kinds) kinds=$2; shift 2 ;;
    -h | --help) sed -n '2,12p' "$0"; exit 0 ;;
    *) bins+=("$1"); shift ;;
  esac
done
[[ ${#bins[@]} -gt 0 ]] || { echo "usage: bench/instructions.sh [--records N] [--kinds K] BIN[:MILL] ..." >&2; exit 2; }
command -v valgrind >/dev/null || { echo "bench/instructions.sh: needs valgrind (apt-get install valgrind)" >&2; exit 2; }

generate="$repo/build/cl_generate"
[[ -x $generate ]] || cmake --build "$repo/build" --target cl_generate >/dev/null
work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-instr.XXXXXX")
trap 'rm -rf "$work"' EXIT

job() {  # KIND: the cached job (mill5-ik and mill5-tcp post the mill5 job)
  local kind=${1%%-*}
  local f="$cache/$kind-$records-seed1-$gen_version.cls"
  if [[ ! -f $f ]]; then
    mkdir -p "$cache"
    "$generate" --kind "$kind" --records "$records" --seed 1 -o "$f"
  fi
  echo "$f"
}

machine_for() {  # KIND MILL
  case $1 in
    lathe2) echo fanuc-0itd-twin ;;
    mill5-ik) echo "$repo/bench/bench-head-head.toml" ;;
    mill5-tcp) echo trunnion-5axis ;;
    *) echo "${2:-$repo/bench/bench-mill.toml}" ;;
  esac
}

# Millions of instructions per thread of one post, as "total t1 t2 t3".
count() {  # BIN MACHINE JOB
  rm -rf "$work/out" "$work/cg" "$work"/cg-*
  valgrind --tool=callgrind --separate-threads=yes --callgrind-out-file="$work/cg" \
    "$1" post "$3" --machine "$2" -o "$work/out" >/dev/null 2>"$work/log" || true
  local total=0 parts=() files=("$work"/cg-*)
  [[ -f ${files[0]} ]] || files=("$work/cg")  # one thread: no per-thread files
  for f in "${files[@]}"; do
    local n
    n=$(grep -m1 '^summary:' "$f" | awk '{print $2}')
    [[ -n $n ]] || n=$(grep -m1 '^totals:' "$f" | awk '{print $2}')
    parts+=("$((n / 1000000))")
    total=$((total + n))
  done
  echo "$((total / 1000000)) ${parts[*]}"
}

printf '| kind | binary | M instructions | per thread (post, reader, check) | of the first |\n|---|---|---:|---|---:|\n'
for kind in $kinds; do
  first=""
  for spec in "${bins[@]}"; do
    bin=${spec%%:*}
    mill=""
    [[ $spec == *:* ]] && mill=${spec#*:}
    read -r total threads <<<"$(count "$bin" "$(machine_for "$kind" "$mill")" "$(job "$kind")")"
    [[ -n $first ]] || first=$total
    printf '| %s | %s | %s | %s | %s |\n' "$kind" "$bin" "$total" "${threads// / + }" \
      "$(awk -v a="$total" -v b="$first" 'BEGIN { printf "%.2f", a / b }')"
  done
done
