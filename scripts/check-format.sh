#!/usr/bin/env bash
# The format check (issue 14): every tracked C++ file must be as the root .clang-format lays it
# out. Prints the files that differ and exits 1; fix them with
#   git ls-files '*.cpp' '*.h' | xargs clang-format -i
# or only the lines you changed with `git clang-format`.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
if ! command -v clang-format >/dev/null; then
  echo "check-format: clang-format is missing; run scripts/install-deps.sh" >&2
  exit 2
fi
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ ${#files[@]} -eq 0 ]; then
  # Not a git checkout (a source tarball): check what is there.
  mapfile -t files < <(find . -path ./build -prune -o \( -name '*.cpp' -o -name '*.h' \) -print)
fi
# One clang-format per file, as many side by side as there are cores (the files are independent);
# each prints the name of a file that differs.
mapfile -t bad < <(printf '%s\0' "${files[@]}" | xargs -0 -n 16 -P "$(nproc)" sh -c '
  for f; do clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || echo "$f"; done' check | sort)
if [ ${#bad[@]} -ne 0 ]; then
  echo "check-format: ${#bad[@]} of ${#files[@]} files differ from .clang-format:" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "fix: clang-format -i FILE... (or git clang-format for your change only)" >&2
  exit 1
fi
echo "check-format: ${#files[@]} files as .clang-format lays them out"
