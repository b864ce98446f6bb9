"""podman for the container tests: a probe that says why containers cannot run here, a base
image made locally (no registry is reachable on the project's CI machines), and the
planner-host image built from docker/Dockerfile on it.

What they leave (README, "Try it"): the base image and the planner-host image, one tag each
whatever the checkout (about 0.3 GB and 0.4 GB more), kept as the cache of the next run.
Images a build replaces and the layers of a failed build are removed (all carry LABEL). One
checkout's container tests run at a time (an exclusive lock): another's build would otherwise
re-tag, and its clean-up remove, the image a run is using."""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO

ROOT = Path(__file__).resolve().parents[2]
CONTAINERS_CONF = Path(__file__).with_name("containers.conf")
#: made by debootstrap from the machine's own Debian/Ubuntu release, then cached by podman
LOCAL_BASE = "localhost/nav2-pyif-test-base:{codename}"
#: set to an existing image (e.g. python:3.11-slim-bookworm where a registry is reachable)
BASE_ENV = "NAV2_PYIF_TEST_BASE_IMAGE"
#: one tag for every checkout (a tag per checkout path left ~0.4 GB behind per checkout)
IMAGE = "localhost/nav2-pyif-host:test"
#: on every image (and build layer) the tests make: what their clean-up may remove
LABEL = "nav2-pyif-test-image=1"
#: held while one checkout's container tests run (podman's images are shared per user)
LOCK = Path(tempfile.gettempdir()) / f"nav2-pyif-container-tests-{os.getuid()}.lock"
HOST_CA = "/etc/nav2-pyif-test-ca.crt"
MIRRORS = {"debian": "http://deb.debian.org/debian", "ubuntu": "http://archive.ubuntu.com/ubuntu"}


class Unavailable(Exception):
    """This machine cannot run the container tests; the message says why."""


def _say(message: str) -> None:
    print(f"[container tests] {message}", file=sys.stderr, flush=True)


def podman_env(**extra: str) -> dict[str, str]:
    """This environment with the tests' podman settings (and ``extra`` variables)."""
    return dict(os.environ, CONTAINERS_CONF=str(CONTAINERS_CONF), **extra)


def podman(
    *args: str, timeout: float = 120, check: bool = True, stdin: IO[bytes] | None = None
) -> subprocess.CompletedProcess[str]:
    result = subprocess.run(
        ["podman", *args],
        stdin=stdin,
        capture_output=True,
        text=True,
        timeout=timeout,
        env=podman_env(),
    )
    if check and result.returncode != 0:
        raise RuntimeError(
            f"podman {' '.join(args)} failed ({result.returncode}):\n{result.stderr}"
        )
    return result


def _os_release() -> dict[str, str]:
    fields = {}
    for line in Path("/etc/os-release").read_text().splitlines():
        key, sep, value = line.partition("=")
        if sep:
            fields[key] = value.strip('"')
    return fields


def _image_exists(tag: str) -> bool:
    return podman("image", "exists", tag, check=False).returncode == 0


def base_image() -> str:
    """The image to build FROM: $NAV2_PYIF_TEST_BASE_IMAGE, or a local debootstrap of this
    machine's release with Python (made once, ~1 min)."""
    if os.environ.get(BASE_ENV):
        return os.environ[BASE_ENV]
    release = _os_release()
    codename, distro = release.get("VERSION_CODENAME", ""), release.get("ID", "")
    if distro not in MIRRORS or not codename:
        raise Unavailable(f"no base image: set {BASE_ENV} (cannot debootstrap {distro!r})")
    tag = LOCAL_BASE.format(codename=codename)
    if _image_exists(tag):
        return tag
    if shutil.which("debootstrap") is None:
        raise Unavailable(f"no base image: debootstrap is not installed and {BASE_ENV} is unset")
    _say(f"making base image {tag} with debootstrap {codename} (about a minute)")
    (ROOT / "build").mkdir(exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="nav2-pyif-rootfs-", dir=ROOT / "build") as tmp:
        rootfs = Path(tmp) / "rootfs"
        result = subprocess.run(
            ["debootstrap", "--variant=minbase", "--include=python3,python3-venv,ca-certificates",
             codename, str(rootfs), MIRRORS[distro]],
            capture_output=True, text=True, timeout=900,
        )  # fmt: skip
        if result.returncode != 0:
            raise Unavailable(f"debootstrap {codename} failed: {result.stdout[-2000:]}")
        # This machine's CA bundle: HTTPS may pass through an intercepting proxy here, which
        # pip inside the build must trust as the machine does. A path of its own: apt's
        # ca-certificates would rewrite the standard bundle without the proxy's CA.
        bundle = Path("/etc/ssl/certs/ca-certificates.crt")
        if bundle.is_file():
            shutil.copy(bundle, rootfs / HOST_CA.lstrip("/"))
        tar = subprocess.Popen(["tar", "-C", str(rootfs), "-c", "."], stdout=subprocess.PIPE)
        imported = podman(
            "import", "--change", f"ENV PIP_CERT={HOST_CA}", "--change", 'CMD ["/bin/bash"]',
            "-", tag, stdin=tar.stdout, timeout=600, check=False,
        )  # fmt: skip
        tar.wait()
        if imported.returncode != 0:
            raise Unavailable(f"podman import failed: {imported.stderr}")
    return tag


def require_podman() -> None:
    if shutil.which("podman") is None:
        raise Unavailable("podman is not installed (scripts/test.sh installs it with apt)")


def probe(base: str) -> None:
    """Can this machine run a container at all? (Not whether our image is right.)"""
    result = podman("run", "--rm", "--init", base, "true", check=False, timeout=120)
    if result.returncode != 0:
        raise Unavailable(f"podman cannot run a container here: {result.stderr.strip()[-800:]}")


def build_image(base: str) -> str:
    """docker/Dockerfile on ``base``; podman's layer cache makes a rebuild quick. The image
    it replaces under IMAGE is removed (remove_stale_images)."""
    _say(f"building {IMAGE} from docker/Dockerfile on {base}")
    try:
        podman(
            "build", "--format", "docker", "-f", str(ROOT / "docker/Dockerfile"), "--build-arg",
            f"BASE_IMAGE={base}", "--label", LABEL, "-t", IMAGE, str(ROOT), timeout=900,
        )  # fmt: skip
    finally:
        remove_stale_images()
    return IMAGE


def stale_images() -> list[str]:
    """Images the tests made that nothing uses any more: untagged (replaced by a later build,
    or the layers of a failed one) and without a container."""
    listed = podman(
        "images", "--all", "--quiet", "--no-trunc", "--filter", f"label={LABEL}",
        "--filter", "dangling=true", check=False,
    )  # fmt: skip
    return listed.stdout.split()


def remove_stale_images() -> None:
    podman("image", "prune", "--force", "--filter", f"label={LABEL}", check=False, timeout=300)


@contextlib.contextmanager
def exclusive(wait: float = 300) -> Iterator[None]:
    """Hold LOCK: one checkout's container tests at a time. Unavailable if another's still
    hold it after ``wait`` seconds."""
    with open(LOCK, "a") as lock:
        deadline = time.monotonic() + wait
        while True:
            try:
                fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if time.monotonic() > deadline:
                    raise Unavailable(
                        f"another checkout's container tests have held {LOCK} for {wait:.0f} s"
                    ) from None
                time.sleep(1)
        try:
            yield
        finally:
            fcntl.flock(lock, fcntl.LOCK_UN)
