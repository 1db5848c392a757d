// The rows of a mip chain as mip.cpp and cascade.cpp share them: how a
// chain's rows are decoded, filtered and encoded (internal to mip/).
#pragma once

#include <vector>

#include "core/pixel_memory.h"
#include "texproc/color.h"
#include "texproc/filters.h"
#include "texproc/image.h"
#include "texproc/mip.h"

namespace texproc::mip_rows {

constexpr int kBlockRows = 16;  // output rows per task; fixed, so bytes never depend on threads

using FloatBuffer = std::vector<float, detail::DefaultInitAllocator<float>>;

// Per-thread scratch, reused from block to block: a fresh multi-megabyte
// allocation per block would cost a page fault per 4 KiB.
struct Scratch {
  FloatBuffer decoded, row, row_out, level_row;
  std::vector<const float*> rows, taps;
};
Scratch& scratch();

struct ChainSetup {
  int channels = 0;
  bool alpha = false;
  bool premultiply = false;
  bool normal_map = false;
  ColorSpace in_cs = ColorSpace::linear();
  ColorSpace out_cs = ColorSpace::linear();
  PixelType out_type = PixelType::u8;
  WrapMode wrap = WrapMode::clamp;
  // 8-bit sRGB RGBA in and out, premultiplied: the SIMD row codecs apply.
  bool rgba8_srgb_fast = false;
};

// Input row y as the filter reads it: linear, premultiplied where set.
void decode_input_row(const ChainSetup& s, const ConstImageView& in, int y, float* dst);
// One level row from linear premultiplied float to the output encoding.
void encode_level_row(const ChainSetup& s, const float* src, int w, float alpha_scale, void* dst);
// Tangent-space normals stored as xyz * 0.5 + 0.5: back to unit length.
void renormalize_row(float* px, int channels, int width);

// Levels 1 .. levels-1 filtered together in waves, each row of level k as
// soon as the rows of level k-1 it reads exist, into `sink`; a float row is
// freed once the next level has read it. Same bytes as whole levels.
void cascade(const ChainSetup& s, const ConstImageView& input, int levels, const Filter& filter, MipRowSink& sink);

}  // namespace texproc::mip_rows

namespace texproc::detail {
// generate_mips by whole float levels, one after the other (the path alpha
// coverage takes): the reference the cascade's bytes are tested against.
MipChain generate_mips_whole_levels(const ConstImageView& image, const MipOptions& options);
}  // namespace texproc::detail
