// BC1-BC5 decoding (Khronos Data Format Specification 1.3, "S3TC Compressed
// Texture Image Formats" and "RGTC Compressed Texture Image Formats").
// Depends on nothing under the encoders.
#include <cmath>
#include <cstring>

#include "texproc/block_decode.h"

#include "astc/astc_decode.h"
#include "texproc/runtime.h"

#include "etc/etc_tables.h"
#include "texproc/error.h"

namespace texproc {
namespace {

std::uint16_t le16(const std::uint8_t* p) { return std::uint16_t(p[0] | p[1] << 8); }
std::uint32_t le32(const std::uint8_t* p) { return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24; }

// RGB565 to 8-bit channels by bit replication.
void expand565(std::uint16_t c, int rgb[3]) {
  const int r = c >> 11 & 31, g = c >> 5 & 63, b = c & 31;
  rgb[0] = r << 3 | r >> 2;
  rgb[1] = g << 2 | g >> 4;
  rgb[2] = b << 3 | b >> 2;
}

// The colour half of BC1/BC2/BC3. `four_color`: BC2 and BC3 always use the
// four-colour mode; BC1 only when c0 > c1. `punch_through`: BC1 with alpha
// (index 3 of the three-colour mode is transparent black).
void decode_color(const std::uint8_t* b, bool always_four, bool punch_through, float out[16][4]) {
  const std::uint16_t c0 = le16(b), c1 = le16(b + 2);
  int p[4][4];
  expand565(c0, p[0]);
  expand565(c1, p[1]);
  p[0][3] = p[1][3] = p[2][3] = p[3][3] = 255;
  if (always_four || c0 > c1) {
    for (int c = 0; c < 3; ++c) {
      p[2][c] = (2 * p[0][c] + p[1][c] + 1) / 3;
      p[3][c] = (p[0][c] + 2 * p[1][c] + 1) / 3;
    }
  } else {
    for (int c = 0; c < 3; ++c) {
      p[2][c] = (p[0][c] + p[1][c] + 1) / 2;
      p[3][c] = 0;
    }
    if (punch_through) p[3][3] = 0;
  }
  const std::uint32_t idx = le32(b + 4);
  for (int i = 0; i < 16; ++i) {
    const int* q = p[idx >> (2 * i) & 3];
    for (int c = 0; c < 4; ++c) out[i][c] = float(q[c]) / 255.0f;
  }
}

// A BC4 (RGTC1) block into channel `ch` of out: exact values.
void decode_rgtc(const std::uint8_t* b, bool snorm, int ch, float out[16][4]) {
  float v[8];
  if (!snorm) {
    const int r0 = b[0], r1 = b[1];
    v[0] = float(r0) / 255.0f;
    v[1] = float(r1) / 255.0f;
    if (r0 > r1) {
      for (int k = 1; k <= 6; ++k) v[k + 1] = float(double(r0 * (7 - k) + r1 * k) / 7.0 / 255.0);
    } else {
      for (int k = 1; k <= 4; ++k) v[k + 1] = float(double(r0 * (5 - k) + r1 * k) / 5.0 / 255.0);
      v[6] = 0.0f;
      v[7] = 1.0f;
    }
  } else {
    // -128 decodes as -127 (the SNORM rule: -1.0 has two codes).
    const int r0 = std::max(-127, int(std::int8_t(b[0]))), r1 = std::max(-127, int(std::int8_t(b[1])));
    v[0] = float(r0) / 127.0f;
    v[1] = float(r1) / 127.0f;
    if (r0 > r1) {
      for (int k = 1; k <= 6; ++k) v[k + 1] = float(double(r0 * (7 - k) + r1 * k) / 7.0 / 127.0);
    } else {
      for (int k = 1; k <= 4; ++k) v[k + 1] = float(double(r0 * (5 - k) + r1 * k) / 5.0 / 127.0);
      v[6] = -1.0f;
      v[7] = 1.0f;
    }
  }
  // 48 bits of 3-bit indices, texel 0 in the lowest bits.
  std::uint64_t bits = 0;
  for (int i = 0; i < 6; ++i) bits |= std::uint64_t(b[2 + i]) << (8 * i);
  for (int i = 0; i < 16; ++i) out[i][ch] = v[bits >> (3 * i) & 7];
}

}  // namespace

void decode_block(TexelFormat f, const std::uint8_t* b, float out[16][4]) {
  for (int i = 0; i < 16; ++i) {
    out[i][0] = out[i][1] = out[i][2] = 0.0f;
    out[i][3] = 1.0f;
  }
  using F = TexelFormat;
  switch (f) {
    case F::bc1_rgb_unorm:
    case F::bc1_rgb_srgb: decode_color(b, false, false, out); break;
    case F::bc1_rgba_unorm:
    case F::bc1_rgba_srgb: decode_color(b, false, true, out); break;
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
    case F::bc4_unorm: decode_rgtc(b, false, 0, out); break;
    case F::bc4_snorm: decode_rgtc(b, true, 0, out); break;
    case F::bc5_unorm:
      decode_rgtc(b, false, 0, out);
      decode_rgtc(b + 8, false, 1, out);
      break;
    case F::bc5_snorm:
      decode_rgtc(b, true, 0, out);
      decode_rgtc(b + 8, true, 1, out);
      break;
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
      for (int i = 0; i < 16; ++i) out[i][0] = out[i][1] = out[i][2] = 0.0f, out[i][3] = 1.0f;
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
    Image decoded = astc::decode(data.data(), data.size(), int(t.level_width(level)), int(t.level_height(level)), t.format);
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
  t.images.emplace_back(blocks.begin(), blocks.end());
  return decode_texture_image(t, 0, 0, 0, type);
}

}  // namespace texproc
