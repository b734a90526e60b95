#!/usr/bin/env bash
# tests/cl_samples_breadth.sh TWINPOST SOURCE_DIR [SHARED_DIR]: posts every real CL file of
# SHARED_DIR/cl-samples on every built-in mill and compares the outcome of each (posted, or the
# first error and the number of errors) with tests/cl-samples-breadth.txt, so that a change in
# how much real CAM output posts is seen in review (issue 24). Exit 77 (skipped) without the
# shared folder. TWINPOST_UPDATE_GOLDEN=1 writes the file instead of comparing.
set -euo pipefail
twinpost=${1:?usage: cl_samples_breadth.sh TWINPOST SOURCE_DIR [SHARED_DIR]}
src=${2:?usage: cl_samples_breadth.sh TWINPOST SOURCE_DIR [SHARED_DIR]}
shared=${TWINPOST_SHARED_DIR:-${3:-$src/../shared}}
samples=$shared/cl-samples
expected=$src/tests/cl-samples-breadth.txt
[[ -d $samples ]] || { echo "cl_samples_breadth.sh: no CL samples at $samples: skipped"; exit 77; }
machines=(head-head-5axis rotary-4axis trunnion-5axis)
# What a user gives for a file that cannot say it itself, posted as a second try: the NX
# operation file calls no tool (the tool in the spindle, post --tool).
declare -A given=([nx/stepnode_simple_block.cls]="--tool 1")
work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-breadth.XXXXXX")
trap 'rm -rf "$work"' EXIT
{
  echo "# Real CL files of shared/cl-samples posted on the built-in mills (tests/cl_samples_breadth.sh)."
  echo "# file | machine | outcome: 'posted', or the errors' count and the first error (path cut to the file)"
  while IFS= read -r -d '' f; do
    rel=${f#"$samples"/}
    tries=("")
    [[ -n ${given[$rel]:-} ]] && tries+=("${given[$rel]}")
    for args in "${tries[@]}"; do
      for m in "${machines[@]}"; do
        rc=0
        # shellcheck disable=SC2086 # the given arguments are words
        "$twinpost" post "$f" --machine "$m" -o "$work/out" $args >/dev/null 2>"$work/err" || rc=$?
        rm -rf "$work/out"
        label=$rel${args:+ ($args)}
        if [[ $rc == 0 ]]; then
          echo "$label | $m | posted"
        else
          n=$(grep -c ': error: ' "$work/err" || true)
          first=$(grep -m1 ': error: ' "$work/err" || head -1 "$work/err")
          first=${first#"$samples"/}
          echo "$label | $m | exit $rc, $n errors: $first"
        fi
      done
    done
  done < <(find "$samples" -type f ! -name README.md -print0 | sort -z)
} >"$work/actual"
if [[ -n ${TWINPOST_UPDATE_GOLDEN:-} ]]; then
  cp "$work/actual" "$expected"
  echo "cl_samples_breadth.sh: wrote $expected"
  exit 0
fi
if ! diff -u "$expected" "$work/actual"; then
  echo "cl_samples_breadth.sh: the outcome of posting the real CL files changed (above: - expected, + now)." >&2
  echo "If the change is meant, run it with TWINPOST_UPDATE_GOLDEN=1 and commit the file." >&2
  exit 1
fi
echo "cl_samples_breadth.sh: $(grep -c ' | posted$' "$expected") of $(grep -vc '^#' "$expected") posts as expected; the refusals unchanged"
