// ETC1, ETC2 and EAC block decoding, to the Khronos Data Format
// Specification 1.3 (chapters "ETC1 compressed texture image formats" and
// "ETC2 compressed texture image formats"). Bit numbers are those of the
// specification: the block is a big-endian 64-bit number.
#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "etc/etc_tables.h"

namespace texproc::etc {
namespace {

// The 2-bit index of texel (x, y): its most significant bit at bit
// x * 4 + y + 16, its least significant bit at bit x * 4 + y.
int pixel_index(std::uint64_t v, int x, int y) {
  const int k = x * 4 + y;
  return int(v >> (k + 16) & 1) << 1 | int(v >> k & 1);
}

// A texel as an RGBA8 word (R in the low byte), opaque.
inline std::uint32_t word(int r, int g, int b) {
  return std::uint32_t(clamp255(r)) | std::uint32_t(clamp255(g)) << 8 | std::uint32_t(clamp255(b)) << 16 | 0xFF000000u;
}

// A 4x4 bit matrix's transpose: bit 4 a + b to bit 4 b + a.
constexpr unsigned transpose4x4(unsigned m) {
  unsigned t = (m ^ (m >> 3)) & 0x0A0Au;
  m ^= t ^ (t << 3);
  t = (m ^ (m >> 6)) & 0x00CCu;
  return m ^ t ^ (t << 6);
}

// A row's four 2-bit indices, one a byte (texel x in byte x), from its four
// least significant bits (bit x) and four most significant bits (bit x + 4).
struct RowIndexTable {
  std::uint32_t v[256];
  constexpr RowIndexTable() : v() {
    for (unsigned n = 0; n < 256; ++n)
      for (unsigned x = 0; x < 4; ++x) v[n] |= ((n >> (x + 4) & 1) << 1 | (n >> x & 1)) << (8 * x);
  }
};
constexpr RowIndexTable kRowIndices;

// Each table's modifiers as 16-bit lanes laid out as two texels' RGBA
// (alpha's lane 0): indices 0 and 1, then 2 and 3.
struct ModifierLanes {
  alignas(16) std::int16_t v[8][2][8];
  constexpr ModifierLanes() : v() {
    for (int t = 0; t < 8; ++t)
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) v[t][i / 2][4 * (i % 2) + c] = std::int16_t(kModifiers[t][i]);
  }
};
constexpr ModifierLanes kModifierLanes;

}  // namespace

// A sub-block's four colours as opaque RGBA8 words (base colour plus each
// modifier, clamped): the plain reference, and below the same words from
// 16-bit lanes whose saturating pack to bytes is the clamp.
void sub_block_palette_scalar(const int c[3], int table, std::uint32_t out[4]) {
  for (int idx = 0; idx < 4; ++idx) {
    const int m = kModifiers[table][idx];
    out[idx] = word(c[0] + m, c[1] + m, c[2] + m);
  }
}

void sub_block_palette(const int c[3], int table, std::uint32_t out[4]) {
#if defined(__SSE2__)
  const __m128i base = _mm_setr_epi16(std::int16_t(c[0]), std::int16_t(c[1]), std::int16_t(c[2]), 255,
                                      std::int16_t(c[0]), std::int16_t(c[1]), std::int16_t(c[2]), 255);
  const __m128i* m = reinterpret_cast<const __m128i*>(kModifierLanes.v[table]);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(out), _mm_packus_epi16(_mm_add_epi16(base, _mm_load_si128(m)),
                                                                     _mm_add_epi16(base, _mm_load_si128(m + 1))));
#else
  sub_block_palette_scalar(c, table, out);
#endif
}

namespace {

// The texels as RGBA8 words (row by row): each sub-block's four colours once
// (sub-block 1's at 4..7), then, a row at a time, the texels' indices into
// them (the index bits transposed from column order to row order).
// `put(y, q0, q1, q2, q3)` takes row y's four texels.
template <class Put>
inline __attribute__((always_inline)) void sub_block_rows(std::uint64_t v, const int c1[3], const int c2[3],
                                                          bool non_opaque, Put put) {
  const int table[2] = {bits(v, 39, 3), bits(v, 36, 3)};
  const bool flip = bits(v, 32, 1) != 0;
  std::uint32_t pal[8];
  if (!non_opaque) {
    sub_block_palette(c1, table[0], pal);
    sub_block_palette(c2, table[1], pal + 4);
  } else {  // ETC2 punch-through: index 0 has no modifier, index 2 is transparent black
    for (int sub = 0; sub < 2; ++sub) {
      const int* c = sub ? c2 : c1;
      for (int idx = 0; idx < 4; ++idx) {
        const int m = idx == 0 ? 0 : kModifiers[table[sub]][idx];
        pal[4 * sub + idx] = idx == 2 ? 0u : word(c[0] + m, c[1] + m, c[2] + m);
      }
    }
  }
  const unsigned lsb = transpose4x4(unsigned(v & 0xFFFF)), msb = transpose4x4(unsigned(v >> 16 & 0xFFFF));
  for (int y = 0; y < 4; ++y) {
    // Sub-block 1: the right half (x >= 2), or with the flip bit the bottom half.
    const std::uint32_t second = flip ? (y >= 2 ? 0x04040404u : 0u) : 0x04040000u;
    const std::uint32_t idx = kRowIndices.v[(msb >> (4 * y) & 15) << 4 | (lsb >> (4 * y) & 15)] + second;
    put(y, pal[idx & 7], pal[idx >> 8 & 7], pal[idx >> 16 & 7], pal[idx >> 24]);
  }
}

void decode_sub_blocks(std::uint64_t v, const int c1[3], const int c2[3], bool non_opaque, std::uint32_t out[16]) {
  sub_block_rows(v, c1, c2, non_opaque,
                 [out](int y, std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
                   std::uint32_t* row = out + 4 * y;
                   row[0] = q0, row[1] = q1, row[2] = q2, row[3] = q3;
                 });
}

void decode_paint(std::uint64_t v, const int paint[4][3], bool non_opaque, std::uint32_t out[16]) {
  std::uint32_t pal[4];
  for (int idx = 0; idx < 4; ++idx)
    pal[idx] = non_opaque && idx == 2 ? 0u : word(paint[idx][0], paint[idx][1], paint[idx][2]);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) out[y * 4 + x] = pal[pixel_index(v, x, y)];
}

void decode_t(std::uint64_t v, bool non_opaque, std::uint32_t out[16]) {
  const int c1[3] = {extend4(bits(v, 60, 2) << 2 | bits(v, 57, 2)), extend4(bits(v, 55, 4)), extend4(bits(v, 51, 4))};
  const int c2[3] = {extend4(bits(v, 47, 4)), extend4(bits(v, 43, 4)), extend4(bits(v, 39, 4))};
  const int d = kDistances[bits(v, 35, 2) << 1 | bits(v, 32, 1)];
  const int paint[4][3] = {{c1[0], c1[1], c1[2]},
                           {c2[0] + d, c2[1] + d, c2[2] + d},
                           {c2[0], c2[1], c2[2]},
                           {c2[0] - d, c2[1] - d, c2[2] - d}};
  decode_paint(v, paint, non_opaque, out);
}

void decode_h(std::uint64_t v, bool non_opaque, std::uint32_t out[16]) {
  const int r1 = bits(v, 62, 4), g1 = bits(v, 58, 3) << 1 | bits(v, 52, 1);
  const int b1 = bits(v, 51, 1) << 3 | bits(v, 49, 2) << 1 | bits(v, 47, 1);
  const int r2 = bits(v, 46, 4), g2 = bits(v, 42, 3) << 1 | bits(v, 39, 1), b2 = bits(v, 38, 4);
  // The distance index's lowest bit is implied by the order of the colours.
  const int order = (r1 << 8 | g1 << 4 | b1) >= (r2 << 8 | g2 << 4 | b2) ? 1 : 0;
  const int d = kDistances[bits(v, 34, 1) << 2 | bits(v, 32, 1) << 1 | order];
  const int c1[3] = {extend4(r1), extend4(g1), extend4(b1)}, c2[3] = {extend4(r2), extend4(g2), extend4(b2)};
  const int paint[4][3] = {{c1[0] + d, c1[1] + d, c1[2] + d},
                           {c1[0] - d, c1[1] - d, c1[2] - d},
                           {c2[0] + d, c2[1] + d, c2[2] + d},
                           {c2[0] - d, c2[1] - d, c2[2] - d}};
  decode_paint(v, paint, non_opaque, out);
}

void decode_planar(std::uint64_t v, std::uint32_t out[16]) {
  const int o[3] = {extend6(bits(v, 62, 6)), extend7(bits(v, 56, 1) << 6 | bits(v, 54, 6)),
                    extend6(bits(v, 48, 1) << 5 | bits(v, 44, 2) << 3 | bits(v, 41, 2) << 1 | bits(v, 39, 1))};
  const int h[3] = {extend6(bits(v, 38, 5) << 1 | bits(v, 32, 1)), extend7(bits(v, 31, 7)),
                    extend6(bits(v, 24, 1) << 5 | bits(v, 23, 5))};
  const int w[3] = {extend6(bits(v, 18, 3) << 3 | bits(v, 15, 3)), extend7(bits(v, 12, 5) << 2 | bits(v, 7, 2)),
                    extend6(bits(v, 5, 6))};
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      int c[3];
      for (int k = 0; k < 3; ++k) c[k] = (x * (h[k] - o[k]) + y * (w[k] - o[k]) + 4 * o[k] + 2) >> 2;
      out[y * 4 + x] = word(c[0], c[1], c[2]);
    }
}

int signed3(int v) { return v >= 4 ? v - 8 : v; }

}  // namespace

namespace {
// ETC1's two base colours (individual or differential).
inline __attribute__((always_inline)) void etc1_colors(std::uint64_t v, int c1[3], int c2[3]) {
  if (bits(v, 33, 1)) {
    for (int k = 0; k < 3; ++k) {
      const int base = bits(v, 63 - 8 * k, 5);
      c1[k] = extend5(base);
      c2[k] = extend5((base + signed3(bits(v, 58 - 8 * k, 3))) & 31);
    }
  } else {
    for (int k = 0; k < 3; ++k) {
      c1[k] = extend4(bits(v, 63 - 8 * k, 4));
      c2[k] = extend4(bits(v, 59 - 8 * k, 4));
    }
  }
}

void etc1_words(const std::uint8_t* block, std::uint32_t out[16]) {
  const std::uint64_t v = load_be64(block);
  int c1[3], c2[3];
  etc1_colors(v, c1, c2);
  decode_sub_blocks(v, c1, c2, false, out);
}

// A row's four RGBA words stored as 16 bytes, or as 12 bytes of RGB: whole
// words built in registers and stored once (no small stores read back as a
// larger word: that stalls store forwarding).
// kChannels 0: RGB as four 4-byte stores left to right, one byte past the
// 12 written (as bc_decode.cpp's color_rows: where another block follows).
template <int kChannels>
inline __attribute__((always_inline)) void store_row(std::uint8_t* row, std::uint32_t q0, std::uint32_t q1,
                                                     std::uint32_t q2, std::uint32_t q3) {
  if constexpr (kChannels == 0) {
    std::memcpy(row, &q0, 4);
    std::memcpy(row + 3, &q1, 4);
    std::memcpy(row + 6, &q2, 4);
    std::memcpy(row + 9, &q3, 4);
  } else if constexpr (kChannels == 4) {
    const std::uint64_t lo = q0 | std::uint64_t(q1) << 32, hi = q2 | std::uint64_t(q3) << 32;
    std::memcpy(row, &lo, 8);
    std::memcpy(row + 8, &hi, 8);
  } else {
    const std::uint64_t lo = std::uint64_t((q0 & 0xFFFFFF) | q1 << 24) | std::uint64_t((q1 >> 8 & 0xFFFF) | q2 << 16)
                                                                             << 32;
    const std::uint32_t hi = (q2 >> 16 & 0xFF) | q3 << 8;
    std::memcpy(row, &lo, 8);
    std::memcpy(row + 8, &hi, 4);
  }
}

// An ETC2 RGB block's rows through `put` (as sub_block_rows): the
// individual and differential modes straight from their palette, T, H and
// planar through a block of words.
template <class Put>
inline __attribute__((always_inline)) void etc2_rows(std::uint64_t v, bool punchthrough, Put put) {
  const bool differential = punchthrough || bits(v, 33, 1);
  const bool non_opaque = punchthrough && !bits(v, 33, 1);
  int c1[3], c2[3];
  if (!differential) {
    for (int k = 0; k < 3; ++k) {
      c1[k] = extend4(bits(v, 63 - 8 * k, 4));
      c2[k] = extend4(bits(v, 59 - 8 * k, 4));
    }
    return sub_block_rows(v, c1, c2, false, put);
  }
  int base[3], second[3];
  for (int k = 0; k < 3; ++k) {
    base[k] = bits(v, 63 - 8 * k, 5);
    second[k] = base[k] + signed3(bits(v, 58 - 8 * k, 3));
  }
  // A second colour outside 0..31 selects the modes ETC2 added.
  if ((second[0] | second[1] | second[2]) & ~31) {
    std::uint32_t t[16];
    if (second[0] < 0 || second[0] > 31) {
      decode_t(v, non_opaque, t);
    } else if (second[1] < 0 || second[1] > 31) {
      decode_h(v, non_opaque, t);
    } else {
      decode_planar(v, t);
    }
    for (int y = 0; y < 4; ++y) put(y, t[4 * y], t[4 * y + 1], t[4 * y + 2], t[4 * y + 3]);
    return;
  }
  for (int k = 0; k < 3; ++k) {
    c1[k] = extend5(base[k]);
    c2[k] = extend5(second[k]);
  }
  sub_block_rows(v, c1, c2, non_opaque, put);
}

void etc2_words(const std::uint8_t* block, bool punchthrough, std::uint32_t out[16]) {
  etc2_rows(load_be64(block), punchthrough,
            [out](int y, std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
              std::uint32_t* row = out + 4 * y;
              row[0] = q0, row[1] = q1, row[2] = q2, row[3] = q3;
            });
}
}  // namespace

void decode_etc1(const std::uint8_t* block, Rgba8Block out) {
  std::uint32_t w[16];
  etc1_words(block, w);
  std::memcpy(out, w, 64);
}

void decode_etc2(const std::uint8_t* block, bool punchthrough, Rgba8Block out) {
  std::uint32_t w[16];
  etc2_words(block, punchthrough, w);
  std::memcpy(out, w, 64);
}

void decode_etc_run(const std::uint8_t* blocks, int count, int block_bytes, EtcRun kind, std::uint8_t* dst,
                    std::size_t stride) {
  if (kind == EtcRun::etc1_rgb) {  // ETC1: the texels straight from the palette into the rows
    for (int k = 0; k < count; ++k) {
      const std::uint64_t v = load_be64(blocks + std::size_t(k) * block_bytes);
      int c1[3], c2[3];
      etc1_colors(v, c1, c2);
      std::uint8_t* out = dst + std::size_t(k) * 12;
      const bool last = k + 1 == count;
      sub_block_rows(
          v, c1, c2, false,
          [out, stride, last](int y, std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
            if (last) {
              store_row<3>(out + y * stride, q0, q1, q2, q3);
            } else {
              store_row<0>(out + y * stride, q0, q1, q2, q3);
            }
          });
    }
    return;
  }
  for (int k = 0; k < count; ++k) {
    const std::uint8_t* b = blocks + std::size_t(k) * block_bytes;
    if (kind == EtcRun::etc2_rgb) {
      std::uint8_t* out = dst + std::size_t(k) * 12;
      const bool last = k + 1 == count;
      etc2_rows(load_be64(b), false,
                [out, stride, last](int y, std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
                  if (last) {
                    store_row<3>(out + y * stride, q0, q1, q2, q3);
                  } else {
                    store_row<0>(out + y * stride, q0, q1, q2, q3);
                  }
                });
    } else if (kind == EtcRun::etc2_rgba1) {
      std::uint8_t* out = dst + std::size_t(k) * 16;
      etc2_rows(load_be64(b), true,
                [out, stride](int y, std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
                  store_row<4>(out + y * stride, q0, q1, q2, q3);
                });
    } else {  // ETC2 + EAC: the alpha block first
      std::uint8_t alpha[16];
      decode_eac8(b, alpha);
      std::uint8_t* out = dst + std::size_t(k) * 16;
      etc2_rows(load_be64(b + 8), false,
                [out, stride, &alpha](int y, std::uint32_t q0, std::uint32_t q1, std::uint32_t q2, std::uint32_t q3) {
                  const std::uint8_t* a = alpha + 4 * y;
                  auto with = [](std::uint32_t q, std::uint8_t av) {
                    return (q & 0xFFFFFFu) | std::uint32_t(av) << 24;
                  };
                  store_row<4>(out + y * stride, with(q0, a[0]), with(q1, a[1]), with(q2, a[2]), with(q3, a[3]));
                });
    }
  }
}

void decode_eac11(const std::uint8_t* block, bool snorm, int out[16]) {
  const std::uint64_t v = load_be64(block);
  const int mult = bits(v, 55, 4);
  const int* mods = kEacModifiers[bits(v, 51, 4)];
  int base = bits(v, 63, 8);
  if (snorm) {
    base = base >= 128 ? base - 256 : base;
    if (base == -128) base = -127;
  }
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int m = mods[bits(v, 47 - 3 * (x * 4 + y), 3)];
      const int step = mult ? m * mult * 8 : m;
      int value = snorm ? base * 8 + step : base * 8 + 4 + step;
      const int lo = snorm ? -1023 : 0, hi = snorm ? 1023 : 2047;
      value = value < lo ? lo : value > hi ? hi : value;
      out[y * 4 + x] = value;
    }
}

void decode_eac8(const std::uint8_t* block, std::uint8_t out[16]) {
  const std::uint64_t v = load_be64(block);
  const int base = bits(v, 63, 8), mult = bits(v, 55, 4);
  const int* mods = kEacModifiers[bits(v, 51, 4)];
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      out[y * 4 + x] = std::uint8_t(clamp255(base + mods[bits(v, 47 - 3 * (x * 4 + y), 3)] * mult));
    }
}

namespace {
// Each 11-bit EAC value as the 8 bits Image::set stores for the float
// decoder's value (the same float expressions, evaluated once).
struct Eac8Tables {
  std::uint8_t unorm[2048], snorm[2047];  // SNORM indexed by v + 1023
  Eac8Tables() {
    auto to8 = [](float v) {
      const float cl = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f;
      return std::uint8_t(cl * 255.0f + 0.5f);
    };
    for (int v = 0; v < 2048; ++v) unorm[v] = to8(float(v) / 2047.0f);
    for (int v = -1023; v <= 1023; ++v) snorm[v + 1023] = to8((float(v) / 1023.0f + 1.0f) * 0.5f);
  }
};
const Eac8Tables& eac8_tables() {
  static const Eac8Tables t;
  return t;
}

template <int kChannels>
inline __attribute__((always_inline)) void eac11_u8_rows(const std::uint8_t* block, bool snorm, int ch,
                                                         const Eac8Tables& T, std::uint8_t* dst, std::size_t stride) {
  const std::uint64_t v = load_be64(block);
  const int mult = bits(v, 55, 4);
  const int* mods = kEacModifiers[bits(v, 51, 4)];
  int base = bits(v, 63, 8);
  // decode_eac11's value for each of the eight indices, then its 8 bits.
  std::uint8_t pal[8];
  if (snorm) {
    base = base >= 128 ? base - 256 : base;
    if (base == -128) base = -127;
    for (int i = 0; i < 8; ++i) {
      const int value = base * 8 + (mult ? mods[i] * mult * 8 : mods[i]);
      pal[i] = T.snorm[(value < -1023 ? -1023 : value > 1023 ? 1023 : value) + 1023];
    }
  } else {
    for (int i = 0; i < 8; ++i) {
      const int value = base * 8 + 4 + (mult ? mods[i] * mult * 8 : mods[i]);
      pal[i] = T.unorm[value < 0 ? 0 : value > 2047 ? 2047 : value];
    }
  }
  // Texel (x, y)'s index: bits 47 - 3 (4 x + y) down (column by column).
  for (int y = 0; y < 4; ++y) {
    std::uint8_t* row = dst + y * stride + ch;
    for (int x = 0; x < 4; ++x) row[x * kChannels] = pal[v >> (45 - 3 * (4 * x + y)) & 7];
  }
}
}  // namespace

void decode_eac11_u8_run(const std::uint8_t* blocks, int count, int block_bytes, bool snorm, int channels, int ch,
                         std::uint8_t* dst, std::size_t stride) {
  const Eac8Tables& T = eac8_tables();
  if (channels == 1) {
    for (int k = 0; k < count; ++k)
      eac11_u8_rows<1>(blocks + std::size_t(k) * block_bytes, snorm, ch, T, dst + 4 * k, stride);
  } else {
    for (int k = 0; k < count; ++k)
      eac11_u8_rows<2>(blocks + std::size_t(k) * block_bytes, snorm, ch, T, dst + 8 * k, stride);
  }
}

}  // namespace texproc::etc
