// texproc/block_encode.h: block compression: BC1-BC5, BC6H, BC7, ETC1, ETC2,
// EAC, and ASTC through ARM's astc-encoder
// (docs/compression.md describes the encoders and their quality levels).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string_view>

#include "texproc/image.h"
#include "texproc/mip.h"
#include "texproc/texture.h"
#include "texproc/transparent_color.h"

namespace texproc {

// How hard the encoders search. Each codec's levels are one table, a row per
// level with each knob and its measured effect: libtexproc/src/bc/bc1_levels.h
// (BC1, BC2/BC3 colour), bc/bc4_levels.h (BC4, BC5, BC3 alpha),
// etc/etc_levels.h (ETC1, ETC2), etc/eac_levels.h (EAC); docs/compression.md
// describes them. In short, BC4/BC5:
// fast = the range's ends (and whole code steps over a narrow range);
// normal = + both modes, least-squares refinement, +-1 window; high = +-2
// window and 45 partition variants a mode; max = every endpoint pair. BC1:
// fast = principal axis, one least-squares fit; normal = + refits, 15
// partition variants along the axis, endpoint nudges, the three-colour
// mode; high = 45 variants, each refitted; max = iterated full cluster fit.
// ETC: fast = three tables at the mean; normal = + seeds and re-centring,
// planar, T/H; high = every table refined, +-1 base search, every T/H
// distance; max = +-2.
enum class Quality { fast, normal, high, max };
Quality parse_quality(std::string_view name);  // throws Error{bad_arguments}
const char* to_string(Quality q);

// One BC4 block from 16 target values (row by row) in code units: [0, 255]
// for UNORM, [-127, 127] for SNORM (any real value; clamped). Writes 8
// bytes. Chooses the endpoints and mode with the least squared error under
// the exact decoding (decode_block), within the quality's search.
void encode_bc4_block(const float values[16], bool snorm, Quality q, std::uint8_t out[8]);

// Squared error of a BC4 block against the targets, decoded exactly.
double bc4_block_error(const std::uint8_t block[8], const float values[16], bool snorm);

// Compresses a whole image to a block format. BC1-BC3 and ETC1/ETC2 take the
// stored values as RGBA8 (gray fills RGB, missing alpha is opaque; 16-bit and
// float are rounded to 8 bits). BC4 and EAC R11 take the first channel, BC5
// and EAC RG11 the first two (for one-channel input the second is 0), as
// data: integers scaled to [0, 1], SNORM formats map [0, 1] to [-1, 1] (so a
// normal map's stored x * 0.5 + 0.5 becomes x). Partial blocks replicate the
// edge texels. Bytes are identical for any thread count and SIMD target.
// BC7 takes RGBA8 as BC1-BC3 do. BC6H takes RGB as values (float as it is,
// rounded to half, NaN as 0; integers scaled to [0, 1]); UFLOAT stores
// negatives as 0. ASTC formats take RGBA as BC1-BC3 do (8-bit stays 8-bit, 16-bit and
// float in [0, 1] keep their precision); SFLOAT takes the values as they
// are (above 1 kept, negative clamped by the format). ASTC is searched by
// astc-encoder at the preset the quality names (docs/compression.md, or
// EncodeOptions::astc_effort); its library is loaded on first use and
// Error{unsupported} says so when it is missing.
// Throws Error{unsupported} for formats that are not block formats.
std::vector<std::uint8_t> compress_image(const ConstImageView& image, TexelFormat format, Quality q);

// Choices beyond the quality level.
struct EncodeOptions {
  // Opaque BC1 (bc1_rgb_*): a texel may take the three-colour mode's black
  // (index 3) where that lowers the block's error (dark texels beside
  // colour: line art, text, starfields). Off by default: Direct3D's BC1
  // decodes that index as transparent black (alpha 0) even in a texture
  // meant to be opaque, so turn it on only where alpha is not read (Vulkan's
  // and OpenGL's BC1 RGB formats, KTX2's VK_FORMAT_BC1_RGB_*, return
  // opaque black there). Other formats ignore it.
  bool bc1_black = false;
  // Where set: the fraction of the image's block rows done, after each group
  // of rows, one call at a time (from worker threads), rising to 1.
  std::function<void(double)> progress;
  // ASTC: astc-encoder's effort, 0-100 (its numeric quality: 0 -fastest,
  // 10 -fast, 60 -medium, 98 -thorough, 99 -verythorough, 100 -exhaustive),
  // in place of the quality level's preset; unset: the preset.
  std::optional<float> astc_effort;
  // ASTC LDR: the image is a tangent-space normal map (X in red, Y in
  // green): stored with X in RGB and Y in alpha (astc-encoder's rrrg) and
  // searched for angular error. Shaders read X from .r (or .g, .b), Y from
  // .a and rebuild Z = sqrt(1 - X^2 - Y^2) after mapping both to [-1, 1].
  bool normal_map = false;
};
std::vector<std::uint8_t> compress_image(const ConstImageView& image, TexelFormat format, Quality q,
                                         const EncodeOptions& options);

// One block of any block format (BC1-BC5, ETC1, ETC2, EAC) from 16 RGBA8
// texels, row by row, taken as compress_image takes an RGBA8 image (BC4/EAC
// R11 read red, BC5/EAC RG11 red and green). Writes format_info(format).
// block_bytes bytes (8 or 16) to `out` and returns that count: the same
// bytes compress_image writes for that block in any image. Throws
// Error{unsupported} for formats that are not block formats.
int encode_block(TexelFormat format, const std::uint8_t rgba[16][4], Quality q, std::uint8_t* out,
                 const EncodeOptions& options = {});

// BC3's DXT5nm layout of a tangent-space normal map, for platforms without
// BC5: X (red) moves to alpha, coded by BC3's 8-value alpha block; Y stays
// in green, the colour block's 6-bit channel; red is 1 and blue 0, constant,
// so the colour endpoints spend their precision on Y. Shaders read (a, g)
// and rebuild Z. Returns a 4-channel image of the input's type (a
// one-channel input's Y is 0.5).
Image dxt5nm_layout(const ConstImageView& normal_map);

// What compress_texture does beyond compress_image.
struct TextureEncodeOptions {
  EncodeOptions encode;  // per level (its progress is the whole texture's)
  // The chain is a tangent-space normal map: BC3 formats store it in the
  // DXT5nm layout, ASTC in astc-encoder's rrrg mode (EncodeOptions::
  // normal_map); the other formats take X and Y as they are.
  bool normal_map = false;
  // The colour under alpha < 1 of four-channel formats, applied to each
  // stored level (not to normal maps).
  TransparentColor transparent = TransparentColor::keep;
};

// A texture of `format` from one mip chain per surface (`layout`: index
// layer * faces + face; every chain of the same sizes): each level of each surface
// through compress_image. On return the chains hold the levels as they were
// encoded (DXT5nm layout, transparent colour), for measuring the error.
// Bytes are identical for any thread count.
Texture compress_texture(std::vector<std::vector<Image>>& chains, const SurfaceLayout& layout, TexelFormat format,
                         Quality q, const TextureEncodeOptions& options = {});

// compress_texture of the chains generate_mips(surface, mip) builds, one per
// surface (index layer * faces + face, all of one size), without holding
// them: each level's block rows are encoded as the filter finishes their
// texel rows, so memory is the images and the blocks, not the chains. The
// bytes are generate_mips's then compress_texture's. ASTC, and bleeding
// the transparent colour (it reads neighbours), filter whole chains first.
// Level 0 is each image as given (MipOptions::output_type and
// output_color_space must be unset); on return `surfaces` hold level 0 as
// it was encoded (DXT5nm layout, transparent colour).
Texture compress_texture_mips(std::vector<Image>& surfaces, const MipOptions& mip, const SurfaceLayout& layout,
                              TexelFormat format, Quality q, const TextureEncodeOptions& options = {});

}  // namespace texproc
