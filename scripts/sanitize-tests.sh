#!/usr/bin/env bash
# Runs the unit tests of the sanitizer build (build/sanitize, ASan + UBSan) in SHARDS processes
# (default: four per core), each taking its share of the tests through GoogleTest's sharding,
# JOBS of them side by side (default: one per core), instead of one process per test as ctest
# runs them. The few tests that take most of the phase (LONG_TESTS below) each get a process of
# their own, started first, and the shards run without them. Why: GoogleTest deals the tests out
# in turn, so in the CI run of 2026-11-26 the three longest (122, 51 and 26 s of 303 s of CPU)
# all fell in one of the eight shards, which ran 213 s while the other seven took 93 s together.
# With small shards taken from a queue, a core that is done takes the next job. (With the
# libraries at -O1, on the faster host of the next session, the three took 15, 12 and 3 s and
# the whole phase 28 s, where it took 78 s at -O0 on that host.)
# Why: an ASan process costs about 0.3 s of CPU to start (its shadow memory and a 270 MB binary),
# which was most of the phase's time over 678 test processes. The release build's ctest run
# still gives every test a process of its own, so a test that leans on another's leftovers
# shows there.
# Exit codes: 0 all passed, 1 a test failed or a shard crashed (the sanitizer's report is above),
# 2 the binary is missing (run scripts/build.sh sanitize).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
binary="$root/build/sanitize/tests/tidepool_unit_tests"
jobs="${JOBS:-$(nproc)}"
shards="${SHARDS:-$((4 * jobs))}"
if [ ! -x "$binary" ]; then
  echo "sanitize-tests: no $binary; run scripts/build.sh sanitize first" >&2
  exit 2
fi

# The sanitizers' own defaults, as under ctest: ASan stops the process at its first report and
# checks for leaks at exit; UBSan stops at its first (-fno-sanitize-recover=undefined).
logs="$(mktemp -d)"
trap 'rm -rf "$logs"' EXIT
# The longest tests under the sanitizers, longest first (seconds of CPU in that run). A name
# that no longer exists costs nothing: its own process runs no test, and the shards exclude
# nothing for it, so a renamed test still runs in a shard.
long_tests=(
  PairedEstimateTest.NinetyFivePercentIntervalCoversTheTrueEffectUnderMeasuredNoise  # 15 (122 at -O0 in that CI run)
  VariantExpanderTest.PrunedCountsPerRuleEqualABruteForceOnRandomConfigs             # 12 (51)
  PairedEstimateTest.AnEstimateBeyondTheMarginKeepsGoingUntilTheIntervalClearsIt        # 3 (26)
)
without_long="-$(IFS=:; echo "${long_tests[*]}")"
# run_job I: runs job I (a long test, then the shards) into its log and leaves its exit code
# beside it.
run_job() {
  local i="$1" code=0
  # --gtest_brief prints only the failures and the totals; a shard that crashes leaves its
  # sanitizer report in its log. ctest gives one test 600 s; a process here gets 1800 s.
  if [ "$i" -lt "${#long_tests[@]}" ]; then
    timeout 1800 "$binary" --gtest_brief=1 --gtest_filter="${long_tests[$i]}" \
      > "$logs/$i.log" 2>&1 || code=$?
  else
    GTEST_TOTAL_SHARDS="$shards" GTEST_SHARD_INDEX="$((i - ${#long_tests[@]}))" \
      timeout 1800 "$binary" --gtest_brief=1 --gtest_filter="$without_long" \
      > "$logs/$i.log" 2>&1 || code=$?
  fi
  echo "$code" > "$logs/$i.code"
}
job_count=$((${#long_tests[@]} + shards))
running=0
for ((i = 0; i < job_count; ++i)); do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  run_job "$i" &
  running=$((running + 1))
done
wait
status=0
for ((i = 0; i < job_count; ++i)); do
  if [ "$i" -lt "${#long_tests[@]}" ]; then
    echo "-- ${long_tests[$i]}"
  else
    echo "-- shard $((i - ${#long_tests[@]} + 1)) of $shards"
  fi
  if [ "$(cat "$logs/$i.code")" -eq 0 ]; then
    # Passed: its totals only. The whole log would show the sanitizer reports of worker
    # processes that tests crash on purpose (WorkerProcessPoolTest), which are not failures.
    grep -E '^\[(==========|  PASSED  |  SKIPPED )\]' "$logs/$i.log" || true
  else
    status=1
    cat "$logs/$i.log"
  fi
done
if [ "$status" -ne 0 ]; then
  echo "sanitize-tests: a shard failed; its output is above" >&2
fi
exit "$status"
