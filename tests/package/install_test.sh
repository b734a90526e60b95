#!/usr/bin/env bash
# The release as a user gets it: cpack builds the .deb from BUILD_DIR, dpkg -x unpacks it
# into an empty root, and the installed binary must
#   - print the version and commit that the README documents (`twinpost --version`),
#   - carry a man page that names every command of `twinpost --help`,
#   - post a sample with an installed machine file found by name (the summary names it),
#   - print that machine file with `machines --show`.
# Skips (77) where cpack or dpkg-deb is missing.
#   install_test.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -euo pipefail
build=$1 src=$2 work=$3
command -v cpack >/dev/null && command -v dpkg-deb >/dev/null || { echo "skip: no cpack or dpkg-deb"; exit 77; }
rm -rf "$work"
mkdir -p "$work/root"
(cd "$build" && cpack -G DEB -B "$work/pkg" >"$work/cpack.log" 2>&1) || { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/pkg/twinpost_*.deb)
info=$(dpkg-deb --info "$deb")
grep -qx ' Depends: libc6 (>= [0-9.]*)' <<<"$info" || { echo "FAIL: Depends is not libc6 alone"; echo "$info"; exit 1; }
dpkg-deb -x "$deb" "$work/root"
bin=$work/root/usr/bin/twinpost
fail() { echo "FAIL: $*"; exit 1; }

version=$("$bin" --version)
[[ $version =~ ^twinpost\ [0-9]+\.[0-9]+\.[0-9]+\ \(commit\ [0-9a-f]{7,}(-dirty)?\)$ || $version =~ \(commit\ unknown\)$ ]] \
  || fail "--version printed '$version'"
grep -q 'twinpost --version' "$src/README.md" || fail "the README does not mention twinpost --version"

man=$work/root/usr/share/man/man1/twinpost.1
[ -s "$man" ] || fail "no man page"
grep -q "^\.TH TWINPOST 1 \"\" \"twinpost $(echo "$version" | cut -d' ' -f2)\"" "$man" || fail "man page version"
for c in $("$bin" --help | sed -n 's/^  \([a-z]*\) .*/\1/p'); do
  grep -q "^\.B $c " "$man" || fail "man page lacks command $c"
done

for m in $(ls "$work/root/usr/share/twinpost/machines"); do
  name=${m%.toml}
  out=$work/out-$name
  if grep -qx 'syntax = "bang"' "$work/root/usr/share/twinpost/machines/$m" ||
     grep -qx 'check_only = true' "$work/root/usr/share/twinpost/machines/$m"; then
    # A check-only machine (post refuses it): check its sample instead.
    # Its sound sample (samples/check/<maker>-sound) names the files and the machine.
    (cd "$src/samples/check/${name%%-*}-sound" &&
      XDG_CONFIG_HOME=$work/no-config "$bin" check $(cat args) >/dev/null) || fail "check with the installed $m"
    XDG_CONFIG_HOME=$work/no-config "$bin" machines --show "$name" | cmp -s - "$work/root/usr/share/twinpost/machines/$m" \
      || fail "machines --show $name differs from the installed file"
    continue
  fi
  # The turning job, or for a multi-axis mill the sample that names it in its `machines` file.
  job=$src/samples/shaft-od-drill/job.cls
  # (A sample with post.args needs its options: not this plain post.)
  for f in "$src"/samples/*/machines; do
    if grep -qx "$name" "$f" && [ ! -e "$(dirname "$f")/post.args" ]; then job=$(dirname "$f")/job.cls; fi
  done
  # No user or site folders: the installed copy must be the one found.
  XDG_CONFIG_HOME=$work/no-config "$bin" post "$job" --machine "$name" -o "$out" >"$work/$name.stdout"
  grep -qx "  machine $name ($work/root/usr/share/twinpost/machines/$name.toml)" "$work/$name.stdout" \
    || { cat "$work/$name.stdout"; fail "post did not use the installed $m"; }
  "$bin" check "$out"/* --machine "$name" >/dev/null || fail "check of the installed post for $name"
  XDG_CONFIG_HOME=$work/no-config "$bin" machines --show "$name" | cmp -s - "$work/root/usr/share/twinpost/machines/$m" \
    || fail "machines --show $name differs from the installed file"
done
echo "installed package: $(basename "$deb") posts and checks with its own machine files"
