#!/usr/bin/env bash
# The test command (README.md): installs dependencies, checks the format (.clang-format), builds,
# runs clang-tidy over the libraries (.clang-tidy, scripts/clang-tidy.sh), runs every test
# (unit, gl, cli), then runs the unit tests again under AddressSanitizer +
# UndefinedBehaviorSanitizer, then fuzzes each YAML loader for a minute (FUZZ_SECONDS).
# Each phase ends with its elapsed time, so a slow CI run shows where the time went.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"

# phase NAME COMMAND...: announces NAME, runs COMMAND, then stamps NAME with its seconds.
phase() {
  local name="$1" start="$SECONDS"
  shift
  echo "== $name"
  "$@"
  echo "== $name (took $((SECONDS - start)) s)"
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
phase "fuzzing the YAML loaders (libFuzzer, ${FUZZ_SECONDS:-60} s each)" \
  "$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"
echo "== all phases passed in $SECONDS s"
