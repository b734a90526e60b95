#!/usr/bin/env bash
# A block of a document that is a copy of what the tool prints must equal that output, line
# for line: the lines between `<!-- NAME: begin` and `<!-- NAME: end` in DOC (code-fence
# lines left out) against COMMAND's standard output. On a difference, paste the output in.
#   usage: doc_block.sh DOC NAME COMMAND [ARGS...]
#   README.md's synopsis:   doc_block.sh README.md synopsis twinpost --help
#   docs/records.md table:  doc_block.sh docs/records.md records twinpost parse --records
set -euo pipefail
doc=$1 name=$2
shift 2
work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-doc-block-XXXXXX")
trap 'rm -rf "$work"' EXIT

awk -v begin="^<!-- $name: begin" -v end="^<!-- $name: end" \
  '$0 ~ begin { on = 1; next } $0 ~ end { on = 0 } on && !/^```/' "$doc" >"$work/doc"
if [ ! -s "$work/doc" ]; then
  echo "doc_block: no block between <!-- $name: begin --> and <!-- $name: end --> in $doc" >&2
  exit 1
fi
"$@" >"$work/output"
if ! diff -u --label "$(basename "$doc") ($name)" --label "$(basename "$1") ${*:2}" "$work/doc" "$work/output"; then
  echo "doc_block: the $name block of $doc differs from '$(basename "$1") ${*:2}' (above)" >&2
  exit 1
fi
