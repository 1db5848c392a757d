// What the ETC1 and ETC2 block searches share (etc1_encode.cpp: the
// half-block fit and the individual/differential modes; etc2_modes.cpp:
// planar, T and H; etc_encode.cpp: flat blocks and the block entry): the
// texels of a block, a half's fit, a packed candidate, the bit packer.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

#include "block/rgb_block.h"
#include "etc/etc_eval.h"
#include "etc/etc_levels.h"
#include "etc/etc_tables.h"
#include "texproc/block_encode.h"

namespace texproc::etc {

constexpr long kNone = std::numeric_limits<long>::max() / 4;

// The texels of each half block, as (x, y): 0 left, 1 right, 2 top, 3 bottom.
struct HalfLayout {
  int x[8], y[8];
};
const std::array<HalfLayout, 4>& halves();

struct Texels {
  int rgb[16][3];
  bool transparent[16];  // punch-through: alpha < 128
  bool any_transparent = false;
  HalfTexels half[4];  // the texels of each half block, as planes (for eval_half)
  RgbBlock planes;     // all 16 as planes (for rgb_palette_nearest: T and H of opaque blocks)
};

struct HalfFit {
  long err = kNone;
  int q[3] = {0, 0, 0};  // base colour at 4 or 5 bits
  int table = 0;
  std::uint8_t idx[8] = {};
};

inline int expand(int q, int bits) { return bits == 4 ? extend4(q) : extend5(q); }
inline int quantize(double v, int bits) {
  // Rounded to nearest (halves up) and clamped, without a libm call.
  const int top = (1 << bits) - 1;
  const double x = v * top / 255.0;
  if (!(x > 0.0)) return 0;
  return std::min(int(x + 0.5), top);
}

// Bits high..high-count+1 of a block's 64-bit word (bit 63 first).
inline void put(std::uint64_t& v, int high, int count, int value) {
  const int low = high - count + 1;
  const std::uint64_t mask = ((std::uint64_t(1) << count) - 1) << low;
  v = (v & ~mask) | ((std::uint64_t(unsigned(value)) << low) & mask);
}

inline void put_index(std::uint64_t& v, int x, int y, int idx) {
  const int k = x * 4 + y;
  put(v, k + 16, 1, idx >> 1);
  put(v, k, 1, idx & 1);
}

// A packed block and its error; keep() takes a better one.
struct Candidate {
  long err = kNone;
  std::uint64_t bits = 0;
};

inline void keep(Candidate& best, long err, std::uint64_t bits) {
  if (err < best.err) {
    best.err = err;
    best.bits = bits;
  }
}

// The differential mode's 3-bit delta reaches from a to b.
inline bool delta_fits(const int a[3], const int b[3]) {
  for (int c = 0; c < 3; ++c)
    if (b[c] - a[c] < -4 || b[c] - a[c] > 3) return false;
  return true;
}

// etc1_encode.cpp
HalfFit fit_half(const Texels& tx, int h, int bits, const Etc1BlockSearch& search, bool non_opaque);
HalfFit fit_fixed(const Texels& tx, int h, const int q[3], bool non_opaque);
std::uint64_t pack_halves(const HalfFit& a, const HalfFit& b, bool flip, bool differential, int bit33);
void keep_pair(Candidate& best, const HalfFit& a, const HalfFit& b, bool flip, bool differential, int bit33);
void search_etc1_modes(const Texels& tx, const Etc1BlockSearch& search, bool allow_individual, bool non_opaque,
                       int bit33_diff, Candidate& best);

// etc2_modes.cpp
void search_planar(const Texels& tx, const Etc2Modes& modes, Candidate& best);
std::uint64_t pack_planar(const int o[3], const int hq[3], const int vq[3]);
void search_t_h(const Texels& tx, bool non_opaque, const Etc2Modes& modes, Candidate& best);

}  // namespace texproc::etc
