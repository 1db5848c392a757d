// BC1-BC5 block decoding (Khronos Data Format Specification 1.3, "S3TC
// Compressed Texture Image Formats" and "RGTC Compressed Texture Image
// Formats"). Depends on nothing under the encoders.
#include "bc/bc_decode.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace texproc::bc {
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

}  // namespace

// The colour half of BC1/BC2/BC3 as RGBA8: the palette's integers (the
// float decoder below divides them by 255).
void decode_color_rgba8(const std::uint8_t* b, bool always_four, bool punch_through, std::uint8_t out[16][4]) {
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
  std::uint32_t packed[4];
  for (int k = 0; k < 4; ++k)
    packed[k] = std::uint32_t(p[k][0]) | std::uint32_t(p[k][1]) << 8 | std::uint32_t(p[k][2]) << 16 | std::uint32_t(p[k][3]) << 24;
  const std::uint32_t idx = le32(b + 4);
  for (int i = 0; i < 16; ++i) std::memcpy(out[i], &packed[idx >> (2 * i) & 3], 4);
}

void decode_color(const std::uint8_t* b, bool always_four, bool punch_through, float out[16][4]) {
  std::uint8_t px[16][4];
  decode_color_rgba8(b, always_four, punch_through, px);
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) out[i][c] = float(px[i][c]) / 255.0f;
}

namespace {
// BC4's eight palette values (UNORM / 255, SNORM / 127).
void rgtc_palette(const std::uint8_t* b, bool snorm, float v[8]) {
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
}
// 48 bits of 3-bit indices, texel 0 in the lowest bits.
std::uint64_t rgtc_indices(const std::uint8_t* b) {
  std::uint64_t bits = 0;
  for (int i = 0; i < 6; ++i) bits |= std::uint64_t(b[2 + i]) << (8 * i);
  return bits;
}
}  // namespace

// A BC4 (RGTC1) block into channel `ch` of out: exact values.
void decode_rgtc(const std::uint8_t* b, bool snorm, int ch, float out[16][4]) {
  float v[8];
  rgtc_palette(b, snorm, v);
  const std::uint64_t bits = rgtc_indices(b);
  for (int i = 0; i < 16; ++i) out[i][ch] = v[bits >> (3 * i) & 7];
}

void decode_rgtc_u8(const std::uint8_t* b, bool snorm, int ch, std::uint8_t out[16][4]) {
  float v[8];
  rgtc_palette(b, snorm, v);
  std::uint8_t u[8];
  for (int k = 0; k < 8; ++k) u[k] = to_unorm8(snorm ? (v[k] + 1.0f) * 0.5f : v[k]);
  const std::uint64_t bits = rgtc_indices(b);
  for (int i = 0; i < 16; ++i) out[i][ch] = u[bits >> (3 * i) & 7];
}

}  // namespace texproc::bc
