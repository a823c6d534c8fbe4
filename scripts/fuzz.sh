#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) in the sanitizer build (scripts/build.sh sanitize, which
# the test command has already run) and runs each for SECONDS (default 60), seeded with the
# shipped variants.yaml, scenes/*.yaml and shaders. The corpus grows in build/fuzz/corpus/<target>/ across
# runs; crashes, hangs and leaks land in build/fuzz/artifacts/ and make the script fail. The
# binaries are build/sanitize/fuzz/<target>. README.md ("Fuzzing") describes a longer
# corpus-growing run.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-60}"
dir="$root/build/fuzz"

if ! ls /usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a >/dev/null 2>&1; then
  echo "fuzz: clang's libFuzzer runtime is missing; run scripts/install-deps.sh" >&2
  exit 3
fi

"$root/scripts/build.sh" sanitize
binaries="$root/build/sanitize/fuzz"

status=0
run() {
  local target="$1"; shift
  local corpus="$dir/corpus/$target" failed=0
  mkdir -p "$corpus" "$dir/artifacts"
  cp "$@" "$corpus/"   # the shipped files are always part of the seed corpus
  echo "== $target: ${seconds}s"
  # -timeout: one input taking 10 s is a hang; -rss_limit_mb: 2 GB is an allocation bomb.
  if ! "$binaries/$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -print_final_stats=1 -artifact_prefix="$dir/artifacts/$target-" 2>"$dir/$target.log"; then
    echo "fuzz: $target found a failure; see $dir/$target.log and $dir/artifacts/" >&2
    failed=1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^#[0-9]+ *DONE" "$dir/$target.log" || true
  return "$failed"
}
# The targets run side by side: each fuzzer is one process on one core, so on the 2-core CI
# machine this keeps the phase's wall time at SECONDS (max_total_time is wall time), each target
# getting two thirds of a core.
pids=()
# The define walk's inputs are a define list on the first line, then a shader: each shipped
# shader under no defines and under a few of the water shader's.
seeds="$dir/seeds/DefineRelevanceFuzzer"
rm -rf "$seeds" && mkdir -p "$seeds"
for shader in "$root"/shaders/*.vsh "$root"/shaders/*.fsh; do
  name="$(basename "$shader")"
  { echo; cat "$shader"; } > "$seeds/none-$name"
  { echo "ENABLE_FOG ENABLE_FRESNEL ENABLE_REFRACTION REFLECTION_FOURIER"; cat "$shader"; } \
    > "$seeds/some-$name"
done
run VariantConfigFuzzer "$root/variants.yaml" & pids+=($!)
run SceneDescriptionFuzzer "$root"/scenes/*.yaml & pids+=($!)
run DefineRelevanceFuzzer "$seeds"/* & pids+=($!)
for pid in "${pids[@]}"; do
  wait "$pid" || status=1
done
exit "$status"
