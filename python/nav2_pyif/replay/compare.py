"""How a replayed reply differs from the recorded one: a command's dv and dw, a plan's pose
distances, errors, compute time, and a digest of the output for determinism checks."""

from __future__ import annotations

import hashlib
from dataclasses import asdict, dataclass
from typing import Any

import msgpack
import numpy as np
from nav2_pyif_protocol.arrays import unpack_poses

#: the reply fields that are the planner's output (not who answered, nor how long it took)
_NOT_OUTPUT = ("host", "compute_ns", "seq")
_PLAN_OPS = ("create_plan", "smooth")


@dataclass
class CallDiff:
    index: int  # position in the replay
    key: str
    op: str
    t: float  # seconds since the recording's first call, when the host took it
    identical: bool  # the planner's output is the recorded one, bit for bit
    output: str  # digest of the replayed output (two replays of one planner: equal)
    error: str = ""  # the replay's error reply, "[type] message"
    recorded_error: str = ""
    recorded_compute_ms: float | None = None
    compute_ms: float | None = None
    dv: float | None = None  # replayed - recorded linear x [m/s]
    dw: float | None = None  # replayed - recorded angular z [rad/s]
    plan_max: float | None = None  # largest distance of a pose to the other plan [m]
    plan_mean: float | None = None  # mean of those distances [m]

    def to_json(self) -> dict[str, Any]:
        return {k: v for k, v in asdict(self).items() if v is not None and v != ""}


def _unpacked(reply: bytes | None) -> dict[str, Any]:
    if reply is None:
        return {}
    try:
        answer = msgpack.unpackb(reply)
    except Exception:
        return {}
    return answer if isinstance(answer, dict) else {}


def _output(answer: dict[str, Any]) -> bytes:
    return msgpack.packb({k: v for k, v in answer.items() if k not in _NOT_OUTPUT})


def _error(answer: dict[str, Any], missing: str) -> str:
    if not answer:
        return missing
    if answer.get("ok"):
        return ""
    error = answer.get("error") or {}
    return f"[{error.get('type', '?')}] {error.get('message', '')}"


def _twist(answer: dict[str, Any]) -> list[float] | None:
    twist = ((answer.get("body") or {}).get("cmd_vel") or {}).get("twist")
    return list(twist) if isinstance(twist, list) and len(twist) == 6 else None


def _poses(answer: dict[str, Any]) -> np.ndarray | None:
    path = (answer.get("body") or {}).get("path")
    if not isinstance(path, dict) or not isinstance(path.get("poses"), bytes):
        return None
    xy: np.ndarray = unpack_poses(path["poses"])[:, :2]
    return xy


def _nearest(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """For each point of ``a``, the distance to the nearest point of ``b`` (in blocks: two
    plans of thousands of poses stay within a few MB)."""
    out = np.empty(len(a))
    for start in range(0, len(a), 512):
        block = a[start : start + 512]
        out[start : start + len(block)] = np.sqrt(
            ((block[:, None, :] - b[None, :, :]) ** 2).sum(axis=2)
        ).min(axis=1)
    return out


def plan_distance(replayed: np.ndarray, recorded: np.ndarray) -> tuple[float, float] | None:
    """(max, mean) distance between two plans, both ways (a plan that stops short, or
    goes further, differs by what it leaves out); None when only one of them is empty."""
    if len(replayed) == 0 or len(recorded) == 0:
        return (0.0, 0.0) if len(replayed) == len(recorded) else None
    both = np.concatenate([_nearest(replayed, recorded), _nearest(recorded, replayed)])
    return float(both.max()), float(both.mean())


def compare(
    index: int, key: str, op: str, t: float, recorded: bytes | None, replayed: bytes
) -> CallDiff:
    was, now = _unpacked(recorded), _unpacked(replayed)
    output = _output(now)
    diff = CallDiff(
        index,
        key,
        op,
        t,
        identical=bool(was) and output == _output(was),
        output=hashlib.sha256(output).hexdigest()[:16],
        error=_error(now, "undecodable reply"),
        recorded_error=_error(was, "no recorded reply"),
        recorded_compute_ms=was["compute_ns"] / 1e6 if "compute_ns" in was else None,
        compute_ms=now["compute_ns"] / 1e6 if "compute_ns" in now else None,
    )
    old_twist, new_twist = _twist(was), _twist(now)
    if old_twist is not None and new_twist is not None:
        diff.dv = new_twist[0] - old_twist[0]
        diff.dw = new_twist[5] - old_twist[5]
    if op in _PLAN_OPS:
        old_plan, new_plan = _poses(was), _poses(now)
        if old_plan is not None and new_plan is not None:
            distance = plan_distance(new_plan, old_plan)
            if distance is not None:
                diff.plan_max, diff.plan_mean = distance
    return diff
