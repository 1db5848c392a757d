#!/usr/bin/env bash
# The main job on the bundled samples: set up, build, cook samples/ into out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
T=build/cli/texproc
mkdir -p out
# Albedo: gamma-correct Gaussian mips in one MIP-mapped TIFF, and per-level PNGs.
$T mip samples/albedo_desert_512.png -o out/albedo_desert_512.tif --wrap repeat --force
$T mip samples/albedo_desert_512.png -o out/levels/albedo_desert_512.png --wrap repeat --force
# Cutout: premultiplied filtering, alpha coverage kept at 0.5.
$T mip samples/cutout_fence_512x256.png -o out/cutout_fence_512x256.tif --alpha-coverage 0.5 --force
# Normal map: renormalized each level. Heightmap: data, no transfer function.
$T mip samples/normal_stein_256.png -o out/normal_stein_256.tif --normal-map --wrap repeat --force
$T mip samples/height_mount_250.png -o out/height_mount_250.exr --linear --force
echo "demo: results are in $(pwd)/out/"
