#!/usr/bin/env bash
# Builds everything and runs the default test suite (unit, verification, package, benchmark
# smoke tests). Long validation runs carry the CTest label "validation" and are excluded here:
#   ctest --test-dir build -L validation
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release ${MPSFSI_CMAKE_ARGS:-}
cmake --build build -j"$(nproc)"
ctest --test-dir build -LE validation --output-on-failure -j"$(nproc)"
