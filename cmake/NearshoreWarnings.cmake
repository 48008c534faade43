# nearshore_target_defaults(TARGET): C++20, the warning set every target must be clean under,
# and the sanitizers when NEARSHORE_SANITIZE is on (the `asan` preset).
function(nearshore_target_defaults target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic)
  if(NEARSHORE_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
    target_link_options(${target} PRIVATE -fsanitize=address,undefined)
  endif()
endfunction()

# nearshore_add_test(NAME SOURCES... LIBS libs... LABELS labels...): one GoogleTest executable,
# each TEST registered with ctest. Tests find ../shared through NEARSHORE_SHARED_DIR.
function(nearshore_add_test name)
  cmake_parse_arguments(ARG "" "TIMEOUT" "SOURCES;LIBS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  nearshore_target_defaults(${name})
  # Unity batches of four test files: each parses GoogleTest and its libraries' headers once per
  # batch instead of once per file (the CI machine has 2 cores). Helpers in a test file's anonymous
  # namespace must therefore have names no other file of the suite uses.
  set_target_properties(${name} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 4)
  # Test code compiles at -O1 in a Release build: the libraries under test keep -O3 (their speed
  # is what the physics tests spend), while GoogleTest's expanded assertions cost about 30 % less
  # to compile (bake_tests' first batch: 15.2 s against 22.0 s of CPU), the CI budget's largest share.
  if(CMAKE_BUILD_TYPE STREQUAL "Release")
    target_compile_options(${name} PRIVATE -O1)
  endif()
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    NEARSHORE_SHARED_DIR="${NEARSHORE_SHARED_DIR}"
    NEARSHORE_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
    NEARSHORE_BINARY_DIR="${CMAKE_BINARY_DIR}")
  if("asan" IN_LIST ARG_LABELS)
    # The sanitizer build (scripts/test.sh) builds only these suites: target nearshore_asan_suites.
    if(NOT TARGET nearshore_asan_suites)
      add_custom_target(nearshore_asan_suites)
    endif()
    add_dependencies(nearshore_asan_suites ${name})
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 600)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 TEST_LIST ${name}_TESTS
    PROPERTIES TIMEOUT ${ARG_TIMEOUT}
    WORKING_DIRECTORY "${CMAKE_CURRENT_BINARY_DIR}")
  # Labels are set by a script ctest runs after the discovered list is loaded: passed through
  # gtest_discover_tests' PROPERTIES, a list of labels is flattened and only the first survives.
  set(labels_script "${CMAKE_CURRENT_BINARY_DIR}/${name}_labels.cmake")
  file(WRITE "${labels_script}"
    "if(${name}_TESTS)\n  set_tests_properties(\${${name}_TESTS} PROPERTIES LABELS \"${ARG_LABELS}\")\nendif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${labels_script}")
endfunction()
