# tidepool_add_shader_variants(TARGET name CONFIG variants.yaml OUTPUT_DIR dir [PROGRAMS name...])
#
# Expands and validates the shader variants of CONFIG at build time. For each program of the
# configuration, one build step runs
#   tidepool validate --config CONFIG --program P --out OUTPUT_DIR/P --sources --depfile ...
# and writes OUTPUT_DIR/P/manifest.json (the variants with their verdicts, static cost and
# "sources") plus each variant's driver-ready sources, OUTPUT_DIR/P/<target>/P/<variant>.vert|.frag.
# An invalid variant fails the build with its diagnostics at the shader's file:line.
#
# Why one step per program: the step's depfile names CONFIG and the two shader files the program
# reads, so Ninja and Make rerun exactly the steps whose inputs changed: editing one program's
# shader revalidates that program alone, editing CONFIG revalidates every program, and a build
# with nothing changed runs nothing. Sources of unchanged variants keep their time stamps.
#
# The program list is read from CONFIG when CMake configures (`tidepool expand --json`), and
# CMake reconfigures when CONFIG changes; PROGRAMS names them instead (and skips that read).
# TARGET is a custom target that builds every step (part of ALL); its properties
# TIDEPOOL_OUTPUT_DIR and TIDEPOOL_MANIFESTS give OUTPUT_DIR and the manifests' paths.
#
# CONFIG's folder and OUTPUT_DIR may not hold `$`, `:`, `;`, `#` or a newline (refused when CMake
# configures: CMake's depfile handling and its lists break them), and two targets may not share
# an OUTPUT_DIR.
#
# The tidepool binary: TIDEPOOL_EXECUTABLE (set by find_package(tidepool)), else `tidepool`
# on the PATH. Relative CONFIG is taken from the current source folder, relative OUTPUT_DIR from
# the current binary folder. Needs CMake 3.20 (DEPFILE for Ninja and Makefile generators).
include_guard(GLOBAL)

function(tidepool_add_shader_variants)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;CONFIG;OUTPUT_DIR" "PROGRAMS")
  foreach(required TARGET CONFIG OUTPUT_DIR)
    if(NOT arg_${required})
      message(FATAL_ERROR "tidepool_add_shader_variants: ${required} is required")
    endif()
  endforeach()
  if(arg_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "tidepool_add_shader_variants: unknown arguments ${arg_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT TIDEPOOL_EXECUTABLE)
    find_program(TIDEPOOL_EXECUTABLE tidepool)
    if(NOT TIDEPOOL_EXECUTABLE)
      message(FATAL_ERROR "tidepool_add_shader_variants: no tidepool binary; use "
                          "find_package(tidepool) or set TIDEPOOL_EXECUTABLE")
    endif()
  endif()
  get_filename_component(config "${arg_CONFIG}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_SOURCE_DIR}")
  get_filename_component(out "${arg_OUTPUT_DIR}" ABSOLUTE BASE_DIR "${CMAKE_CURRENT_BINARY_DIR}")
  # tidepool's depfile escapes `$` and `:`, but CMake's own depfile transform (3.25) drops the
  # `$$` and turns `\:` into `/:`, so Ninja reran every step on every build and Make stopped on
  # `:`; CMake splits a path at `;` and refuses `#` in an OUTPUT. Refused here, by name.
  get_filename_component(config_dir "${config}" DIRECTORY)
  foreach(path IN ITEMS "${config_dir}" "${out}")
    if(path MATCHES "[$:;#\n]")
      message(FATAL_ERROR "tidepool_add_shader_variants: the path '${path}' holds one of $ : ; # "
                          "or a newline, which CMake's depfile handling or its lists break: "
                          "move CONFIG (with its shaders) or OUTPUT_DIR to a path without them")
    endif()
  endforeach()
  # Two steps writing one manifest would be two rules for one file, which CMake refuses in its
  # own words; say which target has the folder.
  get_property(owner GLOBAL PROPERTY "TIDEPOOL_OUTPUT_DIR_OWNER:${out}")
  if(owner)
    message(FATAL_ERROR "tidepool_add_shader_variants: OUTPUT_DIR '${out}' is already the output "
                        "folder of target '${owner}'; give each target its own OUTPUT_DIR")
  endif()
  set_property(GLOBAL PROPERTY "TIDEPOOL_OUTPUT_DIR_OWNER:${out}" "${arg_TARGET}")

  set(programs ${arg_PROGRAMS})
  if(NOT programs)
    execute_process(COMMAND "${TIDEPOOL_EXECUTABLE}" expand --config "${config}" --json
                    OUTPUT_VARIABLE expansion ERROR_VARIABLE errors RESULT_VARIABLE status)
    if(NOT status EQUAL 0)
      message(FATAL_ERROR "tidepool_add_shader_variants: `tidepool expand --config ${config}` "
                          "failed (exit ${status}):\n${errors}")
    endif()
    string(JSON count LENGTH "${expansion}" programs)
    math(EXPR last "${count} - 1")
    foreach(i RANGE ${last})
      string(JSON name GET "${expansion}" programs ${i} name)
      list(APPEND programs "${name}")
    endforeach()
    # A program added to or removed from CONFIG changes the steps, so CMake must look again.
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS "${config}")
  endif()

  set(manifests)
  foreach(program IN LISTS programs)
    set(manifest "${out}/${program}/manifest.json")
    add_custom_command(
      OUTPUT "${manifest}"
      COMMAND "${TIDEPOOL_EXECUTABLE}" validate --config "${config}" --program "${program}"
              --out "${out}/${program}" --sources --depfile "${out}/${program}.d"
      DEPFILE "${out}/${program}.d"
      # A new tidepool may judge or assemble differently; the depfile adds the shaders.
      DEPENDS "${config}" "${TIDEPOOL_EXECUTABLE}"
      COMMENT "tidepool: validating the ${program} variants of ${arg_CONFIG}"
      VERBATIM)
    list(APPEND manifests "${manifest}")
  endforeach()
  add_custom_target(${arg_TARGET} ALL DEPENDS ${manifests})
  set_target_properties(${arg_TARGET} PROPERTIES TIDEPOOL_OUTPUT_DIR "${out}"
                                                 TIDEPOOL_MANIFESTS "${manifests}")
endfunction()
