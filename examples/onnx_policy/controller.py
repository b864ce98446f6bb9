"""A policy network run by onnxruntime (the extra ``onnx``) as a Nav2 controller.

The model file (parameter ``model``) maps features.py's (N, 3) inputs to (N, 2) commands;
make_model.py writes one. The controller picks the target (the carrot on the plan, or the
goal's heading once within half the goal tolerance), asks the network, clips to the limits.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import onnxruntime as ort
from geometry_msgs.msg import TwistStamped
from nav2_pyif import Controller, InvalidController, NoValidControl, carrot, pose_xy_yaw, wrap

from onnx_policy.features import MAX_SPEED, MAX_TURN, features


class OnnxPolicy(Controller):
    def configure(self) -> None:
        path = self.params.declare("model", "", "the .onnx file (make_model.py writes one)")
        self.lookahead = self.params.declare("lookahead", 0.4, "[m] carrot distance")
        try:
            self.session = ort.InferenceSession(path, providers=["CPUExecutionProvider"])
        except Exception as error:  # onnxruntime's own types: say which file and how to make it
            raise InvalidController(
                f"cannot load the policy {path!r} ({error}); write one with "
                "python examples/onnx_policy/make_model.py FILE and pass --param model=FILE"
            ) from error
        self.progress = 0

    def set_plan(self, plan: Any) -> None:
        super().set_plan(plan)
        self.progress = 0

    def compute_velocity_commands(self, pose: Any, velocity: Any, goal_checker: Any) -> Any:
        if self.plan is None or len(self.plan) == 0:
            raise NoValidControl("no plan yet")
        x, y, yaw = pose_xy_yaw(pose)
        gx, gy, gyaw = self.plan.xy_yaw[-1]
        distance = math.hypot(gx - x, gy - y)
        tolerance = goal_checker.xy_goal_tolerance if goal_checker else 0.25
        if distance < 0.5 * tolerance:
            error, distance = wrap(gyaw - yaw), 0.0  # there: turn to the goal's heading
        else:
            (cx, cy), self.progress = carrot(self.plan.xy_yaw, x, y, self.lookahead, self.progress)
            error = wrap(math.atan2(cy - y, cx - x) - yaw)
        (command,) = self.session.run(["command"], {"features": features([error], [distance])})
        cmd = TwistStamped(header=pose.header)
        cmd.twist.linear.x = float(np.clip(command[0, 0], 0.0, MAX_SPEED))
        cmd.twist.angular.z = float(np.clip(command[0, 1], -MAX_TURN, MAX_TURN))
        return cmd
