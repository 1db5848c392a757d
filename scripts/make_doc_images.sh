#!/usr/bin/env bash
# Regenerates the pictures in docs/images/ from samples/ (needs a build and
# openimageio-tools for oiiotool and maketx).
set -euo pipefail
cd "$(dirname "$0")/.."
T=build/cli/texproc
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
IMG=docs/images

# 1. Gamma: left half a one-texel black/white checkerboard, right half flat
#    sRGB 188 (the checkerboard's true average). Level 3, shown 8x.
oiiotool --pattern checker:width=1:height=1:color1=0,0,0:color2=1,1,1 64x128 3 \
         --pattern constant:color=0.7373,0.7373,0.7373 64x128 3 --mosaic 2x1 -d uint8 -o "$W/gamma.png" >/dev/null
$T mip "$W/gamma.png" -o "$W/g/tp.png" --wrap repeat -q --force
maketx --filter gaussian "$W/gamma.png" -o "$W/mk.tif" >/dev/null
oiiotool "$W/mk.tif" --selectmip 3 -o "$W/mk3.png" >/dev/null
oiiotool "$W/g/tp_mip3.png" --resample:interp=0 128x128 "$W/mk3.png" --resample:interp=0 128x128 \
         --mosaic:pad=8 2x1 -d uint8 -o $IMG/mip_gamma_texproc_vs_maketx.png >/dev/null

# 2. Cutout: level 3 of the fence over grey, with and without --alpha-coverage 0.5.
$T mip samples/cutout_fence_512x256.png -o "$W/c/plain.png" -q --force
$T mip samples/cutout_fence_512x256.png -o "$W/c/cov.png" --alpha-coverage 0.5 -q --force
for n in plain cov; do
  oiiotool --pattern constant:color=0.5,0.6,0.7,1 64x32 4 -d uint8 -o "$W/bg.png" >/dev/null
  oiiotool "$W/c/${n}_mip3.png" --ch R,G,B,A "$W/bg.png" --over --ch R,G,B --resample:interp=0 256x128 -o "$W/c_$n.png" >/dev/null
done
oiiotool "$W/c_plain.png" "$W/c_cov.png" --mosaic:pad=8 2x1 -d uint8 -o $IMG/mip_alpha_coverage.png >/dev/null

# 3. Filters: level 3 of the desert albedo with box, gaussian, lanczos3, mitchell.
for f in box gaussian lanczos3 mitchell; do
  $T mip samples/albedo_desert_512.png -o "$W/f/$f.png" --filter $f --levels 4 -q --force
  oiiotool "$W/f/${f}_mip3.png" --resample:interp=0 192x192 -o "$W/f_$f.png" >/dev/null
done
oiiotool "$W/f_box.png" "$W/f_gaussian.png" "$W/f_lanczos3.png" "$W/f_mitchell.png" --mosaic:pad=8 4x1 \
         -d uint8 -o $IMG/mip_filters.png >/dev/null
# 4. Normal-map kernels side by side on the Stellarium wall heightmap (256x256).
ks="gather2x2 central sobel3 sobel5 prewitt3 prewitt5 scharr3 multiscale"
for k in $ks; do
  $T normalmap samples/height_stein_256.png -o "$W/nm_$k.png" --kernel $k --height-channel r --height-scale 16 -q --force
done
oiiotool samples/height_stein_256.png --ch R,R,R -o "$W/nm_height.png" >/dev/null
$T normalmap samples/height_stein_256.png -o "$W/nm_down.png" --y down --height-channel r --height-scale 16 -q --force
oiiotool "$W/nm_height.png" "$W/nm_down.png" samples/normal_stein_256.png --mosaic:pad=8 3x1 -d uint8 \
         -o $IMG/normalmap_vs_shipped.jpg >/dev/null
oiiotool $(for k in $ks; do echo "$W/nm_$k.png"; done) --mosaic:pad=8 4x2 -d uint8 -o $IMG/normalmap_kernels.jpg >/dev/null
# 5. Variable-radius box blur: a radius map rising from 0 (left) to 1 (right).
oiiotool --pattern fill:left=0:right=1 512x512 1 -d uint8 -o "$W/rmap.png" >/dev/null
$T sat blur samples/albedo_desert_512.png -o "$W/blurred.png" --radius 16 --radius-map "$W/rmap.png" --wrap repeat -q --force
oiiotool "$W/rmap.png" --ch 0,0,0 -o "$W/rmap3.png" >/dev/null
oiiotool samples/albedo_desert_512.png "$W/rmap3.png" "$W/blurred.png" --mosaic:pad=8 3x1 --resize 50% -d uint8 \
         -o $IMG/sat_blur_radius_map.jpg >/dev/null
# 6. Cone map preview: linear search (64 steps), cone stepping and relaxed cone stepping, and their lookup heat maps.
$T conemap samples/height_stein_256.png --height-channel r --depth 0.08 -o "$W/cone.png" \
   --preview "$W/cone_preview.png" --preview-size 256 --view-angle 50 -q --force
oiiotool "$W/cone_preview.png" -d uint8 -o $IMG/conemap_preview.jpg >/dev/null
echo "wrote $IMG/mip_*.png $IMG/normalmap_*.jpg $IMG/sat_*.jpg $IMG/conemap_*.jpg"
