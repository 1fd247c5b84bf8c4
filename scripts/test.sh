#!/usr/bin/env bash
# Builds everything and runs the default test suite (unit, verification, examples, quick start,
# package, benchmark smoke tests). Long validation runs carry the CTest label "validation" and are
# excluded here:
#   ctest --test-dir build -L validation -LE long   # about 45 minutes on 2 cores
#   ctest --test-dir build -L long                  # the coupled plate at h/l0 = 24, the 3D bending beam and the loaded floating beam, about 50-60 minutes
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${MPSFSI_CMAKE_ARGS:-}
cmake --build build -j"$(nproc)"
ctest --test-dir build -LE validation --output-on-failure -j"$(nproc)"
