#!/usr/bin/env bash
# The main job (README.md): installs dependencies, builds, then validates, renders and reports
# every variant of the default variants.yaml (`tidepool run`): reports/out/default/index.html.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" release >/dev/null
cd "$root"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
./build/release/cli/tidepool run --config variants.yaml --out reports/out "$@"
