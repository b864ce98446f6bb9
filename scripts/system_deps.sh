#!/usr/bin/env bash
# Install the Debian/Ubuntu packages some tests need, when absent:
#   scripts/system_deps.sh "WHAT NEEDS THEM" PACKAGE...
# Never fails: without apt-get or root it says what is missing, and those tests skip,
# saying why.
set -uo pipefail
what="$1"; shift
missing=()
for pkg in "$@"; do
  # installed means "install ok installed", not a package left with its config files only
  [ "$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null)" = "install ok installed" ] \
    || missing+=("$pkg")
done
[ ${#missing[@]} -eq 0 ] && exit 0
say() { echo "[system-deps] $what: $*" >&2; }
if ! command -v apt-get >/dev/null; then
  say "no apt-get; these tests will be skipped (need: ${missing[*]})"; exit 0
fi
SUDO=""
if [ "$(id -u)" != 0 ]; then
  if command -v sudo >/dev/null && sudo -n true 2>/dev/null; then SUDO="sudo"; else
    say "not root; these tests will be skipped (need: ${missing[*]})"; exit 0
  fi
fi
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq || say "apt-get update failed"
# A package this release does not have must not keep the others from installing.
available=()
for pkg in "${missing[@]}"; do
  if apt-cache show "$pkg" >/dev/null 2>&1; then available+=("$pkg"); else
    say "$pkg is not available here; tests that need it will be skipped"; fi
done
[ ${#available[@]} -eq 0 ] && exit 0
say "installing ${available[*]}"
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  "${available[@]}" >/dev/null || say "apt-get failed; these tests will be skipped"
exit 0
