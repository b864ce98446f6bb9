# The codec's GoogleTest suite, shared by the two builds of CMakeLists.txt:
#
#   nav2_pyif_codec_test_sources(<out_var> [REQUIRE_VECTORS])
#     the test sources. The vector tests need NAV2_PYIF_VECTORS_DIR (../protocol/vectors);
#     without REQUIRE_VECTORS, a package built outside the nav2_pyif repository leaves them
#     out and says so; with it, their absence is a configuration error.
#   nav2_pyif_codec_test_setup(<target>)
#     includes, definitions and libraries for the test executable <target>. Links with the
#     keyword-less signature, the one ament_add_gtest uses (CMake refuses a mix of both).

find_package(nlohmann_json 3 REQUIRED)  # reads the vectors' expected .json trees
find_package(ZLIB REQUIRED)             # crc32 of the large bins in those trees

set(_nav2_pyif_test_dir ${CMAKE_CURRENT_LIST_DIR}/../test/protocol)

function(nav2_pyif_codec_test_sources out_var)
  cmake_parse_arguments(ARG "REQUIRE_VECTORS" "" "" ${ARGN})
  set(sources
    ${_nav2_pyif_test_dir}/decode_errors_test.cpp
    ${_nav2_pyif_test_dir}/encode_test.cpp
    ${_nav2_pyif_test_dir}/json_tree.cpp
    ${_nav2_pyif_test_dir}/params_test.cpp
    ${_nav2_pyif_test_dir}/test_data.cpp
  )
  if(EXISTS "${NAV2_PYIF_VECTORS_DIR}/index.json")
    list(APPEND sources ${_nav2_pyif_test_dir}/vectors_test.cpp)
  elseif(ARG_REQUIRE_VECTORS)
    message(FATAL_ERROR "no ${NAV2_PYIF_VECTORS_DIR}/index.json: set NAV2_PYIF_VECTORS_DIR")
  else()
    message(STATUS "nav2_pyif_bridge: no shared vectors at ${NAV2_PYIF_VECTORS_DIR}; "
      "the codec tests run without them")
  endif()
  set(${out_var} ${sources} PARENT_SCOPE)
endfunction()

function(nav2_pyif_codec_test_setup target)
  # The default vectors location; the NAV2_PYIF_VECTORS_DIR environment variable overrides it
  # at run time (test_data.cpp).
  target_compile_definitions(${target} PRIVATE
    NAV2_PYIF_VECTORS_DIR="${NAV2_PYIF_VECTORS_DIR}")
  # json_tree.cpp packs the vectors' trees with msgpack-c (linked through the codec).
  target_include_directories(${target} SYSTEM PRIVATE ${MSGPACK_C_INCLUDE_DIR})
  target_link_libraries(${target}
    nav2_pyif_protocol_codec nlohmann_json::nlohmann_json ZLIB::ZLIB)
endfunction()
