"""A network of the tests' own on this machine: a network namespace with only a loopback, in
which commands run exactly as a user types them (README's `nav2-pyif router` on Zenoh's
default port 7447, a host connecting to `tcp/localhost:7447`) and still touch nothing outside:
not a Zenoh router already on 7447 (rmw_zenoh's, on a ROS machine), not planner hosts other
people started. Made with util-linux's unshare (as root, or unprivileged in a user namespace
of its own) and entered with nsenter."""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess

#: The port every documented default uses (rmw_zenoh's router port).
ZENOH_DEFAULT_PORT = 7447


def port_is_free(port: int = ZENOH_DEFAULT_PORT) -> bool:
    """Nothing listens on ``port`` here (a listener on any address would refuse this bind)."""
    with socket.socket() as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            s.bind(("0.0.0.0", port))
        except OSError:
            return False
    return True


class PrivateNetwork:
    """A network namespace with loopback up, held open by a sleeping process we own."""

    def __init__(self) -> None:
        self._user = os.geteuid() != 0  # unprivileged: a user namespace of its own too
        self._holder: subprocess.Popen[str] | None = None

    def open(self) -> str | None:
        """Make the namespace; None when done, else why it cannot be made here."""
        missing = [tool for tool in ("unshare", "nsenter", "ip") if shutil.which(tool) is None]
        if missing:
            return f"{', '.join(missing)} not installed"
        user = ["--user", "--map-root-user"] if self._user else []
        self._holder = subprocess.Popen(
            ["unshare", *user, "--net", "--", "sh", "-c",
             "ip link set lo up && echo up && exec sleep infinity"],
            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
        )  # fmt: skip
        assert self._holder.stdout is not None
        if self._holder.stdout.readline().strip() != "up":
            _, error = self._holder.communicate(timeout=10)
            self._holder = None
            return f"unshare --net failed: {error.strip()[-300:]}"
        return None

    def command(self, argv: list[str]) -> list[str]:
        """``argv`` run inside the namespace (nsenter execs it: same process, same group)."""
        assert self._holder is not None, "open() first"
        user = ["--user", "--preserve-credentials"] if self._user else []
        return ["nsenter", "--target", str(self._holder.pid), *user, "--net", "--", *argv]

    def close(self) -> None:
        if self._holder is not None and self._holder.poll() is None:
            self._holder.send_signal(signal.SIGKILL)  # our own sleep: nothing to clean up
            self._holder.communicate(timeout=10)
        self._holder = None
