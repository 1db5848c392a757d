// texproc/read_limits.h: how much a reader accepts from a file before it
// allocates anything for pixels or texels.
#pragma once

#include <cstdint>

namespace texproc {

// Sizes past these are refused (Error{invalid_file}) before any pixel or
// texel memory is allocated, so a small hostile file cannot make a reader
// allocate gigabytes. Every reader takes one (read_image through its
// ReadOptions, read_texture and the decode_* functions directly).
struct ReadLimits {
  // Image files (PNG, JPEG, TGA, TIFF, OpenEXR and the OpenImageIO module's
  // formats). The defaults hold a 16384 x 8192 image. A TIFF tile is refused
  // when a side is over 1024 and over the image's side rounded up to 16, or
  // when it holds more than max_image_pixels.
  long long max_image_dimension = 65536;
  long long max_image_pixels = 16384LL * 8192;
  // A JPEG with more scans is refused before its coefficients are decoded (a
  // normal progressive file has about ten; each scan can cost a pass over the
  // whole image).
  int max_jpeg_scans = 100;

  // GPU textures (DDS, KTX2, KTX1, PKM, .astc).
  std::uint32_t max_texture_dimension = 16384;  // DirectXTex's limit; raise for bigger textures
  std::uint32_t max_layers = 2048;
  // Texel bytes that supercompressed levels (KTX2 Zstandard or zlib) may
  // inflate to, all levels together. Levels stored as they are are bounded
  // by the file's size. The default, 4 GiB, holds a 16384x16384 RGBA float
  // texture.
  std::uint64_t max_inflated_bytes = std::uint64_t(4) << 30;

  // Not a size: check every header field and the level index of a texture,
  // but leave its images empty (what `texproc info` needs).
  bool headers_only = false;

  // The defaults, with max_image_pixels, max_jpeg_scans and
  // max_inflated_bytes taken from TEXPROC_MAX_IMAGE_PIXELS,
  // TEXPROC_MAX_JPEG_SCANS and TEXPROC_MAX_TEXTURE_BYTES where those are set
  // to positive numbers: what the texproc tool reads with. The library never
  // reads the environment by itself.
  static ReadLimits from_environment();
};

}  // namespace texproc
