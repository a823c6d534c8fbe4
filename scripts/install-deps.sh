#!/usr/bin/env bash
# Installs every Debian 12 package tidepool needs to build, test and run.
# Both README commands call this script, so a fresh machine and CI install the same set.
# Skips apt entirely when everything is already present (fast re-runs).
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config git
  glslang-dev glslang-tools          # glslang as a library; glslangValidator for the benchmark
  libyaml-cpp-dev                    # variants.yaml
  nlohmann-json3-dev                 # manifest / results JSON
  libcli11-dev                       # argument parsing
  libfmt-dev                         # formatting
  libpng-dev                         # PNG images
  libglm-dev                         # CPU-side matrix math
  libgtest-dev googletest            # tests
  libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev   # Mesa: EGL surfaceless + OSMesa
  chromium                           # headless browser: the report page test opens index.html
  clang libclang-rt-14-dev           # libFuzzer targets in fuzz/ (scripts/fuzz.sh)
  clang-format                       # the format check (scripts/check-format.sh)
  clang-tidy                         # the libraries' clang-tidy check (scripts/clang-tidy.sh)
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
