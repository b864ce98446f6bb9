"""The benchmark command runs and prints every table BENCHMARKS.md quotes (figures are not
asserted: performance is judged from benchmark runs, not unit tests)."""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
from importlib.util import find_spec
from pathlib import Path

import pytest

from tests.conftest import free_port

pytestmark = pytest.mark.integration

ROOT = Path(__file__).resolve().parents[1]


def bench(*args: str, timeout: float = 300) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "nav2_pyif_bench.cli", *args],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def assert_prints(result: subprocess.CompletedProcess[str], *lines: str) -> None:
    assert result.returncode == 0, result.stderr[-3000:]
    for line in (*lines, "machine:"):
        assert line in result.stdout


def test_protocol_benchmark_quick_run_prints_its_tables() -> None:
    result = bench("protocol", "--quick")
    assert_prints(
        result,
        "bare Zenoh get -> empty reply",
        "nav2_pyif cycle, worker process (default)",
        "nav2_pyif cycle, --isolation none",
        "rclpy node over topics",
        "1000-pose plan",
        "of which host handler (decode..planner)",
        "over this run's control cycle",
        "400 x 400 costmap",
        "calls/s",
    )
    # --quick: one round of 20 plans, its first (cold, after rclpy's row) shown apart; then
    # 20 calls of each paced row, with the tight loop's median beside it
    counts = {
        match["label"]: int(match["n"])
        for match in re.finditer(
            r"^ {2,}(?P<label>\S.*?)\s{2,}[\d.]+\s+[\d.]+\s+(?P<n>\d+)( +[\d.]+)?$",
            result.stdout,
            re.MULTILINE,
        )
    }
    expected = {
        "nav2_pyif set_plan": 20,
        "first of each round (after rclpy's row)": 1,
        "the rest of each round": 19,
        "rclpy node, nav_msgs/Path topic": 20,
        "nav2_pyif cycle, worker process": 20,  # the paced rows
        "nav2_pyif set_plan, 1000 poses": 20,
    }
    assert {k: counts.get(k) for k in expected} == expected
    assert "the same calls at 20 Hz" in result.stdout
    assert "set_plan at 20 Hz: target <= 1 ms:" in result.stdout


def test_first_of_each_round_takes_every_rounds_first_call() -> None:
    from nav2_pyif_bench.protocol_bench import first_of_each_round

    assert first_of_each_round([9, 1, 2, 8, 3, 4], per_round=3) == ([9, 8], [1, 2, 3, 4])
    assert first_of_each_round([7, 6], per_round=1) == ([7, 6], [])


@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])")
def test_mppi_profile_cycle_prints_each_part_of_the_hosts_cycle_warm_and_cold() -> None:
    assert_prints(
        bench("mppi-profile", "--cycle-only", "--rollouts", "200", "--repeat", "5", "--cold"),
        "whole cycle as the host runs it, 200 rollouts",
        "of which plan pruning",
        "step dispatch",
        "TwistStamped",
        "whole cycle, last cache flushed first",
        "whole cycle, one every 50 ms (20 Hz)",
    )


@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])")
def test_mppi_profile_times_the_whole_step_and_each_part_compiled_apart() -> None:
    assert_prints(
        bench("mppi-profile", "--rollouts", "200", "--repeat", "3"),
        "whole step",
        "roll-out loops (limits, poses)",
        "CostCritic (consider_footprint)",
        "XLA cost analysis",
    )


@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])")
def test_mppi_fleet_prints_cpu_per_robot_cycle_beside_cpp() -> None:
    result = bench("mppi-fleet", "--robots", "1", "3", "--rollouts", "200", "--seconds", "0.5")
    assert_prints(result, "CPU / robot-cycle", "vs C++", "largest fleet with no missed period")
    rows = [line.split() for line in result.stdout.splitlines() if re.match(r"\s+auto ", line)]
    assert [row[1] for row in rows] == ["1", "3"]


@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])")
def test_mppi_fleet_lanes_run_side_by_side_in_a_process_each(tmp_path: Path) -> None:
    figures = tmp_path / "lanes.json"
    result = bench(
        "mppi-fleet", "--robots", "2", "--rollouts", "100", "--seconds", "0.3",
        "--lanes", "1", "2", "--rounds", "2", "--json", str(figures),
    )  # fmt: skip
    assert_prints(result, "on 1 lane(s)", "on 2 lane(s)", "medians of 2 interleaved rounds")
    rows = json.loads(figures.read_text())["rows"]
    assert [(r["lanes"], r["robots"], r["rounds"]) for r in rows] == [(1, 2, 2), (2, 2, 2)]
    assert all(r["cycles"] == 2 * int(0.3 / 0.05) for r in rows)  # 0.3 s at 20 Hz, twice


def test_hop_benchmark_quick_run_prints_each_hop_tight_and_at_20_hz() -> None:
    assert_prints(
        bench("hops", "--quick"),
        "pipe to a worker process and back",
        "FIFO-channel queryable (the host's way)",
        "callback queryable",
        "queryable behind a listening peer",
        "direct by gossip",
        "(at 20 Hz)",
        "a worker's own queryable behind a listening host adds",
        "router -> host -> pipe -> worker (today's isolation)",
        "router -> worker's own queryable, host guarding",
        "behind a router, against today's isolation",
    )


def test_tls_benchmark_quick_run_prints_tcp_and_tls_side_by_side() -> None:
    assert_prints(
        bench("tls", "--quick"),
        "control cycle through a router on loopback",
        "plain TCP",
        "TLS, client certificates (mTLS)",
        "mTLS + router access control",
        "1000-pose set_plan",
    )


def test_cpp_cycle_without_its_binary_says_how_to_build_it(tmp_path: Path) -> None:
    result = bench("cpp-cycle", "--binary", str(tmp_path / "absent"), timeout=60)
    assert result.returncode == 2
    assert "no C++ bench binary" in result.stderr and "build_cpp_bench.sh" in result.stderr


@pytest.mark.cpp
@pytest.mark.nav2
@pytest.mark.timeout(900)
def built_cpp_bench(what: str) -> tuple[str, str]:
    """scripts/build_cpp_bench.sh's two binaries (the cycle bench, the fleet client); skips,
    naming ``what``, without a ROS 2 to build them against."""
    if not os.environ.get("NAV2_PYIF_NAV2_SETUP"):
        pytest.skip(
            f"{what} skipped: NAV2_PYIF_NAV2_SETUP is unset (the setup script of a ROS 2 with "
            "Nav2 and zenoh-cpp, e.g. /opt/ros/jazzy/setup.bash)"
        )
    build = subprocess.run(
        [str(ROOT / "scripts" / "build_cpp_bench.sh")], capture_output=True, text=True, timeout=600
    )
    assert build.returncode == 0, (build.stdout + build.stderr)[-3000:]
    cycle_bench, fleet_client = build.stdout.strip().splitlines()[-2:]
    return cycle_bench, fleet_client


def test_cpp_cycle_benchmark_builds_and_prints_its_table() -> None:
    binary, _ = built_cpp_bench("C++-client cycle bench")
    assert_prints(
        bench("cpp-cycle", "--quick", "--binary", binary),
        "bare Zenoh get -> empty reply",
        "nav2_pyif cycle, worker process (default)",
        "nav2_pyif cycle, --isolation none",
        "of which C++ client",
        "rclpy node via rclcpp client",
        "1000-pose plan, C++ client",
        "nav2_pyif set_plan",
        "at a real control rate (20 Hz",
        "worker cycle / bare get, median",
        "worker cycle at 20 Hz, p99 / median",
    )


def test_fleet_with_cpp_clients_without_their_binary_says_how_to_build_it(
    tmp_path: Path,
) -> None:
    result = bench(
        *("fleet", "--cpp-clients", "--fleet-client", str(tmp_path / "absent")), timeout=60
    )
    assert result.returncode == 2
    assert "no C++ fleet client" in result.stderr and "build_cpp_bench.sh" in result.stderr


@pytest.mark.cpp
@pytest.mark.nav2
@pytest.mark.timeout(900)
@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif[jax])")
def test_fleet_benchmark_with_cpp_clients_compares_both_modes() -> None:
    _, client = built_cpp_bench("the fleet's C++ clients")
    result = bench(
        *("fleet", "--cpp-clients", "--fleet-client", client, "--planner", "learned"),
        *("--compare", "--robots", "3", "--seconds", "1"),
        timeout=600,
    )
    assert_prints(
        result,
        "one worker each, C++ clients: most robots served with no missed period:",
        "batched (5 ms window), C++ clients: most robots served with no missed period:",
    )
    row = r"^  (one worker each.*?|batched .*?) +3 +(\d+) +[\d.]+ ms"
    rows = re.findall(row, result.stdout, re.M)
    assert rows == [
        ("one worker each, C++ clients", "60"),
        ("batched (5 ms window), C++ clients", "60"),
    ], result.stdout


def test_fleet_benchmark_prints_its_table_and_draws_it(tmp_path: Path) -> None:
    png = tmp_path / "fleet.png"
    result = bench("fleet", "--robots", "1", "--seconds", "1", "--plot", str(png))
    assert_prints(result, "fleet: N controllers on one host", "missed:", f"wrote {png}")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and png.stat().st_size > 10_000


@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])")
def test_fleet_benchmark_compares_per_robot_workers_with_one_batched_host(tmp_path: Path) -> None:
    png = tmp_path / "fleet.png"
    result = bench(
        *("fleet", "--planner", "learned", "--compare", "--robots", "2", "--seconds", "1"),
        *("--plot", str(png)),
    )
    assert_prints(
        result,
        "fleet: N controllers on one host (learned planner)",
        "one worker each: most robots served with no missed period:",
        "batched (5 ms window): most robots served with no missed period:",
        f"wrote {png}",
    )
    rows = re.findall(r"^  (one worker each|batched .*?) +2 +(\d+) +[\d.]+ ms", result.stdout, re.M)
    assert rows == [("one worker each", "40"), ("batched (5 ms window)", "40")], result.stdout


def test_host_benchmark_without_a_router_says_where_it_looked() -> None:
    """(The benchmark against a running host: tests/test_topologies.py::test_bench.)"""
    nowhere = f"tcp/127.0.0.1:{free_port()}"
    result = bench("host", "--key", "nav2_pyif/robot1/FollowPath", "--connect", nowhere)
    assert result.returncode == 1, result.stderr
    assert "cannot open a Zenoh session" in result.stderr and nowhere in result.stderr
    assert "Traceback" not in result.stderr


def test_checkers_benchmark_quick_run_prints_the_three_cycles_side_by_side() -> None:
    result = bench("checkers", "--quick")
    assert_prints(
        result,
        "controller only (1 query)",
        "checkers, a query each (3)",
        "checkers carried (1 query)",
        "carried cycles: 700 calls answered from carried replies, 0 sent alone",
    )


def test_path_handler_benchmark_prints_each_cycle_with_its_queries() -> None:
    """A Python path handler carried with the checks costs Lyrical's cycle no query: two a
    cycle, as with Nav2's own; on its own query, three."""
    result = bench("path-handler", "--quick")
    assert_prints(result, "Lyrical's control cycle", "queries/cycle")
    for row, queries in (
        ("Nav2's path handler (in process)", "2.00"),
        ("Python path handler, a query each", "3.00"),
        ("Python path handler, carried", "2.00"),
    ):
        assert re.search(
            rf"{re.escape(row)}\s+[\d.]+\s+[\d.]+\s+300\s+{queries}$", result.stdout, re.M
        ), result.stdout


def test_layer_benchmark_quick_run_prints_both_windows() -> None:
    assert_prints(
        bench("layer", "--quick"),
        "400 x 400 window (whole grid)",
        "60 x 60 window (3 m x 3 m)",
        "of the 200 ms update period at p99",
    )


def test_inputs_benchmark_quick_run_prints_each_message_beside_the_topic() -> None:
    assert_prints(
        bench("inputs", "--quick"),
        "(no input: the control cycle alone)",
        "LaserScan, 720 beams",
        "PointCloud2, 30 000 points",
        "Image, 640 x 480 rgb8",
        "rclpy topic + ack (ms)",
    )


def test_obstacles_benchmark_quick_run_prints_both_methods_per_costmap() -> None:
    result = bench("obstacles", "--quick", timeout=120)
    assert result.returncode == 0, result.stderr
    for row in ("cluttered: global (280 x 200)", "office: local 5 m window (100 x 100)"):
        assert row in result.stdout
    assert result.stdout.count("obstacle_points() (edges)") == 4
    assert result.stdout.count("naive + nearest to 400 poses") == 4


@pytest.mark.skipif(find_spec("jax") is None, reason="JAX not installed (nav2-pyif-planners[jax])")
def test_fleet_benchmark_serves_nav2_mppi_batched_through_a_real_host() -> None:
    result = bench(
        *("fleet", "--planner", "mppi_nav2", "--batch", "--rollouts", "200"),
        *("--robots", "2", "--seconds", "1"),
    )
    assert_prints(result, "fleet: N controllers on one host (mppi_nav2 planner)")
    # Nav2's MPPI block, as the plugin reads it: no parameter ignored
    assert "ignores parameter" not in result.stdout + result.stderr
    rows = re.findall(r"^  (batched .*?) +2 +(\d+) +[\d.]+ ms", result.stdout, re.M)
    assert rows == [("batched (5 ms window)", "40")], result.stdout


def test_mppi_traces_tells_each_drive_and_draws_one(tmp_path: Path) -> None:
    """Two stacks' drives as the side-by-side writes them: one drives 1 m at 0.5 m/s, the
    other at 0.25 m/s; the table tells them apart, --png draws them."""

    def drive(speed: float) -> dict[str, list[list[float]]]:
        times = [0.1 * i for i in range(int(1.0 / speed / 0.1) + 1)]
        return {
            "commands": [[t, speed, 0.1] for t in times],
            "poses": [[t, speed * t, 0.0] for t in times],
        }

    traces = tmp_path / "traces"
    traces.mkdir()
    (traces / "fast.json").write_text(json.dumps([drive(0.5)]))
    (traces / "slow.json").write_text(json.dumps([drive(0.25)]))
    png = tmp_path / "drive.png"
    result = bench("mppi-traces", str(traces), "--drive", "0", "--png", str(png))
    assert_prints(result, f"wrote {png} (drive 0)")
    rows = {line.split()[0]: line.split() for line in result.stdout.splitlines()[3:5]}
    assert rows["fast"][1:5] == ["0", "2.00s", "1.80s", "0.500m/s"]
    assert rows["slow"][1:5] == ["0", "4.00s", "3.60s", "0.250m/s"]
    assert png.read_bytes().startswith(b"\x89PNG")
    missing = bench("mppi-traces", str(tmp_path / "none"))
    assert missing.returncode == 2 and "NAV2_PYIF_MPPI_TRACES" in missing.stderr
    no_such_drive = bench("mppi-traces", str(traces), "--drive", "3", "--png", str(png))
    assert no_such_drive.returncode == 2 and "--drive 3" in no_such_drive.stderr
