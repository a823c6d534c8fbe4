#!/usr/bin/env bash
# The test command (README.md): installs dependencies, checks the format (.clang-format), builds,
# runs clang-tidy over the libraries (.clang-tidy, scripts/clang-tidy.sh), runs every test
# (unit, gl, cli), then runs the unit tests again under AddressSanitizer +
# UndefinedBehaviorSanitizer, then fuzzes the YAML loaders and the define walk for a minute
# (FUZZ_SECONDS).
# Each phase ends with its elapsed time, so a slow CI run shows where the time went.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

# The CPU seconds (user + system) of every finished child process of this script so far: the
# cutime and cstime fields of its /proc/<pid>/stat, in clock ticks.
children_cpu() {
  awk -v hz="$(getconf CLK_TCK)" '{ printf "%d\n", ($16 + $17) / hz }' "/proc/$$/stat"
}

# phase NAME COMMAND...: announces NAME, runs COMMAND, then stamps NAME with its seconds and the
# CPU seconds its processes used: on a shared machine the elapsed time depends on the load, the
# CPU time much less, so the two together show whether a slow phase worked more or waited more.
phase() {
  local name="$1" start="$SECONDS" cpu_start
  cpu_start="$(children_cpu)"
  shift
  echo "== $name"
  "$@"
  echo "== $name (took $((SECONDS - start)) s, CPU $(($(children_cpu) - cpu_start)) s)"
}

phase "install dependencies" "$root/scripts/install-deps.sh"
phase "format check (.clang-format)" "$root/scripts/check-format.sh"
phase "release build" "$root/scripts/build.sh" release
phase "clang-tidy over the libraries (.clang-tidy)" "$root/scripts/clang-tidy.sh"
# llvmpipe's thread count is fixed so that GL results do not depend on the machine's core count.
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
phase "tests (release): unit, gl, cli" \
  ctest --test-dir "$root/build/release" --output-on-failure -j 2 --timeout 600
phase "sanitizer build (ASan + UBSan)" "$root/scripts/build.sh" sanitize
phase "unit tests under ASan + UBSan" "$root/scripts/sanitize-tests.sh"
phase "fuzzing the YAML loaders and the define walk (libFuzzer, ${FUZZ_SECONDS:-60} s)" \
  "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"
echo "== all phases passed in $SECONDS s, CPU $(children_cpu) s"
