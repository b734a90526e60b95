#!/usr/bin/env bash
# shellcheck disable=SC2154  # timing results come back through printf -v
# bench/run.sh: throughput of `twinpost parse` / `twinpost post` on large generated CL jobs.
# See bench/README.md. Prints one table row per kind and size, then the start-up time.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: bench/run.sh [options]
  --sizes "1e5 1e6"    record counts to run (default: "1e5 1e6")
  --kinds "mill3 ..."  job kinds (default: "mill3 mill5 lathe2"); in --mode post also
                       mill5-ik (the mill5 job on bench/bench-head-head.toml: full inverse
                       kinematics, linearised, G93) and mill5-tcp (on the trunnion-5axis
                       built-in: tool-tip control G43.4)
  --mode parse|post    what to time (default: parse)
  --machine NAME       machine for the lathe2 job in --mode post (default: fanuc-0itd-twin);
                       the mill jobs are posted for bench/bench-mill.toml
  --layout L           output layout for the lathe2 job (split, merged-appended,
                       merged-sections; default: the machine's own)
  --build DIR          build directory (default: <repo>/build-bench, Release)
  --no-build           time the binaries in --build as they are (default: build them first,
                       which is quick when they are up to date: a stale binary is never timed)
  --repeat R           timed runs per row, best one reported (default: 3)
  --cache DIR          where generated jobs are kept (default: /tmp/twinpost-bench)
  --baseline BIN       also time another twinpost binary (an older build) on every row,
                       runs interleaved with the tool's, and give the speed-up in the note;
                       may be given more than once (e.g. the session's start and the pinned
                       reference build of docs/benchmark.md), each gets its own ratio
  --baseline-mill F    the machine file the last --baseline before it reads for the mill
                       jobs in --mode post (default: bench/bench-mill.toml; an older build
                       may need the file as it was then)
  --startup            only measure the start-up time (~1 KB job, best of 20)
  --no-startup         skip the start-up measurement
EOF
}

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
sizes="1e5 1e6"
kinds="mill3 mill5 lathe2"
mode=parse
machine=fanuc-0itd-twin
layout=""
baselines=()       # --baseline BIN, in order
baseline_mills=()  # the --baseline-mill of each, "" for the default
build="$repo/build-bench"
build_first=1
repeat=3
cache=${TWINPOST_BENCH_CACHE:-/tmp/twinpost-bench}
do_sizes=1
do_startup=1
seed=1
gen_version=v4  # bump when cl_generate's output changes, so stale cached jobs are not reused

while [[ $# -gt 0 ]]; do
  case $1 in
    --sizes) sizes=$2; shift 2 ;;
    --kinds) kinds=$2; shift 2 ;;
    --mode) mode=$2; shift 2 ;;
    --machine) machine=$2; shift 2 ;;
    --layout) layout=$2; shift 2 ;;
    --baseline) baselines+=("$2"); baseline_mills+=(""); shift 2 ;;
    --baseline-mill)
      [[ ${#baselines[@]} -gt 0 ]] || { echo "run.sh: --baseline-mill follows the --baseline it is for" >&2; exit 2; }
      baseline_mills[${#baselines[@]} - 1]=$2; shift 2 ;;
    --build) build=$2; shift 2 ;;
    --no-build) build_first=0; shift ;;
    --repeat) repeat=$2; shift 2 ;;
    --cache) cache=$2; shift 2 ;;
    --startup) do_sizes=0; shift ;;
    --no-startup) do_startup=0; shift ;;
    -h|--help) usage; exit 0 ;;
    *) echo "run.sh: unknown option '$1'" >&2; usage >&2; exit 2 ;;
  esac
done
[[ $mode == parse || $mode == post ]] || { echo "run.sh: --mode is parse or post" >&2; exit 2; }
[[ $repeat =~ ^[1-9][0-9]*$ ]] || { echo "run.sh: --repeat needs a positive number" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-bench-run.XXXXXX")
trap 'rm -rf "$work"' EXIT  # the cache directory is kept on purpose

# --- build ------------------------------------------------------------------------------
twinpost="$build/twinpost"
generate="$build/cl_generate"
if [[ $build_first == 1 || ! -x $twinpost || ! -x $generate ]]; then
  echo "building into $build (Release) ..." >&2
  cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DTWINPOST_TESTS=OFF >"$work/cmake.log" 2>&1 ||
    { cat "$work/cmake.log" >&2; exit 1; }
  cmake --build "$build" --target twinpost cl_generate -j "$(nproc)" >"$work/build.log" 2>&1 ||
    { tail -40 "$work/build.log" >&2; exit 1; }
fi

# --- peak RSS: /usr/bin/time -f %M (GNU time), installed with apt-get if missing --------
have_time=1
if [[ ! -x /usr/bin/time ]]; then
  if [[ $(id -u) == 0 ]] && command -v apt-get >/dev/null; then
    echo "installing GNU time for peak RSS ..." >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq time >/dev/null 2>&1 || true
  fi
  [[ -x /usr/bin/time ]] || { have_time=0; echo "run.sh: no /usr/bin/time, RSS column is '-'" >&2; }
fi

# stamp VAR: wall clock in nanoseconds into VAR; bash 5's $EPOCHREALTIME (microseconds,
# no fork), else date +%s%N.
if [[ -n ${EPOCHREALTIME:-} ]]; then
  stamp() { printf -v "$1" '%s000' "${EPOCHREALTIME/[.,]/}"; }
  clock="bash \$EPOCHREALTIME"
else
  stamp() { printf -v "$1" '%s' "$(date +%s%N)"; }
  clock='date +%s%N'
fi
# First error line of a failed run (else its first line).
first_error() { grep -m1 'error' "$1" || head -1 "$1"; }

# run_timed PREFIX CMD...: runs CMD once, stdout to /dev/null, stderr to $work/stderr; sets
# ${PREFIX}_s (wall seconds), ${PREFIX}_kb (peak RSS in KiB) and ${PREFIX}_rc (exit code).
# A post run gets a fresh, empty output folder, outside the timed part, and starts with no
# dirty pages of an earlier run waiting to be written back.
run_timed() {
  local prefix=$1; shift
  local t0 t1 rc=0 kb=0
  rm -rf "$work/out"
  sync  # the previous run's output is written back now, not during this one
  stamp t0
  if [[ $have_time == 1 ]]; then
    /usr/bin/time -f %M -o "$work/rss" "$@" >/dev/null 2>"$work/stderr" || rc=$?
  else
    "$@" >/dev/null 2>"$work/stderr" || rc=$?
  fi
  stamp t1
  if [[ $have_time == 1 ]]; then kb=$(tail -1 "$work/rss"); fi
  printf -v "${prefix}_s" '%s' "$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.4f", (b - a) / 1e9 }')"
  printf -v "${prefix}_kb" '%s' "$kb"
  printf -v "${prefix}_rc" '%s' "$rc"
}

# best_of R PREFIX CMD...: R timed runs; the fastest time and the largest RSS. Stops at the
# first failing run.
best_of() {
  local r=$1 prefix=$2; shift 2
  local best="" peak=0 i
  for ((i = 0; i < r; i++)); do
    run_timed one "$@"
    if [[ $one_rc != 0 ]]; then break; fi
    if [[ -z $best ]] || awk -v a="$one_s" -v b="$best" 'BEGIN { exit !(a < b) }'; then best=$one_s; fi
    if ((one_kb > peak)); then peak=$one_kb; fi
  done
  printf -v "${prefix}_s" '%s' "${best:-0}"
  printf -v "${prefix}_kb" '%s' "$peak"
  printf -v "${prefix}_rc" '%s' "$one_rc"
}

# machine_for KIND: the lathe job goes to the twin-turret machine, milling jobs to a mill,
# the 5-axis kinds to a 5-axis mill.
machine_for() {
  case $1 in
    lathe2) echo "$machine" ;;
    mill5-ik) echo "$repo/bench/bench-head-head.toml" ;;
    mill5-tcp) echo "trunnion-5axis" ;;
    *) echo "$repo/bench/bench-mill.toml" ;;
  esac
}

# set_cmd FILE KIND: the command under test for one CL file, in the array `cmd`.
set_cmd() {
  if [[ $mode == parse ]]; then
    cmd=("$twinpost" parse "$1")
  else
    cmd=("$twinpost" post "$1" --machine "$(machine_for "$2")" -o "$work/out")
    if [[ -n $layout && $2 == lathe2 ]]; then cmd+=(--layout "$layout"); fi
  fi
}

# job KIND RECORDS: path of the cached job, generated once.
job() {
  local kind=${1%%-*} n=$2  # mill5-ik and mill5-tcp post the mill5 job
  local f="$cache/$kind-$n-seed$seed-$gen_version.cls"
  if [[ ! -f $f ]]; then
    mkdir -p "$cache"
    echo "generating $f ..." >&2
    "$generate" --kind "$kind" --records "$n" --seed "$seed" -o "$f"
  fi
  echo "$f"
}

# Does `twinpost post` take this kind of job on this machine? (mill jobs on a lathe: no)
post_accepts() {
  local small
  small=$(job "$1" 40)
  rm -rf "$work/probe"
  "$twinpost" post "$small" --machine "$(machine_for "$1")" -o "$work/probe" >/dev/null 2>"$work/probe.err"
}

# --- header -------------------------------------------------------------------------------
cpu=$(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || echo unknown)
commit=$(git -C "$repo" rev-parse --short HEAD 2>/dev/null || echo none)
if [[ -n $(git -C "$repo" status --porcelain 2>/dev/null) ]]; then commit="$commit (dirty tree)"; fi
echo "# twinpost $mode benchmark: $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores ($cpu), commit $commit"
if [[ $mode == post ]]; then echo "# machines: lathe2 on $machine${layout:+ (layout $layout)}, mill3/mill5 on bench/bench-mill.toml, mill5-ik on bench/bench-head-head.toml, mill5-tcp on trunnion-5axis"; fi
echo "# binary: $twinpost, built $(date -u -r "$twinpost" '+%Y-%m-%d %H:%M UTC')"
echo "# best of $repeat warm-cache runs; cache: $cache"
for ((b = 0; b < ${#baselines[@]}; b++)); do
  echo "# baseline B$((b + 1)): ${baselines[b]}, built $(date -u -r "${baselines[b]}" '+%Y-%m-%d %H:%M UTC')${baseline_mills[b]:+, mill file ${baseline_mills[b]}}"
done
echo

fmt='%-7s %10s %8s %8s %9s %11s %8s %8s %8s  %s\n'
if [[ $do_sizes == 1 ]]; then
  # shellcheck disable=SC2059
  printf "$fmt" kind records MB cat_s tool_s records/s MB/s x_cat RSS_MB note
  for n_text in $sizes; do
    n=$(printf '%.0f' "$n_text")
    for kind in $kinds; do
      if [[ $mode == post && $kind != lathe2 ]] && ! post_accepts "$kind"; then
        # shellcheck disable=SC2059
        printf "$fmt" "$kind" "$n" - - - - - - - "post refuses it: $(first_error "$work/probe.err")"
        continue
      fi
      file=$(job "$kind" "$n")
      bytes=$(stat -c %s "$file")
      cat "$file" >/dev/null  # warm the page cache
      best_of "$repeat" cat cat "$file"
      set_cmd "$file" "$kind"
      run_timed warm "${cmd[@]}"  # warm-up run
      note=""
      if [[ ${#baselines[@]} -gt 0 ]]; then
        # Interleaved with the baseline binaries, run for run: a slow spell of this shared
        # machine hits them all alike, so their ratios hold where absolute times do not.
        tool_s="" tool_kb=0
        base_s=() base_rc=()
        for ((b = 0; b < ${#baselines[@]}; b++)); do base_s+=(""); base_rc+=(0); done
        for ((i = 0; i < repeat; i++)); do
          run_timed one "${cmd[@]}"
          tool_rc=$one_rc
          if [[ $one_rc != 0 ]]; then break; fi
          if [[ -z $tool_s ]] || awk -v a="$one_s" -v b="$tool_s" 'BEGIN { exit !(a < b) }'; then tool_s=$one_s; fi
          if ((one_kb > tool_kb)); then tool_kb=$one_kb; fi
          for ((b = 0; b < ${#baselines[@]}; b++)); do
            base_cmd=("${baselines[b]}" "${cmd[@]:1}")
            if [[ -n ${baseline_mills[b]} && $mode == post && $kind != lathe2 ]]; then
              for ((a = 1; a < ${#base_cmd[@]}; a++)); do
                if [[ ${base_cmd[a - 1]} == --machine ]]; then base_cmd[a]=${baseline_mills[b]}; fi
              done
            fi
            run_timed one "${base_cmd[@]}"
            if [[ $one_rc != 0 ]]; then base_rc[b]=$one_rc; fi
            if [[ -z ${base_s[b]} ]] || awk -v a="$one_s" -v b="${base_s[b]}" 'BEGIN { exit !(a < b) }'; then base_s[b]=$one_s; fi
          done
        done
        for ((b = 0; b < ${#baselines[@]}; b++)); do
          if [[ ${base_rc[b]} != 0 ]]; then
            part="B$((b + 1)) failed (exit ${base_rc[b]})"
          elif [[ $tool_rc == 0 ]]; then
            part=$(awk -v n="$((b + 1))" -v a="${base_s[b]}" -v t="$tool_s" 'BEGIN { printf "B%d %.3f s, x%.2f", n, a, a / t }')
          else
            part=""
          fi
          note="${note:+$note; }$part"
        done
        run_timed check "${cmd[@]}"  # for the diagnostics count below: the tool's own stderr
      else
        best_of "$repeat" tool "${cmd[@]}"
      fi
      if [[ $tool_rc != 0 ]]; then
        note="exit $tool_rc: $(first_error "$work/stderr")"
        tool_s=0 tool_kb=0
      else
        diags=$(grep -c ': \(error\|warning\):' "$work/stderr" || true)
        if [[ $diags != 0 ]]; then note="${note:+$note; }$diags diagnostics"; fi
      fi
      awk -v kind="$kind" -v n="$n" -v bytes="$bytes" -v cat_s="$cat_s" -v tool_s="$tool_s" \
          -v kb="$tool_kb" -v have_time="$have_time" -v note="$note" -v fmt="$fmt" 'BEGIN {
        mb = bytes / 1e6
        ok = tool_s > 0
        printf fmt, kind, n, sprintf("%.1f", mb), sprintf("%.3f", cat_s),
               (ok ? sprintf("%.3f", tool_s) : "-"), (ok ? sprintf("%.0f", n / tool_s) : "-"),
               (ok ? sprintf("%.1f", mb / tool_s) : "-"),
               (ok && cat_s > 0 ? sprintf("%.0f", tool_s / cat_s) : "-"),
               (have_time == 1 && ok ? sprintf("%.1f", kb / 1024) : "-"), note
      }'
    done
  done
  echo
fi

# --- start-up: a ~1 KB job, best of 20 --------------------------------------------------
if [[ $do_startup == 1 ]]; then
  small=$(job lathe2 40)
  set_cmd "$small" lathe2
  if command -v hyperfine >/dev/null; then
    hyperfine -N --warmup 3 --runs 20 --prepare "rm -rf $work/out" --export-json "$work/hf.json" "${cmd[*]}" >/dev/null
    best=$(python3 -c 'import json,sys; print("%.2f" % (min(json.load(open(sys.argv[1]))["results"][0]["times"]) * 1e3))' "$work/hf.json")
    how=hyperfine
  else
    "${cmd[@]}" >/dev/null 2>&1 || true
    best=""
    for ((i = 0; i < 20; i++)); do
      rm -rf "$work/out"
      stamp t0
      "${cmd[@]}" >/dev/null 2>&1 || true
      stamp t1
      d=$((t1 - t0))
      if [[ -z $best || $d -lt $best ]]; then best=$d; fi
    done
    best=$(awk -v d="$best" 'BEGIN { printf "%.2f", d / 1e6 }')
    how="bash loop, $clock"
  fi
  echo "startup: twinpost $mode of a $(stat -c %s "$small")-byte lathe2 job: ${best} ms (best of 20, $how)"
fi
