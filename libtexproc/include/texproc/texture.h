// texproc/texture.h: GPU texel formats and textures as engines load them
// (levels, cube faces, array layers of raw texel or block data).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "texproc/image.h"

namespace texproc {

enum class TexelFormat {
  // uncompressed
  r8_unorm,
  r8_srgb,
  rg8_unorm,
  rg8_srgb,
  rgba8_unorm,
  rgba8_srgb,
  bgra8_unorm,
  bgra8_srgb,
  r16_unorm,
  rg16_unorm,
  rgba16_unorm,
  rgba16_float,
  rgba32_float,
  // BC (S3TC / RGTC)
  bc1_rgb_unorm,
  bc1_rgb_srgb,
  bc1_rgba_unorm,
  bc1_rgba_srgb,
  bc2_unorm,
  bc2_srgb,
  bc3_unorm,
  bc3_srgb,
  bc4_unorm,
  bc4_snorm,
  bc5_unorm,
  bc5_snorm,
  // BPTC: BC6H (HDR RGB, unsigned and signed half floats) and BC7 (RGBA)
  bc6h_ufloat,
  bc6h_sfloat,
  bc7_unorm,
  bc7_srgb,
  // ETC / EAC (ETC1 is written as ETC2 RGB, of which it is a subset)
  etc1_rgb,
  etc2_rgb_unorm,
  etc2_rgb_srgb,
  etc2_rgba1_unorm,
  etc2_rgba1_srgb,
  etc2_rgba8_unorm,
  etc2_rgba8_srgb,
  eac_r11_unorm,
  eac_r11_snorm,
  eac_rg11_unorm,
  eac_rg11_snorm,
  // ASTC, every 2D footprint: LDR (UNORM, sRGB) and HDR (SFLOAT); encoded and
  // decoded through ARM's astc-encoder (docs/compression.md)
  astc_4x4_unorm,
  astc_4x4_srgb,
  astc_4x4_sfloat,
  astc_5x4_unorm,
  astc_5x4_srgb,
  astc_5x4_sfloat,
  astc_5x5_unorm,
  astc_5x5_srgb,
  astc_5x5_sfloat,
  astc_6x5_unorm,
  astc_6x5_srgb,
  astc_6x5_sfloat,
  astc_6x6_unorm,
  astc_6x6_srgb,
  astc_6x6_sfloat,
  astc_8x5_unorm,
  astc_8x5_srgb,
  astc_8x5_sfloat,
  astc_8x6_unorm,
  astc_8x6_srgb,
  astc_8x6_sfloat,
  astc_8x8_unorm,
  astc_8x8_srgb,
  astc_8x8_sfloat,
  astc_10x5_unorm,
  astc_10x5_srgb,
  astc_10x5_sfloat,
  astc_10x6_unorm,
  astc_10x6_srgb,
  astc_10x6_sfloat,
  astc_10x8_unorm,
  astc_10x8_srgb,
  astc_10x8_sfloat,
  astc_10x10_unorm,
  astc_10x10_srgb,
  astc_10x10_sfloat,
  astc_12x10_unorm,
  astc_12x10_srgb,
  astc_12x10_sfloat,
  astc_12x12_unorm,
  astc_12x12_srgb,
  astc_12x12_sfloat,
};

// Everything the containers need to know about a format, from one table
// (libtexproc/src/format/formats.cpp).
// The codec a format's texels go through: compress_image and the decoders
// pick the encoder and decoder by it. ETC2 with alpha (etc2_rgba8) carries an
// EAC alpha block; its family is etc2.
enum class CodecFamily : std::uint8_t { uncompressed, bc1, bc2, bc3, bc4, bc5, bc6h, bc7, etc1, etc2, eac, astc };
const char* to_string(CodecFamily family);  // "uncompressed", "bc1", ... "astc"

struct FormatInfo {
  TexelFormat format;
  const char* name;  // "rgba8_srgb", "bc1_rgba_unorm", ...
  CodecFamily family;
  int block_width, block_height;
  int block_bytes;  // bytes per block (per texel for uncompressed formats)
  int channels;     // 1..4
  bool srgb, snorm, is_float, compressed;
  int type_size;                                         // KTX2 typeSize: 1 for block formats, else bytes per component
  std::uint32_t vk_format;                               // VkFormat
  std::uint32_t dxgi_format;                             // DXGI_FORMAT, 0 if DDS cannot hold it
  std::uint32_t gl_internal_format, gl_format, gl_type;  // KTX1
};

const FormatInfo& format_info(TexelFormat f);
bool is_astc(TexelFormat f);
// The ASTC format of a footprint (4x4 ... 12x12): UNORM, sRGB or SFLOAT (hdr).
// Throws Error{bad_arguments} for a footprint ASTC does not have.
TexelFormat astc_format(int block_width, int block_height, bool srgb, bool hdr);
const FormatInfo* find_format_by_vk(std::uint32_t vk_format);
const FormatInfo* find_format_by_dxgi(std::uint32_t dxgi_format);
const FormatInfo* find_format_by_gl(std::uint32_t gl_internal_format);
TexelFormat parse_texel_format(std::string_view name);  // throws Error{bad_arguments}
std::vector<std::string> texel_format_names();

// The block format a name asks for, as `texproc compress --format` reads
// it, in any case: a family ("bc1", "bc1a", "bc2", "bc3", "bc4", "bc4s",
// "bc5", "bc5s", "bc7", "bc6h", "bc6hs", "etc1", "etc2", "etc2a1", "etc2a",
// "eac-r11", "eac-r11s", "eac-rg11", "eac-rg11s", "astc-6x6",
// "astc-6x6-hdr"...), another tool's name for one ("dxt5", "ati2", "3dc",
// ...), or a full name parse_texel_format reads ("bc7_srgb",
// "BC7_UNORM_SRGB", "VK_FORMAT_BC7_SRGB_BLOCK"). A family gives its sRGB
// format where `srgb` and it has one, else its UNORM (SNORM, float) one; a
// full name gives that format whatever `srgb`. Throws Error{bad_arguments}
// listing the names.
TexelFormat block_format_for(std::string_view name, bool srgb);
// The block format a full name names exactly (parse_texel_format of a
// compressed format); std::nullopt for a family name or no format.
std::optional<TexelFormat> exact_block_format(std::string_view name);

// Bytes of one width x height image in format f (whole blocks: sizes that are
// not multiples of the block are rounded up). Returns 0 on overflow past 2^62.
std::uint64_t image_bytes(TexelFormat f, std::uint32_t width, std::uint32_t height);

struct Texture {
  TexelFormat format = TexelFormat::rgba8_unorm;
  std::uint32_t width = 0, height = 0;
  std::uint32_t levels = 1;
  std::uint32_t faces = 1;   // 1, or 6 for a cubemap (+X, -X, +Y, -Y, +Z, -Z)
  std::uint32_t layers = 1;  // array layers (1 for a plain texture)
  bool is_array = false;     // an array texture even with one layer
  // One image per (level, layer, face), index (level * layers + layer) * faces + face.
  std::vector<PixelBytes> images;

  std::uint32_t level_width(std::uint32_t level) const { return width >> level ? width >> level : 1; }
  std::uint32_t level_height(std::uint32_t level) const { return height >> level ? height >> level : 1; }
  PixelBytes& image(std::uint32_t level, std::uint32_t layer = 0, std::uint32_t face = 0) {
    return images[(std::size_t(level) * layers + layer) * faces + face];
  }
  const PixelBytes& image(std::uint32_t level, std::uint32_t layer = 0, std::uint32_t face = 0) const {
    return images[(std::size_t(level) * layers + layer) * faces + face];
  }
};

// Checks a texture's structure: sizes, counts, every image's byte size.
// Throws Error{bad_arguments} naming the problem.
void validate(const Texture& t);

// How the images of a texture with several surfaces are laid out: one per
// (layer, face), index layer * faces + face.
struct SurfaceLayout {
  std::uint32_t faces = 1;   // 1, or 6 for a cube map (+X, -X, +Y, -Y, +Z, -Z)
  std::uint32_t layers = 1;  // array layers
  bool is_array = false;     // an array texture even with one layer
};

// How texture_from_levels and texture_from_surfaces store pixels.
struct UncompressedOptions {
  bool srgb = false;  // 8-bit formats tagged sRGB (r8/rg8/rgba8 _srgb), else UNORM
  bool half = false;  // f32 stored as rgba16_float, else rgba32_float
};

// A mip chain of images (u8 1, 2 or 4 channels; u8 3 channels get alpha 255;
// u16; f32) as an uncompressed texture: r8/rg8/rgba8 (srgb or unorm), r16/
// rg16/rgba16 unorm, rgba16_float (options.half) or rgba32_float. Gray+alpha
// goes to rg8 (rg16); float with fewer than 4 channels is padded to RGBA.
Texture texture_from_levels(const std::vector<Image>& levels, const UncompressedOptions& options = {});
// The same, taking the levels' pixel memory where the layout is already the
// texture's (no copy); `levels` is left empty.
Texture texture_from_levels(std::vector<Image>&& levels, const UncompressedOptions& options = {});
// Cubemaps and arrays: one mip chain per surface (index layer * faces +
// face), each converted as texture_from_levels converts one chain; every
// chain must have the same sizes and layout. The chains are left empty.
Texture texture_from_surfaces(std::vector<std::vector<Image>>&& chains, const SurfaceLayout& layout,
                              const UncompressedOptions& options = {});

// One image of an uncompressed texture back as an Image (bgra swizzled to
// rgba, half widened to f32). Throws Error{unsupported} for block formats.
Image image_from_texture(const Texture& t, std::uint32_t level, std::uint32_t layer = 0, std::uint32_t face = 0);

}  // namespace texproc
