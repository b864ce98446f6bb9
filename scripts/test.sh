#!/usr/bin/env bash
# The whole test suite, from a fresh clone: bootstrap, lint, type-check, then pytest.
# Extra arguments go to pytest (e.g. scripts/test.sh -k codec).
# --fast (first): the unit tier only (tests/tiers.py), lint first; for before every commit.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
FAST=0
if [ "${1:-}" = "--fast" ]; then FAST=1; shift; fi
"$ROOT/scripts/bootstrap.sh"
if [ "$FAST" = 0 ]; then
  "$ROOT/scripts/system_deps.sh" "C++ codec tests" \
    cmake g++ make libmsgpack-dev libgtest-dev nlohmann-json3-dev zlib1g-dev
  # podman (runc, CNI with dnsname for compose) and debootstrap for the local base image
  "$ROOT/scripts/system_deps.sh" "container tests" podman runc debootstrap uidmap iptables \
    catatonit containernetworking-plugins golang-github-containernetworking-plugin-dnsname
  # headless Chromium renders the documentation site's pages (tests/test_site.py)
  "$ROOT/scripts/system_deps.sh" "site rendering tests" chromium fonts-dejavu-core
fi
# shellcheck disable=SC1091
source "${NAV2_PYIF_VENV:-$ROOT/.venv}/nav2_pyif_env.sh"
cd "$ROOT"
echo "== ruff"; ruff check .
if [ "$FAST" = 1 ]; then
  echo "== pytest (unit tier)"; exec python -m pytest -m unit "$@"
fi
echo "== mypy"; mypy
echo "== pytest"; python -m pytest "$@"
