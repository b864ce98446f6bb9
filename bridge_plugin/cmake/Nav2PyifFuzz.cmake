# The libFuzzer harnesses (fuzz/, fuzz/README.md), one executable each: fuzz_<name>. Included
# by the codec-only build when NAV2_PYIF_FUZZ is ON; Nav2PyifSanitize.cmake has already
# instrumented every target for coverage, ASan and UBSan.
#
#   CXX=clang++-14 cmake -S bridge_plugin -B build/cpp_fuzz -DNAV2_PYIF_CODEC_ONLY=ON \
#     -DNAV2_PYIF_FUZZ=ON -DBUILD_TESTING=OFF

set(NAV2_PYIF_FUZZ_HARNESSES request reply structure utf8 params keys)
set(_nav2_pyif_fuzz_dir ${CMAKE_CURRENT_LIST_DIR}/../fuzz)

foreach(harness IN LISTS NAV2_PYIF_FUZZ_HARNESSES)
  add_executable(fuzz_${harness} ${_nav2_pyif_fuzz_dir}/fuzz_${harness}.cpp)
  # src/protocol: the harnesses of the pre-pass, the UTF-8 check and the params reader call
  # the codec's internals (parse.hpp, utf8.hpp, reader.hpp), which include msgpack.h.
  target_include_directories(fuzz_${harness} PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../src/protocol)
  target_include_directories(fuzz_${harness} SYSTEM PRIVATE ${MSGPACK_C_INCLUDE_DIR})
  target_link_libraries(fuzz_${harness} PRIVATE nav2_pyif_client)
  target_link_options(fuzz_${harness} PRIVATE -fsanitize=fuzzer)
endforeach()

# The key harness's seeds: each prefix of protocol/vectors/keys.json as a file of its own (the
# vectors themselves are JSON documents, not keys).
set(_keys_vector "${NAV2_PYIF_VECTORS_DIR}/keys.json")
set(_keys_seeds "${CMAKE_BINARY_DIR}/fuzz_seeds/keys")
if(EXISTS "${_keys_vector}")
  set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${_keys_vector}")
  file(READ "${_keys_vector}" _keys_json)
  file(REMOVE_RECURSE "${_keys_seeds}")
  string(JSON _prefix GET "${_keys_json}" prefix)
  file(WRITE "${_keys_seeds}/prefix" "${_prefix}")
  string(JSON _token GET "${_keys_json}" host_token key)
  file(WRITE "${_keys_seeds}/host_token" "${_token}")
  string(JSON _count LENGTH "${_keys_json}" prefixes)
  math(EXPR _last "${_count} - 1")
  foreach(i RANGE ${_last})
    string(JSON _prefix GET "${_keys_json}" prefixes ${i} prefix)
    file(WRITE "${_keys_seeds}/prefixes_${i}" "${_prefix}")
  endforeach()
endif()
