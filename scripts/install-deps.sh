#!/usr/bin/env bash
# Installs the Debian 12 packages mpsfsi needs to build its tests, examples and benchmarks.
# The library itself needs only Eigen and nanoflann. Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake          # g++ 12, CMake 3.25
  libeigen3-dev libnanoflann-dev # the library's dependencies
  doctest-dev                    # tests
  libbenchmark-dev               # micro-benchmarks
  python3 python3-matplotlib     # plot scripts of the examples
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi

SUDO=""
[ "$(id -u)" -ne 0 ] && SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
