# nav2_pyif_cycle_bench (bench/): the control-cycle benchmark with the plugin's own client code
# (ControllerSession over ZenohTransport) on the client side, beside a bare Zenoh get and an
# rclcpp client of the rclpy-node workaround; nav2_pyif_fleet_client: robots of `nav2-pyif-bench
# fleet --cpp-clients`, on the same client code. Opt-in (NAV2_PYIF_BUILD_BENCH), in the ament
# build only, after the plugin's dependencies and NAV2_PYIF_ZENOH_TARGET are found. Run them
# through `nav2-pyif-bench cpp-cycle` and `fleet`, which start the peers;
# scripts/build_cpp_bench.sh builds them alone.

add_executable(nav2_pyif_cycle_bench
  ${CMAKE_CURRENT_LIST_DIR}/../bench/cycle_bench.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../bench/pyif_rows.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../bench/rclcpp_topic_client.cpp
  # The plugin's transport itself (it needs nothing from Nav2), not a copy of it.
  ${CMAKE_CURRENT_LIST_DIR}/../src/nav2/zenoh_transport.cpp
)
target_include_directories(nav2_pyif_cycle_bench PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../include)
# The benches run from the build tree, where the installed default config is not: they name the
# package's source copy (bench_zenoh.hpp; zenoh-c only, zenoh-pico takes no file).
set(NAV2_PYIF_BENCH_ZENOH_CONFIG
  NAV2_PYIF_BENCH_ZENOH_CONFIG="${CMAKE_CURRENT_LIST_DIR}/../config/default_session.json5")
target_compile_definitions(nav2_pyif_cycle_bench PRIVATE ${NAV2_PYIF_BENCH_ZENOH_CONFIG})
# ROS targets by name: the PyPI wheels' message exports also name Python-only libraries.
target_link_libraries(nav2_pyif_cycle_bench
  nav2_pyif_client
  ${NAV2_PYIF_ZENOH_TARGET}
  rclcpp::rclcpp
  geometry_msgs::geometry_msgs__rosidl_typesupport_cpp
  nav_msgs::nav_msgs__rosidl_typesupport_cpp)
install(TARGETS nav2_pyif_cycle_bench RUNTIME DESTINATION lib/${PROJECT_NAME})

add_executable(nav2_pyif_fleet_client
  ${CMAKE_CURRENT_LIST_DIR}/../bench/fleet_client.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/nav2/zenoh_transport.cpp
)
target_include_directories(nav2_pyif_fleet_client PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../include)
target_compile_definitions(nav2_pyif_fleet_client PRIVATE ${NAV2_PYIF_BENCH_ZENOH_CONFIG})
target_link_libraries(nav2_pyif_fleet_client nav2_pyif_client ${NAV2_PYIF_ZENOH_TARGET})
install(TARGETS nav2_pyif_fleet_client RUNTIME DESTINATION lib/${PROJECT_NAME})
