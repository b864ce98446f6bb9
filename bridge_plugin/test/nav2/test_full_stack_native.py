"""The full-stack baseline with Nav2's own controller and planner: the same goals as
test_full_stack.py, NavigateToPose through the same BT, with nav2_regulated_pure_pursuit_controller
and nav2_navfn_planner in place of PyController and PyGlobalPlanner (skipped, naming them, where
they are not built). A module of its own: one Nav2 stack (and one rclpy) at a time."""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

import nav2_testing
import pytest
from test_full_stack import (
    FULL_STACK,
    NAVIGATIONS,
    PLANNER,
    _record,
    _runs,
    full_stack_params,
    pytestmark,  # noqa: F401  (the same per-test timeout)
)

NATIVE = {
    "nav2_pyif_bridge::PyController": nav2_testing.NATIVE_PURE_PURSUIT,
    "nav2_pyif_bridge::PyGlobalPlanner": "nav2_navfn_planner::NavfnPlanner",
    "nav2_pyif_bridge::PyBackUp": "nav2_behaviors::BackUp",
}


def native_params(text: str) -> str:
    for python, native in NATIVE.items():
        text = text.replace(f'plugin: "{python}"', f'plugin: "{native}"')
    return full_stack_params(text)


@pytest.fixture(scope="module")
def native_stack(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, Any]]:
    missing = [
        lib
        for lib in ("nav2_regulated_pure_pursuit_controller", "nav2_navfn_planner")
        if nav2_testing.find(f"share/{lib}/package.xml") is None
    ]
    if missing:
        pytest.skip("the native comparison needs " + ", ".join(missing))
    for up in nav2_testing.bring_up(
        tmp_path_factory.mktemp("nav2_full_stack_native"),
        planners=PLANNER,  # serves nothing Nav2 asks for: the plugins are native
        edit_params=native_params,
        servers=FULL_STACK,
    ):
        NAVIGATIONS.clear()  # a new robot, at the origin
        states = up["client"].wait_active(FULL_STACK, 120.0)
        assert all(s == "active" for s in states.values()), states
        yield up


def test_navigate_to_pose_through_nav2s_native_rpp_and_navfn(
    native_stack: dict[str, Any],
) -> None:
    runs = _runs(native_stack, None)
    _record("native", runs)
