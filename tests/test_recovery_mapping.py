"""A host failure (none alive, no reply in time, a crashed, restarting or overrunning worker)
must become an exception that Nav2's own behaviour tree sends to a recovery, on every
distribution, while a planner's own typed errors pass through as raised.

Nav2's side is a recorded excerpt (tests/fixtures/nav2_recovery_conditions.json, with the date
and files it was read from): which error code each server gives each nav2_core exception, and
which codes the WouldA*RecoveryHelp conditions of the default navigate_to_pose BT retry.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import nav2_pyif as api
import pytest
from nav2_pyif.client.plugin_client import error_from_reply, no_reply_message
from nav2_pyif_protocol.codec import ErrorInfo
from nav2_pyif_protocol.constants import (
    ERRORS_BY_PLUGIN,
    GENERIC_ERROR,
    HOST_FAILURE_ERROR,
    ErrorType,
    PluginType,
)

pytestmark = pytest.mark.unit

NAV2 = json.loads(
    (Path(__file__).parent / "fixtures" / "nav2_recovery_conditions.json").read_text()
)
ERROR_CODE_DISTROS = ["jazzy", "kilted", "lyrical"]
# The server whose action a plugin type's exception aborts, and so whose codes apply: the
# checkers run inside controller_server's loop. A costmap layer never throws into Nav2.
SERVER = {
    PluginType.CONTROLLER: "controller",
    PluginType.GOAL_CHECKER: "controller",
    PluginType.PROGRESS_CHECKER: "controller",
    PluginType.GLOBAL_PLANNER: "planner",
    PluginType.SMOOTHER: "smoother",
}


def _facts(distro: str) -> dict[str, Any]:
    facts = NAV2[distro]
    same_as: dict[str, Any] = NAV2[facts.split()[-1]] if isinstance(facts, str) else facts
    return same_as  # "same as jazzy"


@pytest.mark.parametrize("distro", ERROR_CODE_DISTROS)
@pytest.mark.parametrize("plugin_type", list(SERVER))
def test_a_host_failure_is_an_error_code_the_bt_recovers_from(
    distro: str, plugin_type: PluginType
) -> None:
    facts = _facts(distro)
    server = SERVER[plugin_type]
    thrown = HOST_FAILURE_ERROR[plugin_type].value
    code = facts[f"{server}_codes"][thrown]
    assert code in facts[f"{server}_recovers"], (
        f"{plugin_type.value}: a host failure throws {thrown}, which {server}_server reports "
        f"as {code}; {distro}'s WouldA{server.title()}RecoveryHelp retries only "
        f"{facts[f'{server}_recovers']}, so one dead host would end the navigation"
    )


@pytest.mark.parametrize("distro", ERROR_CODE_DISTROS)
def test_a_controller_host_failure_is_what_failure_tolerance_retries(distro: str) -> None:
    """controller_server holds the robot still and keeps the FollowPath goal through a host
    restart shorter than its failure_tolerance only for NoValidControl."""
    assert HOST_FAILURE_ERROR[PluginType.CONTROLLER].value in _facts(distro)["tolerance_retries"]


def test_humble_recovers_every_failure_so_planner_exception_is_enough() -> None:
    facts = NAV2["humble"]
    assert facts["recovers_every_failure"]
    assert "PlannerException" in facts["tolerance_retries"]


def test_the_timed_out_exceptions_are_left_to_planners_that_mean_them() -> None:
    """CONTROLLER_TIMED_OUT ends a Jazzy navigation: no host failure may throw it."""
    timed_out = {ErrorType.CONTROLLER_TIMED_OUT, ErrorType.SMOOTHER_TIMED_OUT}
    assert not timed_out & set(HOST_FAILURE_ERROR.values())


def _error(error_type: str) -> ErrorInfo:
    return ErrorInfo(type=error_type, message="msg", traceback="tb", python_type="x.Y")


@pytest.mark.parametrize("plugin_type", list(PluginType))
def test_unavailable_becomes_the_host_failure_and_own_errors_pass_through(
    plugin_type: PluginType,
) -> None:
    unavailable = error_from_reply(_error(ErrorType.UNAVAILABLE.value), plugin_type)
    assert type(unavailable).__name__ == HOST_FAILURE_ERROR[plugin_type].value
    assert str(unavailable) == "[Unavailable] msg"
    for own in ERRORS_BY_PLUGIN[plugin_type]:
        assert type(error_from_reply(_error(own.value), plugin_type)).__name__ == own.value
    for protocol_error in ("SessionUnknown", "VersionMismatch", "BadRequest"):
        generic = error_from_reply(_error(protocol_error), plugin_type)
        assert type(generic).__name__ == GENERIC_ERROR[plugin_type].value


def test_a_planner_raising_controller_timed_out_means_it() -> None:
    error = error_from_reply(_error("ControllerTimedOut"), PluginType.CONTROLLER)
    assert type(error) is api.ControllerTimedOut


def test_a_call_without_reply_says_whether_its_timeout_ran_out_or_its_host_went_away() -> None:
    """The time waited, not only the timeout: a query Zenoh ended at once (the host died in
    it) once read "no reply within 60000 ms" after 4.7 s."""
    assert no_reply_message("configure", "P", 4.7, 60.0) == (
        "configure got no reply from P: the query ended after 4700 ms of 60000 (its host went away)"
    )
    assert no_reply_message("check", "P", 0.0401, 0.04) == "check got no reply from P within 40 ms"
