#!/usr/bin/env bash
# SHA-256 of what texproc writes for a fixed set of inputs and options: every
# compress format at every quality (max on a 64x64 crop; BC7 too; BC6H on the sample sky), with and without
# mips, and mip, normalmap, conemap and sat. A restructuring that keeps these
# hashes changed no byte. Usage:
#   scripts/output_hashes.sh [--texproc PATH]            print the hashes
#   scripts/output_hashes.sh [--texproc PATH] --check    compare with tests/data/output_hashes.txt
#   scripts/output_hashes.sh [--texproc PATH] --update   rewrite that file
set -euo pipefail
cd "$(dirname "$0")/.."
T=build/cli/texproc
mode=print
while [ $# -gt 0 ]; do
  case "$1" in
    --texproc) T=$2; shift 2 ;;
    --check) mode=check; shift ;;
    --update) mode=update; shift ;;
    *) echo "output_hashes.sh: unknown argument $1" >&2; exit 1 ;;
  esac
done
T=$(realpath "$T")
W=$(mktemp -d)
trap 'rm -rf "$W"' EXIT
O=$W/out
mkdir -p "$O"
S=samples
# The 64x64 crops for `max`, cut with Pillow (not with texproc, whose own
# output is what is being checked).
/usr/bin/python3 - "$S" "$W" <<'PY'
import sys
from PIL import Image
s, w = sys.argv[1], sys.argv[2]
Image.open(f"{s}/albedo_desert_512.png").crop((200, 136, 264, 200)).save(f"{w}/crop.png")
Image.open(f"{s}/cutout_fence_512x256.png").crop((100, 80, 164, 144)).save(f"{w}/crop_alpha.png")
PY
formats="bc1 bc1a bc2 bc3 bc4 bc4s bc5 bc5s etc1 etc2 etc2a1 etc2a eac-r11 eac-r11s eac-rg11 eac-rg11s"
# Builds from before ASTC hash the rest (to compare with the lines they share).
astc=false
help=$("$T" compress --help)
if [[ $help == *astc-4x4* ]]; then astc=true; formats="$formats astc-4x4 astc-8x8"; fi
if [[ $help == *" bc7;"* || $help == *" bc7,"* ]]; then formats="$formats bc7"; fi  # builds from before BC7 encoding lack it
run() { "$T" "$@" -q -f --threads 2; }
for f in $formats; do
  ext=.ktx2
  for q in fast normal high; do
    run compress "$S/albedo_desert_512.png" -o "$O/albedo_${f}_$q$ext" --format "$f" --quality "$q"
    run compress "$S/cutout_fence_512x256.png" -o "$O/cutout_${f}_$q$ext" --format "$f" --quality "$q"
  done
  case "$f" in astc-*) ;; *)  # max: the widest search, on crops (ASTC's exhaustive is astc-encoder's)
    run compress "$W/crop.png" -o "$O/crop_${f}_max$ext" --format "$f" --quality max
    run compress "$W/crop_alpha.png" -o "$O/crop_alpha_${f}_max$ext" --format "$f" --quality max ;;
  esac
  run compress "$S/albedo_desert_512.png" -o "$O/albedo_${f}_mips$ext" --format "$f" --mips --wrap repeat
done
if [[ $help == *" bc6h "* ]]; then  # BC6H (builds from before its encoder lack it): the sky, every level, a float chain
  for f in bc6h bc6hs; do
    for q in fast normal high max; do run compress "$S/sky_forest_512x256.exr" -o "$O/sky_${f}_$q.ktx2" --format "$f" --quality "$q"; done
    run compress "$S/sky_forest_512x256.exr" -o "$O/sky_${f}_mips.dds" --format "$f" --mips
  done
fi
run compress "$S/normal_stein_256.png" -o "$O/normal_bc5_nm.ktx2" --format bc5 --mips --normal-map
run compress "$S/normal_stein_256.png" -o "$O/normal_bc3_nm.ktx2" --format bc3 --mips --normal-map
if $astc; then run compress "$S/normal_stein_256.png" -o "$O/normal_astc_nm.ktx2" --format astc-6x6 --mips --normal-map; fi
run compress "$S/albedo_desert_512.png" -o "$O/albedo_bc1_black.ktx2" --format bc1 --bc1-black
for q in fast high; do  # the black index's candidates go block by block at every level
  run compress "$S/albedo_desert_512.png" -o "$O/albedo_bc1_black_$q.ktx2" --format bc1 --bc1-black --quality "$q"
done
run compress "$W/crop.png" -o "$O/crop_bc1_black_max.ktx2" --format bc1 --bc1-black --quality max
run mip "$S/albedo_desert_512.png" -o "$O/mip_albedo.ktx2"
run mip "$S/cutout_fence_512x256.png" -o "$O/mip_cutout.dds" --alpha-coverage 0.5 --filter lanczos3
run mip "$S/height_mount_250.png" -o "$O/mip_height.tif" --linear
run normalmap "$S/height_stein_256.png" -o "$O/normalmap.png" --height-channel r --height-scale 16
run normalmap "$S/height_stein_256.png" -o "$O/normalmap_u16.png" --type u16 --kernel sobel5
run normalmap "$S/height_stein_256.png" -o "$O/normalmap_mips.ktx2" --mips --channels xy
run conemap "$S/height_stein_256.png" -o "$O/cones.png" --height-channel r --depth 0.08
run conemap "$S/height_mount_250.png" -o "$O/cones_relaxed.png" --mode relaxed
run sat "$S/height_mount_250.png" -o "$O/sat.sat"
run sat blur "$S/albedo_desert_512.png" -o "$O/blur.png" --radius 4
(cd "$W/out" && sha256sum $(ls | sort)) > "$W/hashes.txt"
case "$mode" in
  print) cat "$W/hashes.txt" ;;
  update) cp "$W/hashes.txt" tests/data/output_hashes.txt; echo "output_hashes.sh: $(wc -l < "$W/hashes.txt") hashes written" ;;
  check)
    if diff -u tests/data/output_hashes.txt "$W/hashes.txt"; then
      echo "output_hashes.sh: $(wc -l < "$W/hashes.txt") outputs, every byte as recorded"
    else
      echo "output_hashes.sh: outputs differ from tests/data/output_hashes.txt (above)"; exit 1
    fi ;;
esac
