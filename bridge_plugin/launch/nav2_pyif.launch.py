"""A planner host beside Nav2's controller_server and planner_server (nav2_bringup style).

    ros2 launch nav2_pyif_bridge nav2_pyif.launch.py
    ros2 launch nav2_pyif_bridge nav2_pyif.launch.py \\
        controller:=my_pkg.ctrl:MyController planner:=my_pkg.plan:MyPlanner
    # only the host, beside a Nav2 you launch yourself with params/nav2_pyif_params.yaml:
    ros2 launch nav2_pyif_bridge nav2_pyif.launch.py start_nav2:=false

The host serves <key_prefix>/FollowPath (the controller) and <key_prefix>/GridBased (the
planner), listening on `listen`; the plugins in `params_file` name those keys and connect to
that endpoint (zenoh_connect) or to a Zenoh router that does. Restart the host alone to load a
new version of a planner: the plugins re-send their state to it.

The host is the ROS package nav2_pyif's planner-host (what `ros2 run nav2_pyif planner-host`
starts) when a workspace or /opt/ros provides that package, else the planner-host on PATH
(pip); `planner_host:=EXECUTABLE` names another.
"""

import os

from ament_index_python.packages import PackageNotFoundError, get_package_prefix
from launch import LaunchContext, LaunchDescription
from launch.actions import DeclareLaunchArgument, ExecuteProcess, GroupAction, OpaqueFunction
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description() -> LaunchDescription:
    arg = LaunchConfiguration
    params_file = arg("params_file")
    use_sim_time = arg("use_sim_time")
    arguments = [
        DeclareLaunchArgument(
            "params_file",
            default_value=PathJoinSubstitution(
                [FindPackageShare("nav2_pyif_bridge"), "params", "nav2_pyif_params.yaml"]
            ),
            description="Nav2 params with the nav2_pyif plugins",
        ),
        DeclareLaunchArgument("key_prefix", default_value="nav2_pyif/robot1"),
        DeclareLaunchArgument(
            "controller", default_value="nav2_pyif_planners.pure_pursuit:RegulatedPurePursuit"
        ),
        DeclareLaunchArgument("planner", default_value="nav2_pyif_planners.astar:AStar"),
        DeclareLaunchArgument(
            "listen",
            default_value="tcp/127.0.0.1:7447",
            description="where the host listens (no Zenoh router needed)",
        ),
        DeclareLaunchArgument(
            "planner_host",
            default_value="",
            description="the host executable (default: nav2_pyif's, else planner-host on PATH)",
        ),
        DeclareLaunchArgument("start_nav2", default_value="true"),
        DeclareLaunchArgument("use_sim_time", default_value="false"),
        DeclareLaunchArgument("autostart", default_value="true"),
        DeclareLaunchArgument("log_level", default_value="info"),
    ]

    def host(context: LaunchContext) -> list[ExecuteProcess]:
        return [_host_process(arg("planner_host").perform(context) or _installed_host())]

    ros_args = ["--ros-args", "--log-level", arg("log_level")]
    common = [params_file, {"use_sim_time": use_sim_time}]
    nav2 = GroupAction(
        condition=IfCondition(arg("start_nav2")),
        actions=[
            Node(
                package="nav2_controller",
                executable="controller_server",
                output="screen",
                parameters=common,
                arguments=ros_args,
            ),
            Node(
                package="nav2_planner",
                executable="planner_server",
                name="planner_server",
                output="screen",
                parameters=common,
                arguments=ros_args,
            ),
            Node(
                package="nav2_lifecycle_manager",
                executable="lifecycle_manager",
                name="lifecycle_manager_navigation",
                output="screen",
                arguments=ros_args,
                parameters=[
                    {
                        "use_sim_time": use_sim_time,
                        "autostart": arg("autostart"),
                        "node_names": ["controller_server", "planner_server"],
                    }
                ],
            ),
        ],
    )
    return LaunchDescription([*arguments, OpaqueFunction(function=host), nav2])


def _installed_host() -> str:
    """nav2_pyif's planner-host where the ament index has that package, else the one on PATH."""
    try:
        prefix = get_package_prefix("nav2_pyif")
    except PackageNotFoundError:
        return "planner-host"
    return os.path.join(prefix, "lib", "nav2_pyif", "planner-host")


def _host_process(executable: str) -> ExecuteProcess:
    arg = LaunchConfiguration
    return ExecuteProcess(
        cmd=[
            executable,
            "--listen",
            arg("listen"),
            "--serve",
            [arg("key_prefix"), "/FollowPath=", arg("controller")],
            "--serve",
            [arg("key_prefix"), "/GridBased=", arg("planner")],
        ],
        name="planner_host",
        output="screen",
        additional_env={"PYTHONUNBUFFERED": "1"},
        sigterm_timeout="10",
    )
