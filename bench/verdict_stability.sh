#!/usr/bin/env bash
# Benchmark (issue 11): do the whitepaper verdicts survive load? Renders the compared presets
# twice, once as the machine is and once with two CPU-bound processes competing (`yes`), builds
# a report of each and prints both tables side by side with the verdict agreement, the
# contradictions and each row's interval width. Figures only, never pass/fail.
# Usage: bench/verdict_stability.sh [BUILD_DIR (build/release)] [extra `render` flags...]
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/release}"
shift || true
extra=("$@")
tidepool="$build/cli/tidepool"
out="$(mktemp -d /tmp/tidepool-verdicts.XXXXXX)"
cd "$root"

presets=$(python3 - <<'PY'
import re
# Every preset the report compares: the presets section of variants.yaml, minus none.
text = open("variants.yaml").read()
block = text.split("\npresets:", 1)[1]
print(" ".join(f"--preset {m}" for m in re.findall(r"^  ([a-z0-9_]+):\s*$", block, re.M)))
PY
)

"$tidepool" validate --out "$out/manifest" >/dev/null
run_once() {  # LABEL
  local start end label="$1" load="$2"
  shift 2
  start=$(date +%s)
  # shellcheck disable=SC2086
  "$tidepool" render $presets --view three_quarter --out "$out/$label/render" "${extra[@]}" \
      2> "$out/$label.log" >/dev/null || true
  end=$(date +%s)
  "$tidepool" report --manifest "$out/manifest/manifest.json" \
      --results "$out/$label/render/results.json" --out "$out/$label" --name report \
      >/dev/null 2>>"$out/$label.log"
  echo "$label: render $((end - start)) s (load average before: $load)"
}

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
run_once quiet "$load_before"
yes > /dev/null & y1=$!
yes > /dev/null & y2=$!
trap 'kill $y1 $y2 2>/dev/null || true' EXIT
sleep 2
run_once loaded "$(cut -d' ' -f1-3 /proc/loadavg), plus two yes"
kill $y1 $y2 2>/dev/null || true
trap - EXIT

echo
python3 "$root/bench/compare_verdicts.py" quiet "$out/quiet/report/data.json" \
    loaded "$out/loaded/report/data.json"
echo
echo "reports in $out/{quiet,loaded}/report/"
