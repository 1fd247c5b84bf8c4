#!/usr/bin/env bash
# Builds everything and runs the default test suite (unit, verification, package, benchmark
# smoke tests). Long validation runs carry the CTest label "validation" and are excluded here:
#   ctest --test-dir build -L validation -LE long   # about 16 minutes on 2 cores
#   ctest --test-dir build -L long                  # the coupled hydrostatic plate at h/l0 = 24, about 50 minutes
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${MPSFSI_CMAKE_ARGS:-}
cmake --build build -j"$(nproc)"
ctest --test-dir build -LE validation --output-on-failure -j"$(nproc)"
