#!/usr/bin/env bash
# System packages the C++ codec tests need (tests/test_cpp_codec.py skips, saying what is
# missing, when they cannot be installed): installed with apt when absent.
set -uo pipefail
PACKAGES=(cmake g++ make libmsgpack-cxx-dev libgtest-dev nlohmann-json3-dev zlib1g-dev)
missing=()
for pkg in "${PACKAGES[@]}"; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
[ ${#missing[@]} -eq 0 ] && exit 0
if ! command -v apt-get >/dev/null; then
  echo "[cpp-deps] no apt-get: C++ codec tests will be skipped (need: ${missing[*]})" >&2
  exit 0
fi
SUDO=""
if [ "$(id -u)" != 0 ]; then
  if command -v sudo >/dev/null && sudo -n true 2>/dev/null; then SUDO="sudo"; else
    echo "[cpp-deps] not root: C++ codec tests will be skipped (need: ${missing[*]})" >&2
    exit 0
  fi
fi
echo "[cpp-deps] installing ${missing[*]}" >&2
$SUDO env DEBIAN_FRONTEND=noninteractive apt-get update -qq \
  && $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null \
  || echo "[cpp-deps] apt-get failed: C++ codec tests will be skipped" >&2
exit 0
