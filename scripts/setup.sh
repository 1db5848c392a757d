#!/usr/bin/env bash
# Installs what texproc needs to build, test and benchmark on Debian 12, as
# root. Idempotent: installs only the packages that are missing.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(
  build-essential cmake ninja-build pkg-config
  libopenimageio-dev openimageio-tools libopenexr-dev libopencolorio-dev
  libtiff-dev libdeflate-dev libspng-dev libjpeg62-turbo-dev zlib1g-dev libzstd-dev libcli11-dev googletest libgtest-dev libbenchmark-dev libtbb-dev libhwy-dev
  libjsoncpp-dev libtomlplusplus-dev libxxhash-dev
  # the Python package (pybind11, NumPy), its tests (pytest) and its offline pip build
  python3-dev python3-pybind11 pybind11-dev python3-numpy python3-pytest python3-pip python3-setuptools python3-wheel
  # ASTC: ARM's astc-encoder library (dlopen'd on first use) and its CLI, the tests' independent check
  libastcenc-dev astcenc
  # independent checks and peers used by tests and benchmarks
  libnvtt-bin libsquish-dev android-libetc1-dev python3-pil
  # the Bazel rules' test: Debian's Bazel, nginx (WebDAV remote cache), Bazel's RemoteWorker sources and a JDK
  bazel-bootstrap bazel-bootstrap-source nginx default-jdk-headless
  # the libFuzzer harnesses (scripts/fuzz.sh); the format check (ctest Format.Sources)
  clang libclang-rt-14-dev clang-format
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# A second KTX2 parser for the tests, from the npm registry with the machine's own
# node and npm (not installed here: Debian's npm would fight a NodeSource node);
# the test that uses it is skipped if it is absent.
if command -v npm >/dev/null 2>&1 && [ ! -d tests/tools/node_modules/ktx-parse ]; then
  (cd tests/tools && npm install --silent --no-audit --no-fund --no-save ktx-parse@2.0.0 >/dev/null 2>&1) ||
    echo "setup: could not install ktx-parse from npm; its test will be skipped"
fi
echo "setup: all dependencies present"
