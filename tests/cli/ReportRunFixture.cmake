# CTest fixture for tests/cli/ReportCliTest.cpp: runs the suite's one small `tidepool run` once,
# so that each of its tests (a process of its own under gtest_discover_tests) reads the same
# output instead of rendering the matrix again. Called with -DTIDEPOOL=<binary>
# -DSOURCE_ROOT=<repository> -DOUT=<folder> -DARGS=<run arguments, a ;-list>; writes OUT/ (the
# run's output), OUT.exit (its exit code) and OUT.log (its stdout and stderr together).
file(REMOVE_RECURSE "${OUT}")
file(REMOVE "${OUT}.exit" "${OUT}.log")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env LP_NUM_THREADS=2 "${TIDEPOOL}" ${ARGS} --out "${OUT}"
  WORKING_DIRECTORY "${SOURCE_ROOT}"
  OUTPUT_VARIABLE log
  ERROR_VARIABLE log
  RESULT_VARIABLE code)
file(WRITE "${OUT}.log" "${log}")
file(WRITE "${OUT}.exit" "${code}")
if(NOT code EQUAL 0)
  message(FATAL_ERROR "tidepool ${ARGS} exited ${code}:\n${log}")
endif()
