"""The control-cycle targets, as ratios within one run so that they hold on a noisy
machine: the default (crash-isolated) cycle against the bare Zenoh get, against
``--isolation none`` and against the rclpy-node workaround, and its spread at a real rate."""

from __future__ import annotations

from nav2_pyif_bench.stats import Summary, verdict


def cycle_target_lines(c: dict[str, Summary]) -> list[str]:
    """``c``: the cpp-cycle rows by name (bare, pyif, pyif_inproc, rclcpp, pyif.paced?)."""
    bare, worker, inproc, ros = c["bare"], c["pyif"], c["pyif_inproc"], c["rclcpp"]
    over_bare = worker.median_us / bare.median_us
    over_inproc = worker.median_us / inproc.median_us
    below_ros = ros.median_us / worker.median_us
    below_ros_p99 = ros.p99_us / worker.p99_us
    lines = [
        f"  worker cycle / bare get, median: {over_bare:.2f}x (target <= 1.5x): "
        f"{verdict(over_bare, '<=', 1.5, 2)}  [--isolation none: "
        f"{inproc.median_us / bare.median_us:.2f}x]",
        f"  worker cycle / --isolation none, median: {over_inproc:.2f}x (target <= 1.10x): "
        f"{verdict(over_inproc, '<=', 1.10, 2)}",
        f"  rclpy node / worker cycle, median: {below_ros:.2f}x (target >= 1.2x): "
        f"{verdict(below_ros, '>=', 1.2, 2)}",
        f"  rclpy node / worker cycle, p99: {below_ros_p99:.2f}x (target >= 2x, machine "
        f"loaded): {verdict(below_ros_p99, '>=', 2, 2)}",
    ]
    paced = c.get("pyif.paced")
    if paced is not None:
        spread = paced.p99_us / paced.median_us
        lines.append(
            f"  worker cycle at 20 Hz, p99 / median: {spread:.2f}x (target <= 2x): "
            f"{verdict(spread, '<=', 2, 2)}"
        )
    return lines
