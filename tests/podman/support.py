"""podman for the container tests: a probe that says why containers cannot run here, a base
image made locally (no registry is reachable on the project's CI machines), and the
planner-host image built from docker/Dockerfile on it."""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path
from typing import IO

ROOT = Path(__file__).resolve().parents[2]
CONTAINERS_CONF = Path(__file__).with_name("containers.conf")
#: made by debootstrap from the machine's own Debian/Ubuntu release, then cached by podman
LOCAL_BASE = "localhost/nav2-pyif-test-base:{codename}"
#: set to an existing image (e.g. python:3.11-slim-bookworm where a registry is reachable)
BASE_ENV = "NAV2_PYIF_TEST_BASE_IMAGE"
#: one tag per checkout: two checkouts testing at once must not run each other's image
IMAGE = "localhost/nav2-pyif-host:test-" + hashlib.sha1(str(ROOT).encode()).hexdigest()[:10]
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
    """docker/Dockerfile on ``base``; podman's layer cache makes a rebuild quick."""
    _say(f"building {IMAGE} from docker/Dockerfile on {base}")
    podman(
        "build", "--format", "docker", "-f", str(ROOT / "docker/Dockerfile"), "--build-arg",
        f"BASE_IMAGE={base}", "-t", IMAGE, str(ROOT), timeout=900,
    )  # fmt: skip
    return IMAGE
