# The Debian 13 (trixie) root that a ROS 2 Lyrical source build needs (Python 3.13, GCC 14,
# CMake 3.31; Debian 12 has 3.11, 12 and 3.25). Sourced by build.sh for --root DIR.
# shellcheck shell=bash

DEBIAN_MIRROR="${DEBIAN_MIRROR:-http://deb.debian.org/debian}"

make_root() {  # DIR: a minimal trixie made with debootstrap, once
  local root="$1"
  if [ -x "$root/usr/bin/apt-get" ]; then return; fi
  command -v debootstrap >/dev/null || die "root: install debootstrap (apt-get install debootstrap)"
  [ "$(id -u)" = 0 ] || die "root: debootstrap and chroot need root"
  log "root: debootstrap trixie into $root from $DEBIAN_MIRROR (a few minutes)"
  debootstrap --variant=minbase --include=ca-certificates,git,python3 trixie "$root" \
    "$DEBIAN_MIRROR" || die "root: debootstrap failed"
}

unmount_root() {  # on every way out; lazily, as the rbinds hold submounts
  local mount
  for mount in "${ROOT_MOUNTS[@]}"; do umount -l "$mount" 2>/dev/null || true; done
  # (the checkout's own mount point, when it was build.sh's: see run_in_root)
  [ -z "${ROOT_CHECKOUT:-}" ] || rmdir "$ROOT_CHECKOUT" 2>/dev/null || true
}

root_mount() {  # WHERE MOUNT-ARGS...: mount, and remember to unmount
  local where="$1"
  shift
  mount "$@" "$where" || die "root: mount $* $where failed"
  ROOT_MOUNTS=("$where" "${ROOT_MOUNTS[@]}")
}

run_in_root() {  # DIR ARGS...: build.sh again inside DIR, on the same distribution and steps
  local root="$1"
  make_root "$root"
  # The host's resolver, CA bundle (HTTPS may go through an intercepting proxy) and Rust
  # toolchain (trixie's rustc is older than zenoh-c wants): what the build inside needs.
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  cp /etc/ssl/certs/ca-certificates.crt "$root/usr/local/share/ca-certificates/host.crt" \
    2>/dev/null || true
  ROOT_MOUNTS=()
  trap unmount_root EXIT
  # Each build's checkout at a mount point of its own, as run-in-root.sh's: other builds and
  # test runs may use the root meanwhile, from other checkouts (one mounted on another's point
  # would change the script under a running build). proc, sys and dev are mounted again even
  # where they are mounted (stacked): each run unmounts one on its way out, and the others keep
  # theirs.
  local at="/nav2_pyif_build.$$"
  mkdir -p "$root$at" "$root/root/.cargo" "$root/root/.rustup" "$root/mirrors"
  ROOT_CHECKOUT="$root$at"
  root_mount "$root/proc" -t proc proc
  root_mount "$root/sys" --rbind /sys
  root_mount "$root/dev" --rbind /dev
  root_mount "$root$at" --bind "$REPO_ROOT"
  if [ -d "$HOME/.cargo" ] && [ -d "$HOME/.rustup" ]; then
    root_mount "$root/root/.cargo" --bind "$HOME/.cargo"
    root_mount "$root/root/.rustup" --bind "$HOME/.rustup"
  fi
  local args=(--prefix "$PREFIX" --sources "$SOURCES" --jobs "$JOBS")
  if [ -n "$MIRRORS" ]; then
    root_mount "$root/mirrors" --bind "$MIRRORS"
    args+=(--mirrors /mirrors)
  fi
  cp "$REPOS" "$root/tmp/testenv.repos" && args+=(--repos /tmp/testenv.repos)
  [ "$APT" = 1 ] || args+=(--no-apt)
  log "root: running build.sh $DISTRO ${STEPS[*]} inside $root"
  chroot "$root" /usr/bin/env -i HOME=/root TERM="${TERM:-dumb}" \
    PATH=/root/.cargo/bin:/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    bash -c 'update-ca-certificates >/dev/null 2>&1; exec "$@"' build \
    "$at/testenv/build.sh" "${args[@]}" "$DISTRO" "${STEPS[@]}"
}
