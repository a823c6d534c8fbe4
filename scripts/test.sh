#!/usr/bin/env bash
# The test command (README.md): installs dependencies, checks the format (.clang-format), builds,
# runs every test (unit, gl, cli), then runs the unit tests again under AddressSanitizer +
# UndefinedBehaviorSanitizer, then fuzzes each YAML loader for a minute (FUZZ_SECONDS).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"

echo "== format check (.clang-format)"
"$root/scripts/check-format.sh"

echo "== release build"
"$root/scripts/build.sh" release
echo "== tests (release): unit, gl, cli"
# llvmpipe's thread count is fixed so that GL results do not depend on the machine's core count.
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
(cd "$root/build/release" && ctest --output-on-failure -j 2 --timeout 600)

echo "== sanitizer build (ASan + UBSan)"
"$root/scripts/build.sh" sanitize
echo "== unit tests under ASan + UBSan"
(cd "$root/build/sanitize" && ctest --output-on-failure -j 2 -L unit --timeout 600)

echo "== fuzzing the YAML loaders (libFuzzer, ${FUZZ_SECONDS:-60} s each)"
"$root/scripts/fuzz.sh" "${FUZZ_SECONDS:-60}"
