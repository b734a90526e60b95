#!/usr/bin/env bash
# tests/browser/timeline_page.sh TWINPOST SOURCE_DIR WORK_DIR
# The timeline page in a real browser: headless Chromium renders the pages of the hand-timed
# sample (two channels, `twinpost timeline -o`) and of balanced-turning on fanuc-31i-3path
# (three channels, `post --timeline`); the DOM after the page's script ran must hold one
# lane per channel, one totals row per channel built by the script, and the cycle time the
# summary printed. Screenshots are left in WORK_DIR. Exit 77 (skipped) without Chromium.
set -euo pipefail
twinpost=${1:?usage: timeline_page.sh TWINPOST SOURCE_DIR WORK_DIR}
src=${2:?}
work=${3:?}
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [[ -z $browser ]]; then
  echo "timeline_page.sh: no chromium: skipped"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
cd "$work"
fail() {
  echo "timeline_page.sh: $*" >&2
  exit 1
}
render() {  # PAGE NAME: the DOM after the scripts ran, and a screenshot
  local page=$1 name=$2
  local flags=(--headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$work/profile-$name")
  timeout 120 "$browser" "${flags[@]}" --dump-dom "file://$work/$page" >"$name.dom" 2>"$name.log" ||
    fail "chromium --dump-dom $page failed: $(tail -3 "$name.log")"
  timeout 120 "$browser" "${flags[@]}" --window-size=1280,560 --screenshot="$work/$name.png" \
    "file://$work/$page" >>"$name.log" 2>&1 || fail "chromium --screenshot $page failed"
  [[ -s $name.png ]] || fail "no screenshot of $page"
}
check_dom() {  # NAME CHANNELS CYCLE
  local name=$1 channels=$2 cycle=$3
  local lanes rows
  lanes=$(grep -o '<g class="lane" data-channel="[0-9]*"' "$name.dom" | wc -l)
  rows=$(grep -o '<tr class="total[^"]*" data-channel="[0-9]*">' "$name.dom" | wc -l)
  [[ $lanes == "$channels" ]] || fail "$name: $lanes lanes in the DOM, expected $channels"
  [[ $rows == "$channels" ]] || fail "$name: $rows totals rows built by the script, expected $channels"
  grep -q "<b id=\"cycle\">$cycle s</b>" "$name.dom" || fail "$name: the cycle time $cycle s is not in the DOM"
  # The last channel's row ends at the cycle time (the script's own toFixed(2)).
  grep -q "<tr class=\"total last\" data-channel=\"[0-9]*\">.*<td>$cycle s</td><td>[0-9]*</td></tr>" "$name.dom" ||
    fail "$name: no totals row ending at $cycle s"
  echo "$name: $lanes lanes, $rows totals rows, cycle time $cycle s"
}

cp "$src/samples/timeline/hand-timed/PART_1.nc" "$src/samples/timeline/hand-timed/PART_2.nc" .
"$twinpost" timeline PART_1.nc PART_2.nc --machine fanuc-0itd-twin -o hand.html >hand.txt
cycle=$(sed -n 's/^cycle time \(at least \)\{0,1\}\([0-9.]*\) s.*/\2/p' hand.txt)
render hand.html hand
check_dom hand 2 "$cycle"

cp "$src/samples/balanced-turning/job.cls" .
"$twinpost" post job.cls --machine fanuc-31i-3path -o out --sync auto --timeline page.html >post.txt
cycle=$(sed -n 's/^  cycle time \(at least \)\{0,1\}\([0-9.]*\) s.*/\2/p' post.txt)
render out/page.html three
check_dom three 3 "$cycle"
