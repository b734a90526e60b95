#!/usr/bin/env bash
# Installs everything twinpost needs to build and test, from Debian's packages.
# The one place where dependencies are named.
set -euo pipefail
packages=(
  make                          # CMake's default generator
  libboost-dev                  # Spirit X3 (header-only)
  libboost-program-options-dev  # the command line
  libfmt-dev                    # formatting
  catch2                        # tests (v2, as Debian packages it)
  libtomlplusplus-dev           # machine definition files
  liblua5.4-dev                 # the machine's event script (docs/customising.md)
  pkg-config                    # how CMake finds Lua 5.4
  dpkg-dev                      # the .deb's Depends (dpkg-shlibdeps, used by CPack)
  file                          # CPack's test for which installed files are programs
  clang-format-14               # the style check (ctest format, scripts/format.sh)
)
missing=()
for p in "${packages[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
as_root=()
[ "$(id -u)" -eq 0 ] || as_root=(sudo)
echo "setup: installing ${missing[*]}" >&2
"${as_root[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${as_root[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
