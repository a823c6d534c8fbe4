#!/usr/bin/env bash
# The main job (README.md): installs dependencies, builds, then validates, renders and reports
# every variant of the default variants.yaml (`tidepool run`): reports/out/default/index.html.
# Extra arguments go to `tidepool run` (see `tidepool run --help`).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/install-deps.sh"
echo "== building tidepool (release; the first build takes a few minutes)"
"$root/scripts/build.sh" release
cd "$root"
echo "== tidepool run (progress on stderr; the report goes to reports/out/default/)"
./build/release/cli/tidepool run --config variants.yaml --out reports/out "$@"
