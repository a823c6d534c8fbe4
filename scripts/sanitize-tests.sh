#!/usr/bin/env bash
# Runs the unit tests of the sanitizer build (build/sanitize, ASan + UBSan) in SHARDS processes
# (default: four per core), each taking its share of the tests through GoogleTest's sharding,
# JOBS of them side by side (default: one per core), instead of one process per test as ctest
# runs them. Why more shards than cores: GoogleTest deals the tests out in turn, so a few long
# tests can land in one shard and leave the other cores idle while it finishes; with small
# shards taken from a queue, a core that is done takes the next shard.
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
# run_shard I: runs shard I into its log and leaves its exit code beside it.
run_shard() {
  local i="$1" code=0
  # --gtest_brief prints only the failures and the totals; a shard that crashes leaves its
  # sanitizer report in its log. The timeout matches ctest's per-test 600 s, for a whole shard.
  GTEST_TOTAL_SHARDS="$shards" GTEST_SHARD_INDEX="$i" \
    timeout 1800 "$binary" --gtest_brief=1 > "$logs/$i.log" 2>&1 || code=$?
  echo "$code" > "$logs/$i.code"
}
running=0
for ((i = 0; i < shards; ++i)); do
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  run_shard "$i" &
  running=$((running + 1))
done
wait
status=0
for ((i = 0; i < shards; ++i)); do
  echo "-- shard $((i + 1)) of $shards"
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
