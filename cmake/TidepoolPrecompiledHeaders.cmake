# TIDEPOOL_FAST_COLD_BUILD: precompiled headers and a unity build of the CLI and of the unit and
# CLI tests, for builds without a compiler cache (CI builds from a fresh clone). Without them
# every file parses the standard library, fmt, nlohmann/json and GoogleTest again, and every file
# that includes cli/Commands.h compiles CLI11's validator objects again (about 10 s of CPU per
# file at -O3).
#
# Off by default when a compiler launcher (ccache) is set: ccache does not cache a file compiled
# with a precompiled header unless its sloppiness has pch_defines,time_macros, so a warm cache
# would miss every file, and a unity file is recompiled whenever one of its files changes.
if(CMAKE_CXX_COMPILER_LAUNCHER)
  set(tidepool_fast_cold_build_default OFF)
else()
  set(tidepool_fast_cold_build_default ON)
endif()
option(TIDEPOOL_FAST_COLD_BUILD "Precompiled headers and a unity build of the CLI and tests"
       ${tidepool_fast_cold_build_default})

if(TIDEPOOL_FAST_COLD_BUILD)
  set(std_headers <algorithm> <filesystem> <functional> <map> <memory> <optional> <string>
      <string_view> <vector>)
  # Making a precompiled header costs as much as compiling two to four ordinary files, so the
  # libraries share one and the tests share another (REUSE_FROM). The flags that decide whether
  # a precompiled header can be used (-O, -g, -fsanitize, FMT_SHARED) are the same within each
  # group; a mismatch is an error (-Winvalid-pch with -Werror), not a silent slowdown.
  # nlohmann/json is left out of the libraries' header: loading it costs the files that do not
  # include it more than parsing it costs the files that do (its cost is in the instantiations).
  target_precompile_headers(tidepool_base PRIVATE ${std_headers} <fmt/format.h>)
  # Sha256.cpp's SHA-extension code needs <immintrin.h> as -O0 builds declare it (_mm_alignr_epi8
  # as a macro); behind the precompiled header GCC 12 takes the inline function, whose last
  # argument is then not an immediate, and the sanitizer build fails. For the same reason it stays
  # out of its library's unity file, which is compiled behind the precompiled header.
  set_source_files_properties("${PROJECT_SOURCE_DIR}/base/src/Sha256.cpp" TARGET_DIRECTORY tidepool_base
                              PROPERTIES SKIP_PRECOMPILE_HEADERS ON SKIP_UNITY_BUILD_INCLUSION ON)
  # The libraries are compiled eight files to a compile (unity): a library's files include the
  # same standard, fmt, nlohmann/json, yaml-cpp and glslang headers and instantiate the same
  # templates, which a file-by-file build parses and compiles again for every file (e.g.
  # stagefiles' four JSON readers, about 10 s of CPU each at -O3, most of it nlohmann/json).
  # Eight, not the whole library in one: the fuzz build needs only base, stagefiles and compiler,
  # and compiler as one file would keep one core busy long after the other is done. The names in
  # a library's anonymous namespaces are unique across the library (checked with all its files in
  # one compile), so a new file that moves the batch boundaries brings no clash but its own.
  # clang-tidy still checks the files one by one (scripts/clang-tidy.sh takes their commands from
  # the unity files' entries).
  set(tidepool_libraries tidepool_base tidepool_stagefiles tidepool_compiler tidepool_runner
                         tidepool_lab tidepool_report tidepool_pipeline tidepool_pipeline_gl)
  set_target_properties(${tidepool_libraries} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
  # GCC takes a class defined in an #included file for a header's (-Wsubobject-linkage), so
  # WaterRenderer::Impl, whose members are of types from the file's anonymous namespace, would
  # fail the unity file; WaterRenderer.cpp is compiled on its own instead.
  set_source_files_properties("${PROJECT_SOURCE_DIR}/runner/src/gl/WaterRenderer.cpp"
                              TARGET_DIRECTORY tidepool_runner PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
  # The CLI targets are one file each (unity), so CLI11 is compiled once per target.
  set_target_properties(tidepool_cli_common tidepool-gl PROPERTIES UNITY_BUILD ON)
  foreach(target tidepool_compiler tidepool_runner tidepool_lab tidepool_report tidepool_pipeline
                 tidepool_pipeline_gl tidepool_cli_common tidepool-gl)
    target_precompile_headers(${target} REUSE_FROM tidepool_base)
  endforeach()
  if(TARGET tidepool_unit_tests)
    target_precompile_headers(tidepool_unit_tests PRIVATE ${std_headers} <nlohmann/json.hpp>
                              <gtest/gtest.h>)
    foreach(target tidepool_gl_tests tidepool_cli_tests)
      if(TARGET ${target})
        target_precompile_headers(${target} REUSE_FROM tidepool_unit_tests)
      endif()
    endforeach()
    # The unit and CLI test files are compiled eight to a file (unity): each file costs about
    # 2 s of CPU before its own code (the precompiled header, GoogleTest's and nlohmann/json's
    # templates and the same inline functions compiled again), so this takes the release build's
    # unit tests from 479 to 313 s of CPU and the CLI tests from 87 to 56 s. The files of a batch
    # share one anonymous namespace, so each test file's helpers have names of their own. The GL
    # tests (9 files, 52 s) are left as they are: their helpers share many names and it would
    # save little.
    foreach(target tidepool_unit_tests tidepool_cli_tests)
      if(TARGET ${target})
        set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE 8)
      endif()
    endforeach()
  endif()
endif()
