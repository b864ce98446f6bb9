#!/usr/bin/env bash
# The whole test suite, from a fresh clone: bootstrap, lint, type-check, then pytest.
# Extra arguments go to pytest (e.g. scripts/test.sh -k codec).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/bootstrap.sh"
"$ROOT/scripts/system_deps.sh" "C++ codec tests" \
  cmake g++ make libmsgpack-dev libgtest-dev nlohmann-json3-dev zlib1g-dev
# podman (runc, CNI with dnsname for compose) and debootstrap for the local base image
"$ROOT/scripts/system_deps.sh" "container tests" podman runc debootstrap uidmap iptables \
  catatonit containernetworking-plugins golang-github-containernetworking-plugin-dnsname
# shellcheck disable=SC1091
source "${NAV2_PYIF_VENV:-$ROOT/.venv}/nav2_pyif_env.sh"
cd "$ROOT"
echo "== ruff"; ruff check .
echo "== mypy"; mypy
echo "== pytest"; python -m pytest "$@"
