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

}  // namespace

// The colour half of BC1/BC2/BC3 as RGBA8: the palette's integers (the
// float decoder below divides them by 255).
void decode_color_rgba8(const std::uint8_t* b, bool always_four, bool punch_through, std::uint8_t out[16][4]) {
  decode_color_run(b, 1, 8, always_four, punch_through, 4, out[0], 16);
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

namespace {
// BC4's palette as 8-bit values, each exactly what rgtc_palette's float
// gives through to_unorm8 (SNORM biased to [0, 1] first): the float
// decoder's values depend only on the endpoint (v[0], v[1]) or on the sum
// n = r0 (d - k) + r1 k over d = 7 or 5, so each is a table entry, filled
// once from the same expressions.
struct Rgtc8Tables {
  std::uint8_t end_u[256], end_s[256];            // an endpoint (SNORM indexed by its byte + 128)
  std::uint8_t u7[1786], u5[1276];                // UNORM: n in [0, 255 d]
  std::uint8_t s7[2 * 889 + 1], s5[2 * 635 + 1];  // SNORM: n + 127 d
  Rgtc8Tables() {
    for (int r = 0; r < 256; ++r) {
      end_u[r] = to_unorm8(float(r) / 255.0f);
      const int sr = std::max(-127, r - 128);
      end_s[r] = to_unorm8((float(sr) / 127.0f + 1.0f) * 0.5f);
    }
    for (int n = 0; n <= 1785; ++n) u7[n] = to_unorm8(float(double(n) / 7.0 / 255.0));
    for (int n = 0; n <= 1275; ++n) u5[n] = to_unorm8(float(double(n) / 5.0 / 255.0));
    for (int n = -889; n <= 889; ++n) s7[n + 889] = to_unorm8((float(double(n) / 7.0 / 127.0) + 1.0f) * 0.5f);
    for (int n = -635; n <= 635; ++n) s5[n + 635] = to_unorm8((float(double(n) / 5.0 / 127.0) + 1.0f) * 0.5f);
  }
};
const Rgtc8Tables& rgtc8() {
  static const Rgtc8Tables t;
  return t;
}

void rgtc_palette_u8(const std::uint8_t* b, bool snorm, std::uint8_t u[8]) {
  const Rgtc8Tables& T = rgtc8();
  if (!snorm) {
    const int r0 = b[0], r1 = b[1];
    u[0] = T.end_u[r0];
    u[1] = T.end_u[r1];
    if (r0 > r1) {
      for (int k = 1; k <= 6; ++k) u[k + 1] = T.u7[r0 * (7 - k) + r1 * k];
    } else {
      for (int k = 1; k <= 4; ++k) u[k + 1] = T.u5[r0 * (5 - k) + r1 * k];
      u[6] = 0;
      u[7] = 255;
    }
    return;
  }
  const int r0 = std::max(-127, int(std::int8_t(b[0]))), r1 = std::max(-127, int(std::int8_t(b[1])));
  u[0] = T.end_s[b[0] ^ 0x80];
  u[1] = T.end_s[b[1] ^ 0x80];
  if (r0 > r1) {
    for (int k = 1; k <= 6; ++k) u[k + 1] = T.s7[r0 * (7 - k) + r1 * k + 889];
  } else {
    for (int k = 1; k <= 4; ++k) u[k + 1] = T.s5[r0 * (5 - k) + r1 * k + 635];
    u[6] = 0;
    u[7] = 255;  // -1 and 1, biased
  }
}

// The colour half's palette as RGBA8 words (R in the low byte; 565
// expanded by bit replication), channel by channel in scalar registers.
inline __attribute__((always_inline)) void color_palette(const std::uint8_t* b, bool always_four, bool punch_through,
                                                         std::uint32_t packed[4]) {
  const std::uint32_t c0 = le16(b), c1 = le16(b + 2);
  auto rep5 = [](std::uint32_t v) { return v << 3 | v >> 2; };
  auto rep6 = [](std::uint32_t v) { return v << 2 | v >> 4; };
  const std::uint32_t r0 = rep5(c0 >> 11), g0 = rep6(c0 >> 5 & 63), b0 = rep5(c0 & 31);
  const std::uint32_t r1 = rep5(c1 >> 11), g1 = rep6(c1 >> 5 & 63), b1 = rep5(c1 & 31);
  auto pack = [](std::uint32_t r, std::uint32_t g, std::uint32_t bl, std::uint32_t a) {
    return r | g << 8 | bl << 16 | a << 24;
  };
  packed[0] = pack(r0, g0, b0, 255);
  packed[1] = pack(r1, g1, b1, 255);
  if (always_four || c0 > c1) {
    packed[2] = pack((2 * r0 + r1 + 1) / 3, (2 * g0 + g1 + 1) / 3, (2 * b0 + b1 + 1) / 3, 255);
    packed[3] = pack((r0 + 2 * r1 + 1) / 3, (g0 + 2 * g1 + 1) / 3, (b0 + 2 * b1 + 1) / 3, 255);
  } else {
    packed[2] = pack((r0 + r1 + 1) / 2, (g0 + g1 + 1) / 2, (b0 + b1 + 1) / 2, 255);
    packed[3] = punch_through ? 0u : pack(0, 0, 0, 255);
  }
}
}  // namespace

void decode_rgtc_u8(const std::uint8_t* b, bool snorm, int ch, std::uint8_t out[16][4]) {
  std::uint8_t u[8];
  rgtc_palette_u8(b, snorm, u);
  const std::uint64_t bits = rgtc_indices(b);
  for (int i = 0; i < 16; ++i) out[i][ch] = u[bits >> (3 * i) & 7];
}

namespace {
// `spill`: RGB rows may write one byte past the block's 12 (each texel one
// 4-byte store, left to right, the next texel's store overwriting the
// previous one's fourth byte): where a block follows in the same run.
template <bool spill = false>
inline __attribute__((always_inline)) void color_rows(const std::uint8_t* b, bool always_four, bool punch_through,
                                                      int channels, std::uint8_t* dst, std::size_t stride) {
  std::uint32_t pal[4];
  color_palette(b, always_four, punch_through, pal);
  std::uint32_t idx;
  std::memcpy(&idx, b + 4, 4);  // every index read before any texel is written
  for (int r = 0; r < 4; ++r, idx >>= 8) {
    std::uint8_t* row = dst + r * stride;
    const std::uint32_t q0 = pal[idx & 3], q1 = pal[idx >> 2 & 3], q2 = pal[idx >> 4 & 3], q3 = pal[idx >> 6 & 3];
    // Whole words built in registers and stored once (no small stores read
    // back as a larger word: that stalls store forwarding).
    if (channels == 4) {
      const std::uint64_t lo = q0 | std::uint64_t(q1) << 32, hi = q2 | std::uint64_t(q3) << 32;
      std::memcpy(row, &lo, 8);
      std::memcpy(row + 8, &hi, 8);
    } else if (spill) {
      std::memcpy(row, &q0, 4);
      std::memcpy(row + 3, &q1, 4);
      std::memcpy(row + 6, &q2, 4);
      std::memcpy(row + 9, &q3, 4);
    } else {  // RGB: the four texels' 12 bytes
      const std::uint64_t lo = std::uint64_t((q0 & 0xFFFFFF) | q1 << 24) | std::uint64_t((q1 >> 8 & 0xFFFF) | q2 << 16)
                                                                               << 32;
      const std::uint32_t hi = (q2 >> 16 & 0xFF) | q3 << 8;
      std::memcpy(row, &lo, 8);
      std::memcpy(row + 8, &hi, 4);
    }
  }
}

inline __attribute__((always_inline)) void rgtc_rows(const std::uint8_t* b, bool snorm, int channels, int ch,
                                                     std::uint8_t* dst, std::size_t stride) {
  std::uint8_t u[8];
  rgtc_palette_u8(b, snorm, u);
  const std::uint64_t bits = rgtc_indices(b);
  for (int r = 0; r < 4; ++r) {
    std::uint8_t* row = dst + r * stride + ch;
    const unsigned idx = unsigned(bits >> (12 * r));
    for (int x = 0; x < 4; ++x) row[x * channels] = u[idx >> (3 * x) & 7];
  }
}

// BC3 in one pass: the colour half's words with the alpha half's bytes in
// their top byte, each row stored once.
inline __attribute__((always_inline)) void bc3_rows(const std::uint8_t* b, std::uint8_t* dst, std::size_t stride) {
  std::uint32_t pal[4];
  color_palette(b + 8, true, false, pal);
  for (auto& p : pal) p &= 0xFFFFFFu;
  // rgtc_palette_u8's UNORM values, straight into the words' top byte.
  const Rgtc8Tables& T = rgtc8();
  const int r0 = b[0], r1 = b[1];
  std::uint32_t alpha[8];
  alpha[0] = std::uint32_t(T.end_u[r0]) << 24, alpha[1] = std::uint32_t(T.end_u[r1]) << 24;
  if (r0 > r1) {
    for (int k = 1; k <= 6; ++k) alpha[k + 1] = std::uint32_t(T.u7[r0 * (7 - k) + r1 * k]) << 24;
  } else {
    for (int k = 1; k <= 4; ++k) alpha[k + 1] = std::uint32_t(T.u5[r0 * (5 - k) + r1 * k]) << 24;
    alpha[6] = 0;
    alpha[7] = 0xFF000000u;
  }
  std::uint64_t abits;
  std::memcpy(&abits, b, 8);  // the indices: bytes 2..7 (little-endian hosts, as the rest of texproc)
  abits >>= 16;
  std::uint32_t idx;
  std::memcpy(&idx, b + 12, 4);
  for (int r = 0; r < 4; ++r, idx >>= 8) {
    const unsigned ai = unsigned(abits >> (12 * r));
    const std::uint32_t q0 = pal[idx & 3] | alpha[ai & 7], q1 = pal[idx >> 2 & 3] | alpha[ai >> 3 & 7];
    const std::uint32_t q2 = pal[idx >> 4 & 3] | alpha[ai >> 6 & 7], q3 = pal[idx >> 6 & 3] | alpha[ai >> 9 & 7];
    const std::uint64_t lo = q0 | std::uint64_t(q1) << 32, hi = q2 | std::uint64_t(q3) << 32;
    std::memcpy(dst + r * stride, &lo, 8);
    std::memcpy(dst + r * stride + 8, &hi, 8);
  }
}

// BC2's alpha byte (two texels' 4-bit values) as the top bytes of the two
// texels' 32-bit words in a 64-bit pair: each value times 17.
struct Bc2AlphaPairs {
  std::uint64_t v[256];
  constexpr Bc2AlphaPairs() : v() {
    for (unsigned n = 0; n < 256; ++n) v[n] = std::uint64_t((n & 15) * 17) << 24 | std::uint64_t((n >> 4) * 17) << 56;
  }
};
constexpr Bc2AlphaPairs kBc2AlphaPairs;

// BC2 in one pass: the colour half's words with the explicit 4-bit alpha
// (times 17) in their top byte.
inline __attribute__((always_inline)) void bc2_rows(const std::uint8_t* b, std::uint8_t* dst, std::size_t stride) {
  std::uint32_t pal[4];
  color_palette(b + 8, true, false, pal);
  for (auto& p : pal) p &= 0xFFFFFFu;
  std::uint32_t idx;
  std::memcpy(&idx, b + 12, 4);
  for (int r = 0; r < 4; ++r, idx >>= 8) {  // row r's alpha: bytes 2 r (texels 0, 1) and 2 r + 1 (texels 2, 3)
    const std::uint64_t lo = (pal[idx & 3] | std::uint64_t(pal[idx >> 2 & 3]) << 32) | kBc2AlphaPairs.v[b[2 * r]];
    const std::uint64_t hi =
        (pal[idx >> 4 & 3] | std::uint64_t(pal[idx >> 6 & 3]) << 32) | kBc2AlphaPairs.v[b[2 * r + 1]];
    std::memcpy(dst + r * stride, &lo, 8);
    std::memcpy(dst + r * stride + 8, &hi, 8);
  }
}

}  // namespace

void decode_bc2_run(const std::uint8_t* blocks, int count, std::uint8_t* dst, std::size_t stride) {
  for (int k = 0; k < count; ++k) bc2_rows(blocks + std::size_t(k) * 16, dst + 16 * k, stride);
}

void decode_bc3_run(const std::uint8_t* blocks, int count, std::uint8_t* dst, std::size_t stride) {
  for (int k = 0; k < count; ++k) bc3_rows(blocks + std::size_t(k) * 16, dst + 16 * k, stride);
}

void decode_color_run(const std::uint8_t* blocks, int count, int block_bytes, bool always_four, bool punch_through,
                      int channels, std::uint8_t* dst, std::size_t stride) {
  // The channel count a constant in each loop.
  if (channels == 4) {
    for (int k = 0; k < count; ++k)
      color_rows(blocks + std::size_t(k) * block_bytes, always_four, punch_through, 4, dst + 16 * k, stride);
  } else if (count > 0) {
    for (int k = 0; k + 1 < count; ++k)
      color_rows<true>(blocks + std::size_t(k) * block_bytes, always_four, punch_through, 3, dst + 12 * k, stride);
    color_rows(blocks + std::size_t(count - 1) * block_bytes, always_four, punch_through, 3, dst + 12 * (count - 1),
               stride);
  }
}

void decode_rgtc_run(const std::uint8_t* blocks, int count, int block_bytes, bool snorm, int channels, int ch,
                     std::uint8_t* dst, std::size_t stride) {
  switch (channels) {
    case 1:
      for (int k = 0; k < count; ++k)
        rgtc_rows(blocks + std::size_t(k) * block_bytes, snorm, 1, ch, dst + 4 * k, stride);
      break;
    case 2:
      for (int k = 0; k < count; ++k)
        rgtc_rows(blocks + std::size_t(k) * block_bytes, snorm, 2, ch, dst + 8 * k, stride);
      break;
    default:
      for (int k = 0; k < count; ++k)
        rgtc_rows(blocks + std::size_t(k) * block_bytes, snorm, 4, ch, dst + 16 * k, stride);
  }
}

}  // namespace texproc::bc
