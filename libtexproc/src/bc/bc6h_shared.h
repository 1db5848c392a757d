// BC6H's arithmetic that the decoder (bptc_decode.cpp) and the encoder
// (bc6h_lanes*.cpp, bc6h_pack.cpp) share, as ARB_texture_compression_bptc
// and the Khronos Data Format Specification's BPTC chapter give it: the
// modes' bit layouts, endpoint unquantization, the final scaling to half
// floats; and what the encoder adds: endpoint quantization, the limits of
// transformed (delta) endpoints, and the chosen block's packing.
#pragma once

#include <cmath>
#include <cstdint>

#include "bc/bptc_tables.h"

namespace texproc::bc6h {

// A mode's layout string (bptc_tables.h), parsed: each field's variable
// (m, r0-r3, g0-g3, b0-b3), its bit count and where its first bit goes.
struct Field {
  int var;    // 0: m; 1 + 4 * channel + endpoint: r0..r3, g0..g3, b0..b3
  int count;  // bits
  int first;  // the variable's bit that takes the first bit of the field
  int step;   // +1 or -1: where the next goes
};
struct Layout {
  Field fields[32];
  int n = 0;
};

inline Layout parse_layout(const char* s) {
  Layout L;
  while (*s) {
    Field f{};
    if (*s == 'm') {
      f.var = 0;
      ++s;
    } else {
      const int ch = *s == 'r' ? 0 : *s == 'g' ? 1 : 2;
      f.var = 1 + 4 * ch + (s[1] - '0');
      s += 2;
    }
    ++s;  // '['
    int a = 0, b = -1;
    while (*s >= '0' && *s <= '9') a = a * 10 + (*s++ - '0');
    if (*s == ':') {
      ++s;
      b = 0;
      while (*s >= '0' && *s <= '9') b = b * 10 + (*s++ - '0');
    } else {
      b = a;
    }
    ++s;  // ']'
    if (*s == ',') ++s;
    f.count = (a >= b ? a - b : b - a) + 1;
    f.first = b;
    f.step = a >= b ? 1 : -1;
    L.fields[L.n++] = f;
  }
  return L;
}

struct Layouts {
  Layout modes[14];
  int by_number[32];  // mode number -> index in kBc6hModes, -1 reserved
  Layouts() {
    for (int& v : by_number) v = -1;
    for (int k = 0; k < 14; ++k) {
      modes[k] = parse_layout(bptc::kBc6hModes[k].layout);
      by_number[bptc::kBc6hModes[k].number] = k;
    }
  }
};
inline const Layouts& layouts() {
  static const Layouts L;
  return L;
}

// kBc6hModes[k] for k < kOneRegion has two regions (32 partitions, 3-bit
// indices); from it on, one (4-bit indices).
inline constexpr int kOneRegion = 10;
inline int regions(int k) { return k < kOneRegion ? 2 : 1; }
inline int index_bits(int k) { return k < kOneRegion ? 3 : 4; }

inline int sign_extend(int v, int bits) { return v & (1 << (bits - 1)) ? v - (1 << bits) : v; }

// An endpoint of `bits` bits to 16 (UF16: [0, 0xFFFF]; SF16: [-0x7FFF, 0x7FFF]).
inline int unquantize(int x, int bits, bool is_signed) {
  if (!is_signed) {
    if (bits >= 15) return x;
    if (x == 0) return 0;
    if (x == (1 << bits) - 1) return 0xFFFF;
    return ((x << 15) + 0x4000) >> (bits - 1);
  }
  if (bits >= 16) return x;
  const bool negative = x < 0;
  if (negative) x = -x;
  int unq;
  if (x == 0) {
    unq = 0;
  } else if (x >= (1 << (bits - 1)) - 1) {
    unq = 0x7FFF;
  } else {
    unq = ((x << 15) + 0x4000) >> (bits - 1);
  }
  return negative ? -unq : unq;
}

// The interpolated value's final scaling: the half float's bits as a signed
// magnitude (UF16: the bits; SF16: minus the magnitude bits for a negative
// half). The encoder compares texels in this form; half_bits stores it.
inline int finish(int v, bool is_signed) {
  if (!is_signed) return (v * 31) >> 6;
  return v < 0 ? -((-v * 31) >> 5) : (v * 31) >> 5;
}
// The decoder's half: finish's bits, the sign kept where the magnitude
// rounds to 0 (SF16's -0).
inline std::uint16_t finish_bits(int v, bool is_signed) {
  const int f = finish(v, is_signed);
  return is_signed && v < 0 ? std::uint16_t(0x8000 | -f) : std::uint16_t(f);
}

// A half float's bits as the encoder's target: finish's form, the largest
// finite magnitude 0x7BFF (infinities and NaN clamp; UF16 negative to 0).
inline int target(std::uint16_t h, bool is_signed) {
  const int mag = h & 0x7FFF;
  const int m = mag > 0x7BFF ? (mag > 0x7C00 ? 0 : 0x7BFF) : mag;  // NaN to 0, infinity to the largest
  if (h & 0x8000) return is_signed ? -m : 0;
  return m;
}

// The largest finite texel the format decodes: 0x7BFF (65504).
inline constexpr int kMaxFinish = 0x7BFF;

// The search's texel error: the squared difference of finish values per
// channel, each difference limited to kErrorLimit (a factor of 16 in the
// value), so a block's sum stays an int (48 * 4095^2 < 2^31). Differences of
// half bits are close to relative (logarithmic) differences of the values:
// the error HDR needs, a step of a half's mantissa weighing the same at
// every exponent.
inline constexpr int kErrorLimit = 4095;

// The endpoint code (`bits` bits) whose unquantized value is nearest u (the
// unquantized domain: [0, 65535] UF16, [-32767, 32767] SF16): the code of
// the bin u falls in, or a neighbour that unquantizes closer (ties: the
// bin's, then the lower).
inline int quantize(float u, int bits, bool is_signed) {
  const int top = is_signed ? (1 << (bits - 1)) - 1 : (1 << bits) - 1;
  const float m = is_signed ? (u < 0.0f ? -u : u) : u;
  const float limit = is_signed ? 32767.0f : 65535.0f;
  const float c = m < 0.0f ? 0.0f : m > limit ? limit : m;
  // bins of 2^(16 - bits) (unsigned) or 2^(15 - (bits - 1)) (signed) values
  const float scale = float(1 << (bits - 1)) * (1.0f / 32768.0f);
  int q = int(std::floor(c * scale));
  q = q < 0 ? 0 : q > top ? top : q;
  auto dist = [&](int code) {
    const float v = float(unquantize(code, bits, is_signed));
    return v > c ? v - c : c - v;
  };
  int best = q;
  float bd = dist(q);
  if (q > 0 && dist(q - 1) < bd) {
    best = q - 1;
    bd = dist(q - 1);
  }
  if (q < top && dist(q + 1) < bd) best = q + 1;
  return is_signed && u < 0.0f ? -best : best;
}

// A transformed mode's endpoint j: the code qj where the decoder can reach
// it from the base q0 (q0 plus a delta of `delta_bits`, wrapped to
// `endpoint_bits`), else the nearest it can reach, q0 + the delta clamped.
inline int limit_delta(int q0, int qj, int endpoint_bits, int delta_bits) {
  const int lo = -(1 << (delta_bits - 1)), hi = (1 << (delta_bits - 1)) - 1;
  const int diff = qj - q0;
  const int half = 1 << (endpoint_bits - 1);
  const int wrapped = ((diff + half) & ((1 << endpoint_bits) - 1)) - half;
  if (wrapped >= lo && wrapped <= hi) return qj;
  return q0 + (diff < lo ? lo : diff > hi ? hi : diff);
}

// One block as the encoder chose it: the mode (an index in kBc6hModes), the
// partition (two regions), the endpoints' codes as the decoder reads them
// back at the mode's endpoint bits (region 0: 0 and 1, region 1: 2 and 3;
// SF16 signed; a transformed mode's delta must reach them), and the indices
// (each region's anchor texel below half of the range).
struct Choice {
  int mode = kOneRegion;
  int partition = 0;
  int code[4][3] = {};
  std::uint8_t index[16] = {};
};

// The 16 bytes of `c`.
void pack_block(const Choice& c, std::uint8_t out[16]);

}  // namespace texproc::bc6h
