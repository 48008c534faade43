# nearshore_find_libfuzzer(): sets NEARSHORE_LIBFUZZER_CLANGXX to a clang++ that builds libFuzzer
# targets (-fsanitize=fuzzer), or leaves it empty and says why. The parsers' fuzz targets
# (tests/*/fuzz) are built with it from their sources directly, since the project builds with GCC.
function(nearshore_find_libfuzzer)
  set(NEARSHORE_LIBFUZZER_CLANGXX "" PARENT_SCOPE)
  find_program(NEARSHORE_CLANGXX NAMES clang++ clang++-15 clang++-14)
  if(NOT NEARSHORE_CLANGXX)
    message(STATUS "clang++ not found: no libFuzzer targets (the GoogleTest mutation fuzz still runs)")
    return()
  endif()
  set(probe "${CMAKE_BINARY_DIR}/libfuzzer_probe.cpp")
  file(WRITE "${probe}" "#include <cstddef>\n#include <cstdint>\nextern \"C\" int LLVMFuzzerTestOneInput(const std::uint8_t*, std::size_t) { return 0; }\n")
  execute_process(COMMAND "${NEARSHORE_CLANGXX}" -fsanitize=fuzzer "${probe}" -o "${CMAKE_BINARY_DIR}/libfuzzer_probe"
                  RESULT_VARIABLE probe_result OUTPUT_QUIET ERROR_QUIET)
  if(NOT probe_result EQUAL 0)
    message(STATUS "${NEARSHORE_CLANGXX} has no libFuzzer: no fuzz targets")
    return()
  endif()
  set(NEARSHORE_LIBFUZZER_CLANGXX "${NEARSHORE_CLANGXX}" PARENT_SCOPE)
endfunction()
