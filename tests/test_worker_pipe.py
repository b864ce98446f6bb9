"""The supervisor <-> worker call pipe: whole messages of any size in order, the other end's
death seen as EOF, and a worker killed from outside in the middle of a call."""

from __future__ import annotations

import multiprocessing
import os
import signal
import threading

import nav2_pyif as api
import pytest
from nav2_pyif.server.frames import FramedPipe

from tests.test_faults import (  # fresh_rig: the fault suite's fixture, a rig per test
    Rig,
    assert_recovered,
    clear_fault_once_back,
    fresh_rig,  # noqa: F401
    inject,
    worker_pid,
)

pytestmark = pytest.mark.integration

SIZES = [0, 1, 3, 4, 5, 200, 65_531, 65_536, 65_540, 1_000_000, 7]


def _echo(connection: multiprocessing.connection.Connection) -> None:
    pipe = FramedPipe(connection)
    while message := pipe.recv():
        pipe.send(message[::-1])


def test_messages_of_every_size_cross_a_process_whole_and_in_order() -> None:
    parent, child = multiprocessing.get_context("spawn").Pipe()
    echo = multiprocessing.get_context("spawn").Process(target=_echo, args=(child,))
    echo.start()
    child.close()
    pipe = FramedPipe(parent)
    messages = [os.urandom(n) or b"x" for n in SIZES]  # an empty message stops the echo

    def send_all() -> None:
        for message in messages:
            pipe.send(message)

    sender = threading.Thread(target=send_all)
    sender.start()  # all sent before any is read: replies queue up, read several at once
    replies = [pipe.recv() for _ in messages]
    sender.join()
    assert replies == [m[::-1] for m in messages]
    pipe.send(b"")
    echo.join(10)
    with pytest.raises(EOFError):
        pipe.recv()  # the echo exited: its end is closed
    pipe.close()


def test_a_worker_killed_during_a_call_is_a_typed_error_and_the_session_comes_back(
    fresh_rig: Rig,  # noqa: F811
) -> None:
    rig = fresh_rig
    inject(rig, "sleep", sleep_s=0.45)  # within the 0.5 s deadline
    worker = worker_pid(rig)
    assert worker is not None, rig.host.log()
    killer = threading.Timer(0.1, os.kill, (worker, signal.SIGKILL))  # while it sleeps
    killer.start()
    with pytest.raises(
        api.ControllerException, match="killed by signal SIGKILL during compute_velocity_commands"
    ):
        rig.cycle()
    killer.join()
    clear_fault_once_back(rig)
    assert_recovered(rig)
    assert worker_pid(rig) not in (worker, None)
