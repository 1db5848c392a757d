#!/usr/bin/env bash
# Builds the asan preset (RelWithDebInfo, AddressSanitizer + UBSan; build-asan/)
# and runs the whole test suite under it. Slow (about 30 minutes of build on
# two cores), so CI runs the fuzzers and the `sanitized` subset of the tests
# (scripts/fuzz.sh) instead, and this is run by hand before
# a release or after touching the encoders: scalar and SIMD bytes must agree
# here as in Release (GCC 12.2 once miscompiled an index under UBSan; see
# bc1_lanes_simd.cpp's nudge). Usage: scripts/asan.sh [ctest args]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset asan >/dev/null
cmake --build build-asan -j "$(nproc)"
cd build-asan && ctest -j "$(nproc)" --output-on-failure "$@"
