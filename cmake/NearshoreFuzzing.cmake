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

# nearshore_add_libfuzzer(NAME target OUTPUT file FUZZED sources... SUPPORT sources...
#                         [FLAGS flags...] [LIBS flags...] [DEPENDS files...]):
# a libFuzzer executable built with NEARSHORE_LIBFUZZER_CLANGXX, one object per source so that a
# changed file rebuilds alone and the objects compile in parallel; a library source's object is
# shared by every fuzzer that links it at the same level (fuzz_objects/ of the build folder), so the
# ctest tests that build fuzzers take the resource lock nearshore_fuzz_objects (two builds at once
# would write the same object). FUZZED sources (the harness and
# the parser it explores) compile at -O1, where the fuzzer runs fast; SUPPORT sources (what the
# parser links but the fuzzer seldom reaches: gridding, spectra, file formats behind paths the
# fuzzer cannot create) at -O0, which halves their build time (CI has 2 cores). Every object keeps
# AddressSanitizer, UndefinedBehaviorSanitizer without recovery and the coverage instrumentation;
# -gline-tables-only is all a symbolised stack trace needs.
function(nearshore_add_libfuzzer)
  cmake_parse_arguments(ARG "" "NAME;OUTPUT" "FUZZED;SUPPORT;FLAGS;LIBS;DEPENDS" ${ARGN})
  set(sanitizers -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined)
  set(objects)
  set(shared_objects)
  foreach(kind FUZZED SUPPORT)
    if(kind STREQUAL "FUZZED")
      set(optimisation -O1)
    else()
      set(optimisation -O0)
    endif()
    foreach(source IN LISTS ARG_${kind})
      file(RELATIVE_PATH relative "${CMAKE_SOURCE_DIR}" "${source}")
      string(REGEX REPLACE "[/.]" "_" stem "${relative}")
      if(relative MATCHES "^tests/")
        # A harness: this fuzzer's own object.
        set(object "${CMAKE_CURRENT_BINARY_DIR}/${ARG_NAME}.objects/${stem}.o")
        set(owner "${ARG_NAME}")
      else()
        # A library source: one object per optimisation level for every fuzzer that links it
        # (the core's files, checksums and sequence readers were compiled up to five times). The
        # flags only name include folders, so the first fuzzer's flags build it as well as any other's.
        set(object "${CMAKE_BINARY_DIR}/fuzz_objects/${stem}${optimisation}.o")
        set(owner "fuzz_object_${stem}${optimisation}")
        list(APPEND shared_objects "${owner}")
        get_property(made GLOBAL PROPERTY "NEARSHORE_FUZZ_OBJECT_${owner}")
        if(made)
          list(APPEND objects "${object}")
          continue()
        endif()
        set_property(GLOBAL PROPERTY "NEARSHORE_FUZZ_OBJECT_${owner}" TRUE)
      endif()
      get_filename_component(folder "${object}" DIRECTORY)
      add_custom_command(OUTPUT "${object}"
        COMMAND "${CMAKE_COMMAND}" -E make_directory "${folder}"
        COMMAND "${NEARSHORE_LIBFUZZER_CLANGXX}" -std=c++20 ${optimisation} -gline-tables-only ${sanitizers}
                ${ARG_FLAGS} -MD -MF "${object}.d" -c "${source}" -o "${object}"
        DEPENDS "${source}" ${ARG_DEPENDS}
        DEPFILE "${object}.d"
        COMMENT "libFuzzer object ${relative} (${owner}, ${optimisation})"
        VERBATIM)
      if(NOT owner STREQUAL ARG_NAME)
        # Other folders' fuzzers reach the object through this target (a custom command's output
        # is attached to targets of its own folder only).
        add_custom_target("${owner}" DEPENDS "${object}")
      endif()
      list(APPEND objects "${object}")
    endforeach()
  endforeach()
  add_custom_command(OUTPUT "${ARG_OUTPUT}"
    COMMAND "${NEARSHORE_LIBFUZZER_CLANGXX}" -fsanitize=fuzzer,address,undefined ${objects} ${ARG_LIBS} -o "${ARG_OUTPUT}"
    DEPENDS ${objects}
    COMMENT "Linking the libFuzzer target ${ARG_NAME} with ${NEARSHORE_LIBFUZZER_CLANGXX}"
    VERBATIM)
  add_custom_target(${ARG_NAME} DEPENDS "${ARG_OUTPUT}")
  if(shared_objects)
    add_dependencies(${ARG_NAME} ${shared_objects})
  endif()
endfunction()

# What a fuzzer of one of the sequence folder's JSON files (loops.json, library.json) links beside
# its parser, and how it compiles and links: checksums and the core's files, errors and hashes.
set(NEARSHORE_FUZZ_SEQUENCE_JSON_SUPPORT
  "${CMAKE_SOURCE_DIR}/sequence/src/checksum.cpp"
  "${CMAKE_SOURCE_DIR}/core/src/atomic_file.cpp"
  "${CMAKE_SOURCE_DIR}/core/src/error.cpp"
  "${CMAKE_SOURCE_DIR}/core/src/hash.cpp")
set(NEARSHORE_FUZZ_SEQUENCE_JSON_FLAGS -I${CMAKE_SOURCE_DIR}/core/include -I${CMAKE_SOURCE_DIR}/sequence/include)
set(NEARSHORE_FUZZ_SEQUENCE_JSON_LIBS -lfmt -lxxhash)
