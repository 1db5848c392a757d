// The scalar reference of rgb_block.h (namespace ref): what rgb_block_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "block/rgb_block.h"

#include <algorithm>

namespace texproc::ref {

void rgb_moments(const RgbBlock& tx, RgbMoments& m) {
  m = RgbMoments{};
  for (int i = 0; i < 16; ++i) {
    if (tx.transparent[i]) continue;
    const std::int32_t r = tx.r[i], g = tx.g[i], b = tx.b[i];
    ++m.n;
    m.sum[0] += r;
    m.sum[1] += g;
    m.sum[2] += b;
    m.sq[0] += r * r;
    m.sq[1] += r * g;
    m.sq[2] += r * b;
    m.sq[3] += g * g;
    m.sq[4] += g * b;
    m.sq[5] += b * b;
  }
}

void rgb_project_range(const RgbBlock& tx, const float axis[3], float& lo, float& hi) {
  lo = 1e30f;
  hi = -1e30f;
  for (int i = 0; i < 16; ++i) {
    if (tx.transparent[i]) continue;
    const float p = float(tx.r[i]) * axis[0] + float(tx.g[i]) * axis[1] + float(tx.b[i]) * axis[2];
    lo = std::min(lo, p);
    hi = std::max(hi, p);
  }
}

std::int32_t rgb_palette_nearest(const RgbBlock& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]) {
  std::int32_t total = 0;
  for (int i = 0; i < 16; ++i) {
    if (tx.transparent[i]) {
      codes[i] = 3;
      continue;
    }
    int best = 0;
    std::int32_t be = -1;
    for (int k = 0; k < candidates; ++k) {
      const std::int32_t dr = tx.r[i] - pal[k][0], dg = tx.g[i] - pal[k][1], db = tx.b[i] - pal[k][2];
      const std::int32_t d = dr * dr + dg * dg + db * db;
      if (be < 0 || d < be) {
        be = d;
        best = k;
      }
    }
    codes[i] = std::uint8_t(best);
    total += be;
  }
  return total;
}

void rgb_ls_sums(const RgbBlock& tx, const std::uint8_t codes[16], const int weight[4], int den, RgbLsSums& s) {
  s = RgbLsSums{};
  for (int i = 0; i < 16; ++i) {
    const int w = weight[codes[i]];
    if (tx.transparent[i] || w < 0) continue;
    const int u = den - w;
    s.aa += u * u;
    s.ab += u * w;
    s.bb += w * w;
    s.at[0] += u * tx.r[i];
    s.at[1] += u * tx.g[i];
    s.at[2] += u * tx.b[i];
    s.bt[0] += w * tx.r[i];
    s.bt[1] += w * tx.g[i];
    s.bt[2] += w * tx.b[i];
  }
}

}  // namespace texproc::ref
