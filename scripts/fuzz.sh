#!/usr/bin/env bash
# Builds the libFuzzer harnesses (tests/fuzz) with clang, ASan and UBSan into
# build-fuzz/, runs the unit tests labelled `sanitized` (the block decoders,
# BPTC, the resampler's SIMD twins) under the same sanitizers, then runs each
# harness for SECONDS (default 60), seeded from samples/ and files texproc
# writes. Usage: scripts/fuzz.sh [SECONDS]
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_EACH=${1:-60}
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTEXPROC_FUZZ=ON \
  -DTEXPROC_BUILD_TESTS=OFF -DTEXPROC_BUILD_BENCH=OFF -DTEXPROC_STATIC_CODECS=OFF >/dev/null
# texproc_exr: the OpenEXR module, built with the same sanitizers; fuzz_images loads it for EXR input.
cmake --build build-fuzz -j "$(nproc)" --target fuzz_containers fuzz_block_decoders fuzz_images fuzz_textures texproc_exr \
  texproc_sanitized_tests
# A subset of the unit tests under ASan and UBSan (the whole suite: scripts/asan.sh).
ASAN_OPTIONS=detect_leaks=0 ctest --test-dir build-fuzz/tests/fuzz -L sanitized --output-on-failure -j "$(nproc)"
# Seeds come from the Release build's texproc (scripts/build.sh).
T=${TEXPROC:-build/cli/texproc}
[ -x "$T" ] || bash scripts/build.sh
S=build-fuzz/seeds
rm -rf "$S"; mkdir -p "$S/containers" "$S/blocks" "$S/images"
cp samples/*.png "$S/images/"
export ASAN_OPTIONS=detect_leaks=0
$T compress samples/normal_stein_256.png -o "$S/containers/a.dds" --format bc5 --mips -q -f
$T compress samples/albedo_desert_512.png -o "$S/containers/b.ktx2" --format bc1 --mips -q -f
$T compress samples/cutout_fence_512x256.png -o "$S/containers/c.ktx" --format etc2a --mips -q -f
$T compress samples/albedo_desert_512.png -o "$S/containers/d.pkm" --format etc1 -q -f
$T compress samples/height_stein_256.png -o "$S/containers/e.astc" --format astc-8x6 --quality fast -q -f
$T compress samples/cutout_fence_512x256.png -o "$S/containers/f.ktx2" --format astc-12x12 --mips --quality fast -q -f
$T mip samples/height_mount_250.png -o "$S/images/h.tif" -q -f
$T sat samples/height_mount_250.png -o "$S/images/h.sat" -q -f
$T mip samples/albedo_desert_512.png -o "$S/images/a.tga" --levels 1 -q -f
# Small OpenEXR seeds (half, float, tiled MIP chain, three compressions) for the EXR module.
oiiotool samples/height_mount_250.png --resize 24x20 -d half --compression zip -o "$S/images/e_zip.exr"
oiiotool samples/albedo_desert_512.png --resize 16x16 -d float --compression piz -o "$S/images/e_piz.exr"
oiiotool samples/albedo_desert_512.png --resize 20x12 -d half --compression rle -o "$S/images/e_rle.exr"
$T mip "$S/images/e_piz.exr" -o "$S/images/e_mip.exr" --type f32 -q -f
head -c 4096 "$S/containers/b.ktx2" > "$S/blocks/seed"
# From here on the harnesses load the sanitized EXR module, not build/'s.
export TEXPROC_EXR_MODULE="$PWD/build-fuzz/cli/texproc_exr.so"
# Each harness with the dictionary of the fields that declare work; a file
# that makes a reader allocate past -rss_limit_mb or work past -timeout is a
# finding, as a crash is.
for entry in containers:containers:textures block_decoders:blocks: images:images:images textures:containers:textures; do
  IFS=: read -r h seeds dict <<<"$entry"
  echo "fuzz.sh: fuzz_$h for ${SECONDS_EACH}s"
  mkdir -p "build-fuzz/corpus_$h"
  dict_arg=()
  [ -n "$dict" ] && dict_arg=(-dict="tests/fuzz/$dict.dict")
  build-fuzz/tests/fuzz/fuzz_$h -max_total_time="$SECONDS_EACH" -max_len=262144 -rss_limit_mb=2048 -timeout=20 \
    "${dict_arg[@]}" -print_final_stats=1 "build-fuzz/corpus_$h" "$S/$seeds" > "build-fuzz/fuzz_$h.log" 2>&1 ||
    { tail -40 "build-fuzz/fuzz_$h.log"; echo "fuzz.sh: fuzz_$h found a crash"; exit 1; }
  grep -E "stat::number_of_executed_units|cov: .*ft:|Done" "build-fuzz/fuzz_$h.log" | tail -3
done
echo "fuzz.sh: no crash"
