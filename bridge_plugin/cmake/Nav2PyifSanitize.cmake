# Sanitizer builds of everything this tree compiles (codec, client library, tests, harnesses):
#
#   -DNAV2_PYIF_SANITIZE=address,undefined   ASan + UBSan (GCC or Clang)
#   -DNAV2_PYIF_SANITIZE=thread              TSan: the carried cycle, host watcher and fake
#                                            transport callbacks run on threads of their own
#   -DNAV2_PYIF_FUZZ=ON                      the libFuzzer harnesses of fuzz/ (Clang only),
#                                            with ASan + UBSan unless NAV2_PYIF_SANITIZE says
#
# Set before any target is defined: every object of a sanitized program must be instrumented
# alike, or a report can blame the wrong line (ASan) or miss a race (TSan).

set(NAV2_PYIF_SANITIZE "" CACHE STRING
  "-fsanitize= checks for the whole build (address,undefined or thread); empty: none")
option(NAV2_PYIF_FUZZ "Build the libFuzzer harnesses of fuzz/ (needs Clang)" OFF)

if(NAV2_PYIF_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "NAV2_PYIF_FUZZ needs Clang's libFuzzer (compiler here: "
      "${CMAKE_CXX_COMPILER_ID}): configure with CXX=clang++-14 and install Debian's "
      "clang-14 and libclang-rt-14-dev")
  endif()
  if(NOT NAV2_PYIF_SANITIZE)
    set(NAV2_PYIF_SANITIZE address,undefined)
  endif()
  # Coverage feedback for the libraries too, not only the harness; the harness links the
  # fuzzer's main (Nav2PyifFuzz.cmake).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(NAV2_PYIF_SANITIZE)
  add_compile_options(-fsanitize=${NAV2_PYIF_SANITIZE} -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=${NAV2_PYIF_SANITIZE})
  if(NAV2_PYIF_SANITIZE MATCHES "undefined")
    # Undefined behaviour stops the program (a failed test, a fuzzer crash), not just a line.
    add_compile_options(-fno-sanitize-recover=undefined)
  endif()
  message(STATUS "nav2_pyif_bridge: built with -fsanitize=${NAV2_PYIF_SANITIZE}")
endif()
