// The inner loops of the cone-map search: a cell of up to 8x8 apex texels
// against obstacles, SIMD across the cell's texels in row order (Highway)
// with a plain scalar reference beside it; both give identical ratios.
//
// One candidate, the same float operations everywhere (brute force included):
//   dx, dy  = texel distances along each axis (the nearest periodic copy with
//             repeat; for a block, to its nearest texel), minus `shrink`,
//             never below 0
//   d2      = float(dx * dx) * sx + float(dy * dy) * sy
//   counted when hq > hp and d2 > 0, as r2 = d2 / (dd * ((hq - hp) * (hq - hp)))
// and a texel's squared ratio is the smallest r2 (or the cap it starts from).
#pragma once

#include <cstddef>

namespace texproc::detail {

constexpr int kConeCell = 8;

struct ConeGeometry {
  int W = 0, H = 0;
  bool repeat = true;
  float sx = 0, sy = 0, dd = 0;  // 1 / W^2, 1 / H^2, depth^2
  int shrink = 0;                // texels taken off each axis distance (0: the classic cones)
  // Optional: the highest of each run of 8 texels in a row (x / 8, y), with
  // (W + 7) / 8 per row: lets a scan skip obstacle rows no higher than the apexes.
  const float* row_max8 = nullptr;
  // Relaxed cones: per texel, which 4-neighbours are lower (bit 0: +x,
  // 1: -x, 2: +y, 3: -y); a texel counts for an apex only where the ray can
  // leave the relief behind it (cone_exits). Null: conservative cones.
  const unsigned char* exit_bits = nullptr;
};

// The relaxed-cone exit rule, written once: the 4-neighbours of q that lie
// behind q as seen from p, one step farther from p along x or y (both ways
// when p and q share that coordinate, or are half the map apart with
// repeat), as bits (0: +x, 1: -x, 2: +y, 3: -y). q counts for p only where
// one of those neighbours is lower than q: the ray can leave the relief.
inline unsigned exit_directions(int px, int py, int qx, int qy, int W, int H, bool repeat) {
  auto offset = [&](int p, int q, int n) {
    int d = q - p;
    if (repeat) {
      if (d > n / 2) d -= n;
      if (d < -n / 2) d += n;
    }
    return d;
  };
  const int ox = offset(px, qx, W), oy = offset(py, qy, H);
  const bool both_x = repeat && 2 * (ox < 0 ? -ox : ox) == W, both_y = repeat && 2 * (oy < 0 ? -oy : oy) == H;
  return ((ox >= 0 || both_x) ? 1u : 0u) | ((ox <= 0 || both_x) ? 2u : 0u) | ((oy >= 0 || both_y) ? 4u : 0u) |
         ((oy <= 0 || both_y) ? 8u : 0u);
}

// Relaxed cones: whether texel q, higher than p, has a lower 4-neighbour
// behind it as seen from p (exit_directions against q's exit bits).
inline bool cone_exits(const ConeGeometry& g, int px, int py, int qx, int qy) {
  return (exit_directions(px, py, qx, qy, g.W, g.H, g.repeat) & g.exit_bits[std::size_t(qy) * g.W + qx]) != 0;
}

struct ConeCell {
  int x0 = 0, y0 = 0;                            // apex texel of lane 0, row 0
  alignas(64) float apex[kConeCell][kConeCell];  // apex heights; +inf where no texel is
  alignas(64) float best[kConeCell][kConeCell];  // squared ratios so far
};

// Every texel of columns [bx0, bx1] and rows [by0, by1] (at most 8 of each,
// inside the map, bx0 a multiple of 8) as an obstacle to the apex rows r
// with rows[r] (others may be scanned too: they cannot change). Returns
// whether any ratio narrowed.
bool cone_cell_texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                      const bool rows[kConeCell]);
// The block [bx0, bx1] x [by0, by1] as one obstacle of height M at its
// nearest texel to each apex (--fast: a bound for everything in it).
bool cone_cell_block(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M,
                     const bool rows[kConeCell]);

// Whether the block [bx0, bx1] x [by0, by1] of height M can narrow no cone
// of the cell, each apex paired with its own cone and its own distance (a
// bound from the cell's lowest apex and widest cone fails on mixed cells:
// white noise, a capped cone on a peak beside narrow ones). With rise > 0,
// the block's heights climb at least `rise` per texel away from the cell
// along `axis` (0: x, 1: y), `extent` texels deep: a texel at offset a from
// the near edge is at most M - (extent - a) rise high, and the least ratio
// over a is at a = 0 or a = extent (the bound is linear-fractional in a,
// with the apex-to-texel distance taken as its projection on the direction
// from the apex to the block). Needs shrink == 0 when rise > 0.
bool cone_cell_clear(const ConeGeometry& g, const ConeCell& c, int bx0, int bx1, int by0, int by1, float M, int axis,
                     float rise, int extent);
// The cheaper test --fast uses (its blocks are near the cell): max over the
// apexes of best * (M - apex)^2, to compare with the cell's gap term / depth^2.
float cone_cell_reach(const ConeCell& c, float M);

// Distance along one axis from texel p to the nearest texel of [lo, hi]
// (0 inside), with repeat the nearest periodic copy.
inline int cone_axis_distance(int p, int lo, int hi, int n, bool repeat) {
  int d = p < lo ? lo - p : p > hi ? p - hi : 0;
  if (repeat && d > 0) {
    const int a = lo + n - p, b = p - hi + n;
    d = d < a ? d : a;
    d = d < b ? d : b;
  }
  return d;
}

// One candidate's squared ratio term, as defined above (d2 from the two
// axis distances after shrinking).
inline float cone_d2(const ConeGeometry& g, int dx, int dy) {
  dx = dx > g.shrink ? dx - g.shrink : 0;
  dy = dy > g.shrink ? dy - g.shrink : 0;
  return float(dx * dx) * g.sx + float(dy * dy) * g.sy;
}

inline float cone_r2(const ConeGeometry& g, float d2, float dh) { return d2 / (g.dd * (dh * dh)); }

namespace ref {
bool cone_cell_texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                      const bool rows[kConeCell]);
bool cone_cell_block(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M,
                     const bool rows[kConeCell]);
bool cone_cell_clear(const ConeGeometry& g, const ConeCell& c, int bx0, int bx1, int by0, int by1, float M, int axis,
                     float rise, int extent);
float cone_cell_reach(const ConeCell& c, float M);
}  // namespace ref

}  // namespace texproc::detail
