// The block decoders' dispatcher: one block of any block format (BC1-BC7,
// ETC1, ETC2, EAC, ASTC) by its format, and whole images and texture levels
// decoded block by block. Above the formats, as encode/ is for the encoders.
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <type_traits>

#include "astc/astc_decode.h"
#include "bc/bc_decode.h"
#include "etc/etc_tables.h"
#include "texproc/block_decode.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

using bc::decode_color;
using bc::decode_rgtc;

void decode_block(TexelFormat f, const std::uint8_t* b, float out[16][4]) {
  for (int i = 0; i < 16; ++i) {
    out[i][0] = out[i][1] = out[i][2] = 0.0f;
    out[i][3] = 1.0f;
  }
  using F = TexelFormat;
  switch (f) {
    case F::bc1_rgb_unorm:
    case F::bc1_rgb_srgb:
      decode_color(b, false, false, out);
      break;
    case F::bc1_rgba_unorm:
    case F::bc1_rgba_srgb:
      decode_color(b, false, true, out);
      break;
    case F::bc2_unorm:
    case F::bc2_srgb: {
      decode_color(b + 8, true, false, out);
      for (int i = 0; i < 16; ++i) {
        const int a = b[i / 2] >> (4 * (i & 1)) & 15;
        out[i][3] = float(a * 17) / 255.0f;
      }
      break;
    }
    case F::bc3_unorm:
    case F::bc3_srgb:
      decode_color(b + 8, true, false, out);
      decode_rgtc(b, false, 3, out);
      break;
    case F::bc4_unorm:
      decode_rgtc(b, false, 0, out);
      break;
    case F::bc4_snorm:
      decode_rgtc(b, true, 0, out);
      break;
    case F::bc5_unorm:
      decode_rgtc(b, false, 0, out);
      decode_rgtc(b + 8, false, 1, out);
      break;
    case F::bc5_snorm:
      decode_rgtc(b, true, 0, out);
      decode_rgtc(b + 8, true, 1, out);
      break;
    case F::bc6h_ufloat:
    case F::bc6h_sfloat: {
      std::uint16_t h[16][3];
      bc::decode_bc6h(b, f == F::bc6h_sfloat, h);
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c) {
          Imath::half v;
          v.setBits(h[i][c]);
          out[i][c] = float(v);
        }
      break;
    }
    case F::bc7_unorm:
    case F::bc7_srgb: {
      std::uint8_t px[16][4];
      bc::decode_bc7(b, px);
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c) out[i][c] = float(px[i][c]) / 255.0f;
      break;
    }
    case F::etc1_rgb:
    case F::etc2_rgb_unorm:
    case F::etc2_rgb_srgb:
    case F::etc2_rgba1_unorm:
    case F::etc2_rgba1_srgb:
    case F::etc2_rgba8_unorm:
    case F::etc2_rgba8_srgb: {
      const bool rgba8 = f == F::etc2_rgba8_unorm || f == F::etc2_rgba8_srgb;
      const std::uint8_t* color = rgba8 ? b + 8 : b;
      std::uint8_t px[16][4];
      if (f == F::etc1_rgb) {
        etc::decode_etc1(color, px);
      } else {
        etc::decode_etc2(color, f == F::etc2_rgba1_unorm || f == F::etc2_rgba1_srgb, px);
      }
      std::uint8_t alpha[16];
      if (rgba8) etc::decode_eac8(b, alpha);
      for (int i = 0; i < 16; ++i) {
        for (int c = 0; c < 3; ++c) out[i][c] = px[i][c] / 255.0f;
        out[i][3] = (rgba8 ? alpha[i] : px[i][3]) / 255.0f;
      }
      break;
    }
    case F::eac_r11_unorm:
    case F::eac_r11_snorm:
    case F::eac_rg11_unorm:
    case F::eac_rg11_snorm: {
      const bool snorm = f == F::eac_r11_snorm || f == F::eac_rg11_snorm;
      const int channels = f == F::eac_rg11_unorm || f == F::eac_rg11_snorm ? 2 : 1;
      for (int i = 0; i < 16; ++i) {
        out[i][0] = out[i][1] = out[i][2] = 0.0f;
        out[i][3] = 1.0f;
      }
      for (int c = 0; c < channels; ++c) {
        int v[16];
        etc::decode_eac11(b + 8 * c, snorm, v);
        for (int i = 0; i < 16; ++i) out[i][c] = float(v[i]) / (snorm ? 1023.0f : 2047.0f);
      }
      break;
    }
    default:
      throw Error(ErrorCode::unsupported, std::string("decoding ") + format_info(f).name + " is not supported yet");
  }
}

namespace {

// One block straight to 8 bits a channel, the bytes the float decoder gives
// through Image::set (the 8-bit decoders' texels as they are; BC4's palette
// converted once a block; the rest through the float decoder).
void decode_block_u8(TexelFormat f, const std::uint8_t* b, bool snorm, std::uint8_t out[16][4]) {
  using F = TexelFormat;
  switch (f) {
    case F::bc1_rgb_unorm:
    case F::bc1_rgb_srgb:
      bc::decode_color_rgba8(b, false, false, out);
      return;
    case F::bc1_rgba_unorm:
    case F::bc1_rgba_srgb:
      bc::decode_color_rgba8(b, false, true, out);
      return;
    case F::bc2_unorm:
    case F::bc2_srgb:
      bc::decode_color_rgba8(b + 8, true, false, out);
      for (int i = 0; i < 16; ++i) out[i][3] = std::uint8_t((b[i / 2] >> (4 * (i & 1)) & 15) * 17);
      return;
    case F::bc3_unorm:
    case F::bc3_srgb:
      bc::decode_color_rgba8(b + 8, true, false, out);
      bc::decode_rgtc_u8(b, false, 3, out);
      return;
    case F::bc4_unorm:
    case F::bc4_snorm:
      bc::decode_rgtc_u8(b, f == F::bc4_snorm, 0, out);
      return;
    case F::bc5_unorm:
    case F::bc5_snorm:
      bc::decode_rgtc_u8(b, f == F::bc5_snorm, 0, out);
      bc::decode_rgtc_u8(b + 8, f == F::bc5_snorm, 1, out);
      return;
    case F::bc7_unorm:
    case F::bc7_srgb:
      bc::decode_bc7(b, out);
      return;
    case F::etc1_rgb:
      etc::decode_etc1(b, out);
      return;
    case F::etc2_rgb_unorm:
    case F::etc2_rgb_srgb:
      etc::decode_etc2(b, false, out);
      return;
    case F::etc2_rgba1_unorm:
    case F::etc2_rgba1_srgb:
      etc::decode_etc2(b, true, out);
      return;
    case F::etc2_rgba8_unorm:
    case F::etc2_rgba8_srgb: {
      etc::decode_etc2(b + 8, false, out);
      std::uint8_t alpha[16];
      etc::decode_eac8(b, alpha);
      for (int i = 0; i < 16; ++i) out[i][3] = alpha[i];
      return;
    }
    default: {
      float texels[16][4];
      decode_block(f, b, texels);
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 4; ++c) out[i][c] = bc::to_unorm8(snorm ? (texels[i][c] + 1.0f) * 0.5f : texels[i][c]);
    }
  }
}

// The first `count` blocks of a block row (whole blocks) straight into the
// rows (dst, `stride` bytes apart, kC channels) where the format has such a
// decoder: the bytes decode_block_u8 gives. False where it has none.
template <int kC>
bool decode_run(TexelFormat f, const std::uint8_t* b, int count, std::uint8_t* dst, std::size_t stride) {
  using F = TexelFormat;
  switch (f) {
    case F::bc1_rgb_unorm:
    case F::bc1_rgb_srgb:
      if (kC != 3) return false;
      bc::decode_color_run(b, count, 8, false, false, 3, dst, stride);
      return true;
    case F::bc1_rgba_unorm:
    case F::bc1_rgba_srgb:
      if (kC != 4) return false;
      bc::decode_color_run(b, count, 8, false, true, 4, dst, stride);
      return true;
    case F::bc2_unorm:
    case F::bc2_srgb:
      if (kC != 4) return false;
      bc::decode_bc2_run(b, count, dst, stride);
      return true;
    case F::bc3_unorm:
    case F::bc3_srgb:
      if (kC != 4) return false;
      bc::decode_bc3_run(b, count, dst, stride);
      return true;
    case F::bc4_unorm:
    case F::bc4_snorm:
      if (kC != 1) return false;
      bc::decode_rgtc_run(b, count, 8, f == F::bc4_snorm, 1, 0, dst, stride);
      return true;
    case F::bc5_unorm:
    case F::bc5_snorm:
      if (kC != 2) return false;
      bc::decode_rgtc_run(b, count, 16, f == F::bc5_snorm, 2, 0, dst, stride);
      bc::decode_rgtc_run(b + 8, count, 16, f == F::bc5_snorm, 2, 1, dst, stride);
      return true;
    case F::bc7_unorm:
    case F::bc7_srgb:
      if (kC != 4) return false;
      bc::decode_bc7_run(b, count, dst, stride);
      return true;
    case F::etc1_rgb:
      if (kC != 3) return false;
      etc::decode_etc_run(b, count, 8, etc::EtcRun::etc1_rgb, dst, stride);
      return true;
    case F::etc2_rgb_unorm:
    case F::etc2_rgb_srgb:
      if (kC != 3) return false;
      etc::decode_etc_run(b, count, 8, etc::EtcRun::etc2_rgb, dst, stride);
      return true;
    case F::etc2_rgba1_unorm:
    case F::etc2_rgba1_srgb:
      if (kC != 4) return false;
      etc::decode_etc_run(b, count, 8, etc::EtcRun::etc2_rgba1, dst, stride);
      return true;
    case F::etc2_rgba8_unorm:
    case F::etc2_rgba8_srgb:
      if (kC != 4) return false;
      etc::decode_etc_run(b, count, 16, etc::EtcRun::etc2_rgba8, dst, stride);
      return true;
    case F::eac_r11_unorm:
    case F::eac_r11_snorm:
      if (kC != 1) return false;
      etc::decode_eac11_u8_run(b, count, 8, f == F::eac_r11_snorm, 1, 0, dst, stride);
      return true;
    case F::eac_rg11_unorm:
    case F::eac_rg11_snorm:
      if (kC != 2) return false;
      etc::decode_eac11_u8_run(b, count, 16, f == F::eac_rg11_snorm, 2, 0, dst, stride);
      etc::decode_eac11_u8_run(b + 8, count, 16, f == F::eac_rg11_snorm, 2, 1, dst, stride);
      return true;
    default:
      return false;
  }
}

}  // namespace

Image decode_texture_image(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face,
                           PixelType type) {
  const FormatInfo& info = format_info(t.format);
  if (!info.compressed) {
    Image raw = image_from_texture(t, level, layer, face);
    if (raw.type() == type) return raw;
    Image out = Image::uninitialized(raw.width(), raw.height(), raw.channels(), type);
    for (int y = 0; y < raw.height(); ++y)
      for (int x = 0; x < raw.width(); ++x)
        for (int c = 0; c < raw.channels(); ++c) out.set(x, y, c, raw.get(x, y, c));
    return out;
  }
  if (is_astc(t.format)) {
    const PixelBytes& data = t.image(level, layer, face);
    Image decoded =
        astc::decode(data.data(), data.size(), int(t.level_width(level)), int(t.level_height(level)), t.format);
    if (decoded.type() == type) return decoded;
    Image out = Image::uninitialized(decoded.width(), decoded.height(), 4, type);
    for_each_row_block(decoded.height(), 64, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < decoded.width(); ++x)
          for (int c = 0; c < 4; ++c) out.set(x, y, c, decoded.get(x, y, c));
    });
    return out;
  }
  if (info.block_width != 4) {
    throw Error(ErrorCode::unsupported, std::string("decoding ") + info.name + " is not supported");
  }
  const int w = int(t.level_width(level)), h = int(t.level_height(level));
  const int C = info.channels;
  Image out = Image::uninitialized(w, h, C, type);
  const PixelBytes& data = t.image(level, layer, face);
  const int bw = (w + 3) / 4, bh = (h + 3) / 4;
  if (type == PixelType::u8) {  // 8 bits a channel: a block's texels straight into the rows
    // The copy, with the channel count a constant (1: R, 2: RG, 3: RGB, 4: RGBA).
    auto rows = [&](auto channels) {
      constexpr int kC = decltype(channels)::value;
      for_each_row_block(bh, 16, [&](int by0, int by1) {
        std::uint8_t px[16][4];
        const std::uint8_t* block = data.data() + std::size_t(by0) * bw * info.block_bytes;
        for (int by = by0; by < by1; ++by) {
          // A row's whole blocks in one run where the format has one; the rest block by block.
          int bx = 0;
          const int whole = 4 * by + 4 <= h ? w / 4 : 0;
          if (whole > 0 && decode_run<kC>(t.format, block, whole, out.row<std::uint8_t>(4 * by), out.row_stride()))
            bx = whole, block += std::size_t(whole) * info.block_bytes;
          for (; bx < bw; ++bx, block += info.block_bytes) {
            const int nx = std::min(4, w - 4 * bx), ny = std::min(4, h - 4 * by);
            decode_block_u8(t.format, block, info.snorm, px);
            for (int r = 0; r < ny; ++r) {
              std::uint8_t* row = out.row<std::uint8_t>(4 * by + r) + std::size_t(4 * bx) * kC;
              const std::uint8_t(*src)[4] = px + 4 * r;
              if (kC == 4 && nx == 4) {
                std::memcpy(row, src, 16);
              } else {
                for (int x = 0; x < nx; ++x)
                  for (int c = 0; c < kC; ++c) row[x * kC + c] = src[x][c];
              }
            }
          }
        }
      });
    };
    switch (C) {
      case 1:
        rows(std::integral_constant<int, 1>{});
        break;
      case 2:
        rows(std::integral_constant<int, 2>{});
        break;
      case 3:
        rows(std::integral_constant<int, 3>{});
        break;
      default:
        rows(std::integral_constant<int, 4>{});
        break;
    }
    return out;
  }
  if (type == PixelType::f32) {  // floats: a block's texels straight into the rows, block rows over the threads
    const bool bc6h = t.format == TexelFormat::bc6h_ufloat || t.format == TexelFormat::bc6h_sfloat;
    for_each_row_block(bh, 16, [&](int by0, int by1) {
      float texels[16][4];
      for (int by = by0; by < by1; ++by)
        for (int bx = 0; bx < bw; ++bx) {
          const std::uint8_t* block = data.data() + (std::size_t(by) * bw + bx) * info.block_bytes;
          const int nx = std::min(4, w - 4 * bx), ny = std::min(4, h - 4 * by);
          if (bc6h && C == 3 && nx == 4 && ny == 4) {  // a whole block's floats straight into the rows
            bc::decode_bc6h_f32_rows(block, t.format == TexelFormat::bc6h_sfloat,
                                     out.row<float>(4 * by) + std::size_t(4 * bx) * 3,
                                     out.row_stride() / sizeof(float));
            continue;
          }
          if (bc6h && C == 3) {  // the halves straight into the rows
            std::uint16_t hv[16][3];
            bc::decode_bc6h(block, t.format == TexelFormat::bc6h_sfloat, hv);
            for (int r = 0; r < ny; ++r) {
              float* row = out.row<float>(4 * by + r) + std::size_t(4 * bx) * 3;
              for (int x = 0; x < nx; ++x)
                for (int c = 0; c < 3; ++c) {
                  Imath::half v;
                  v.setBits(hv[4 * r + x][c]);
                  row[3 * x + c] = float(v);
                }
            }
            continue;
          }
          decode_block(t.format, block, texels);
          for (int r = 0; r < ny; ++r) {
            float* row = out.row<float>(4 * by + r) + std::size_t(4 * bx) * C;
            if (C == 4 && nx == 4) {
              std::memcpy(row, texels[4 * r], sizeof(float) * 16);
            } else {
              for (int x = 0; x < nx; ++x) std::memcpy(row + x * C, texels[4 * r + x], sizeof(float) * std::size_t(C));
            }
          }
        }
    });
    return out;
  }
  float texels[16][4];
  for (int by = 0; by < bh; ++by)
    for (int bx = 0; bx < bw; ++bx) {
      decode_block(t.format, data.data() + (std::size_t(by) * bw + bx) * info.block_bytes, texels);
      for (int i = 0; i < 16; ++i) {
        const int x = bx * 4 + i % 4, y = by * 4 + i / 4;
        if (x >= w || y >= h) continue;
        for (int c = 0; c < C; ++c) {  // 1: R, 2: RG, 3: RGB, 4: RGBA
          float v = texels[i][c];
          if (type != PixelType::f32 && info.snorm) v = (v + 1.0f) * 0.5f;  // the usual biased storage
          out.set(x, y, c, v);
        }
      }
    }
  return out;
}

Image decompress_image(std::vector<std::uint8_t> blocks, int width, int height, TexelFormat format, PixelType type) {
  Texture t;
  t.format = format;
  t.width = std::uint32_t(width);
  t.height = std::uint32_t(height);
  t.images.emplace_back(blocks);
  return decode_texture_image(t, 0, 0, 0, type);
}

}  // namespace texproc
