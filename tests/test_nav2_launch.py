"""The Nav2 launch tests (bridge_plugin/test/nav2): controller_server, planner_server and a
lifecycle manager with the nav2_pyif plugins, a real planner host and a simulated robot;
FollowPath reaches the goal, a host killed mid-goal aborts it with the matching error code
while the servers stay active, a restarted host serves the next goal; through a router, a host
whose machine vanishes is noticed within a lease and comes back by itself, with the recovery
figures of RELIABILITY.md printed; a 1000 x 1000 costmap and 10 000-pose plans cross whole;
map -> odom moving while driving; the secure fleet of DEPLOYMENT.md section 6 (TLS, client
certificates, access control) carries robot1's goal; the function-delegate YAML starts its
own hosts; and two robots' Nav2 stacks, in two ROS domains, share one batched planner host
(test_fleet_batched.py). Apart, the examples/ gallery: the OMPL example plans and the DWA
example drives to the goal (bridge_plugin/test/nav2/test_gallery.py).

Needs a ROS 2 with Nav2 (nav2_controller, nav2_planner, nav2_lifecycle_manager, nav2_msgs),
colcon and zenoh-cpp, once per distribution (humble, jazzy, lyrical) and zenoh-cpp backend:
NAV2_PYIF_NAV2_SETUP_<DISTRO>_<BACKEND> (e.g. NAV2_PYIF_NAV2_SETUP_HUMBLE_ZENOHPICO) names the
setup script of each; NAV2_PYIF_NAV2_SETUP_ZENOHC and NAV2_PYIF_NAV2_SETUP_ZENOHPICO, then
NAV2_PYIF_NAV2_SETUP, then /opt/ros/<distro>/setup.bash (whose zenoh_cpp_vendor is zenoh-c)
serve the distribution they source ($ROS_DISTRO) for the backend their zenoh-cpp has. The
rmw_zenoh variant (NAV2_PYIF_NAV2_SETUP_<DISTRO>_RMW_ZENOH, or the same fallbacks) needs
rmw_zenoh_cpp there: it runs every launch test with RMW_IMPLEMENTATION=rmw_zenoh_cpp and its
router on a free port, which test_host_recovery.py's plugins and host share. The test builds
nav2_pyif_bridge with colcon into build/nav2_ws_<distro>_<backend>, checks which Zenoh
library the plugin links, then runs the launch tests with that environment. Each
distribution and backend is skipped, saying what is missing, where its environment is absent.
"""

from __future__ import annotations

import importlib.util
import os
import shlex
import subprocess
from pathlib import Path

import pytest

from tests.conftest import free_port

pytestmark = pytest.mark.nav2

ROOT = Path(__file__).resolve().parents[1]
# Each variant: the Zenoh library the plugin must link. rmw_zenoh: Nav2's servers, the test's
# nodes and the robot on rmw_zenoh_cpp with its router, which the plugins and host share.
BACKENDS = {"zenoh-c": "libzenohc", "zenoh-pico": "libzenohpico", "rmw_zenoh": "libzenohc"}
# The maintained Nav2 distributions: one variant each (testenv/ builds them).
DISTROS = ("humble", "jazzy", "lyrical")
RMW_ZENOH_CONFIGS = "share/rmw_zenoh_cpp/config/DEFAULT_RMW_ZENOH_{}_CONFIG.json5"
# The PyPI ROS wheels name Python-only libraries as dependencies of C++ ones: link only what
# is used. Harmless on a system ROS install.
CMAKE_ARGS = [
    "-DCMAKE_BUILD_TYPE=Release",
    "-DBUILD_TESTING=OFF",
    "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed -Wl,--allow-shlib-undefined",
    "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,--as-needed",
]


def _own_variable(distro: str, backend: str) -> str:
    return f"NAV2_PYIF_NAV2_SETUP_{distro.upper()}_{backend.replace('-', '').upper()}"


def _setup_script(distro: str, backend: str) -> str | None:
    """The setup script of ``distro``'s variant: its own variable, else one that serves every
    distribution (the probe then checks that it sources ``distro``)."""
    shared = ("NAV2_PYIF_NAV2_SETUP_" + backend.replace("-", "").upper(), "NAV2_PYIF_NAV2_SETUP")
    for variable in (_own_variable(distro, backend), *shared):
        if os.environ.get(variable):
            return os.environ[variable]
    candidate = Path(f"/opt/ros/{distro}/setup.bash")
    return str(candidate) if candidate.is_file() else None


def _bash(script: str, timeout: float) -> subprocess.CompletedProcess[str]:
    env = {
        k: v
        for k, v in os.environ.items()
        if k
        not in (
            "PYTHONPATH",
            "LD_LIBRARY_PATH",
            "VIRTUAL_ENV",
            "AMENT_PREFIX_PATH",
            "_ROS_WHEELS_BOOTSTRAP_COMPLETE",
        )
    }
    env["PATH"] = os.pathsep.join(
        p for p in env.get("PATH", "").split(os.pathsep) if ".venv" not in p
    )
    return subprocess.run(
        ["bash", "-c", script], capture_output=True, text=True, timeout=timeout, env=env, cwd=ROOT
    )


def _tail(result: subprocess.CompletedProcess[str], lines: int = 80) -> str:
    return "\n".join((result.stdout + result.stderr).splitlines()[-lines:])


# What test_record_replay.py there recorded of a Nav2 run, which tests/test_record_replay.py
# replays (build/nav2_ws_<distro>_<backend>/nav2_run.mcap)
RECORDING = "nav2_run.mcap"
# The full-stack fault suite: 20 NavigateToPose runs per fault (about an hour per backend),
# run when NAV2_PYIF_FULL_STACK_RUNS says how many.
FULL_STACK = ["test_full_stack.py", "test_full_stack_native.py"]
# Nav2's MPPI beside the project's (a benchmark, BENCHMARKS.md), run when asked for.
SIDE_BY_SIDE = "test_mppi_side_by_side.py"
# N robots on one machine, a stack each, with Nav2's MPPI and then with the project's
# batched one: the fleet benchmark
FLEET_STACKS = "test_mppi_fleet_stacks.py"
# The examples/ gallery in Nav2 (OMPL's planner, the DWA controller): a case of its own, which
# needs the gallery's extras in the project's environment.
GALLERY = "test_gallery.py"
# nav2_bringup's own launch and params with the Python plugins, beside the native stack: a case
# of its own, which needs nav2_bringup's stack in the environment (testenv/build.sh builds it
# for Jazzy, and Nav2's MPPI with its mppi step).
BRINGUP = "test_bringup.py"
# What only Lyrical's Nav2 has (nav2_core::PathHandler): run in the lyrical variants only.
LYRICAL_ONLY = ["test_lyrical_path_handler.py", "test_lyrical_api.py"]
# The plugin side soaked: 100 000 control cycles and 100 lifecycle cycles of a controller_server
# under LeakSanitizer (about 30 min), run when NAV2_PYIF_SOAK_CYCLES says how many cycles.
SOAK = "test_plugin_soak.py"
BRINGUP_NEEDS = {
    "nav2_bringup": "share/nav2_bringup/launch/bringup_launch.py",
    "nav2_loopback_sim": "lib/nav2_loopback_sim/loopback_simulator",
    "robot_state_publisher": "lib/robot_state_publisher/robot_state_publisher",
    "nav2_minimal_tb3_sim": "share/nav2_minimal_tb3_sim/package.xml",
    "ros2lifecycle": "share/ros2lifecycle/package.xml",
}
# The stock params' own controller, which the native side of the comparison runs: Humble's is
# DWB, later ones' MPPI (testenv/build.sh DISTRO mppi builds it).
STOCK_CONTROLLER = {"humble": "dwb_core"}
# Humble's robot: its nav2_bringup carries the TurtleBot 3 URDF (nav2_minimal_tb3_sim is from
# Jazzy on), and the loopback simulator is Jazzy's, built on Humble (testenv/build.sh).
TB3_URDF = {"humble": ("nav2_bringup's URDF", "share/nav2_bringup/urdf/turtlebot3_waffle.urdf")}


def _bringup_needs(distro: str) -> dict[str, str]:
    package = STOCK_CONTROLLER.get(distro, "nav2_mppi_controller")
    build = "" if distro in STOCK_CONTROLLER else f" (testenv/build.sh {distro} mppi)"
    needs = {**BRINGUP_NEEDS, f"{package}{build}": f"share/{package}/package.xml"}
    if distro in TB3_URDF:
        del needs["nav2_minimal_tb3_sim"]
        name, path = TB3_URDF[distro]
        needs[name] = path
    return needs


@pytest.mark.timeout(1800)
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distro", DISTROS)
def test_nav2_launch_tests_pass_against_a_real_nav2(distro: str, backend: str) -> None:
    apart = [*FULL_STACK, SIDE_BY_SIDE, FLEET_STACKS, GALLERY, BRINGUP, SOAK]
    if distro != "lyrical":
        apart += LYRICAL_ONLY  # they would skip there, and a skip fails the run
    ignored = " ".join(f"--ignore=bridge_plugin/test/nav2/{name}" for name in apart)
    _launch_tests(distro, backend, f"{ignored} bridge_plugin/test/nav2", timeout=900)


@pytest.mark.timeout(1800)
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distro", DISTROS)
def test_gallery_ompl_planner_and_dwa_controller_in_a_real_nav2(distro: str, backend: str) -> None:
    if importlib.util.find_spec("ompl") is None:
        pytest.skip(
            "the gallery's Nav2 launch test needs OMPL in the planner host's environment: "
            "python -m pip install '.[ompl]' in the clone (scripts/bootstrap.sh installs it)"
        )
    selection = f"bridge_plugin/test/nav2/{GALLERY}"
    _launch_tests(distro, backend, selection, timeout=900, recovery_figures=False)


@pytest.mark.timeout(3600)
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distro", DISTROS)
def test_nav2_bringup_stock_launch_with_python_plugins(distro: str, backend: str) -> None:
    selection = f"-s bridge_plugin/test/nav2/{BRINGUP}"
    _launch_tests(
        distro,
        backend,
        selection,
        timeout=3000,
        recovery_figures=False,
        needs=_bringup_needs(distro),
    )


@pytest.mark.timeout(4 * 3600)
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distro", DISTROS)
def test_full_stack_navigations_survive_every_fault(distro: str, backend: str) -> None:
    runs = os.environ.get("NAV2_PYIF_FULL_STACK_RUNS")
    if not runs:
        pytest.skip(
            "the full-stack fault suite (bridge_plugin/test/nav2/test_full_stack*.py: 20 "
            "NavigateToPose runs per fault, about an hour per backend) runs only when "
            "NAV2_PYIF_FULL_STACK_RUNS gives the runs per fault"
        )
    files = " ".join(f"bridge_plugin/test/nav2/{name}" for name in FULL_STACK)
    # NAV2_PYIF_FULL_STACK_SELECT: a pytest -k expression, to run some faults again
    select = os.environ.get("NAV2_PYIF_FULL_STACK_SELECT")
    chosen = f"-k {shlex.quote(select)} " if select else ""
    # -x: a failed navigation leaves the robot where the next test does not expect it
    _launch_tests(distro, backend, f"-s -x {chosen}{files}", timeout=4 * 3600 - 600)


@pytest.mark.timeout(3 * 3600)
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distro", DISTROS)
def test_plugin_soaked_in_controller_server(distro: str, backend: str) -> None:
    cycles = os.environ.get("NAV2_PYIF_SOAK_CYCLES")
    if not cycles:
        pytest.skip(
            "the plugin soak (bridge_plugin/test/nav2/test_plugin_soak.py: 100 000 control "
            "cycles and 100 lifecycle cycles under LeakSanitizer, about 30 min) runs only when "
            "NAV2_PYIF_SOAK_CYCLES gives the cycles"
        )
    assert int(cycles) >= 100_000 or os.environ.get("NAV2_PYIF_SOAK_SHORT") == "1", (
        "NAV2_PYIF_SOAK_CYCLES below 100 000 is not the soak (NAV2_PYIF_SOAK_SHORT=1 to try it)"
    )
    selection = f"-s bridge_plugin/test/nav2/{SOAK}"
    _launch_tests(distro, backend, selection, timeout=3 * 3600 - 600, recovery_figures=False)


# The benchmarks against Nav2's own MPPI, each run only when its variable is 1: by pytest id,
# (the variable, the launch test file, what it is)
MPPI_BENCHMARKS = {
    "side_by_side": (
        "NAV2_PYIF_MPPI_SIDE_BY_SIDE",
        SIDE_BY_SIDE,
        "the MPPI side-by-side benchmark (Nav2's nav2_mppi_controller beside the project's JAX "
        "MPPI, about 20 min)",
    ),
    "fleet_stacks": (
        "NAV2_PYIF_MPPI_FLEET_STACKS",
        FLEET_STACKS,
        "the MPPI fleet benchmark (N stacks with Nav2's nav2_mppi_controller, then N with the "
        "project's batched Nav2MPPI, about 5 min for 1, 5 and 10 robots, 10 min with 20)",
    ),
}


@pytest.mark.timeout(3 * 3600)
@pytest.mark.parametrize("benchmark", MPPI_BENCHMARKS)
@pytest.mark.parametrize("backend", BACKENDS)
@pytest.mark.parametrize("distro", DISTROS)
def test_mppi_benchmark_with_nav2s_own(distro: str, backend: str, benchmark: str) -> None:
    variable, name, what = MPPI_BENCHMARKS[benchmark]
    if os.environ.get(variable) != "1":
        pytest.skip(f"{what}, bridge_plugin/test/nav2/{name}, runs only when {variable}=1")
    selection = f"-s bridge_plugin/test/nav2/{name}"
    _launch_tests(distro, backend, selection, timeout=3 * 3600 - 600, recovery_figures=False)


def _launch_tests(
    distro: str,
    backend: str,
    selection: str,
    timeout: float,
    recovery_figures: bool = True,
    needs: dict[str, str] | None = None,
) -> None:
    """Build nav2_pyif_bridge for ``distro`` and ``backend`` with colcon and run the launch
    tests ``selection`` names (pytest arguments) in that environment; skips, saying what is
    missing, where it is absent. ``recovery_figures``: the selection holds
    test_host_recovery.py, which must have written its figures (others print theirs when
    they wrote some). ``needs``: what else the selection needs, by name, each a path under
    one of the environment's prefixes."""
    setup = _setup_script(distro, backend)
    variable = _own_variable(distro, backend)
    if setup is None:
        pytest.skip(
            f"Nav2 launch tests on {distro} {backend} skipped: no ROS 2 {distro} with Nav2 here "
            f"(set {variable} to a setup script of one: testenv/build.sh {distro} writes them)"
        )
    workspace = ROOT / "build" / f"nav2_ws_{distro}_{backend}"
    source = f"set -e; source {shlex.quote(setup)} >/dev/null"
    required = {
        exe: f"lib/{exe}"
        for exe in (
            "nav2_controller/controller_server",
            "nav2_planner/planner_server",
            "nav2_lifecycle_manager/lifecycle_manager",
        )
    }
    required.update(needs or {})
    look_for = "".join(
        f"found=; for p in ${{AMENT_PREFIX_PATH//:/ }}; do [ -e $p/{path} ] && found=1; done; "
        f'[ -n "$found" ] || echo missing: {shlex.quote(name)}; '
        for name, path in required.items()
    )
    probe = _bash(
        f"{source}; echo distro: ${{ROS_DISTRO:-unset}}; "
        "command -v colcon >/dev/null || echo missing: colcon; "
        "python -c 'import nav2_msgs.action, rclpy' 2>/dev/null || echo missing: nav2_msgs; "
        + look_for,
        timeout=60,
    )
    lines = probe.stdout.splitlines()
    sourced = next((line[8:] for line in lines if line.startswith("distro: ")), "")
    if probe.returncode == 0 and sourced != distro:
        # A setup script named for this distribution that sources another is a mistake.
        assert not os.environ.get(variable), f"{variable}={setup} sources ROS 2 {sourced}"
        pytest.skip(f"Nav2 launch tests on {distro} skipped: {setup} sources ROS 2 {sourced}")
    missing = [line for line in lines if line.startswith("missing:")]
    if probe.returncode != 0 or missing:
        pytest.skip(
            f"Nav2 launch tests skipped: {setup} lacks {', '.join(missing) or _tail(probe, 5)}"
        )

    (workspace / "src").mkdir(parents=True, exist_ok=True)
    link = workspace / "src" / "nav2_pyif_bridge"
    if not link.is_symlink():
        link.symlink_to(ROOT / "bridge_plugin")
    build = _bash(
        f"{source}; cd {shlex.quote(str(workspace))}; colcon build --merge-install "
        f"--packages-select nav2_pyif_bridge --cmake-args {' '.join(map(shlex.quote, CMAKE_ARGS))}",
        timeout=1200,
    )
    assert build.returncode == 0, "colcon build of nav2_pyif_bridge failed:\n" + _tail(build)
    plugin = workspace / "install" / "lib" / "libnav2_pyif_bridge.so"
    linked = _bash(f"{source}; ldd {shlex.quote(str(plugin))}", timeout=60).stdout
    found = [name for name, lib in BACKENDS.items() if lib in linked]
    if backend not in found:
        pytest.skip(f"Nav2 launch tests on {backend} skipped: {setup} gives {found or linked}")
    router = _rmw_zenoh_router(source, workspace) if backend == "rmw_zenoh" else ""

    wrapper = workspace / "in-project-env.sh"  # the project's own environment for its tools
    wrapper.write_text(
        "#!/bin/bash\nunset PYTHONPATH; export LD_LIBRARY_PATH=\n"
        f"source {shlex.quote(str(ROOT / '.venv' / 'nav2_pyif_env.sh'))}\n"
        'exec "$@"\n'
    )
    wrapper.chmod(0o755)
    host = workspace / "planner-host.sh"  # one executable: the delegate YAML's planner_host_command
    host.write_text(f'#!/bin/bash\nexec {shlex.quote(str(wrapper))} planner-host "$@"\n')
    host.chmod(0o755)
    figures = workspace / "recovery_figures.json"
    figures.unlink(missing_ok=True)
    (workspace / RECORDING).unlink(missing_ok=True)  # a new one, or none: not the last run's
    # The Nav2 processes' logs, kept here until the next run: pytest's default base keeps
    # only its last three runs, and other runs on the machine would remove these.
    logs = workspace / "logs"
    zenoh_cpp = "zenoh-c" if backend == "rmw_zenoh" else backend
    run = _bash(
        f"{source}; source {shlex.quote(str(workspace / 'install' / 'local_setup.bash'))}; "
        f"{router}NAV2_PYIF_ZENOH_BACKEND={zenoh_cpp} NAV2_PYIF_RUN={shlex.quote(str(wrapper))} "
        f"NAV2_PYIF_PLANNER_HOST={shlex.quote(str(host))} "
        f"NAV2_PYIF_FIGURES={shlex.quote(str(figures))} "
        f"NAV2_PYIF_RECORDING_OUT={shlex.quote(str(workspace / RECORDING))} python -m pytest "
        f"-p no:cacheprovider -q -rs --basetemp={shlex.quote(str(logs))} {selection}",
        timeout=timeout,
    )
    assert run.returncode == 0, f"Nav2 launch tests failed (logs in {logs}):\n" + _tail(run, 120)
    assert " passed" in run.stdout and "skipped" not in run.stdout, _tail(run)
    # RELIABILITY.md's recovery figures (test_host_recovery.py), the full stack's, the MPPI
    # side-by-side's: whatever the selection recorded
    if recovery_figures or figures.exists():
        print(f"{backend} figures: {figures.read_text()}")


def _rmw_zenoh_router(source: str, workspace: Path) -> str:
    """Shell lines that start rmw_zenoh's router on a free port and export where it is
    (rmw_zenoh_router_lines); skips, saying why, where the setup has no rmw_zenoh_cpp."""
    found = _bash(
        f"{source}; for p in ${{AMENT_PREFIX_PATH//:/ }}; do "
        "[ -x $p/lib/rmw_zenoh_cpp/rmw_zenohd ] && echo $p && break; done; true",
        timeout=60,
    ).stdout.split()
    if not found:
        pytest.skip(
            "Nav2 launch tests on rmw_zenoh skipped: the setup script has no rmw_zenoh_cpp "
            "(lib/rmw_zenoh_cpp/rmw_zenohd)"
        )
    return rmw_zenoh_router_lines(Path(found[0]), workspace, free_port())


def rmw_zenoh_router_lines(prefix: Path, workspace: Path, port: int) -> str:
    """Shell lines that run ROS on rmw_zenoh_cpp (RMW_IMPLEMENTATION) with its router
    rmw_zenohd of ``prefix`` on ``port`` (rmw_zenoh's own default router and session configs,
    only the port replaced, written into ``workspace``), export the router's endpoint for the
    plugins and the host to share (NAV2_PYIF_SHARED_ROUTER), and stop the router by its PID
    when the shell exits. testenv/run-in-root.sh takes them too (``python -m
    tests.test_nav2_launch --rmw-zenoh-router WORKSPACE``)."""
    lines = ["export RMW_IMPLEMENTATION=rmw_zenoh_cpp; "]
    for kind in ("ROUTER", "SESSION"):
        default = (prefix / RMW_ZENOH_CONFIGS.format(kind)).read_text()
        assert ":7447" in default, f"rmw_zenoh's {kind} config no longer names port 7447"
        config = workspace / f"rmw_zenoh_{kind.lower()}.json5"
        config.write_text(default.replace(":7447", f":{port}"))
        lines.append(f"export ZENOH_{kind}_CONFIG_URI={shlex.quote(str(config))}; ")
    log = shlex.quote(str(workspace / "rmw_zenohd.log"))
    return (
        "".join(lines)
        + f"{shlex.quote(str(prefix / 'lib/rmw_zenoh_cpp/rmw_zenohd'))} >{log} 2>&1 & "
        + "NAV2_PYIF_RMW_ZENOHD=$!; trap 'kill $NAV2_PYIF_RMW_ZENOHD 2>/dev/null' EXIT; "
        + f"export NAV2_PYIF_SHARED_ROUTER=tcp/127.0.0.1:{port}; "
    )


if __name__ == "__main__":
    # python -m tests.test_nav2_launch --rmw-zenoh-router WORKSPACE, in a ROS environment
    # with rmw_zenoh_cpp: print rmw_zenoh_router_lines for it (testenv/run-in-root.sh).
    import sys

    if len(sys.argv) != 3 or sys.argv[1] != "--rmw-zenoh-router":
        sys.exit("usage: python -m tests.test_nav2_launch --rmw-zenoh-router WORKSPACE")
    ament = [Path(p) for p in os.environ.get("AMENT_PREFIX_PATH", "").split(os.pathsep) if p]
    with_router = [p for p in ament if (p / "lib/rmw_zenoh_cpp/rmw_zenohd").is_file()]
    if not with_router:
        sys.exit("no lib/rmw_zenoh_cpp/rmw_zenohd under $AMENT_PREFIX_PATH")
    print(rmw_zenoh_router_lines(with_router[0], Path(sys.argv[2]), free_port()))
