#!/usr/bin/env bash
# The main job, from a fresh clone: bootstrap, then run the offline runner — a planner host
# serving the reference planners over Zenoh, a simulated robot on a bundled map — and write
# out/<map>_<controller>.png and .json in the current directory. Arguments go to
# `nav2-pyif sim` (see --help), e.g.
#   scripts/sim.sh --map cluttered --controller mppi
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/bootstrap.sh"
# shellcheck disable=SC1091
source "${NAV2_PYIF_VENV:-$ROOT/.venv}/nav2_pyif_env.sh"
# Stay in the caller's directory: planners named on the command line are imported from it,
# and out/ is written there.
exec nav2-pyif sim "$@"
