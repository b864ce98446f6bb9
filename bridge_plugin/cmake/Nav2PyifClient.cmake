# The plugin's logic without Nav2 or Zenoh (src/client): session/epoch/seq handling, the call
# procedure of PROTOCOL.md section 4, error mapping, costmap versions, settings, the local
# planner host's start and stop. A static library linked into the Nav2 plugins, and tested on its
# own in both builds of CMakeLists.txt:
#
#   nav2_pyif_client_test_sources(<out_var>)   the GoogleTest sources (test/client)
#   nav2_pyif_client_test_setup(<target>)      includes and libraries for that executable

find_package(Threads REQUIRED)

add_library(nav2_pyif_client STATIC
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/behavior_session.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/carried_cycle.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/command_check.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/controller_session.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/costmap_version.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/error_mapping.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/host_watcher.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/keys.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/local_host.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/path_handler_session.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/planner_session.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/plugin_session.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/client/settings.cpp
)
target_include_directories(nav2_pyif_client PUBLIC ${CMAKE_CURRENT_LIST_DIR}/../include)
target_link_libraries(nav2_pyif_client PUBLIC nav2_pyif_protocol_codec Threads::Threads)
set_target_properties(nav2_pyif_client PROPERTIES POSITION_INDEPENDENT_CODE ON)

set(_nav2_pyif_client_test_dir ${CMAKE_CURRENT_LIST_DIR}/../test/client)

function(nav2_pyif_client_test_sources out_var)
  set(sources
    ${_nav2_pyif_client_test_dir}/behavior_session_test.cpp
    ${_nav2_pyif_client_test_dir}/carried_test.cpp
    ${_nav2_pyif_client_test_dir}/controller_session_test.cpp
    ${_nav2_pyif_client_test_dir}/fakes.cpp
    ${_nav2_pyif_client_test_dir}/local_host_test.cpp
    ${_nav2_pyif_client_test_dir}/planner_session_test.cpp
    ${_nav2_pyif_client_test_dir}/settings_test.cpp
    ${_nav2_pyif_client_test_dir}/units_test.cpp)
  # The shared session transcripts (PROTOCOL.md section 18) and key rules, where the vectors
  # are.
  if(EXISTS "${NAV2_PYIF_VECTORS_DIR}/transcripts")
    list(APPEND sources ${_nav2_pyif_client_test_dir}/transcripts_test.cpp
      ${_nav2_pyif_client_test_dir}/keys_test.cpp)
  endif()
  set(${out_var} ${sources} PARENT_SCOPE)
endfunction()

function(nav2_pyif_client_test_setup target)
  target_include_directories(${target} PRIVATE ${_nav2_pyif_client_test_dir})
  target_link_libraries(${target} nav2_pyif_client)
  if(EXISTS "${NAV2_PYIF_VECTORS_DIR}/transcripts")
    target_compile_definitions(${target} PRIVATE
      NAV2_PYIF_TRANSCRIPTS_DIR="${NAV2_PYIF_VECTORS_DIR}/transcripts"
      NAV2_PYIF_KEYS_VECTOR="${NAV2_PYIF_VECTORS_DIR}/keys.json")
    target_link_libraries(${target} nlohmann_json::nlohmann_json)
  endif()
endfunction()
