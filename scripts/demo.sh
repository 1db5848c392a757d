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
# Normal map from the height map (OpenGL green), with its renormalized chain, as BC5 too.
$T normalmap samples/height_stein_256.png -o out/normal_from_height_256.png --height-channel r --height-scale 16 --force
$T compress out/normal_from_height_256.png -o out/normal_from_height_256_bc5.ktx2 --format bc5 --mips --normal-map --wrap repeat --force
# Albedo and cutout block-compressed with mips; the cutout's hidden colour bled.
$T compress samples/albedo_desert_512.png -o out/albedo_desert_512_bc1.dds --format bc1 --mips --wrap repeat --force
$T compress samples/cutout_fence_512x256.png -o out/cutout_fence_bc3.dds --format bc3 --mips --transparent-color bleed --force
# Summed-area table and a box query; a cone map with its preview.
$T sat samples/height_mount_250.png -o out/height_mount_250.sat --force
$T sat query out/height_mount_250.sat 0 0 250 250 --json
$T conemap samples/height_stein_256.png -o out/cone_stein_256.png --height-channel r --depth 0.08 \
   --preview out/cone_stein_256_preview.png --force
# Environment map: a cube texture with seamless mips; GGX specular and irradiance IBL, SH, a preview.
$T cubemap samples/sky_forest_512x256.exr -o out/sky_forest.ktx2 --mips --force
$T cubemap samples/sky_forest_512x256.exr -o out/sky_forest_specular.ktx2 --ibl both --sh out/sky_forest_sh.json \
   --preview out/sky_forest_preview.png --force
$T info out/albedo_desert_512_bc1.dds out/normal_from_height_256_bc5.ktx2
# The build-system way: samples/Makefile cooks every sample with depfiles
# (run it again and nothing is redone).
make -s -C samples TEXPROC="$(realpath "$T")" OUT="$(pwd)/out/cooked"
# The same samples from the version-controlled recipe, two files at a time, with a JSON report.
$T build samples/recipe.toml --out-dir out/recipe -j 2 --force --json > out/recipe-report.json
$T compare samples/albedo_desert_512.png out/recipe/textures/albedo_desert_512.dds --ssim --min-psnr 30
echo "demo: results are in $(pwd)/out/ (samples/Makefile: out/cooked/, samples/recipe.toml: out/recipe/)"
