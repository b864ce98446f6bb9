#!/usr/bin/env bash
# The main job, from a fresh clone: bootstrap, then run the offline runner — a planner host
# serving the reference planners over Zenoh, a simulated robot on a bundled map — and write
# out/<map>_<controller>.png and .json in the current directory. Arguments go to
# `nav2-pyif sim` (see --help), e.g.
#   scripts/sim.sh --map cluttered --controller mppi
set -euo pipefail
# Ctrl-C (or SIGTERM) while bootstrapping ends here with the conventional code, whatever the
# interrupted step returned; nav2-pyif, exec'd below, handles signals itself.
trap 'exit 130' INT
trap 'exit 143' TERM
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$ROOT/scripts/bootstrap.sh"
# shellcheck disable=SC1091
source "${NAV2_PYIF_VENV:-$ROOT/.venv}/nav2_pyif_env.sh"
# With the terminating signals blocked until nav2-pyif can handle them (nav2_pyif_entry
# unblocks them once its modules are imported): a Ctrl-C while Python starts waits until then,
# instead of ending in a KeyboardInterrupt traceback. (env --block-signal: coreutils 8.31+.)
# Stay in the caller's directory: planners named on the command line are imported from it,
# and out/ is written there.
if env --block-signal=INT true 2>/dev/null; then
  exec env --block-signal=INT --block-signal=TERM --block-signal=HUP nav2-pyif sim "$@"
fi
exec nav2-pyif sim "$@"
