"""Nav2MPPI (nav2_pyif_planners.mppi_nav2): each critic scores hand-made rollouts as Nav2's
does, a Nav2 FollowPath MPPI block is accepted as parameters, the Savitzky-Golay smoothing,
the acceleration limits, reversing and the Omni model."""

from __future__ import annotations

import logging
import math
from typing import Any

import numpy as np
import pytest
import yaml
from geometry_msgs.msg import Twist
from nav2_pyif import Costmap, GoalTolerances, Inflation, InvalidController, NoValidControl, Plan
from nav2_pyif.runner.run import pose_msg

from tests.test_planners import attach

pytestmark = pytest.mark.unit

jax = pytest.importorskip("jax", reason="JAX is not installed (nav2-pyif-planners[jax])")
jnp = jax.numpy

from nav2_pyif_planners.mppi_nav2 import (  # noqa: E402
    NAV2_JAZZY_FILE,
    Nav2MPPI,
    critics,
    flatten,
)
from nav2_pyif_planners.mppi_nav2.costs import Grid  # noqa: E402
from nav2_pyif_planners.mppi_nav2.models import Controls, constrain_sequence  # noqa: E402
from nav2_pyif_planners.mppi_nav2.params import CRITIC_PARAMS, Critic, read_settings  # noqa: E402
from nav2_pyif_planners.mppi_nav2.smoothing import COEFFICIENTS, smooth  # noqa: E402

RECTANGLE = [[0.2, 0.15], [0.2, -0.15], [-0.2, -0.15], [-0.2, 0.15]]

# Nav2 Jazzy's nav2_bringup FollowPath MPPI block (the package's nav2_jazzy.yaml)
NAV2_JAZZY_FOLLOW_PATH = NAV2_JAZZY_FILE.read_text()

LOG = logging.getLogger("test")


def critic(name: str, **values: Any) -> Critic:
    """A critic with Nav2's defaults but ``values``."""
    merged = {**CRITIC_PARAMS[name], **values}
    return Critic(name, True, tuple(merged.items()))


def settings(**params: Any) -> Any:
    from nav2_pyif import Parameters

    return read_settings(Parameters(params), 20.0, LOG)


def grid(data: np.ndarray, resolution: float = 0.05, possible: float = -1.0) -> Grid:
    """The costmap at the origin; the robot: (possible collision cost, inscribed 0.15 m,
    inflation radius 0.55 m, cost scaling 3)."""
    outline = Costmap(data, resolution, footprint=RECTANGLE).footprint_outline(resolution)
    return Grid(
        data=jnp.asarray(data),
        meta=jnp.asarray([0.0, 0.0, resolution], jnp.float32),
        outline=jnp.asarray(outline, jnp.float32),
        robot=jnp.asarray([possible, 0.15, 0.55, 3.0], jnp.float32),
    )


FREE = np.zeros((80, 120), np.uint8)


def data(
    x: Any,
    y: Any,
    yaw: Any = None,
    vx: Any = None,
    wz: Any = None,
    pose: tuple[float, float, float] = (0.5, 2.0, 0.0),
    goal: tuple[float, float, float] = (5.0, 2.0, 0.0),
    path: np.ndarray | None = None,
    costs: np.ndarray = FREE,
    goal_tolerance: float = -1.0,
    **grid_args: Any,
) -> critics.CriticData:
    """Rollouts (batch, T) by hand; velocities default to zero, the plan to a straight
    line along y = 2 from the pose to the goal."""
    x, y = np.atleast_2d(np.asarray(x, np.float32)), np.atleast_2d(np.asarray(y, np.float32))
    zeros = np.zeros_like(x)
    yaw = zeros if yaw is None else np.broadcast_to(np.asarray(yaw, np.float32), x.shape)
    vx = zeros if vx is None else np.broadcast_to(np.asarray(vx, np.float32), x.shape)
    wz = zeros if wz is None else np.broadcast_to(np.asarray(wz, np.float32), x.shape)
    if path is None:
        px = np.arange(pose[0], goal[0] + 1e-6, 0.05)
        path = np.column_stack([px, np.full_like(px, 2.0), np.zeros_like(px)])
    g = grid(costs, **grid_args)
    padded = jnp.asarray(np.vstack([path, np.repeat(path[-1:], 128 - len(path), 0)]), jnp.float32)
    count = jnp.int32(len(path))
    from nav2_pyif_planners.mppi_nav2.optimizer import furthest_reached, path_valid

    s = settings(track_unknown_space=False)
    # the step's layout is time-major: (T, batch)
    xj, yj, yawj = jnp.asarray(x.T), jnp.asarray(y.T), jnp.asarray(yaw.T)
    return critics.CriticData(
        x=xj, y=yj, yaw=yawj, cos=jnp.cos(yawj), sin=jnp.sin(yawj),
        v=Controls(jnp.asarray(vx.T), jnp.zeros_like(xj), jnp.asarray(wz.T)),
        pose=jnp.asarray(pose, jnp.float32), goal=jnp.asarray(goal, jnp.float32),
        path=padded, count=count, valid=path_valid(g, padded, count, s),
        furthest=furthest_reached(xj[-1], yj[-1], padded, count), grid=g,
        goal_tolerance=jnp.float32(goal_tolerance),
    )  # fmt: skip


def straight(v: float, steps: int = 56, y: float = 2.0, x0: float = 0.5) -> tuple[Any, Any]:
    """A rollout moving along y at ``v`` [m/s] from x0, one pose per 0.05 s step."""
    x = x0 + v * 0.05 * np.arange(1, steps + 1)
    return x, np.full(steps, y)


# --- the critics, one by one -------------------------------------------------------------


def test_prefer_forward_penalises_reversing_until_near_the_goal() -> None:
    s = settings()
    fx, fy = straight(0.3)
    bx, by = straight(-0.3)
    far = data([fx, bx], [fy, by], vx=np.array([[0.3], [-0.3]]))
    cost = np.asarray(critics.prefer_forward(far, critic("PreferForwardCritic"), s))
    assert cost[0] == 0.0
    assert cost[1] == pytest.approx(5.0 * 0.3 * 0.05 * 56, rel=1e-5)
    near = data([fx, bx], [fy, by], vx=np.array([[0.3], [-0.3]]), goal=(0.9, 2.0, 0.0))
    cost = np.asarray(critics.prefer_forward(near, critic("PreferForwardCritic"), s))
    assert cost.tolist() == [0, 0]


def test_constraint_penalises_speeds_over_the_limits_only() -> None:
    # Nav2 1.3 reads vy_max even for DiffDrive: the band is +-hypot(vx, vy_max)
    s = settings(vy_max=0.0)
    x, y = straight(0.5)
    d = data([x, x, x], [y, y, y], vx=np.array([[0.4], [0.6], [-0.5]]))
    cost = np.asarray(critics.constraint(d, critic("ConstraintCritic"), s))
    assert cost[0] == 0.0
    assert cost[1] == pytest.approx(4.0 * 0.1 * 0.05 * 56, rel=1e-4)
    assert cost[2] == pytest.approx(4.0 * 0.15 * 0.05 * 56, rel=1e-4)
    with_vy = np.asarray(critics.constraint(d, critic("ConstraintCritic"), settings()))
    assert with_vy[1] == 0.0  # 0.6 < hypot(0.5, 0.5): Nav2's defaults let it pass


def test_goal_angle_counts_only_within_threshold_to_consider() -> None:
    s = settings()
    x, y = straight(0.0)
    c = critic("GoalAngleCritic")
    near = data([x, x], [y, y], yaw=np.array([[0.0], [1.0]]), pose=(4.6, 2.0, 0.0))
    cost = np.asarray(critics.goal_angle(near, c, s))  # the plan's last heading is 0
    assert cost[0] == 0.0 and cost[1] == pytest.approx(3.0, rel=1e-5)
    far = data([x, x], [y, y], yaw=np.array([[0.0], [1.0]]), pose=(4.4, 2.0, 0.0))
    assert np.asarray(critics.goal_angle(far, c, s)).tolist() == [0.0, 0.0]


def test_goal_critic_pulls_to_the_goal_within_its_threshold() -> None:
    s = settings()
    c = critic("GoalCritic")
    near = data(np.full((2, 56), 4.0), np.array([[2.0], [3.0]]) * np.ones((2, 56)), pose=(4, 2, 0))
    cost = np.asarray(critics.goal(near, c, s))
    assert cost[0] == pytest.approx(5.0) and cost[1] == pytest.approx(5.0 * math.sqrt(2))
    far = data(np.full((2, 56), 4.0), np.full((2, 56), 2.0), pose=(3.0, 2.0, 0.0))
    assert np.asarray(critics.goal(far, c, s)).tolist() == [0.0, 0.0]


def wall(x_cell: int = 40) -> np.ndarray:
    costs: np.ndarray = FREE.copy()
    costs[:, x_cell:] = Costmap.LETHAL
    return costs


def test_obstacles_critic_gives_collisions_its_collision_cost() -> None:
    s = settings()
    c = critic("ObstaclesCritic")
    into, y = straight(0.5)  # reaches x = 1.9 m: through the wall at 2.0 m? no: stops short
    through, _ = straight(1.0)  # reaches 3.3 m
    d = data([into, through], [y, y], costs=wall())
    cost, all_collide = critics.obstacles(d, c, s)
    cost = np.asarray(cost)
    assert cost[1] >= 20.0 * 100000.0
    assert cost[0] < 1000.0
    assert not bool(all_collide)
    _, both = critics.obstacles(data([through, through], [y, y], costs=wall()), c, s)
    assert bool(both)  # Nav2's fail_flag: the optimizer resets and retries


def test_cost_critic_collisions_and_critical_cost() -> None:
    s = settings()
    c = critic("CostCritic")
    short, y = straight(0.5)
    long, _ = straight(1.0)
    costs = wall()
    costs[:, 36:40] = 200  # inflated, below near_collision_cost
    cost, all_collide = critics.cost_critic(data([short, long], [y, y], costs=costs), c, s)
    cost = np.asarray(cost)
    assert cost[1] == pytest.approx(1000000.0 * 3.81 / 254.0 / 28, rel=1e-5)
    assert 0.0 < cost[0] < cost[1] and not bool(all_collide)


def test_cost_critic_checks_the_footprint_where_it_may_touch() -> None:
    s = settings()
    costs = FREE.copy()
    costs[30:50, 18:25] = 100  # around the centre: above the possible-collision cost
    costs[40, 25] = Costmap.LETHAL  # under the footprint's front edge (x 1.275 m)
    x, y = np.full(56, 1.075), np.full(56, 2.025)
    for consider, collides in ((False, False), (True, True)):
        c = critic("CostCritic", consider_footprint=consider)
        cost, _ = critics.cost_critic(data([x], [y], costs=costs, possible=50.0), c, s)
        # collision_cost 1e6 * 3.81 / 254 / 28 poses = 536, else one pose's 100 * 3.81 / 254 / 28
        assert (float(cost[0]) > 500.0) == collides


def test_path_follow_and_align_prefer_rollouts_on_the_plan() -> None:
    s = settings()
    on, y = straight(0.5)
    off = (on, np.full(56, 2.4))
    d = data([on, off[0]], [y, off[1]])
    follow = np.asarray(critics.path_follow(d, critic("PathFollowCritic"), s))
    align = np.asarray(critics.path_align(d, critic("PathAlignCritic"), s))
    assert follow[0] < follow[1]
    # Nav2 matches plan points by distance travelled from each rollout's first pose, 2.5 cm
    # ahead of the robot here: 10 x 0.025 on the plan, 10 x hypot(0.4, 0.025) beside it
    assert align[0] == pytest.approx(0.25, abs=0.01) and align[1] == pytest.approx(4.0, abs=0.05)
    near = data([on, off[0]], [y, off[1]], pose=(4.7, 2.0, 0.0))
    assert np.asarray(critics.path_align(near, critic("PathAlignCritic"), s)).tolist() == [0, 0]


def test_path_angle_only_when_the_robot_faces_away_from_the_plan() -> None:
    s = settings()
    x, y = straight(0.0)
    yaw = np.array([[0.0], [math.pi / 2]])
    facing = data([x, x], [y, y], yaw=yaw, pose=(0.5, 2.0, 0.0))
    assert np.asarray(critics.path_angle(facing, critic("PathAngleCritic"), s)).tolist() == [0, 0]
    away = data([x, x], [y, y], yaw=yaw, pose=(0.5, 2.0, math.pi / 2))
    cost = np.asarray(critics.path_angle(away, critic("PathAngleCritic"), s))
    assert cost[0] == pytest.approx(0.0, abs=1e-5) and cost[1] == pytest.approx(2.2 * math.pi / 2)


def test_twirling_penalises_turning_outside_the_goal_tolerance() -> None:
    s = settings()
    x, y = straight(0.3)
    d = data([x, x], [y, y], wz=np.array([[0.0], [1.0]]))
    assert np.asarray(critics.twirling(d, critic("TwirlingCritic"), s)).tolist() == [0.0, 10.0]
    turns = np.array([[0.0], [1.0]])
    at_goal = data([x, x], [y, y], wz=turns, goal=(0.6, 2, 0), goal_tolerance=0.25)
    assert np.asarray(critics.twirling(at_goal, critic("TwirlingCritic"), s)).tolist() == [0, 0]


# --- smoothing and limits ----------------------------------------------------------------


def nav2_savitzky_golay(sequence: np.ndarray, history: np.ndarray) -> np.ndarray:
    """Nav2's loop, point by point: a window sliding from the history into the sequence,
    the last point repeated past the end; the last control left alone."""
    out: np.ndarray = sequence.copy()
    n = len(sequence) - 1
    window = [*history, *sequence[:5]]
    for i in range(n):
        out[i] = float(np.dot(window, COEFFICIENTS))
        window = [*window[1:], sequence[i + 5] if i + 5 < n else sequence[n]]
    return out


def test_savitzky_golay_as_nav2_smooths() -> None:
    rng = np.random.default_rng(1)
    sequence = rng.normal(size=56).astype(np.float32)
    history = rng.normal(size=4).astype(np.float32)
    got = np.asarray(smooth(jnp.asarray(sequence), jnp.asarray(history)))
    np.testing.assert_allclose(got, nav2_savitzky_golay(sequence, history), atol=1e-5)
    # a quadratic filter keeps a quadratic where its window sees only the quadratic
    t = np.arange(-4, 56, dtype=np.float32) * 0.05
    quad = 0.3 + t - 2 * t**2
    kept = np.asarray(smooth(jnp.asarray(quad[4:]), jnp.asarray(quad[:4])))
    np.testing.assert_allclose(kept[:51], quad[4:55], atol=1e-5)
    short = jnp.asarray(sequence[:20])
    assert np.array_equal(np.asarray(smooth(short, jnp.asarray(history))), sequence[:20])


def test_sequence_constraints_keep_speed_and_acceleration_limits() -> None:
    s = settings()
    rng = np.random.default_rng(2)
    u = Controls(*(jnp.asarray(rng.normal(0, 1.0, 56), jnp.float32) for _ in range(3)))
    limits = jnp.asarray([0.5, -0.35, 0.5, 1.9], jnp.float32)
    out = constrain_sequence(u, s, limits)
    vx, wz = np.asarray(out.vx), np.asarray(out.wz)
    assert vx.max() <= 0.5 + 1e-6 and vx.min() >= -0.35 - 1e-6 and np.abs(wz).max() <= 1.9 + 1e-6
    assert np.abs(np.diff(vx)).max() <= 3.0 * 0.05 + 1e-5
    assert np.abs(np.diff(wz)).max() <= 3.5 * 0.05 + 1e-5


# --- the controller ----------------------------------------------------------------------


def free_costmap() -> Costmap:
    return Costmap(FREE, 0.05, footprint=RECTANGLE, inflation=Inflation(0.55, 3.0))


def controller(costmap: Costmap | None = None, **params: Any) -> Nav2MPPI:
    c: Nav2MPPI = attach(Nav2MPPI(), costmap or free_costmap(), **{"batch_size": 500, **params})
    return c


def drive(
    c: Nav2MPPI,
    pose: tuple[float, float, float],
    cycles: int,
    checker: GoalTolerances | None = None,
) -> list[tuple[float, ...]]:
    """Cycles of a perfect robot at 20 Hz -> (x, y, yaw, vx, wz, vy) after each."""
    x, y, yaw = pose
    v = Twist()
    out: list[tuple[float, ...]] = []
    for _ in range(cycles):
        cmd = c.compute_velocity_commands(pose_msg(x, y, yaw), v, checker)
        v = cmd.twist
        yaw += v.angular.z * 0.05
        x += (v.linear.x * math.cos(yaw) - v.linear.y * math.sin(yaw)) * 0.05
        y += (v.linear.x * math.sin(yaw) + v.linear.y * math.cos(yaw)) * 0.05
        out.append((x, y, yaw, v.linear.x, v.angular.z, v.linear.y))
    return out


def line(x0: float, x1: float, y: float = 2.0, yaw: float = 0.0) -> Plan:
    x = np.linspace(x0, x1, max(2, int(abs(x1 - x0) / 0.05) + 1))
    return Plan(np.column_stack([x, np.full_like(x, y), np.full_like(x, yaw)]), "map")


def test_commands_accelerate_within_ax_max_and_reach_vx_max() -> None:
    c = controller(ax_max=1.0, ax_min=-1.0)
    c.set_plan(line(0.5, 5.5))
    run = drive(c, (0.5, 2.0, 0.0), 60)
    vx = np.array([r[3] for r in run])
    # the smoothed sequence may overshoot its constrained one a little (Nav2's too)
    assert np.abs(np.diff(vx)).max() <= 1.0 * 0.05 * 1.3
    assert vx.max() > 0.35
    assert abs(run[-1][1] - 2.0) < 0.1


def test_each_reset_takes_new_noise_as_nav2_draws_it_and_the_bank_comes_round() -> None:
    """Nav2 draws new noise on every reset (a goal ended, a fallback); regenerate_noises off,
    the cycle's noise stays the same between resets."""
    c = controller(noise_sets=3)
    c.set_plan(line(0.5, 5.5))

    def first_cycle() -> tuple[float, float]:
        c.reset()
        cmd = c.compute_velocity_commands(pose_msg(0.5, 2.0, 0.0), Twist(), None)
        return cmd.twist.linear.x, cmd.twist.angular.z

    firsts = [first_cycle() for _ in range(4)]
    assert len(set(firsts[:3])) == 3  # three sets, three different first commands
    assert firsts[3] == firsts[0]  # the fourth reset is the first set again
    inputs = c.cycle_inputs(np.array([0.5, 2.0, 0.0]), Twist(), None)
    c.pick_noise(inputs)
    assert tuple(inputs[5, :2]) == (1.0, 0.0)  # between resets: the same set, unrolled


def test_speed_limits_scale_the_commands() -> None:
    c = controller()
    c.set_plan(line(0.5, 5.5))
    c.set_speed_limit(50.0, True)
    vx = [r[3] for r in drive(c, (0.5, 2.0, 0.0), 50)]
    assert max(vx) <= 0.25 * 1.05 and max(vx) > 0.2


def test_reverses_to_a_goal_just_behind_and_never_with_vx_min_zero() -> None:
    plan = line(1.0, 0.7)  # behind the robot at x = 1.0 facing +x, plan heading +x
    c = controller(vx_min=-0.35)
    c.set_plan(plan)
    reversing = drive(c, (1.0, 2.0, 0.0), 30)
    assert min(r[3] for r in reversing) < -0.05
    assert reversing[-1][0] < 0.9
    forward_only = controller(vx_min=0.0)
    forward_only.set_plan(plan)
    assert min(r[3] for r in drive(forward_only, (1.0, 2.0, 0.0), 30)) >= -1e-6


def test_omni_moves_sideways() -> None:
    c = controller(motion_model="Omni")
    y = np.linspace(2.0, 3.5, 31)
    c.set_plan(Plan(np.column_stack([np.full_like(y, 1.0), y, np.zeros_like(y)]), "map"))
    run = drive(c, (1.0, 2.0, 0.0), 40)
    assert run[-1][1] > 2.6
    assert max(r[5] for r in run[:10]) > 0.2  # sideways from the start, before any turn
    diff = controller()
    diff.set_plan(c.plan)  # type: ignore[arg-type]
    assert max(abs(r[5]) for r in drive(diff, (1.0, 2.0, 0.0), 10)) == 0.0


def test_every_rollout_colliding_is_no_valid_control() -> None:
    costs = FREE.copy()
    costs[30:50, 5:40] = Costmap.LETHAL
    c = controller(Costmap(costs, 0.05, footprint=RECTANGLE, inflation=Inflation(0.55, 3.0)))
    c.set_plan(line(0.5, 3.0))
    with pytest.raises(NoValidControl, match="Optimizer fail to compute path"):
        c.compute_velocity_commands(pose_msg(1.0, 2.0, 0.0), Twist(), None)


# --- parameters --------------------------------------------------------------------------


def test_nav2_jazzy_follow_path_block_is_accepted_as_is(caplog: pytest.LogCaptureFixture) -> None:
    block = flatten(yaml.safe_load(NAV2_JAZZY_FOLLOW_PATH))
    assert block["PathAlignCritic.cost_weight"] == 14.0
    with caplog.at_level(logging.WARNING):
        c = attach(Nav2MPPI(), free_costmap(), **block)
    s = c.settings
    assert (s.batch_size, s.time_steps, s.vx_min, s.motion_model) == (2000, 56, -0.35, "DiffDrive")
    assert [k.name for k in s.critics if k.enabled] == [
        "ConstraintCritic", "CostCritic", "GoalCritic", "GoalAngleCritic", "PathAlignCritic",
        "PathFollowCritic", "PathAngleCritic", "PreferForwardCritic",
    ]  # fmt: skip
    assert s.critic("PathAngleCritic")["max_angle_to_furthest"] == 1.0  # type: ignore[index]
    assert s.critic("CostCritic")["near_goal_distance"] == 1.0  # type: ignore[index]
    # only the key naming Nav2's own plugin class is not this controller's
    assert set(c.params.undeclared()) == {"plugin"}
    assert "visualize=True is not honoured" in caplog.text
    c.set_plan(line(0.5, 5.5))
    assert c.compute_velocity_commands(pose_msg(0.5, 2.0, 0.0), Twist(), None).twist.linear.x >= 0


def test_refuses_what_nav2_refuses() -> None:
    with pytest.raises(InvalidController, match="Model Tank is not valid"):
        controller(motion_model="Tank")
    with pytest.raises(InvalidController, match="no robot footprint"):
        attach(
            Nav2MPPI(),
            Costmap(FREE, 0.05, robot_radius=0.2),
            **{"CostCritic.consider_footprint": True},
        )


def test_its_own_defaults_agree_with_the_costmaps_robot(caplog: pytest.LogCaptureFixture) -> None:
    """consider_footprint defaults to what the costmap's robot is (a footprint polygon, or a
    robot_radius), so the defaults draw no "Inconsistent configuration" warning (Nav2's own
    default, false, suits only a round robot)."""
    from nav2_pyif import Parameters

    for footprint in (True, False):
        s = read_settings(Parameters({}), 20.0, LOG, footprint=footprint)
        cost_critic = s.critic("CostCritic")
        assert cost_critic is not None and cost_critic["consider_footprint"] is footprint
    explicit = read_settings(
        Parameters({"CostCritic.consider_footprint": False}), 20.0, LOG, footprint=True
    )
    assert explicit.critic("CostCritic")["consider_footprint"] is False  # type: ignore[index]
    with caplog.at_level(logging.WARNING):
        controller()  # a footprint polygon's costmap
    assert "Inconsistent configuration" not in caplog.text


def test_takes_lyricals_motion_model_plugins() -> None:
    """Lyrical's nav2_bringup names the model by a namespace with a plugin class; Jazzy's
    names stay valid; a class Nav2 has not, or a namespace without a plugin, is refused."""
    for model in ("DiffDrive", "Omni", "Ackermann"):
        plugin = {"motion_model": "m", "m.plugin": f"mppi::{model}MotionModel"}
        assert settings(**plugin).motion_model == model
    assert settings(motion_model="Omni").motion_model == "Omni"
    lyrical: dict[str, Any] = {"diff_drive.plugin": "mppi::DiffDriveMotionModel"}
    c = controller(None, motion_model="diff_drive", **lyrical)
    assert c.settings.motion_model == "DiffDrive"
    assert "diff_drive.plugin" not in c.params.undeclared()  # read: no "ignored" warning
    with pytest.raises(InvalidController, match="Failed to load motion model plugin 'tank'"):
        controller(None, motion_model="tank", **{"tank.plugin": "mppi::TankMotionModel"})
    with pytest.raises(InvalidController, match="Model diff_drive is not valid"):
        controller(motion_model="diff_drive")


def test_ackermann_turns_no_tighter_than_min_turning_r() -> None:
    s = settings(motion_model="Ackermann", **{"AckermannConstraints.min_turning_r": 0.4})
    limits = jnp.asarray([0.5, -0.35, 0.5, 1.9], jnp.float32)
    zeros = jnp.zeros(56, jnp.float32)
    for turn, kept in ((1.0, 0.5), (0.3, 0.3)):  # 0.2 m/s at 1 rad/s: a 0.2 m radius
        u = Controls(jnp.full(56, 0.2, jnp.float32), zeros, jnp.full(56, turn, jnp.float32))
        wz = np.asarray(constrain_sequence(u, s, limits).wz)
        np.testing.assert_allclose(wz, kept, atol=1e-6)
    c = critic("ConstraintCritic")
    x, y = straight(0.2)
    tight = data([x, x], [y, y], vx=np.array([[0.2], [0.2]]), wz=np.array([[1.0], [0.3]]))
    cost = np.asarray(critics.constraint(tight, c, s))
    assert cost[0] == pytest.approx(4.0 * 0.2 * 0.05 * 56, rel=1e-4) and cost[1] == 0.0


# --- the step's own arithmetic -----------------------------------------------------------


def test_cos_sin_by_products_matches_libm_at_any_heading() -> None:
    from nav2_pyif_planners.mppi_nav2.models import cos_sin

    angles = np.concatenate(
        [np.linspace(-40.0, 40.0, 20001), [0.0, math.pi, -math.pi, 2 * math.pi, 1e-8]]
    ).astype(np.float32)
    c, s = (np.asarray(a) for a in jax.jit(cos_sin)(jnp.asarray(angles)))
    assert np.abs(c - np.cos(angles.astype(np.float64))).max() < 2e-6
    assert np.abs(s - np.sin(angles.astype(np.float64))).max() < 2e-6
    assert np.abs(c * c + s * s - 1.0).max() < 2e-6


def test_counting_finds_what_searchsorted_finds() -> None:
    rng = np.random.default_rng(7)
    along = np.concatenate([[0.0], np.cumsum(rng.choice([0.0, 0.05, 0.0707], 40))])
    along = np.concatenate([along, np.full(15, np.inf)]).astype(np.float32)  # the padding
    queries = rng.uniform(-0.1, along[40] + 0.3, (13, 500)).astype(np.float32)
    queries[0, :41] = along[:41]  # exact hits: "right" counts them
    counted = np.asarray(critics._count_at_most(jnp.asarray(along), jnp.asarray(queries)))
    assert counted.tolist() == np.searchsorted(along, queries, side="right").tolist()


def test_the_step_compiles_with_xlas_defaults_where_its_cpu_options_are_unknown(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    from nav2_pyif_planners.mppi_nav2 import optimizer

    assert dict(optimizer.compiler_options("cpu")) == optimizer.CPU_OPTIONS
    assert optimizer.compiler_options("gpu") == ()
    # an XLA that does not know the option (an older JAX): the step is compiled without it
    monkeypatch.setattr(optimizer, "CPU_OPTIONS", {"xla_cpu_no_such_option": ""})
    optimizer.compiler_options.cache_clear()
    try:
        assert optimizer.compiler_options("cpu") == ()
        double = optimizer.jit_on("cpu", lambda v: v * 2)
        assert float(double(np.float32(2.5))) == 5.0
    finally:
        optimizer.compiler_options.cache_clear()
