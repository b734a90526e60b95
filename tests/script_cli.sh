#!/usr/bin/env bash
# tests/script_cli.sh TWINPOST SOURCE_DIR: [events] script through the command line
# (docs/scripting.md): the loader's errors for a script that is not a plain file name beside
# the machine file or is missing, and `machines --show` naming the script. Exact output.
set -uo pipefail
tp=${1:?usage: script_cli.sh TWINPOST SOURCE_DIR}
src=${2:?usage: script_cli.sh TWINPOST SOURCE_DIR}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
cp "$src/samples/script-shop/shop-0itd.toml" m.toml
sed 's/script = "shop.lua"/script = "sub\/shop.lua"/' m.toml > path.toml
sed 's/script = "shop.lua"/script = "..lua"/' m.toml > dot.toml
bad=0
expect() {  # expect NAME STATUS STDOUT_LAST_LINE STDERR -- ARGS...
  local name=$1 status=$2 out=$3 err=$4
  shift 5
  local got_out got_err got_status
  got_out=$(timeout 60 "$tp" "$@" 2>err.txt | tail -n 1)  # a hang is a failure too
  got_status=${PIPESTATUS[0]}
  got_err=$(cat err.txt)
  if [[ $got_out != "$out" || $got_err != "$err" || $got_status != "$status" ]]; then
    echo "script_cli.sh: case '$name' differs"
    echo "--- expected (status $status)"; echo "$out"; echo "$err"
    echo "--- got (status $got_status)"; echo "$got_out"; echo "$got_err"
    bad=1
  fi
}
expect "missing script" 2 "" "./m.toml:265:10: error: events.script \"shop.lua\": no such file beside the machine file ('./shop.lua')" -- machines --show ./m.toml
expect "a path" 2 "" "./path.toml:265:10: error: events.script \"sub/shop.lua\" must be a file name beside the machine file (no '/', '\\', ':' or leading '.')" -- machines --show ./path.toml
expect "a leading dot" 2 "" "./dot.toml:265:10: error: events.script \"..lua\" must be a file name beside the machine file (no '/', '\\', ':' or leading '.')" -- machines --show ./dot.toml
cp "$src/samples/script-shop/shop.lua" shop.lua
expect "--show" 0 "# [events] script: shop.lua (read from ./shop.lua): copy it beside this file too" "" -- machines --show ./m.toml

# An on_block that gives every block back as it came changes nothing: the same programs,
# byte for byte, as without the script (bench/bench-lathe-script.toml is fanuc-0itd-twin
# with such a script).
cp "$src/bench/bench-lathe-script.toml" "$src/bench/bench_on_block.lua" .
for job in balanced-turning thread-groove shaft-od-drill; do
  "$tp" post "$src/samples/$job/job.cls" -m fanuc-0itd-twin -o "plain-$job" >/dev/null 2>&1
  "$tp" post "$src/samples/$job/job.cls" -m ./bench-lathe-script.toml -o "kept-$job" >/dev/null 2>&1
  if ! diff -r "plain-$job" "kept-$job" >/dev/null || [[ -z $(ls "plain-$job") ]]; then
    echo "script_cli.sh: $job: on_block returning its argument changed the program"
    diff -r "plain-$job" "kept-$job" | head -10
    bad=1
  fi
done
# script_records: PPRINT (a record the post knows) goes to on_record in place of the post's
# comment; FOO (unknown) goes to on_record too, not to an error.
mkdir rec && cd rec || exit 1
sed 's/script = "shop.lua"/script = "pp.lua"\nscript_records = ["pprint"]/' ../m.toml > m.toml
cat > pp.lua <<'LUA'
function on_record(rec)
  post.emit("(NOTE " .. rec.major .. " " .. table.concat(rec.words, "|") .. " AT " .. rec.line .. ")")
end
LUA
printf 'PARTNO / PP\nUNITS / MM\nLOADTL / 1, 1\nPPRINT / ROUGH, OD\nSPINDL / RPM, 1500, CLW\nRAPID\nGOTO / 22, 0, 2\nFOO / 1, 2\nFINI\n' > job.cls
"$tp" post job.cls -m ./m.toml -o o >/dev/null 2>&1
want='%
O1000 (PP)
G0 G18 G21 G40 G54 G80 G99
G28 U0.
G28 W0.
T0101
(NOTE PPRINT ROUGH|OD AT 4)
G97 S1500 M3
G0 X44. Z2.
(NOTE FOO 1|2 AT 8)
M100
M9
G28 U0.
G28 W0.
M5
M30
%'
if [[ $(cat o/PP_1.nc 2>&1) != "$want" ]]; then
  echo "script_cli.sh: script_records: PP_1.nc differs"; cat o/PP_1.nc; bad=1
fi
cd ..

# Issue 38: reads confined to regular files in the machine file's folder. A symbolic link
# beside the machine file is refused, not followed; a FIFO is refused, not waited on; the
# script itself likewise, and bounded in size.
mkdir confined && cd confined || exit 1
cp ../m.toml m.toml
printf 'PARTNO / PP\nUNITS / MM\nLOADTL / 1, 1\nSPINDL / RPM, 1500, CLW\nRAPID\nGOTO / 22, 0, 2\nFINI\n' > job.cls
ln -s /etc/passwd passwd
mkfifo fifo
reader() {  # the script reading file $1 at the tool change
  printf 'function on_tool_change(tool)\n  post.emit("(" .. post.read_file("%s") .. ")")\nend\n' "$1" > shop.lua
}
note='job.cls:3:1: note: channel 1: the script failed while this record was posted
LOADTL / 1, 1
^
post: failed with 1 error; no file written'
reader passwd
expect "read_file: a symbolic link" 1 "" "shop.lua:2: error: post.read_file: 'passwd' is a symbolic link (only a regular file beside the machine file is read)
  post.emit(\"(\" .. post.read_file(\"passwd\") .. \")\")
  ^
$note" -- post job.cls -m ./m.toml -o o
reader fifo
expect "read_file: a FIFO" 1 "" "shop.lua:2: error: post.read_file: 'fifo' is not a regular file (a FIFO, a device or a folder)
  post.emit(\"(\" .. post.read_file(\"fifo\") .. \")\")
  ^
$note" -- post job.cls -m ./m.toml -o o
mv shop.lua real.lua
ln -s real.lua shop.lua
expect "the script, a symbolic link" 2 "" "./m.toml:265:10: error: events.script \"shop.lua\": './shop.lua' is not a regular file (a symbolic link, a FIFO, a device or a folder): only a regular file beside the machine file is read" -- post job.cls -m ./m.toml -o o
rm shop.lua
mkfifo shop.lua
expect "the script, a FIFO" 2 "" "./m.toml:265:10: error: events.script \"shop.lua\": './shop.lua' is not a regular file (a symbolic link, a FIFO, a device or a folder): only a regular file beside the machine file is read" -- machines --show ./m.toml
rm shop.lua
head -c 4194305 /dev/zero | tr '\0' ' ' > shop.lua
expect "the script, too large" 1 "" "shop.lua: error: the script './shop.lua' is larger than 4194304 bytes
post: failed with 1 error; no file written" -- post job.cls -m ./m.toml -o o
# [events] script_seconds and script_instructions: the loader's ranges.
sed 's/^script = "shop.lua"/script = "shop.lua"\nscript_seconds = 0.5/' m.toml > s.toml
expect "script_seconds out of range" 2 "" "./s.toml:266:18: error: events.script_seconds must be 1..86400, not 0.5" -- machines --show ./s.toml
cd ..
exit $bad
