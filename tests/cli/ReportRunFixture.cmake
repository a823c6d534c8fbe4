# CTest fixture for tests/cli/ReportCliTest.cpp: runs the suite's one small `tidepool run` once,
# so that each of its tests (a process of its own under gtest_discover_tests) reads the same
# output instead of rendering the matrix again. Called with -DTIDEPOOL=<binary>
# -DSOURCE_ROOT=<repository> -DOUT=<folder> -DARGS=<run arguments, a ;-list>; writes OUT/ (the
# run's output), OUT.exit (its exit code), OUT.out (its stdout), OUT.err (its stderr) and
# OUT.progress.jsonl (its progress log).
file(REMOVE_RECURSE "${OUT}")
file(REMOVE "${OUT}.exit" "${OUT}.out" "${OUT}.err" "${OUT}.progress.jsonl")
# The validation cache goes beside the output, never into the real ~/.cache (--cache, not
# XDG_CACHE_HOME, which would also move Mesa's shader cache and make the run slower).
file(REMOVE_RECURSE "${OUT}.cache")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env LP_NUM_THREADS=2 "${TIDEPOOL}" ${ARGS} --out "${OUT}"
          --cache "${OUT}.cache" --progress-log "${OUT}.progress.jsonl"
  WORKING_DIRECTORY "${SOURCE_ROOT}"
  OUTPUT_VARIABLE out
  ERROR_VARIABLE err
  RESULT_VARIABLE code)
file(WRITE "${OUT}.out" "${out}")
file(WRITE "${OUT}.err" "${err}")
file(WRITE "${OUT}.exit" "${code}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "tidepool ${ARGS} exited ${code}:\n${err}")
endif()
