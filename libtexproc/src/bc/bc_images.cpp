// BC1-BC5 images: cut into 4x4 blocks (partial blocks repeat their edge
// texels), sixteen blocks a batch for the lanes (bc1_lanes.h, bc4_lanes.h) or
// one at a time for `max`, over block rows on texproc's threads. The blocks'
// searches are in bc1_encode.cpp and bc4_encode.cpp.
#include "bc/bc_images.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <Imath/half.h>

#include "bc/bc1_encode.h"
#include "bc/bc1_lanes.h"
#include "bc/bc4_lanes.h"
#include "bc/bc6h_lanes.h"
#include "bc/bc6h_shared.h"
#include "bc/bc7_lanes.h"
#include "block/block_gather.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

static_assert(kBc1Batch == kBlockBatch, "the lanes take the texels gather_rows_rgba8 reads");

namespace {
// block_gather.h's two_colours for 16 RGBA8 texels (`max`, which has no lanes).
bool two_colours_rgba(const std::uint8_t rgba[16][4]) {
  std::uint32_t texel[16][kBlockBatch];
  for (int i = 0; i < 16; ++i) texel[i][0] = pack_texel(rgba[i]);
  return two_colours(texel, 0);
}

}  // namespace

std::vector<std::uint8_t> compress_bc13(const ConstImageView& img, TexelFormat format, Quality q,
                                        const EncodeOptions& options) {
  using F = TexelFormat;
  const bool bc1 = format == F::bc1_rgb_unorm || format == F::bc1_rgb_srgb;
  const bool bc1a = format == F::bc1_rgba_unorm || format == F::bc1_rgba_srgb;
  const bool bc2 = format == F::bc2_unorm || format == F::bc2_srgb;
  const int block_bytes = bc1 || bc1a ? 8 : 16;  // colour only, or an alpha block first
  const int bw = (img.width + 3) / 4, bh = (img.height + 3) / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * block_bytes);
  const Bc1Mode color_mode = bc1 ? Bc1Mode::bc1 : bc1a ? Bc1Mode::bc1_punch_through : Bc1Mode::four_only;
  // The colour (bc1_lanes.h) and BC3's alpha (bc4_lanes.h) go a block per
  // lane where their levels say so (bc1_levels.h, bc4_levels.h); else block by block.
  const Bc1Level& level = bc1_level(q);
  const Bc4Level& alpha_level = bc4_level(q);
  const bool lanes = level.lanes;
  const bool colour_only = bc1 || bc1a;  // no alpha block; the lanes read alpha from the texels
  const bool black = bc1 && options.bc1_black;
  for_each_row_block(
      bh, 4,
      [&](int by0, int by1) {
        std::uint8_t rgba[kBc1Batch][16][4];
        std::uint32_t texel[16][kBc1Batch] = {};
        std::uint8_t color[kBc1Batch][8];
        bool handled[kBc1Batch] = {};
        float alpha[16][kBc4Batch] = {};
        std::uint8_t alpha_blocks[kBc4Batch][8];
        bool uniform_valid = false;
        std::uint32_t uniform_texel = 0;
        std::uint8_t uniform_block[8] = {};
        for (int by = by0; by < by1; ++by)
          for (int bx0 = 0; bx0 < bw; bx0 += kBc1Batch) {
            const int count = std::min(kBc1Batch, bw - bx0);
            // RGBA8 texels straight from the rows where they can be.
            const bool rows_direct = lanes && gather_rows_rgba8(img, bx0, by, count, texel);
            for (int k = 0; k < count; ++k) {
              if (rows_direct) continue;  // gathered below only if the lanes leave it
              gather_rgba8(img, bx0 + k, by, rgba[k]);
              if (lanes)
                for (int i = 0; i < 16; ++i) texel[i][k] = pack_texel(rgba[k][i]);
            }
            // Sixteen blocks at a time; those of one opaque colour (or none) are
            // left to the block-by-block encoder's single-colour tables.
            if (lanes) bc1_encode_lanes(texel, count, level.lane, colour_only, bc1a, color, handled);
            for (int k = 0; k < count; ++k) {
              std::uint8_t* dst = out.data() + (std::size_t(by) * bw + bx0 + k) * block_bytes;
              std::uint8_t* color_dst = colour_only ? dst : dst + 8;
              if (lanes && handled[k]) {
                std::memcpy(color_dst, color[k], 8);
              } else {
                if (rows_direct) gather_rgba8(img, bx0 + k, by, rgba[k]);
                // A block of one texel value (what the lanes leave, mostly) is
                // the same block as the last such block of that value.
                const std::uint32_t first = pack_texel(rgba[k][0]);
                bool uniform = true;
                for (int i = 1; i < 16 && uniform; ++i) uniform = pack_texel(rgba[k][i]) == first;
                if (uniform && uniform_valid && uniform_texel == first) {
                  std::memcpy(color_dst, uniform_block, 8);
                } else {
                  encode_bc1_color_block_by_block(rgba[k], color_mode, q, color_dst);
                  if (uniform) uniform_valid = true, uniform_texel = first, std::memcpy(uniform_block, color_dst, 8);
                }
              }
              // Two colours exactly (text, line art): their best palette positions
              // (above `fast`, which keeps its speed: a palette texture at half of it).
              // The passes below read rgba[k], which a block the lanes took from
              // the rows does not have yet: gathered once, where a pass needs it.
              bool gathered = !(lanes && handled[k] && rows_direct);
              auto texels = [&]() -> const std::uint8_t(&)[16][4] {
                if (!gathered) gather_rgba8(img, bx0 + k, by, rgba[k]), gathered = true;
                return rgba[k];
              };
              if (level.two_colours && (lanes ? two_colours(texel, k) : two_colours_rgba(rgba[k])))
                bc1_try_two_colours(texels(), color_mode, color_dst);
              if (black) bc1_try_black(texels(), q, color_dst);
              if (colour_only) continue;
              // The lanes' texels hold every block's alpha; `max` has the gathered ones.
              auto alpha_of = [&](int i) { return lanes ? int(texel[i][k] >> 24) : int(rgba[k][i][3]); };
              if (bc2) {  // explicit 4-bit alpha, rounded
                for (int i = 0; i < 16; i += 2) {
                  const int a0 = (alpha_of(i) * 15 + 127) / 255, a1 = (alpha_of(i + 1) * 15 + 127) / 255;
                  dst[i / 2] = std::uint8_t(a0 | a1 << 4);
                }
              } else if (alpha_level.lanes) {  // BC3: the alpha as a BC4 block, in lanes below
                for (int i = 0; i < 16; ++i) alpha[i][k] = float(alpha_of(i));
              } else {
                float a[16];
                for (int i = 0; i < 16; ++i) a[i] = float(alpha_of(i));
                encode_bc4_block(a, false, q, dst);
              }
            }
            if (!colour_only && !bc2 && alpha_level.lanes) {
              bc4_encode_lanes(alpha, count, false, alpha_level.lane, alpha_blocks);
              for (int k = 0; k < count; ++k)
                std::memcpy(out.data() + (std::size_t(by) * bw + bx0 + k) * block_bytes, alpha_blocks[k], 8);
            }
          }
      },
      options.progress);
  return out;
}

std::vector<std::uint8_t> compress_bc7(const ConstImageView& img, Quality q, const EncodeOptions& options) {
  const int bw = (img.width + 3) / 4, bh = (img.height + 3) / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * 16);
  const Bc7Level& level = bc7_level(q);  // bc7_levels.h
  for_each_row_block(
      bh, 4,
      [&](int by0, int by1) {
        std::uint8_t rgba[16][4];
        // Up to a span of blocks a call, row after row (the rows' blocks are
        // consecutive in `out`): the encoder steps its winners together.
        std::vector<Bc7Texels> texel(kBc7Span / kBc7Batch);
        const int first = by0 * bw, total = (by1 - by0) * bw;
        for (int s0 = 0; s0 < total; s0 += kBc7Span) {
          const int span = std::min(kBc7Span, total - s0);
          for (int b = 0; b * kBc7Batch < span; ++b) {
            const int n0 = first + s0 + b * kBc7Batch, count = std::min(kBc7Batch, span - b * kBc7Batch);
            const int by = n0 / bw, bx0 = n0 % bw;
            if (bx0 + count <= bw && gather_rows_rgba8(img, bx0, by, count, texel[b])) continue;
            for (int k = 0; k < count; ++k) {
              gather_rgba8(img, (n0 + k) % bw, (n0 + k) / bw, rgba);
              for (int i = 0; i < 16; ++i) texel[b][i][k] = pack_texel(rgba[i]);
            }
          }
          bc7_encode_lanes(texel.data(), span, level,
                           reinterpret_cast<std::uint8_t(*)[16]>(out.data() + std::size_t(first + s0) * 16));
        }
      },
      options.progress);
  return out;
}

namespace {
// Channel c (RGB) of texel (x, y) as a float: 8- and 16-bit as [0, 1], gray
// in every channel.
float texel_float(const ConstImageView& img, int x, int y, int c) {
  const int src = img.channels <= 2 ? 0 : c;
  const std::size_t at = std::size_t(x) * img.channels + src;
  switch (img.type) {
    case PixelType::u8:
      return img.row<const std::uint8_t>(y)[at] / 255.0f;
    case PixelType::u16:
      return img.row<const std::uint16_t>(y)[at] / 65535.0f;
    case PixelType::f32:
      return img.row<const float>(y)[at];
  }
  return 0.0f;
}
}  // namespace

std::vector<std::uint8_t> compress_bc6h(const ConstImageView& img, bool is_signed, Quality q,
                                        const EncodeOptions& options) {
  const int bw = (img.width + 3) / 4, bh = (img.height + 3) / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * 16);
  const Bc6hLevel& level = bc6h_level(q);  // bc6h_levels.h
  for_each_row_block(
      bh, 4,
      [&](int by0, int by1) {
        std::int32_t texel[16][3][kBc6hBatch] = {};
        for (int by = by0; by < by1; ++by)
          for (int bx0 = 0; bx0 < bw; bx0 += kBc6hBatch) {
            const int count = std::min(kBc6hBatch, bw - bx0);
            for (int k = 0; k < count; ++k)
              for (int i = 0; i < 16; ++i) {
                // Texels past the right and bottom edges repeat the edge's.
                const int x = std::min((bx0 + k) * 4 + i % 4, img.width - 1),
                          y = std::min(by * 4 + i / 4, img.height - 1);
                for (int c = 0; c < 3; ++c) {
                  const float v = texel_float(img, x, y, c);
                  // Rounded to the nearest half (ties to even); beyond the largest, the largest.
                  const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, -65504.0f, 65504.0f);
                  texel[i][c][k] = bc6h::target(Imath::half(clamped).bits(), is_signed);
                }
              }
            bc6h_encode_lanes(texel, count, is_signed, level,
                              reinterpret_cast<std::uint8_t(*)[16]>(out.data() + (std::size_t(by) * bw + bx0) * 16));
          }
      },
      options.progress);
  return out;
}

std::vector<std::uint8_t> compress_bc45(const ConstImageView& img, TexelFormat format, Quality q,
                                        const EncodeOptions& options) {
  const bool bc5 = format == TexelFormat::bc5_unorm || format == TexelFormat::bc5_snorm;
  const bool snorm = format == TexelFormat::bc4_snorm || format == TexelFormat::bc5_snorm;
  if (!bc5 && format != TexelFormat::bc4_unorm && format != TexelFormat::bc4_snorm) {
    throw Error(ErrorCode::unsupported, std::string("encoding ") + format_info(format).name + " is not supported");
  }
  const int bw = (img.width + 3) / 4, bh = (img.height + 3) / 4;
  const int block_bytes = bc5 ? 16 : 8;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * block_bytes);
  // A texel in [0, 1] as code units: [0, 255], or [-127, 127] for SNORM.
  auto code_units = [&](float u) { return snorm ? (u * 2.0f - 1.0f) * 127.0f : u * 255.0f; };
  auto value = [&](int x, int y, int c) -> float {
    if (c >= img.channels) return snorm ? 0.0f : 0.0f;
    float v = 0.0f;
    switch (img.type) {
      case PixelType::u8:
        v = img.row<const std::uint8_t>(y)[x * img.channels + c] / 255.0f;
        break;
      case PixelType::u16:
        v = img.row<const std::uint16_t>(y)[x * img.channels + c] / 65535.0f;
        break;
      case PixelType::f32:
        v = img.row<const float>(y)[x * img.channels + c];
        break;
    }
    return code_units(v);
  };
  const Bc4Level& level = bc4_level(q);  // bc4_levels.h
  const bool lanes = level.lanes;        // a block per lane (bc4_lanes.h)
  float u8_value[256];
  for (int i = 0; i < 256; ++i) {
    u8_value[i] = code_units(float(i) / 255.0f);
  }
  for_each_row_block(
      bh, 4,
      [&](int by0, int by1) {
        float v[16];
        float batch[16][kBc4Batch] = {};
        std::uint8_t blocks[kBc4Batch][8];
        for (int by = by0; by < by1; ++by)
          for (int bx0 = 0; bx0 < bw; bx0 += kBc4Batch) {
            const int count = std::min(kBc4Batch, bw - bx0);
            for (int ch = 0; ch < (bc5 ? 2 : 1); ++ch) {
              if (lanes && img.type == PixelType::u8 && ch < img.channels) {
                // 8-bit texels through a table of the same values value() gives.
                for (int y = 0; y < 4; ++y) {
                  const std::uint8_t* row = img.row<const std::uint8_t>(std::min(by * 4 + y, img.height - 1));
                  for (int k = 0; k < count; ++k)
                    for (int x = 0; x < 4; ++x)
                      batch[4 * y + x][k] =
                          u8_value[row[std::min((bx0 + k) * 4 + x, img.width - 1) * img.channels + ch]];
                }
              } else if (lanes && ch < img.channels && img.type != PixelType::u8) {
                // 16-bit and float texels a row at a time (value() without its switch per texel).
                for (int y = 0; y < 4; ++y) {
                  const int sy = std::min(by * 4 + y, img.height - 1);
                  for (int k = 0; k < count; ++k)
                    for (int x = 0; x < 4; ++x) {
                      const std::size_t at =
                          std::size_t(std::min((bx0 + k) * 4 + x, img.width - 1)) * img.channels + ch;
                      const float u = img.type == PixelType::u16 ? img.row<const std::uint16_t>(sy)[at] / 65535.0f
                                                                 : img.row<const float>(sy)[at];
                      batch[4 * y + x][k] = code_units(u);
                    }
                }
              } else {
                for (int k = 0; k < count; ++k)
                  for (int i = 0; i < 16; ++i) {
                    // Partial blocks: the edge texels repeat into the missing ones.
                    const int x = std::min((bx0 + k) * 4 + i % 4, img.width - 1),
                              y = std::min(by * 4 + i / 4, img.height - 1);
                    (lanes ? batch[i][k] : v[i]) = value(x, y, ch);
                    if (!lanes && i == 15)
                      encode_bc4_block(v, snorm, q,
                                       out.data() + (std::size_t(by) * bw + bx0 + k) * block_bytes + 8 * ch);
                  }
              }
              if (!lanes) continue;
              bc4_encode_lanes(batch, count, snorm, level.lane, blocks);  // sixteen blocks at a time
              for (int k = 0; k < count; ++k)
                std::memcpy(out.data() + (std::size_t(by) * bw + bx0 + k) * block_bytes + 8 * ch, blocks[k], 8);
            }
          }
      },
      options.progress);
  return out;
}

}  // namespace texproc
