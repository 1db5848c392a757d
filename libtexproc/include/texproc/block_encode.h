// texproc/block_encode.h: block compression: BC1-BC5 so far (the ETC family
// is in progress; see the open compression issues and docs/compression.md).
#pragma once

#include <cstdint>
#include <string_view>

#include "texproc/image.h"
#include "texproc/texture.h"

namespace texproc {

enum class Quality {
  fast,    // BC4: min/max endpoints, 8-value mode
  normal,  // + both modes, least-squares endpoint refinement, +-1 window
  high,    // + +-3 around the refined endpoints and +-8 around min/max
  max      // exhaustive endpoint pairs (slow; for reference)
};
Quality parse_quality(std::string_view name);  // throws Error{bad_arguments}
const char* to_string(Quality q);

// One BC4 block from 16 target values (row by row) in code units: [0, 255]
// for UNORM, [-127, 127] for SNORM (any real value; clamped). Writes 8
// bytes. Chooses the endpoints and mode with the least squared error under
// the exact decoding (decode_bc_block), within the quality's search.
void encode_bc4_block(const float values[16], bool snorm, Quality q, std::uint8_t out[8]);

// Squared error of a BC4 block against the targets, decoded exactly.
double bc4_block_error(const std::uint8_t block[8], const float values[16], bool snorm);

// Compresses a whole image to a BC format. BC1-BC3 take the stored values
// as RGBA8 (gray fills RGB, missing alpha is opaque; 16-bit and float are
// rounded to 8 bits). BC4 takes the first channel, BC5 the first two (for
// one-channel input BC5's green is 0), as data: integers scaled to [0, 1],
// SNORM formats map [0, 1] to [-1, 1] (so a normal map's stored
// x * 0.5 + 0.5 becomes x). Partial blocks replicate the edge texels. Bytes
// are identical for any thread count. Throws Error{unsupported} for ETC.
std::vector<std::uint8_t> compress_image(const ImageView& image, TexelFormat format, Quality q);

}  // namespace texproc
