# nav2_pyif_cycle_bench (bench/): the control-cycle benchmark with the plugin's own client code
# (ControllerSession over ZenohTransport) on the client side, beside a bare Zenoh get and an
# rclcpp client of the rclpy-node workaround. Opt-in (NAV2_PYIF_BUILD_BENCH), in the ament
# build only, after the plugin's dependencies and NAV2_PYIF_ZENOH_TARGET are found. Run it
# through `nav2-pyif-bench cpp-cycle`, which starts the peers; scripts/build_cpp_bench.sh
# builds it alone.

add_executable(nav2_pyif_cycle_bench
  ${CMAKE_CURRENT_LIST_DIR}/../bench/cycle_bench.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../bench/pyif_rows.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../bench/rclcpp_topic_client.cpp
  # The plugin's transport itself (it needs nothing from Nav2), not a copy of it.
  ${CMAKE_CURRENT_LIST_DIR}/../src/nav2/zenoh_transport.cpp
)
target_include_directories(nav2_pyif_cycle_bench PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../include)
# ROS targets by name: the PyPI wheels' message exports also name Python-only libraries.
target_link_libraries(nav2_pyif_cycle_bench
  nav2_pyif_client
  ${NAV2_PYIF_ZENOH_TARGET}
  rclcpp::rclcpp
  geometry_msgs::geometry_msgs__rosidl_typesupport_cpp
  nav_msgs::nav_msgs__rosidl_typesupport_cpp)
install(TARGETS nav2_pyif_cycle_bench RUNTIME DESTINATION lib/${PROJECT_NAME})
