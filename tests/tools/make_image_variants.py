#!/usr/bin/env python3
"""Writes small images in the layouts texproc's direct readers must handle,
with Pillow (an encoder no one here wrote): every PNG colour type and bit
depth, palette and tRNS transparency, TGA raw and run-length in both
origins, TIFF strips with each compression, grey and RGB JPEG.
Usage: make_image_variants.py OUT_DIR"""
import os
import sys

from PIL import Image

out = sys.argv[1]
os.makedirs(out, exist_ok=True)
W, H = 37, 23


def rgba(x, y):
    return ((x * 7 + y * 3) % 256, (x * 13) % 256, (y * 11 + 40) % 256, (x * y * 5) % 256)


base = Image.new("RGBA", (W, H))
base.putdata([rgba(x, y) for y in range(H) for x in range(W)])
rgb = base.convert("RGB")
gray = base.convert("L")

# PNG
rgb.save(f"{out}/rgb8.png")
base.save(f"{out}/rgba8.png")
gray.save(f"{out}/g8.png")
base.convert("LA").save(f"{out}/ga8.png")
gray.point(lambda v: 255 if v > 100 else 0).convert("1").save(f"{out}/g1.png")
for bits in (2, 4):
    gray.save(f"{out}/g{bits}.png", bits=bits)  # Pillow quantizes to a palette of 2^bits
pal = rgb.quantize(colors=20)
pal.save(f"{out}/pal8.png")
pal.save(f"{out}/pal8_trns.png", transparency=3)
g16 = Image.new("I;16", (W, H))
g16.putdata([(x * 1777 + y * 311) % 65536 for y in range(H) for x in range(W)])
g16.save(f"{out}/g16.png")
rgb.save(f"{out}/rgb8_trns.png", transparency=(0, 0, 40))
gray.save(f"{out}/g8_trns.png", transparency=17)
rgb.save(f"{out}/rgb8_srgb.png", icc_profile=None)

# TGA
rgb.save(f"{out}/rgb_raw.tga")
base.save(f"{out}/rgba_raw.tga")
rgb.save(f"{out}/rgb_rle.tga", compression="tga_rle")
base.save(f"{out}/rgba_rle.tga", compression="tga_rle")
gray.save(f"{out}/g_raw.tga")
gray.save(f"{out}/g_rle.tga", compression="tga_rle")
base.save(f"{out}/rgba_top.tga", orientation=1)
pal.save(f"{out}/pal.tga")

# TIFF
for comp in (None, "tiff_deflate", "tiff_lzw", "packbits"):
    name = comp or "none"
    rgb.save(f"{out}/rgb_{name}.tif", compression=comp)
    base.save(f"{out}/rgba_{name}.tif", compression=comp)
    gray.save(f"{out}/g_{name}.tif", compression=comp)
g16.save(f"{out}/g16.tif")
fimg = Image.new("F", (W, H))
fimg.putdata([x * 0.25 - y * 0.5 for y in range(H) for x in range(W)])
fimg.save(f"{out}/f32.tif")

# JPEG
rgb.save(f"{out}/rgb.jpg", quality=90)
gray.save(f"{out}/g.jpg", quality=90)
rgb.save(f"{out}/rgb_progressive.jpg", quality=80, progressive=True)
rgb.save(f"{out}/rgb_444.jpg", quality=95, subsampling=0)
