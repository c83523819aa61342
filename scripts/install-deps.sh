#!/usr/bin/env bash
# Installs every Debian package pba needs to build, test, render and plot (and the NumPy and Numba
# of bench/peers, whose validation is a test, and Bullet, the pile's peer). Idempotent.
# Run as root (or through sudo) on Debian 12.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git ccache
  libglm-dev libglfw3-dev libepoxy-dev libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  libimgui-dev libstb-dev nlohmann-json3-dev libcli11-dev libfmt-dev libspdlog-dev libtbb-dev
  libqhull-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  xvfb xauth ffmpeg gnuplot-nox
  clang-14 libfuzzer-14-dev libclang-rt-14-dev
  python3-numba python3-numpy
  libbullet-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
echo "install-deps: installing ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
