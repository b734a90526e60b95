#!/usr/bin/env bash
# docs/records.md lists the record policy as `twinpost parse --records` prints it from the
# one table (parser/record_table.cpp): the lines between the markers below in the document
# must equal that output. On a difference, paste `twinpost parse --records` into the block.
#   usage: records_doc.sh docs/records.md path/to/twinpost
set -euo pipefail
doc=$1 bin=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/twinpost-records-XXXXXX")
trap 'rm -rf "$work"' EXIT

awk '/^<!-- records: begin/ { on = 1; next }
     /^<!-- records: end/   { on = 0 }
     on' "$doc" >"$work/doc"
if [ ! -s "$work/doc" ]; then
  echo "records_doc: no table between <!-- records: begin --> and <!-- records: end --> in $doc" >&2
  exit 1
fi
"$bin" parse --records >"$work/table"
if ! diff -u --label "docs/records.md table" --label "twinpost parse --records" "$work/doc" "$work/table"; then
  echo "records_doc: docs/records.md's table differs from 'twinpost parse --records' (above)" >&2
  exit 1
fi
