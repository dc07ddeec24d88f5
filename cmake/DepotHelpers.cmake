# depot_library(NAME SOURCES ... DEPS ...): a static library with project warnings.
function(depot_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${DEPOT_SOURCE_DIR})
  target_compile_options(${name} PRIVATE ${DEPOT_WARNINGS})
  target_link_libraries(${name} PUBLIC ${ARG_DEPS})
  depot_register_folder(${name} "${ARG_SOURCES}")
endfunction()

# depot_test(NAME SOURCES ... DEPS ... [LABELS ...] [SERIAL]): a GoogleTest
# binary beside the code it tests, registered with CTest. SERIAL: its cases run
# with no other test beside them (they observe machine-wide state).
function(depot_test name)
  if(NOT DEPOT_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "SERIAL" "TIMEOUT" "SOURCES;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_compile_options(${name} PRIVATE ${DEPOT_WARNINGS})
  # Tests build maps and read them back on one thread without the map lock;
  # the analysis is for the code they test.
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    target_compile_options(${name} PRIVATE -Wno-thread-safety)
  endif()
  target_compile_definitions(${name} PRIVATE
    DEPOT_SOURCE_DIR="${DEPOT_SOURCE_DIR}"
    DEPOT_SHARED_DATA="${DEPOT_SHARED_DATA}"
    DEPOT_BINARY_DIR="${CMAKE_BINARY_DIR}")
  target_link_libraries(${name} PRIVATE ${ARG_DEPS} GTest::gmock GTest::gtest GTest::gtest_main)
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  # Sanitizer builds run 3-25x slower (cmake/DepotSanitizers.cmake).
  if(DEPOT_SANITIZE)
    math(EXPR ARG_TIMEOUT "${ARG_TIMEOUT} * 3")
  endif()
  set(_props TIMEOUT ${ARG_TIMEOUT})
  if(ARG_LABELS)
    list(GET ARG_LABELS 0 _first)
    list(APPEND _props LABELS ${_first})
  endif()
  if(ARG_SERIAL)
    list(APPEND _props RUN_SERIAL TRUE)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${_props})
  # gtest_discover_tests passes a property's value as one word, so a test's
  # further labels are set by a file ctest reads after the discovered tests.
  list(LENGTH ARG_LABELS _count)
  if(_count GREATER 1)
    set(_labels_file "${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake")
    file(WRITE "${_labels_file}"
         "foreach(_test IN LISTS ${name}_TESTS)\n"
         "  set_tests_properties(\"\${_test}\" PROPERTIES LABELS \"${ARG_LABELS}\")\n"
         "endforeach()\n")
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${_labels_file}")
  endif()
endfunction()
