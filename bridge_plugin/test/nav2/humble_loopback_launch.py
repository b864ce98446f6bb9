"""nav2_bringup's stack on Humble with Nav2's loopback simulator, as Jazzy's
tb3_loopback_simulation.launch.py runs it there: Humble's navigation2 (1.1) has neither the
simulator nor that launch, so this file stands in for the launch, made of nav2_bringup's own
parts and nothing of the project's.

- nav2_bringup's navigation_launch.py with the params file given, composed (its servers
  components of one component_container_isolated, `nav2_container`, started as Humble's
  bringup_launch.py starts it) or not (`use_composition`);
- map_server and its lifecycle manager on nav2_bringup's turtlebot3_world map (the map Jazzy's
  nav2_bringup calls tb3_sandbox: the same image), as Jazzy's loopback launch starts them;
- Jazzy's nav2_loopback_sim (pure Python; testenv/build.sh builds it on Humble): map -> odom
  -> base_footprint from /cmd_vel, /odom, /clock and a /scan ray-cast on the map, with the
  parameters Jazzy's nav2_params.yaml gives it (Humble's has no such section);
- robot_state_publisher with nav2_bringup's TurtleBot 3 URDF (base_footprint -> base_link ->
  base_scan).

No localization, as in Jazzy's launch (`use_localization: False`): the simulator puts the robot
where /initialpose says, and publishes map -> odom itself.

    ros2 launch bridge_plugin/test/nav2/humble_loopback_launch.py params_file:=P \
        use_composition:=True
"""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import (
    DeclareLaunchArgument,
    GroupAction,
    IncludeLaunchDescription,
    SetEnvironmentVariable,
)
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node, SetParameter
from launch_ros.descriptions import ParameterFile
from nav2_common.launch import RewrittenYaml

# The loopback simulator's section of Jazzy's (1.3.8) nav2_params.yaml.
LOOPBACK_PARAMS = {
    "base_frame_id": "base_footprint",
    "odom_frame_id": "odom",
    "map_frame_id": "map",
    "scan_frame_id": "base_scan",
    "update_duration": 0.02,
    "scan_range_min": 0.05,
    "scan_range_max": 30.0,
    "scan_angle_min": -3.1415,
    "scan_angle_max": 3.1415,
    "scan_angle_increment": 0.02617,
    "scan_use_inf": True,
}


def generate_launch_description() -> LaunchDescription:
    bringup_dir = get_package_share_directory("nav2_bringup")
    params_file = LaunchConfiguration("params_file")
    map_yaml_file = LaunchConfiguration("map")
    autostart = LaunchConfiguration("autostart")
    use_composition = LaunchConfiguration("use_composition")
    use_respawn = LaunchConfiguration("use_respawn")
    remappings = [("/tf", "tf"), ("/tf_static", "tf_static")]
    arguments = [
        DeclareLaunchArgument(
            "params_file",
            default_value=os.path.join(bringup_dir, "params", "nav2_params.yaml"),
            description="Full path to the ROS2 parameters file to use for all launched nodes",
        ),
        DeclareLaunchArgument(
            "map", default_value=os.path.join(bringup_dir, "maps", "turtlebot3_world.yaml")
        ),
        DeclareLaunchArgument("autostart", default_value="true"),
        DeclareLaunchArgument("use_composition", default_value="True"),
        DeclareLaunchArgument("use_respawn", default_value="False"),
        DeclareLaunchArgument("use_rviz", default_value="False", description="(no RViz here)"),
    ]
    # as Humble's bringup_launch.py gives them to its container and map_server: the map
    # rewritten into map_server's own section (its stock `yaml_filename: ""`), since a node's
    # own section there outranks any later parameters for all nodes (`/**`)
    configured_params = ParameterFile(
        RewrittenYaml(
            source_file=params_file,
            root_key="",
            param_rewrites={"use_sim_time": "True", "yaml_filename": map_yaml_file},
            convert_types=True,
        ),
        allow_substs=True,
    )
    with open(os.path.join(bringup_dir, "urdf", "turtlebot3_waffle.urdf")) as urdf:
        robot_description = urdf.read()
    robot = [
        Node(
            package="robot_state_publisher",
            executable="robot_state_publisher",
            name="robot_state_publisher",
            output="screen",
            parameters=[{"use_sim_time": True, "robot_description": robot_description}],
            remappings=remappings,
        ),
        Node(
            package="nav2_loopback_sim",
            executable="loopback_simulator",
            name="loopback_simulator",
            output="screen",
            parameters=[params_file, LOOPBACK_PARAMS],
        ),
    ]
    map_server = GroupAction(
        [
            SetParameter("use_sim_time", True),
            Node(
                package="nav2_map_server",
                executable="map_server",
                name="map_server",
                output="screen",
                respawn=use_respawn,
                respawn_delay=2.0,
                parameters=[configured_params],
                remappings=remappings,
            ),
            Node(
                package="nav2_lifecycle_manager",
                executable="lifecycle_manager",
                name="lifecycle_manager_map_server",
                output="screen",
                parameters=[
                    configured_params,
                    {"autostart": autostart},
                    {"node_names": ["map_server"]},
                ],
            ),
        ]
    )
    container = Node(
        condition=IfCondition(use_composition),
        name="nav2_container",
        package="rclcpp_components",
        executable="component_container_isolated",
        parameters=[configured_params, {"autostart": autostart}],
        remappings=remappings,
        output="screen",
    )
    navigation = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(bringup_dir, "launch", "navigation_launch.py")),
        launch_arguments={
            "namespace": "",
            "use_sim_time": "True",
            "autostart": autostart,
            "params_file": params_file,
            "use_composition": use_composition,
            "use_respawn": use_respawn,
            "container_name": "nav2_container",
        }.items(),
    )
    return LaunchDescription(
        [
            SetEnvironmentVariable("RCUTILS_LOGGING_BUFFERED_STREAM", "1"),
            *arguments,
            *robot,
            map_server,
            container,
            navigation,
        ]
    )
