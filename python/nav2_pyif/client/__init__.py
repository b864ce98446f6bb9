"""The reference client: the plugin side of the protocol, in Python.

It is what the offline runner and the tests use, and the executable specification the C++
Nav2 plugin follows: session id and epoch, state re-sent after a host restart, timeouts,
liveliness fail-fast, costmap sent only when changed.
"""

from nav2_pyif.client.behavior import BehaviorClient
from nav2_pyif.client.calls import CallRecord
from nav2_pyif.client.checkers import GoalCheckerClient, ProgressCheckerClient
from nav2_pyif.client.controller import ControllerClient
from nav2_pyif.client.cycle import ControlCycle
from nav2_pyif.client.global_planner import GlobalPlannerClient
from nav2_pyif.client.hosts import HostWatcher
from nav2_pyif.client.layer import CostmapLayerClient
from nav2_pyif.client.path_handler import PathHandlerClient
from nav2_pyif.client.plugin_client import PluginClient, Timeouts
from nav2_pyif.client.smoother import SmootherClient

__all__ = [
    "BehaviorClient",
    "CallRecord",
    "ControlCycle",
    "ControllerClient",
    "CostmapLayerClient",
    "GlobalPlannerClient",
    "GoalCheckerClient",
    "HostWatcher",
    "PathHandlerClient",
    "PluginClient",
    "ProgressCheckerClient",
    "SmootherClient",
    "Timeouts",
]
