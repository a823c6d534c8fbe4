#!/usr/bin/env bash
# The main job (README.md): installs dependencies, builds, then validates and renders every
# variant of the default variants.yaml.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" release >/dev/null
cd "$root"
export LP_NUM_THREADS="${LP_NUM_THREADS:-2}"
./build/release/cli/tidepool validate --config variants.yaml --out reports/out/manifest "$@"
./build/release/cli/tidepool render --config variants.yaml --out reports/out/render
