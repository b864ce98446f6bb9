"""Serve the reference path handler from a planner host and walk a robot along a plan, as
Lyrical's controller_server would ask it each cycle: prints the segment the controller would
follow, and how much of the plan is pruned behind the robot.

    python examples/path_handler/run.py                     # the reference PruningPathHandler
    python examples/path_handler/run.py --handler my_pkg.module:MyHandler --prune-distance 0.5
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from geometry_msgs.msg import PoseStamped
from nav2_pyif import Costmap, Plan
from nav2_pyif.client import PathHandlerClient
from nav2_pyif.common.host_process import PlannerHostProcess, wait_alive
from nav2_pyif.common.signals import Interrupted, raise_on_signals
from nav2_pyif.common.zenoh_config import connect_to

KEY = "nav2_pyif/example/path_handler"


def parse(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--handler",
        default="nav2_pyif_planners.path_handler:PruningPathHandler",
        help="the PathHandler to serve, module:Class (default: %(default)s)",
    )
    parser.add_argument(
        "--prune-distance", type=float, default=1.0, help="[m] (default: %(default)s)"
    )
    parser.add_argument("--steps", type=int, default=6, help="cycles to walk (default: 6)")
    return parser.parse_args(argv)


def robot_at(x: float, y: float) -> PoseStamped:
    pose = PoseStamped()
    pose.header.frame_id = "map"
    pose.pose.position.x, pose.pose.position.y = x, y
    return pose


def main(argv: list[str] | None = None) -> int:
    args = parse(argv)
    raise_on_signals()  # Ctrl-C and SIGTERM end the host and the session below too
    plan = Plan(np.column_stack([np.linspace(0.0, 4.0, 81), 0.3 * np.sin(np.linspace(0, 3, 81))]))
    host = PlannerHostProcess([{"key": KEY, "planner": args.handler}])
    session = None
    try:
        host.start()
        session = connect_to([host.endpoint], "peer")
        costmap = Costmap(np.zeros((100, 100), np.uint8), 0.05, frame_id="map")
        handler = PathHandlerClient(
            session, KEY, costmap, params={"prune_distance": args.prune_distance}
        )
        wait_alive(host, handler.wait_for_host)
        handler.configure()
        handler.set_plan(plan)
        print(f"plan: {len(plan)} poses, {plan.frame_id} frame")
        for step in range(args.steps):
            x = 0.6 * step
            start, end = handler.find_plan_segment(robot_at(x, float(np.interp(x, *plan.xy.T))))
            print(f"robot at x = {x:.1f} m: segment [{start}, {end}), {start} poses pruned")
        handler.cleanup()
        return 0
    except Interrupted as exc:
        return exc.exit_code
    finally:
        if session is not None:
            session.close()
        host.close()


if __name__ == "__main__":
    sys.exit(main())
