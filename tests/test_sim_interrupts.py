"""How the runner ends when it is interrupted: a signal arriving while rclpy converts a message
is still a clean stop, and a runner killed outright leaves no planner host, worker or
temporary directory behind. Real signals, real processes."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from tests.conftest import survivors, wait_until
from tests.test_signals import TRACKER, WORKER, Command, python

pytestmark = pytest.mark.integration

# SIGINT at random moments while the main thread converts a large message (rclpy's C code
# calls the message constructors, where the handler runs): each must end as Interrupted.
CONVERT_UNDER_SIGNALS = textwrap.dedent(
    """
    import os, random, signal, sys, threading
    from geometry_msgs.msg import Point
    from visualization_msgs.msg import Marker, MarkerArray
    from nav2_pyif.client.ros_messages import from_cdr, to_cdr
    from nav2_pyif.common.signals import Interrupted, deferred, raise_on_signals

    markers = MarkerArray(markers=[Marker(points=[Point(x=float(j)) for j in range(50)])] * 200)
    cdr = to_cdr(markers)
    wrong = []
    for trial in range(int(sys.argv[1])):
        raise_on_signals()
        convert = trial % 2 == 0  # both ways
        timer = threading.Timer(random.uniform(0, 0.02), os.kill, (os.getpid(), signal.SIGINT))
        try:
            with deferred():
                timer.start()
            while True:
                if convert:
                    from_cdr("visualization_msgs/msg/MarkerArray", cdr)
                else:
                    to_cdr(markers)
        except Interrupted:
            pass
        except Exception as exc:
            wrong.append(f"{type(exc).__name__}: {exc}")
        timer.join()
    print(len(wrong), "of", sys.argv[1], "ended otherwise:", *wrong[:3], sep="\\n")
    """
)


def test_a_signal_during_a_message_conversion_is_a_clean_interrupt() -> None:
    done = subprocess.run(
        [sys.executable, "-c", CONVERT_UNDER_SIGNALS, "40"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert done.returncode == 0, done.stdout + done.stderr
    assert done.stdout.startswith("0\nof\n40\n"), done.stdout


def test_a_runner_killed_outright_leaves_no_host_worker_or_directory(tmp_path: Path) -> None:
    sim = Command(tmp_path, *python("nav2_pyif.tools.main", "sim", "--realtime", "--no-progress"))
    sim.wait_for(children={"nav2_pyif.server.cli": 1, WORKER: 2, TRACKER: 1}, words="driving with")
    assert next(d.name for d in sim.tmp.iterdir()).startswith("nav2_pyif_host_")
    assert sim.signal_and_wait(signal.SIGKILL) == -signal.SIGKILL
    assert wait_until(lambda: not survivors(sim.tree), 20), survivors(sim.tree)
    assert wait_until(lambda: not list(sim.tmp.iterdir()), 5), list(sim.tmp.iterdir())
