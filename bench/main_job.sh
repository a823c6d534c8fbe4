#!/usr/bin/env bash
# Benchmark (issue 11): the main job as a user runs it, `tidepool run` on the default
# variants.yaml (install and build excluded), once as the machine is and once with two
# CPU-bound processes competing (`yes`). Prints the wall time of each run with the share of
# each stage and the report's size, and the two runs' whitepaper verdicts side by side. Figures
# only.
# Usage: [COMPETITORS=N] bench/main_job.sh [BUILD_DIR (build/release)] [extra `run` flags...]
# COMPETITORS: how many `yes` processes compete in the loaded run (default 2, as the issue's
# target says; 4 shows a load heavier than the one the targets name).
# COMPETITOR: the competing command instead of `yes`, run through `sh -c`: for example
# 'exec dd if=/dev/zero of=/dev/null bs=32M', which also streams memory through the caches that
# llvmpipe's frames use (a load of another shape than `yes`, which touches almost no memory).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/release}"
shift || true
extra=("$@")
tidepool="$build/cli/tidepool"
out="$(mktemp -d /tmp/tidepool-mainjob.XXXXXX)"
cd "$root"

run_once() {  # LABEL
  local start end
  start=$(date +%s%N)
  "$tidepool" run --config variants.yaml --out "$out/$1" --progress-log "$out/$1.progress.jsonl" \
      "${extra[@]}" > "$out/$1.stdout" 2> "$out/$1.log" || true
  end=$(date +%s%N)
  echo "$(( (end - start) / 1000000 ))" > "$out/$1.ms"
}

stages() {  # LABEL DESCRIPTION
  python3 - "$out/$1.log" "$out/$1.stdout" "$(cat "$out/$1.ms")" "$1" "$2" "$out/$1/default" <<'PY'
import os, re, sys
log, stdout, total_ms, label, what = open(sys.argv[1]).read(), open(sys.argv[2]).read(), \
    int(sys.argv[3]), sys.argv[4], sys.argv[5]
report_dir = sys.argv[6]
total = total_ms / 1000
found = {
    "render": re.search(r"^render: \d+ configurations, \d+ failed, (\d+) s", log, re.M),
    # The stability catalogue and the scene plans are one stage of wall time, run in a second
    # process beside the render: its seconds overlap the render's and are not added up.
    "stability+plans": re.search(r"^stability and plans: (\d+) s.*$", log, re.M),
    # Then the second process takes configurations and comparisons off the render's list.
    "units beside": re.search(r"^units beside the render: .*, (\d+) s$", log, re.M),
    "report": re.search(r"written in ([\d.]+) s", stdout),
}
print(f"{label} ({what}): {total:.0f} s wall in all")
accounted = 0.0
for stage, m in found.items():
    if m:
        seconds = float(m.group(m.lastindex))
        beside = "beside the render" in m.group(0)
        if not beside:
            accounted += seconds
        print(f"  {stage:<15} {seconds:7.1f} s  {100 * seconds / total:5.1f}%"
              + ("  (beside the render, not added)" if beside else ""))
print(f"  {'validate, start-up and the rest':<15} {total - accounted:7.1f} s  "
      f"{100 * (total - accounted) / total:5.1f}%")
# The report's size (issue 14): report.md under 300 KB, index.html under 6 MB.
for name, limit_kb in (("report.md", 300), ("index.html", 6 * 1024)):
    path = os.path.join(report_dir, name)
    if os.path.exists(path):
        kb = os.path.getsize(path) / 1024
        print(f"  {name:<15} {kb:9.0f} KB (target under {limit_kb} KB: "
              f"{'met' if kb < limit_kb else 'NOT met'})")
# The render's progress lines against what happened: each line's predicted render end
# (elapsed + ETA) and percentage against the render's real end, over lines after the first 10%.
def duration_s(text):
    m = re.fullmatch(r"(?:(\d+)m)?(\d+)s", text)
    return int(m.group(1) or 0) * 60 + int(m.group(2)) if m else None
render = found["render"]
if render:
    render_s = float(render.group(1))
    eta_errors, percent_errors = [], []
    for m in re.finditer(r"^\[\s*(\d+)%\] .*\(elapsed (\S+), ETA (\S+)\)$", log, re.M):
        elapsed, eta = duration_s(m.group(2)), duration_s(m.group(3))
        if elapsed is None or eta is None or elapsed < 0.1 * render_s:
            continue
        eta_errors.append(abs(elapsed + eta - render_s) / render_s * 100)
        percent_errors.append(abs(int(m.group(1)) - 100 * elapsed / render_s))
    if eta_errors:
        print(f"  progress after the first 10% of the render ({len(eta_errors)} lines): predicted "
              f"end off by at most {max(eta_errors):.1f}% (median {sorted(eta_errors)[len(eta_errors) // 2]:.0f}%), "
              f"percentage off by at most {max(percent_errors):.0f} points (target: within 20%)")
PY
}

quiet_load=$(cut -d' ' -f1-3 /proc/loadavg)
run_once quiet
competitors="${COMPETITORS:-2}"
pids=()
for _ in $(seq "$competitors"); do
  if [[ -n "${COMPETITOR:-}" ]]; then
    sh -c "$COMPETITOR" > /dev/null 2>&1 & pids+=($!)
  else
    yes > /dev/null & pids+=($!)
  fi
done
trap 'kill "${pids[@]}" 2>/dev/null || true' EXIT
sleep 2
loaded_load=$(cut -d' ' -f1-3 /proc/loadavg)
run_once loaded
kill "${pids[@]}" 2>/dev/null || true
trap - EXIT

echo "targets: <= 150 s quiet, <= 300 s with two competing processes, report <= 5 s"
stages quiet "load average before: $quiet_load"
stages loaded "$competitors ${COMPETITOR:-yes} processes; load average after 2 s: $loaded_load"
echo
python3 "$root/bench/compare_verdicts.py" quiet "$out/quiet/default/data.json" \
    loaded "$out/loaded/default/data.json"
echo
python3 - "$out/quiet/render/plans.json" "$out/loaded/render/plans.json" <<'PY'
import json, sys
a, b = (json.load(open(p))["plans"] for p in sys.argv[1:3])
same = 0
print("scene plans (chosen configuration), quiet vs loaded:")
for pa, pb in zip(a, b):
    ca = pa.get("chosen", {}).get("id", "-")
    cb = pb.get("chosen", {}).get("id", "-")
    same += ca == cb
    print(f"  {pa['scene']:<16} {'same' if ca == cb else 'DIFFERENT'}: {ca}" +
          ("" if ca == cb else f" vs {cb}"))
print(f"same plan for {same} of {len(a)} scenes (target: all)")
PY
echo
echo "outputs in $out/{quiet,loaded}/; every progress state, with the figures behind its ETA, in"
echo "$out/{quiet,loaded}.progress.jsonl"
