# The wire codec: a static library with no ROS dependency, linked into the Nav2 plugins and
# into the codec tests. It is built on msgpack-c, the C library (msgpack.h), because that is
# what the rosdep key `msgpack` installs on every platform (Debian/Ubuntu: libmsgpack-dev, or
# on Debian 13 its successor libmsgpack-c-dev); the C++ headers (msgpack.hpp, msgpack-cxx) are
# no rosdep key's and are missing from Debian 13's. msgpack-c is used only inside
# src/protocol, so consumers of this target need nothing but its public headers.

# Found by file rather than by CMake package: the package, its target and the library's name
# differ between msgpack-c releases (3.x/4.x: package msgpack, target msgpackc, libmsgpackc;
# 6.x: package msgpack-c, target msgpack-c, libmsgpack-c).
find_path(MSGPACK_C_INCLUDE_DIR msgpack.h)
find_library(MSGPACK_C_LIBRARY NAMES msgpack-c msgpackc)
if(NOT MSGPACK_C_INCLUDE_DIR OR NOT MSGPACK_C_LIBRARY)
  message(FATAL_ERROR
    "msgpack-c not found (msgpack.h: '${MSGPACK_C_INCLUDE_DIR}', library: "
    "'${MSGPACK_C_LIBRARY}'): install it with rosdep (key msgpack), or Debian/Ubuntu's "
    "libmsgpack-dev (Debian 13 and later: libmsgpack-c-dev), or set MSGPACK_C_INCLUDE_DIR "
    "and MSGPACK_C_LIBRARY")
endif()

# body_codec.cpp and envelopes.cpp (and the public headers ops, types, bodies, fields,
# messages, constants) are generated from protocol/nav2_pyif_protocol/schema.py:
# python -m nav2_pyif_codegen.generate
add_library(nav2_pyif_protocol_codec STATIC
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/body_codec.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/envelopes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/parse.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/reader.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/utf8.cpp
  ${CMAKE_CURRENT_LIST_DIR}/../src/protocol/writer.cpp
)
target_include_directories(nav2_pyif_protocol_codec
  PUBLIC ${CMAKE_CURRENT_LIST_DIR}/../include)
target_include_directories(nav2_pyif_protocol_codec SYSTEM PRIVATE ${MSGPACK_C_INCLUDE_DIR})
# PUBLIC: a static library's own dependencies reach whatever links it (the plugins, the tests).
target_link_libraries(nav2_pyif_protocol_codec PUBLIC ${MSGPACK_C_LIBRARY})
# Linked into the plugins' shared library.
set_target_properties(nav2_pyif_protocol_codec PROPERTIES POSITION_INDEPENDENT_CODE ON)
