#!/usr/bin/env bash
# Installs the build and test dependencies of cmt from Debian 12 packages. Idempotent; run as root (or with sudo).
set -euo pipefail
packages=(
  build-essential cmake ccache pkg-config clang-format
  libmujoco-dev libeigen3-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libpng-dev
  libbenchmark-dev libgtest-dev libgmock-dev
  libpolyclipping-dev libyaml-cpp-dev nlohmann-json3-dev libcli11-dev libtbb-dev libsqlite3-dev libfmt-dev
  libopenmpi-dev openmpi-bin
  libjs-three chromium  # the 3-D pages (cmt view, cmt report) and their browser test
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ "${#missing[@]}" -gt 0 ]; then
  sudo_cmd=""
  [ "$(id -u)" -ne 0 ] && sudo_cmd="sudo"
  $sudo_cmd apt-get update
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y --no-install-recommends "${missing[@]}"
fi
