# The wire codec: a static library with no ROS dependency, linked into the Nav2 plugins and
# into the codec tests. msgpack-cxx is header-only and used only inside src/protocol, so
# consumers of this target need nothing but its public headers.

# Found by header rather than by CMake package: the package's name and targets differ between
# msgpack-cxx releases (msgpack, msgpack-cxx, msgpackc-cxx), and Debian's config file also
# requires Boost, which this codec does not use (MSGPACK_NO_BOOST).
find_path(MSGPACK_CXX_INCLUDE_DIR msgpack.hpp)
if(NOT MSGPACK_CXX_INCLUDE_DIR)
  message(FATAL_ERROR
    "msgpack.hpp not found: install msgpack-cxx (Debian/Ubuntu: libmsgpack-cxx-dev) "
    "or set MSGPACK_CXX_INCLUDE_DIR")
endif()

# body_codec.cpp (and the public headers ops, types, bodies, fields, constants) are generated
# from protocol/nav2_pyif_protocol/schema.py: python -m nav2_pyif_protocol.generate
add_library(nav2_pyif_protocol_codec STATIC
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/body_codec.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/decode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/encode.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/utf8.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/writer.cpp
)
target_include_directories(nav2_pyif_protocol_codec
  PUBLIC ${CMAKE_CURRENT_LIST_DIR}/../include)
target_include_directories(nav2_pyif_protocol_codec SYSTEM PRIVATE ${MSGPACK_CXX_INCLUDE_DIR})
target_compile_definitions(nav2_pyif_protocol_codec PRIVATE MSGPACK_NO_BOOST)
# Linked into the plugins' shared library.
set_target_properties(nav2_pyif_protocol_codec PROPERTIES POSITION_INDEPENDENT_CODE ON)
