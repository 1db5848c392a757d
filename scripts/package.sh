#!/usr/bin/env bash
# Builds texproc's Debian package (tool, library and headers, runtime
# modules, Python package) into build-deb/, configured for /usr, and checks
# it (tests/install/deb_test.sh). Install it with `apt install ./build-deb/texproc_*.deb`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build-deb -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DTEXPROC_BUILD_TESTS=OFF -DTEXPROC_BUILD_BENCH=OFF >/dev/null
cmake --build build-deb -j "$(nproc)"
(cd build-deb && cpack -G DEB)
bash tests/install/deb_test.sh build-deb .
