#!/usr/bin/env bash
# The clang-tidy check (issue 14): runs the root .clang-tidy over every library source file
# (base, stagefiles, compiler, runner, lab, reports, pipeline; their headers through
# HeaderFilterRegex) with the compile commands of build/release, two compiles at a time. Any
# finding fails it (WarningsAsErrors). Needs a configured build/release (scripts/build.sh release).
#
# Where the build compiles a library's files in unity batches (a fresh clone, CI: see
# cmake/TidepoolPrecompiledHeaders.cmake), clang-tidy checks each batch as one translation unit:
# the headers every file includes (the standard library, fmt, nlohmann/json, glslang) are then
# parsed and matched once per batch instead of once per file, which took the check from 36 to 13
# CPU seconds over reports/ (2026-11-26). The batch files are CMake's own, with the compile
# flags the build used. Diagnostics in a library file still name that file and line (the files are
# inside HeaderFilterRegex); the line filter drops those located in the generated batch file
# itself, which are bugprone-suspicious-include firing on the batch's own #include of each .cpp.
# A build without unity batches (ccache) is checked file by file, as before.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/release}"
jobs="${TIDY_JOBS:-2}"
db_dir="$build/clang-tidy"

for tool in clang-tidy-14 run-clang-tidy-14 python3; do
  if ! command -v "$tool" >/dev/null; then
    echo "clang-tidy: $tool is missing; run scripts/install-deps.sh" >&2
    exit 2
  fi
done
if [ ! -f "$build/compile_commands.json" ]; then
  echo "clang-tidy: no $build/compile_commands.json; run scripts/build.sh release first" >&2
  exit 2
fi

cd "$root"
mapfile -t sources < <(ls base/src/*.cpp stagefiles/src/*.cpp compiler/src/*.cpp runner/src/*.cpp \
  runner/src/gl/*.cpp lab/src/*.cpp reports/src/*.cpp pipeline/src/*.cpp \
  pipeline/src/rendering/*.cpp)

# The library files' entries of the release build's compile database, without GCC's precompiled
# header (TIDEPOOL_FAST_COLD_BUILD, when no compiler launcher is set): clang cannot read a GCC
# .gch and fails on it; the header only collects standard and fmt headers every file includes
# itself. A unity_*.cxx made only of library files is checked whole; a file of one that also
# holds other files gets that entry's command with the unity file replaced by its own path:
# CMake puts a file in a unity file only when it has no flags of its own, so the command is the
# one the file would have had. A library file missing from the database is an error rather than
# a file silently left unchecked.
mkdir -p "$db_dir"
python3 - "$build/compile_commands.json" "$db_dir/compile_commands.json" "$root" "${sources[@]}" <<'EOF'
import json, os, re, shlex, sys

source_db, target_db, root, sources = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
wanted = {os.path.join(root, s) for s in sources}


# (file, command) for each file an entry compiles: its own, or each file its unity file includes.
def units_of(entry):
    """The translation units to check for one compile: (file, arguments, library files it
    covers). A unity batch made only of wanted files is one unit; otherwise each file is."""
    path = os.path.normpath(os.path.join(entry["directory"], entry["file"]))
    words = entry["arguments"] if "arguments" in entry else shlex.split(entry["command"])
    if not re.search(r"/Unity/unity_[^/]*\.cxx$", path):
        return [(path, words, [path])]
    included = [os.path.normpath(f) for f in
                re.findall(r'^#include "([^"]+)"$', open(path).read(), re.MULTILINE)]
    if included and all(f in wanted for f in included):
        return [(path, words, included)]
    return [(f, [f if w == entry["file"] else w for w in words], [f]) for f in included]


# "-include <dir>/cmake_pch.hxx" and -Winvalid-pch go; everything else stays.
def without_pch(words):
    cleaned = []
    i = 0
    while i < len(words):
        if words[i] == "-include" and i + 1 < len(words) and words[i + 1].endswith("cmake_pch.hxx"):
            i += 2
            continue
        if words[i] != "-Winvalid-pch":
            cleaned.append(words[i])
        i += 1
    return cleaned


entries = []
missing = set(wanted)
for entry in json.load(open(source_db)):
    for path, words, covered in units_of(entry):
        if all(f in missing for f in covered):
            entries.append({"directory": entry["directory"], "file": path,
                            "arguments": without_pch(words)})
            missing.difference_update(covered)
if missing:
    sys.exit("clang-tidy: not in the compile database: " + ", ".join(sorted(missing)))
json.dump(entries, open(target_db, "w"), indent=1)
EOF

units="$(python3 -c 'import json, sys; print(len(json.load(open(sys.argv[1]))))' \
  "$db_dir/compile_commands.json")"
echo "clang-tidy: ${#sources[@]} library files in $units translation units, $jobs at a time"
# Every unit of the database above; -quiet prints findings only, and any finding fails the run
# (WarningsAsErrors: '*'). The line filter keeps findings in .cpp and .h files, which drops only
# those in a generated unity_*.cxx (see the top).
run-clang-tidy-14 -clang-tidy-binary "$(command -v clang-tidy-14)" -p "$db_dir" -j "$jobs" -quiet \
  -line-filter='[{"name": ".cpp"}, {"name": ".h"}]'
