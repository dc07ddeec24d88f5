# DEPOT_SANITIZE: build every target of the project with a sanitizer.
#   ""        off (default)
#   thread    ThreadSanitizer
#   address   AddressSanitizer + UndefinedBehaviorSanitizer
# Third-party libraries (OpenCV, Ceres, MuJoCo, OSMesa, GoogleTest) come from
# Debian packages and are not instrumented; tools/sanitizers/ holds the
# run-time options and the suppressions for races inside them
# (tools/sanitize.sh sets TSAN_OPTIONS / ASAN_OPTIONS / UBSAN_OPTIONS).
# The flags are directory-wide (add_compile_options / add_link_options before
# the project's subdirectories), so every library, program, test and benchmark
# gets them, not only those made with depot_library / depot_test.
set(DEPOT_SANITIZE "" CACHE STRING "Sanitizer build: empty (off), thread, address (ASan+UBSan)")
set_property(CACHE DEPOT_SANITIZE PROPERTY STRINGS "" thread address)

set(DEPOT_SANITIZE_FLAGS "")
if(DEPOT_SANITIZE STREQUAL "")
  # off
elseif(DEPOT_SANITIZE STREQUAL "thread")
  set(DEPOT_SANITIZE_FLAGS -fsanitize=thread)
elseif(DEPOT_SANITIZE STREQUAL "address")
  # Recovery off for UBSan: a finding fails the test instead of scrolling by.
  set(DEPOT_SANITIZE_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined)
else()
  message(FATAL_ERROR "DEPOT_SANITIZE: '${DEPOT_SANITIZE}' is not one of: (empty), thread, address")
endif()

if(DEPOT_SANITIZE_FLAGS)
  message(STATUS "depot: sanitizer build (${DEPOT_SANITIZE}): ${DEPOT_SANITIZE_FLAGS}")
  # Readable stacks at a speed the tests can bear: -O1 at least (Debug would be
  # far too slow under the sanitizer), debug info and frame pointers always.
  add_compile_options(${DEPOT_SANITIZE_FLAGS} -fno-omit-frame-pointer -g)
  if(CMAKE_BUILD_TYPE STREQUAL "Debug")
    add_compile_options(-O1)
  endif()
  add_link_options(${DEPOT_SANITIZE_FLAGS})
endif()

# DEPOT_FUZZ (tests/fuzz/, tools/fuzz.sh): the libFuzzer build. Every
# library gets coverage instrumentation without libFuzzer's main
# (-fsanitize=fuzzer-no-link) plus ASan and UBSan, so a reader's bug shows
# where it is; the fuzz targets themselves link -fsanitize=fuzzer. Only
# clang has libFuzzer (Debian: clang, libclang-rt-14-dev).
if(DEPOT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "DEPOT_FUZZ needs clang (configure with CC=clang CXX=clang++, as tools/fuzz.sh does)")
  endif()
  if(DEPOT_SANITIZE_FLAGS)
    message(FATAL_ERROR "DEPOT_FUZZ brings its own sanitizers; leave DEPOT_SANITIZE empty")
  endif()
  set(DEPOT_FUZZ_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined)
  message(STATUS "depot: fuzz build: -fsanitize=fuzzer-no-link ${DEPOT_FUZZ_FLAGS}")
  add_compile_options(-fsanitize=fuzzer-no-link ${DEPOT_FUZZ_FLAGS} -fno-omit-frame-pointer -g)
  add_link_options(${DEPOT_FUZZ_FLAGS})
endif()
