#!/usr/bin/env bash
# Installs the build dependencies (Debian 12 packages) and builds Sablier in
# build/ (Release). Safe to run again.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(build-essential cmake pkg-config libeigen3-dev libtomlplusplus-dev libcli11-dev
          libfmt-dev libgtest-dev libbenchmark-dev libpng-dev zlib1g-dev
          python3-vtk9   # the test that VTK reads our files
          python3-matplotlib   # scripts/validation_figures.py and its test
          imagemagick ffmpeg)  # sablier render --gif / --mp4, and their test
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  echo "installing: ${missing[*]}"
  $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get update -q
  $sudo_cmd env DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends "${missing[@]}"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "$(nproc)"
