#!/bin/bash
# Container entry point: set up the venv's environment (library paths of the ROS 2 wheels),
# then run planner-host with the given options, or the given command (nav2-pyif ..., bash).
set -euo pipefail
# shellcheck disable=SC1091
. "${NAV2_PYIF_VENV:-/opt/nav2_pyif}/nav2_pyif_env.sh"
case "${1:-}" in
  "" | -*) exec planner-host "$@" ;;  # options only: they are planner-host's
  *) exec "$@" ;;
esac
