#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (CTest over GoogleTest).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh -DTEXPROC_WERROR=ON  # CI: a warning fails the build
# The readers and decoders under libFuzzer with ASan and UBSan, 10 s each
# (scripts/fuzz.sh SECONDS runs them longer).
bash scripts/fuzz.sh 10
cd build
ctest --output-on-failure -j "$(nproc)"
