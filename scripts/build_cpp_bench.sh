#!/usr/bin/env bash
# Build nav2_pyif_cycle_bench (bridge_plugin/bench: the control-cycle benchmark with the C++
# plugin's client code) and nav2_pyif_fleet_client (the robots of `fleet --cpp-clients`) into
# build/cpp_bench, against an installed ROS 2 with Nav2 and
# zenoh-cpp: the setup script in $NAV2_PYIF_NAV2_SETUP, else /opt/ros/<distro>/setup.bash.
# Builds only this repository's bridge_plugin sources, nothing fetched. Then:
#   nav2-pyif-bench cpp-cycle      (finds build/cpp_bench/nav2_pyif_cycle_bench)
#   nav2-pyif-bench fleet --cpp-clients   (finds build/cpp_bench/nav2_pyif_fleet_client)
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build/cpp_bench"
setup="${NAV2_PYIF_NAV2_SETUP:-}"
if [ -z "$setup" ]; then
  for distro in jazzy kilted humble; do
    [ -f "/opt/ros/$distro/setup.bash" ] && { setup="/opt/ros/$distro/setup.bash"; break; }
  done
fi
if [ -z "$setup" ] || [ ! -f "$setup" ]; then
  echo "build_cpp_bench: no ROS 2 setup script: set NAV2_PYIF_NAV2_SETUP to one of a ROS 2" \
    "with Nav2 and zenoh-cpp (e.g. /opt/ros/jazzy/setup.bash)" >&2
  exit 1
fi
# The project's venv must not leak into the ROS environment (its own Python paths, libraries).
unset PYTHONPATH VIRTUAL_ENV AMENT_PREFIX_PATH _ROS_WHEELS_BOOTSTRAP_COMPLETE LD_LIBRARY_PATH
PATH="$(tr ':' '\n' <<<"$PATH" | grep -v '/\.venv/' | paste -sd: -)"
set +u  # ROS setup scripts read unset variables
# shellcheck disable=SC1090
source "$setup" >/dev/null
set -u
# The PyPI ROS wheels name Python-only libraries as dependencies of C++ ones: link only what
# is used (harmless on a system ROS install).
cmake -S "$ROOT/bridge_plugin" -B "$BUILD" -DNAV2_PYIF_BUILD_BENCH=ON -DBUILD_TESTING=OFF \
  -DCMAKE_BUILD_TYPE=Release \
  "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed -Wl,--allow-shlib-undefined" \
  "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,--as-needed" >/dev/null
cmake --build "$BUILD" --target nav2_pyif_cycle_bench nav2_pyif_fleet_client -j2
echo "$BUILD/nav2_pyif_cycle_bench"
echo "$BUILD/nav2_pyif_fleet_client"
