#!/usr/bin/env bash
# Configures and builds one flavour of tidepool: `release` (build/release) or `sanitize`
# (build/sanitize: AddressSanitizer + UndefinedBehaviorSanitizer, the libraries at -O1 with
# libFuzzer's coverage, compiled by clang: the unit tests and the fuzzers).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
flavour="${1:-release}"
jobs="$(nproc)"
case "$flavour" in
  release)  dir="$root/build/release";  flags=(-DCMAKE_BUILD_TYPE=Release -DTIDEPOOL_WERROR=ON); targets=() ;;
  # The sanitizer build exists for the unit tests and the fuzzers (scripts/fuzz.sh), so only they
  # are built there, by clang: libFuzzer needs it, and an instrumented file costs it about half
  # the CPU it costs GCC (ReportModel.cpp at -O0: 8.9 s against 17.0 s). Building the fuzzers
  # here rather than in a build of their own saved the test command about 50 s of its 294 s for
  # these three phases (2026-11-26).
  sanitize) dir="$root/build/sanitize"; flags=(-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=Debug -DTIDEPOOL_SANITIZE=ON -DTIDEPOOL_FUZZ=ON -DTIDEPOOL_WERROR=ON -DTIDEPOOL_BUILD_BENCH=OFF)
            targets=(--target tidepool_unit_tests VariantConfigFuzzer SceneDescriptionFuzzer
                     DefineRelevanceFuzzer) ;;
  *) echo "usage: $0 [release|sanitize]" >&2; exit 2 ;;
esac
cmake -S "$root" -B "$dir" -G Ninja "${flags[@]}" >/dev/null
cmake --build "$dir" -j "$jobs" "${targets[@]}"
