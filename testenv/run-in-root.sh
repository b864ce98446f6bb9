#!/usr/bin/env bash
# Run nav2_pyif's Nav2 launch tests inside the Debian 13 root that `build.sh --root` made
# (Lyrical): the host's .venv cannot run there. See testenv/README.md ("Lyrical").
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO_ROOT="$(cd "$HERE/.." && pwd)"
# Run apart, as tests/test_nav2_launch.py does (each has a case or an opt-in of its own).
APART=(test_full_stack.py test_full_stack_native.py test_mppi_side_by_side.py test_gallery.py
  test_bringup.py test_plugin_soak.py)
# The plugin's build, as tests/test_nav2_launch.py's CMAKE_ARGS.
CMAKE_ARGS=(-DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF
  "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed -Wl,--allow-shlib-undefined"
  "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,--as-needed")

usage() {
  cat <<EOF
Usage: testenv/run-in-root.sh [OPTIONS] ROOT [TEST_FILE...]

From the host, inside the Debian 13 root ROOT (testenv/build.sh --root ROOT lyrical):
  1. installs nav2-pyif[record,runner] and nav2-pyif-planners[jax] from this checkout into
     PREFIX/venv (not editable: from a copy, so nothing is written into the checkout);
  2. builds nav2_pyif_bridge with colcon into PREFIX/ws_BACKEND against the root's ROS 2;
  3. runs the launch tests of bridge_plugin/test/nav2, one file at a time (pytest -x), the
     planner host from PREFIX/venv, and prints a table: file, result, seconds.
With --workspace-trial, step 3 is instead tests/test_ros_workspace.py's Lyrical trials (a fresh
colcon workspace with a clone of this checkout's HEAD: colcon build, ros2 run, colcon test,
ros2 launch to the goal; and the host alone with pip beside ROS 2), on zenoh-pico.
TEST_FILE: file names in bridge_plugin/test/nav2 (default: every test file but those run
apart: ${APART[*]}).

OPTIONS:
  --prefix DIR      the environment, a path inside ROOT (default /opt/nav2_pyif_testenv/lyrical)
  --backend NAME    zenoh-pico (default) or zenoh-c: PREFIX/setup-NAME.bash; or rmw_zenoh:
                    ROS on rmw_zenoh_cpp (PREFIX/setup-rmw-zenoh.bash, build.sh's rmw-zenoh
                    step), the plugin on zenoh-cpp over rmw_zenoh's zenoh-c, rmw_zenohd on a
                    free port (its default configs, the port replaced), which the plugins and
                    the host share, stopped by its PID at the end
  --no-install      skip step 1 (the venv has this checkout's packages already)
  --no-build        skip step 2
  --workspace-trial run the workspace trials, not the launch tests (commit first: they clone
                    HEAD)
  -k EXPRESSION     only the tests pytest's -k selects in each file
  -h, --help        this text

The checkout is bind-mounted at ROOT/nav2_pyif_run.PID for the run, and proc, sys and dev in
ROOT (stacked on any mounted there: a build running beside it keeps its own); all are
unmounted on exit, on SIGINT and on SIGTERM. Logs:
PREFIX/ws_BACKEND/logs/FILE (the Nav2 processes' logs) and FILE.log (pytest's output).
Exit status: 0 every file passed, 1 a step or a file failed, 2 usage.
EOF
}

log() { printf '[run-in-root %s] %s\n' "$(date +%H:%M:%S)" "$*" >&2; }
die() { log "error: $*"; exit 1; }
usage_error() { log "$*"; echo "Run testenv/run-in-root.sh --help for usage." >&2; exit 2; }
# root_mount and unmount_root: build.sh --root's own mounts
# shellcheck source=testenv/rootfs.sh
source "$HERE/rootfs.sh"

# --- inside the root: the three steps ------------------------------------------------------
use_environment() {  # SETUP: source a setup script (they read unset variables)
  set +u
  # shellcheck source=/dev/null
  source "$1" >/dev/null
  set -u
}
inside() {  # REPO PREFIX BACKEND INSTALL BUILD TRIAL SELECT FILE...
  local repo="$1" prefix="$2" backend="$3" install="$4" build="$5" trial="$6" select="$7"
  shift 7
  local chosen=()
  [ -z "$select" ] || chosen=(-k "$select")
  local setup="$prefix/setup-${backend//_/-}.bash" ws="$prefix/ws_$backend"
  [ -f "$setup" ] || die "no $setup: run testenv/build.sh --root ROOT lyrical first"
  if [ "$install" = 1 ]; then
    local copy
    copy="$(mktemp -d)"
    log "install: nav2-pyif and nav2-pyif-planners into $prefix/venv"
    tar -C "$repo" --exclude=./.git --exclude=./.venv --exclude=./build -cf - . | tar -C "$copy" -xf -
    "$prefix/venv/bin/python" -m pip install -q "${copy}[record,runner,ompl]" "${copy}/planners[jax]" cryptography \
      || { rm -rf "$copy"; die "pip install failed"; }
    rm -rf "$copy"
  fi
  mkdir -p "$ws/src" "$ws/logs"
  if [ "$trial" = 1 ]; then
    workspace_trial "$repo" "$prefix" "$setup" "$ws"
    return
  fi
  use_environment "$setup"
  ln -sfn "$repo/bridge_plugin" "$ws/src/nav2_pyif_bridge"
  if [ "$build" = 1 ]; then
    log "build: nav2_pyif_bridge in $ws (log: $ws/build.log)"
    local start=$SECONDS
    (cd "$ws" && colcon build --merge-install --event-handlers console_direct+ \
      --packages-select nav2_pyif_bridge --cmake-args "${CMAKE_ARGS[@]}") >"$ws/build.log" 2>&1 \
      || { tail -40 "$ws/build.log"; die "colcon build failed"; }
    log "build: $((SECONDS - start)) s, $(grep -c 'warning:' "$ws/build.log" || true) compiler warnings"
  fi
  use_environment "$ws/install/local_setup.bash"
  local zenoh_cpp="$backend"
  if [ "$backend" = rmw_zenoh ]; then
    # The plugin on rmw_zenoh's own zenoh-c (one libzenohc in each process), then rmw_zenohd
    # and the environment tests/test_nav2_launch.py gives its rmw_zenoh variant.
    ldd "$ws/install/lib/libnav2_pyif_bridge.so" | grep -q 'rmw-zenoh-c/lib/libzenohc' \
      || die "the plugin does not link rmw_zenoh's libzenohc: $(ldd "$ws/install/lib/libnav2_pyif_bridge.so" | grep zenoh)"
    zenoh_cpp=zenoh-c
    local router
    router="$(cd "$repo" && python -m tests.test_nav2_launch --rmw-zenoh-router "$ws")" \
      || die "rmw_zenoh's router: no configuration"
    eval "$router"
    log "rmw_zenohd (PID $NAV2_PYIF_RMW_ZENOHD) on $NAV2_PYIF_SHARED_ROUTER, log $ws/rmw_zenohd.log"
  fi
  # The planner host's environment: the venv, with the ROS 2 the tests run in.
  # shellcheck disable=SC2016
  printf '#!/bin/bash\nexport PATH=%q/venv/bin:"$PATH"\nexec "$@"\n' "$prefix" >"$ws/in-venv.sh"
  printf '#!/bin/bash\nexec %q planner-host "$@"\n' "$ws/in-venv.sh" >"$ws/planner-host.sh"
  chmod +x "$ws/in-venv.sh" "$ws/planner-host.sh"
  export NAV2_PYIF_ZENOH_BACKEND="$zenoh_cpp" NAV2_PYIF_RUN="$ws/in-venv.sh"
  export NAV2_PYIF_PLANNER_HOST="$ws/planner-host.sh" NAV2_PYIF_FIGURES="$ws/recovery_figures.json"
  export NAV2_PYIF_RECORDING_OUT="$ws/nav2_run.mcap"
  if [ $# -eq 0 ]; then
    local path name
    for path in "$repo"/bridge_plugin/test/nav2/test_*.py; do
      name="$(basename "$path")"
      [[ " ${APART[*]} " == *" $name "* ]] || set -- "$@" "$name"
    done
  fi
  cd "$repo"
  local file start status failed=0 rows=()
  for file in "$@"; do
    log "test: $file"
    start=$SECONDS
    status=0
    python -m pytest -p no:cacheprovider -q -rs -x "${chosen[@]}" --basetemp="$ws/logs/${file%.py}" \
      "bridge_plugin/test/nav2/$file" >"$ws/logs/$file.log" 2>&1 || status=$?
    local summary
    summary="$(grep -E '^(=+ )?[0-9]+ (passed|failed|error|skipped)' "$ws/logs/$file.log" | tail -1)"
    summary="${summary//=/}"
    if [ "$status" != 0 ] || [[ "$summary" == *skipped* ]] || [[ "$summary" != *passed* ]]; then
      failed=1
      tail -30 "$ws/logs/$file.log" >&2
    fi
    rows+=("| $file | ${summary# } | $((SECONDS - start)) |")
    log "test: $file: ${summary# } ($((SECONDS - start)) s)"
  done
  printf '| file | result | seconds |\n|---|---|---|\n'
  printf '%s\n' "${rows[@]}"
  return "$failed"
}

# The trials run by the venv's pytest, which the plugin's workspace would only shadow: they
# build their own from a clone, on the setup script alone.
workspace_trial() {  # REPO PREFIX SETUP WS
  local repo="$1" prefix="$2" setup="$3" ws="$4" status=0 start=$SECONDS
  log "workspace trial: tests/test_ros_workspace.py, lyrical (log: $ws/logs/workspace_trial.log)"
  cd "$repo"
  use_environment "$setup"  # for the test process's own imports; each step sources it anew
  NAV2_PYIF_NAV2_SETUP_LYRICAL_ZENOHPICO="$setup" "$prefix/venv/bin/python" -m pytest \
    -p no:cacheprovider -q -rs -s -k lyrical tests/test_ros_workspace.py \
    >"$ws/logs/workspace_trial.log" 2>&1 || status=$?
  grep -E '^[a-z0-9 -]+: [0-9]+ s \(' "$ws/logs/workspace_trial.log" || true
  tail -3 "$ws/logs/workspace_trial.log"
  log "workspace trial: exit $status ($((SECONDS - start)) s)"
  return "$status"
}

# --- arguments -----------------------------------------------------------------------------
PREFIX=/opt/nav2_pyif_testenv/lyrical BACKEND=zenoh-pico INSTALL=1 BUILD=1 ROOTFS="" FILES=()
TRIAL=0 SELECT=""
if [ "${1:-}" = --inside ]; then
  shift
  inside "$@"
  exit $?
fi
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --prefix) PREFIX="${2:?--prefix needs a directory}"; shift 2 ;;
    --backend) BACKEND="${2:?--backend needs a name}"; shift 2 ;;
    --no-install) INSTALL=0; shift ;;
    --no-build) BUILD=0; shift ;;
    --workspace-trial) TRIAL=1; shift ;;
    -k) SELECT="${2:?-k needs a pytest expression}"; shift 2 ;;
    -*) usage_error "unknown option: $1" ;;
    *)
      if [ -z "$ROOTFS" ]; then ROOTFS="$1"; else FILES+=("$1"); fi
      shift ;;
  esac
done
[ -n "$ROOTFS" ] || usage_error "no ROOT given"
case "$BACKEND" in zenoh-pico | zenoh-c | rmw_zenoh) ;; *) usage_error "unknown backend: $BACKEND" ;; esac
[ -x "$ROOTFS/usr/bin/apt-get" ] || die "$ROOTFS is no Debian root (testenv/build.sh --root)"
[ "$(id -u)" = 0 ] || die "mount and chroot need root"

# --- the mounts, undone on every way out ---------------------------------------------------
ROOT_MOUNTS=()
# shellcheck disable=SC2317
unmount() {
  unmount_root
  ROOT_MOUNTS=()
  [ -z "${AT:-}" ] || rmdir "$ROOTFS$AT" 2>/dev/null || true
}
CHILD=""
# shellcheck disable=SC2317
stop() {  # SIGNAL STATUS: end the run inside (its own process group), then unmount
  [ -z "$CHILD" ] || kill "-$1" -- "-$CHILD" 2>/dev/null || true
  [ -z "$CHILD" ] || wait "$CHILD" 2>/dev/null || true
  exit "$2"
}
trap unmount EXIT
trap 'stop INT 130' INT
trap 'stop TERM 143' TERM
# Mounted again even where something is mounted already (stacked): a build.sh --root or
# another run that mounted them first unmounts its own on exit, and this run must keep /proc.
root_mount "$ROOTFS/proc" -t proc proc
root_mount "$ROOTFS/sys" --rbind /sys
root_mount "$ROOTFS/dev" --rbind /dev
AT="/nav2_pyif_run.$$"
mkdir -p "$ROOTFS$AT"
root_mount "$ROOTFS$AT" --bind "$REPO_ROOT"

log "in $ROOTFS: $BACKEND, environment $PREFIX"
status=0
setsid chroot "$ROOTFS" /usr/bin/env -i HOME=/root TERM="${TERM:-dumb}" \
  PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
  bash "$AT/testenv/run-in-root.sh" --inside "$AT" "$PREFIX" "$BACKEND" "$INSTALL" "$BUILD" \
  "$TRIAL" "$SELECT" "${FILES[@]}" &
CHILD=$!
wait "$CHILD" || status=$?
exit "$status"
