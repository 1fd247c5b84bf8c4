#!/usr/bin/env bash
# Installs the Debian 12 packages mpsfsi needs to build its tests, examples and benchmarks.
# The library itself needs only Eigen and nanoflann. Run as root (or with sudo).
set -euo pipefail

packages=(
  build-essential cmake          # g++ 12, CMake 3.25
  libeigen3-dev libnanoflann-dev # the library's dependencies
  doctest-dev                    # tests
  libbenchmark-dev               # micro-benchmarks
  libhypre-dev                   # optional: BoomerAMG PPE solver (mpsfsi::hypre)
  libopenmpi-dev openmpi-bin     # optional: distribution over MPI processes (mpsfsi::mpi; mpirun for its tests)
  libcli11-dev libyaml-cpp-dev   # the examples' command lines and YAML case files
  python3 python3-matplotlib     # the examples' plot scripts
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all packages present"
  exit 0
fi

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null; then
    echo "install-deps: run as root (no sudo here) to install: ${missing[*]}" >&2
    exit 1
  fi
  SUDO=(sudo -n)  # never prompt: CI has no standard input
fi
# Noninteractive through sudo too, so tzdata and friends ask no debconf questions.
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -qq
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
