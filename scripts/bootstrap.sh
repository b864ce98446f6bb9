#!/usr/bin/env bash
# Make (or refresh) the project's virtualenv: the ROS 2 Jazzy base from PyPI (or the system
# ROS 2 when one is sourced or installed under /opt/ros), eclipse-zenoh, msgpack, NumPy and
# nav2_pyif itself in editable mode, with the reference planners, the benchmarks and the
# protocol's code generators (distributions of their own: planners/, benchmarks/ and
# protocol/codegen/). Idempotent: does nothing when already up to date.
#
# Writes <venv>/nav2_pyif_env.sh, which sets LD_LIBRARY_PATH and AMENT_PREFIX_PATH itself so
# the ROS wheels' start-up re-exec never runs (it surprises process supervisors).
#
# Environment: NAV2_PYIF_VENV (default: <repo>/.venv), PYTHON (interpreter to use),
# NAV2_PYIF_EXTRAS (default: dev, the test tools with the examples/ gallery's extras ompl,
# casadi and onnx, so that tests/test_examples.py runs them; "ros" is added without a system
# ROS 2), NAV2_PYIF_WITH (default "planners benchmarks protocol/codegen": the distributions
# installed beside the core, by folder; the container image takes only planners),
# NAV2_PYIF_EDITABLE
# (default 1; 0 installs a copy, as the container image does).
set -euo pipefail
# Ctrl-C ends the bootstrap with 130 (SIGTERM 143), whatever the interrupted step returned: a
# check interrupted half-way must not be taken for its answer (a missing venv module, ...).
trap 'exit 130' INT
trap 'exit 143' TERM

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${NAV2_PYIF_VENV:-$ROOT/.venv}"
log() { printf '[bootstrap] %s\n' "$*" >&2; }

as_root() {
  if [ "$(id -u)" = 0 ]; then "$@"; elif command -v sudo >/dev/null; then sudo "$@"; else
    log "need root for: $*  (install it by hand, or run as root)"; return 1; fi
}

apt_install() {
  command -v apt-get >/dev/null || { log "missing system packages: $*; no apt-get here"; return 1; }
  log "installing system packages: $*"
  as_root env DEBIAN_FRONTEND=noninteractive apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >/dev/null
}

# --- system ROS 2 (used instead of the PyPI wheels when present) --------------------------
SYSTEM_ROS=""
if [ -n "${ROS_DISTRO:-}" ] && [ -d "/opt/ros/${ROS_DISTRO}" ]; then
  SYSTEM_ROS="/opt/ros/${ROS_DISTRO}"
else
  for distro in jazzy kilted humble rolling; do
    if [ -f "/opt/ros/$distro/setup.bash" ]; then SYSTEM_ROS="/opt/ros/$distro"; break; fi
  done
fi

# --- interpreter: the ROS wheels exist for CPython 3.10-3.12 ------------------------------
pick_python() {
  local candidates=("${PYTHON:-}" python3 python3.12 python3.11 python3.10)
  [ -n "$SYSTEM_ROS" ] && candidates=("${PYTHON:-}" /usr/bin/python3)
  for py in "${candidates[@]}"; do
    [ -n "$py" ] || continue
    command -v "$py" >/dev/null || continue
    if "$py" -c 'import sys; sys.exit(0 if (3, 10) <= sys.version_info[:2] <= (3, 12) else 1)' 2>/dev/null; then
      echo "$py"; return 0
    fi
  done
  return 1
}
if ! PY="$(pick_python)"; then
  if command -v apt-get >/dev/null; then apt_install python3 python3-venv; PY="$(pick_python)"; else
    log "no Python 3.10-3.12 found (the ROS 2 Jazzy wheels need one); set PYTHON=..."; exit 1; fi
fi
if ! "$PY" -c 'import venv, ensurepip' 2>/dev/null; then
  ver="$("$PY" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')"
  apt_install "python${ver}-venv" || apt_install python3-venv
fi

# --- venv, re-made only when the inputs changed --------------------------------------------
EXTRAS="${NAV2_PYIF_EXTRAS-dev}"
[ -z "$SYSTEM_ROS" ] && EXTRAS="${EXTRAS:+$EXTRAS,}ros"
# What pip installs (the core with its extras, then each sibling's folder) and the files that
# say what they need.
TARGETS=("$ROOT${EXTRAS:+[$EXTRAS]}") METADATA=("$ROOT/pyproject.toml")
WITH="${NAV2_PYIF_WITH-planners benchmarks protocol/codegen}"
for folder in $WITH; do
  case "$folder" in
    planners) METADATA+=("$ROOT/planners/setup.py") ;;
    benchmarks | protocol/codegen) METADATA+=("$ROOT/$folder/pyproject.toml") ;;
    *) log "NAV2_PYIF_WITH names planners, benchmarks and protocol/codegen, not '$folder'"
      exit 2 ;;
  esac
  TARGETS+=("$ROOT/$folder")
done
EDITABLE="${NAV2_PYIF_EDITABLE:-1}"
case "$EDITABLE" in 0 | 1) ;; *) log "NAV2_PYIF_EDITABLE must be 0 or 1, not '$EDITABLE'"; exit 2 ;; esac
STAMP_INPUT="$(cat "${METADATA[@]}" "$ROOT/scripts/bootstrap.sh"; echo "$PY $SYSTEM_ROS $EXTRAS $WITH $EDITABLE")"
STAMP="$(printf '%s' "$STAMP_INPUT" | sha256sum | cut -d' ' -f1)"
if [ -f "$VENV/.nav2_pyif_stamp" ] && [ "$(cat "$VENV/.nav2_pyif_stamp")" = "$STAMP" ]; then
  exit 0
fi

log "creating $VENV with $PY ($("$PY" --version 2>&1))${SYSTEM_ROS:+ on system ROS $SYSTEM_ROS}"
if [ -n "$SYSTEM_ROS" ]; then
  "$PY" -m venv --system-site-packages "$VENV"
else
  "$PY" -m venv "$VENV"
fi
PIP=("$VENV/bin/python" -m pip --disable-pip-version-check -q)
"${PIP[@]}" install --upgrade pip >/dev/null
INSTALL=("${TARGETS[@]}") HOW="a copy"
if [ "$EDITABLE" = 1 ]; then
  INSTALL=() HOW="editable"
  for target in "${TARGETS[@]}"; do INSTALL+=(-e "$target"); done
fi
# In one pip command, so that the siblings' requirement of the core is met by this checkout.
log "installing nav2_pyif${EXTRAS:+[$EXTRAS]}${WITH:+ with $WITH} ($HOW) and its dependencies"
# setuptools tells of every editable install in a BuildBackendWarning block ("Editable
# installation. Please be careful with folders ... with the same name as your package"): by
# design here, and noise that hides a real warning, so the build backends ignore that one.
QUIET="ignore:Editable installation.:UserWarning${PYTHONWARNINGS:+,$PYTHONWARNINGS}"
_ROS_WHEELS_BOOTSTRAP_COMPLETE=1 PYTHONWARNINGS="$QUIET" "${PIP[@]}" install "${INSTALL[@]}" 2>&1 \
  | grep -v "^WARNING: Location" || true
_ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -c 'import nav2_pyif, zenoh, msgpack' \
  || { log "install failed: see the pip output above"; exit 1; }

# --- environment script ---------------------------------------------------------------------
PYVER="$("$VENV/bin/python" -c 'import sys; print(f"{sys.version_info[0]}.{sys.version_info[1]}")')"
{
  echo "# Generated by scripts/bootstrap.sh: source it to use nav2_pyif from this venv."
  if [ -n "$SYSTEM_ROS" ]; then
    echo "set +u; source '$SYSTEM_ROS/setup.bash'; set -u 2>/dev/null || true"
  else
    echo "_nav2_pyif_libs='$VENV/lib'"
    echo "for _d in '$VENV/lib/python$PYVER/site-packages/'ros_*.libs; do _nav2_pyif_libs=\"\$_nav2_pyif_libs:\$_d\"; done"
    echo "export LD_LIBRARY_PATH=\"\$_nav2_pyif_libs\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}\""
    echo "export AMENT_PREFIX_PATH='$VENV'\${AMENT_PREFIX_PATH:+:\$AMENT_PREFIX_PATH}"
    echo "export _ROS_WHEELS_BOOTSTRAP_COMPLETE=1"
    echo "unset _nav2_pyif_libs _d"
  fi
  echo "export VIRTUAL_ENV='$VENV'"
  echo "export PATH='$VENV/bin':\"\$PATH\""
} > "$VENV/nav2_pyif_env.sh"

# shellcheck disable=SC1091
( source "$VENV/nav2_pyif_env.sh" && python -c 'import rclpy, geometry_msgs.msg, nav_msgs.msg' ) \
  || { log "ROS 2 Python packages do not import; see above"; exit 1; }
echo "$STAMP" > "$VENV/.nav2_pyif_stamp"
log "ready: source $VENV/nav2_pyif_env.sh"
