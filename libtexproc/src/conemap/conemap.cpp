// Cone maps by branch and bound over a maximum mip pyramid (the approach of
// Valasek and Ban, "Quick Cone Map Generation on the GPU", EGS 2022, made
// exact): blocks of the pyramid are visited nearest first; a block whose
// maximum height M at its nearest distance d cannot give a ratio below the
// best so far, d / (depth * (M - h_p)) >= best, is skipped with everything
// in it. Conservative cones walk the pyramid once per 8x8 cell of apex
// texels and scan the surviving 8x8 blocks with SIMD (cone_cells.h);
// relaxed cones too, with the exit rule and pyramids of exits.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "conemap/cone_cells.h"
#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

void check(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o) {
  if (width <= 0 || height <= 0 || heights.size() != std::size_t(width) * height) {
    throw Error(ErrorCode::bad_arguments, "heights do not match the size");
  }
  if (!(o.depth > 0.0f) || !std::isfinite(o.depth)) throw Error(ErrorCode::bad_arguments, "ConeMapOptions::depth must be > 0");
  if (!(o.max_ratio > 0.0f) || !std::isfinite(o.max_ratio)) throw Error(ErrorCode::bad_arguments, "ConeMapOptions::max_ratio must be > 0");
  if (o.wrap == WrapMode::mirror) throw Error(ErrorCode::bad_arguments, "ConeMapOptions::wrap: valid: repeat, clamp");
  if (o.fast_reach < 0) throw Error(ErrorCode::bad_arguments, "ConeMapOptions::fast_reach must be >= 1 (0: exact cones)");
  if (o.bilinear_safe && o.mode == ConeMode::relaxed) {
    throw Error(ErrorCode::bad_arguments, "ConeMapOptions::bilinear_safe makes conservative cones (use it without ConeMode::relaxed)");
  }
}

// The terms of a squared ratio, (dx^2 sx + dy^2 sy) / (dd dh^2), in double
// for the search's bounds (candidates are in float: cone_cells.h).
struct Metric {
  double sx, sy, dd;  // 1 / W^2, 1 / H^2, depth^2
};

int texel_distance(int p, int q, int n, bool repeat) {
  const int d = p > q ? p - q : q - p;
  return repeat ? std::min(d, n - d) : d;
}

struct Pyramid {
  const float* base = nullptr;          // level 0: the heights (not copied)
  std::vector<std::vector<float>> max;  // levels 1 and up (max[0] unused)
  std::vector<int> w, h;
  const float* level(int k) const { return k == 0 ? base : max[std::size_t(k)].data(); }
  int levels() const { return int(w.size()); }
};

// `heights` must outlive the pyramid.
Pyramid build_pyramid(const std::vector<float>& heights, int W, int H) {
  Pyramid p;
  p.base = heights.data();
  p.max.emplace_back();
  p.w.push_back(W);
  p.h.push_back(H);
  while (p.w.back() > 1 || p.h.back() > 1) {
    const int k = p.levels() - 1;
    const int pw = p.w.back(), ph = p.h.back(), nw = (pw + 1) / 2, nh = (ph + 1) / 2;
    const float* prev = p.level(k);
    std::vector<float> next(std::size_t(nw) * nh);
    for_each_row_block(nh, 64, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < nw; ++x) {
          float m = prev[std::size_t(2 * y) * pw + 2 * x];
          if (2 * x + 1 < pw) m = std::max(m, prev[std::size_t(2 * y) * pw + 2 * x + 1]);
          if (2 * y + 1 < ph) {
            m = std::max(m, prev[std::size_t(2 * y + 1) * pw + 2 * x]);
            if (2 * x + 1 < pw) m = std::max(m, prev[std::size_t(2 * y + 1) * pw + 2 * x + 1]);
          }
          next[std::size_t(y) * nw + x] = m;
        }
    });
    p.max.push_back(std::move(next));
    p.w.push_back(nw);
    p.h.push_back(nh);
  }
  return p;
}

// Prune only when the bound exceeds the best by more than rounding could
// explain: bounds are in double, candidates in float (within a few float
// ulps, 1e-7 relative, of the real quotient).
constexpr double kPruneSlack = 1.0 + 1e-5;

struct Node {
  int level, x, y;
  double bound;
  int gx = 0, gy = 0;  // cells: the block's gap to the cell along x and y
  float M = 0.0f;      // cells: the block's bound height (its highest texel that can count)
};

// Relaxed cones count a higher texel q only if a 4-neighbour behind it, as
// seen from p (one step farther from p along x or y; both ways when p and q
// share that coordinate), is lower: the ray can leave the relief there.
// With clamp, no neighbour exists past the edge (a ray leaves the texture).
struct Behind {
  const std::vector<float>& h;
  int W, H;
  bool repeat;
  bool lower(int qx, int qy, float hq, int sx, int sy) const {
    int nx = qx + sx, ny = qy + sy;
    if (repeat) {
      nx = (nx + W) % W;
      ny = (ny + H) % H;
    } else if (nx < 0 || ny < 0 || nx >= W || ny >= H) {
      return false;
    }
    return h[std::size_t(ny) * W + nx] < hq;
  }
  // The rule of exit_directions (cone_cells.h), on the heights themselves.
  bool exits(int px, int py, int qx, int qy, float hq) const {
    const unsigned d = detail::exit_directions(px, py, qx, qy, W, H, repeat);
    return ((d & 1) && lower(qx, qy, hq, 1, 0)) || ((d & 2) && lower(qx, qy, hq, -1, 0)) ||
           ((d & 4) && lower(qx, qy, hq, 0, 1)) || ((d & 8) && lower(qx, qy, hq, 0, -1));
  }
};

// Gap in texels between texel ranges [a0, a1] and [b0, b1] along an axis of
// n texels (with repeat, to the nearest periodic copy of b).
inline int range_gap(int a0, int a1, int b0, int b1, int n, bool repeat, int* side = nullptr) {
  // The gap to [b0, b1] shifted by `shift`, and the side it lies on.
  auto gap = [a0, a1, b0, b1](int shift, int& sd) {
    const int after = b0 + shift - a1, before = a0 - (b1 + shift);
    sd = after > 0 ? 1 : before > 0 ? -1 : 0;
    return after > 0 ? after : before > 0 ? before : 0;
  };
  int sd = 0, g = gap(0, sd);
  if (repeat && g > 0) {
    int s2 = 0;
    int g2 = gap(-n, s2);
    if (g2 < g) g = g2, sd = s2;
    g2 = gap(n, s2);
    if (g2 < g) g = g2, sd = s2;
  }
  if (side) *side = sd;
  return g;
}

// From pyramid level 3 up: for each block, the smallest height step between
// 4-neighbours in each direction over the steps that start in the block
// ([0] h(x+1) - h(x), [1] h(x) - h(x+1), [2] h(y+1) - h(y), [3] h(y) - h(y+1));
// +inf where a block starts none (clamp, at the far edge). Where the smallest
// step away from a cell is positive, the heights of the block climb at least
// that fast away from it: h_q <= M - (extent - offset) * step, a much better
// bound than M at the near side on slopes (a plane: every block uphill).
struct SlopePyramid {
  static constexpr int kBase = 3;
  std::vector<std::vector<float>> rise[4];  // [direction][level - kBase]
};

SlopePyramid build_slopes(const std::vector<float>& h, int W, int H, bool repeat, const Pyramid& pyr) {
  SlopePyramid sp;
  const int top = pyr.levels() - 1;
  if (top < SlopePyramid::kBase) return sp;
  const float inf = std::numeric_limits<float>::infinity();
  const int bw = pyr.w[SlopePyramid::kBase], bh = pyr.h[SlopePyramid::kBase];
  for (auto& r : sp.rise) r.assign(1, std::vector<float>(std::size_t(bw) * bh, inf));
  for_each_row_block(bh, 4, [&](int b0, int b1) {
    for (int y = b0 << SlopePyramid::kBase; y < std::min(H, b1 << SlopePyramid::kBase); ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t b = std::size_t(y >> SlopePyramid::kBase) * bw + std::size_t(x >> SlopePyramid::kBase);
        const float v = h[std::size_t(y) * W + x];
        if (repeat || x + 1 < W) {
          const float step = h[std::size_t(y) * W + (x + 1) % W] - v;
          sp.rise[0][0][b] = std::min(sp.rise[0][0][b], step);
          sp.rise[1][0][b] = std::min(sp.rise[1][0][b], -step);
        }
        if (repeat || y + 1 < H) {
          const float step = h[std::size_t((y + 1) % H) * W + x] - v;
          sp.rise[2][0][b] = std::min(sp.rise[2][0][b], step);
          sp.rise[3][0][b] = std::min(sp.rise[3][0][b], -step);
        }
      }
  });
  for (int k = SlopePyramid::kBase + 1; k <= top; ++k) {
    const int pw = pyr.w[std::size_t(k - 1)], ph = pyr.h[std::size_t(k - 1)], nw = pyr.w[std::size_t(k)], nh = pyr.h[std::size_t(k)];
    for (auto& r : sp.rise) {
      const std::vector<float>& prev = r.back();
      std::vector<float> next(std::size_t(nw) * nh, inf);
      for (int y = 0; y < ph; ++y)
        for (int x = 0; x < pw; ++x) {
          float& o = next[std::size_t(y / 2) * nw + std::size_t(x / 2)];
          o = std::min(o, prev[std::size_t(y) * pw + x]);
        }
      r.push_back(std::move(next));
    }
  }
  return sp;
}

detail::ConeGeometry geometry(int W, int H, const ConeMapOptions& o, int shrink) {
  detail::ConeGeometry g;
  g.W = W;
  g.H = H;
  g.repeat = o.wrap == WrapMode::repeat;
  g.sx = float(1.0 / (double(W) * W));
  g.sy = float(1.0 / (double(H) * H));
  g.dd = o.depth * o.depth;
  g.shrink = shrink;
  return g;
}

// Relaxed cones on the cell walk: the exit rule per texel, and four maximum
// pyramids of the texels with a lower +x, -x, +y or -y neighbour (-1
// elsewhere). A block wholly on one side of the cell along an axis can only
// hold exits that way for every apex of the cell, so its bound height takes
// the maximum of the matching pyramids.
struct RelaxedBounds {
  std::vector<unsigned char> exit_bits;
  std::vector<std::vector<float>> exit_heights;  // level 0 of each pyramid
  std::vector<Pyramid> exit_pyr;
};

RelaxedBounds relaxed_bounds(const std::vector<float>& heights, int W, int H, bool repeat) {
  RelaxedBounds rb;
  const Behind behind{heights, W, H, repeat};
  const int sx[4] = {1, -1, 0, 0}, sy[4] = {0, 0, 1, -1};
  rb.exit_bits.assign(heights.size(), 0);
  rb.exit_heights.assign(4, std::vector<float>(heights.size()));
  for_each_row_block(H, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t i = std::size_t(y) * W + x;
        for (int f = 0; f < 4; ++f) {
          const bool lower = behind.lower(x, y, heights[i], sx[f], sy[f]);
          rb.exit_bits[i] = static_cast<unsigned char>(rb.exit_bits[i] | (lower ? 1 << f : 0));
          rb.exit_heights[std::size_t(f)][i] = lower ? heights[i] : -1.0f;
        }
      }
  });
  for (int f = 0; f < 4; ++f) rb.exit_pyr.push_back(build_pyramid(rb.exit_heights[std::size_t(f)], W, H));
  return rb;
}

// Squared cone ratios, a cell of 8x8 apex texels at a time: one walk of the
// pyramid per cell, nearest block first, a block skipped when even the
// cell's lowest apex at the cell's nearest point could not narrow the widest
// cone in the cell, or no apex with its own cone and distance could be
// narrowed (and, for classic cones, by the slope bound); the blocks of 8x8
// texels that survive are scanned against every apex row that a row-wise
// bound cannot rule out, SIMD across the cell (cone_cells.h). With
// o.fast_reach, the blocks next to the cell are still scanned, but a farther
// block whose gap to the cell is at least fast_reach of its own sizes counts
// as one obstacle. `apex`: the apex heights (the heights, or their 3x3
// minima for --bilinear-safe, with distances shrunk by `shrink`);
// `relaxed`: relaxed cones (their exits and bound heights).
std::vector<float> cell_cones(const std::vector<float>& heights, const std::vector<float>& apex, int W, int H,
                                      const ConeMapOptions& o, const Pyramid& pyr, int shrink,
                                      const RelaxedBounds* relaxed = nullptr) {
  using detail::kConeCell;
  constexpr int kScanLevel = 3;  // 8x8-texel blocks are scanned
  detail::ConeGeometry g = geometry(W, H, o, shrink);
  const int runs = (W + kConeCell - 1) / kConeCell;
  std::vector<float> row_max8(std::size_t(runs) * H);
  for_each_row_block(H, 64, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < W; ++x) {
        float& v = row_max8[std::size_t(y) * runs + std::size_t(x / kConeCell)];
        v = x % kConeCell == 0 ? heights[std::size_t(y) * W + x] : std::max(v, heights[std::size_t(y) * W + x]);
      }
  });
  g.row_max8 = row_max8.data();
  const Metric m{1.0 / (double(W) * W), 1.0 / (double(H) * H), double(o.depth) * o.depth};
  const bool repeat = g.repeat;
  const int top = pyr.levels() - 1;
  float summit = pyr.level(top)[0];
  if (relaxed) {
    g.exit_bits = relaxed->exit_bits.data();
    summit = -1.0f;
    for (const Pyramid& e : relaxed->exit_pyr) summit = std::max(summit, e.level(top)[0]);
  }
  const float cap2 = o.max_ratio * o.max_ratio;
  const int cw = (W + kConeCell - 1) / kConeCell, ch = (H + kConeCell - 1) / kConeCell;
  const int reach = o.fast_reach;
  auto shrunk = [&](int gap) { return gap > shrink ? gap - shrink : 0; };
  // (--fast does not use the slope bound: its blocks are near the cell.)
  // (Nor do relaxed cones: their bound heights are not the slope's anchor.)
  const SlopePyramid slopes =
      shrink > 0 || reach > 0 || relaxed ? SlopePyramid{} : build_slopes(heights, W, H, repeat, pyr);
  // The bound height of block (x, y) at level k, on sides (sx, sy) of the cell.
  auto bound_height = [&](int k, int x, int y, int sx, int sy) {
    const std::size_t at = std::size_t(y) * pyr.w[std::size_t(k)] + x;
    if (!relaxed) return pyr.level(k)[at];
    float M = -1.0f;
    if (sx >= 0) M = std::max(M, relaxed->exit_pyr[0].level(k)[at]);
    if (sx <= 0) M = std::max(M, relaxed->exit_pyr[1].level(k)[at]);
    if (sy >= 0) M = std::max(M, relaxed->exit_pyr[2].level(k)[at]);
    if (sy <= 0) M = std::max(M, relaxed->exit_pyr[3].level(k)[at]);
    return M;
  };
  std::vector<float> out(heights.size());
  for_each_row_block(ch, 1, [&](int r0, int r1) {
    std::vector<Node> stack;
    detail::ConeCell c;
    for (int cy = r0; cy < r1; ++cy)
      for (int cx = 0; cx < cw; ++cx) {
        c.x0 = cx * kConeCell;
        c.y0 = cy * kConeCell;
        const int w = std::min(kConeCell, W - c.x0), h = std::min(kConeCell, H - c.y0);
        const int x1 = c.x0 + w - 1, y1 = c.y0 + h - 1;
        // Bounds: the lowest apex and the widest cone of each row and of the
        // cell. An apex at the summit of the map has nothing above it: its
        // cone stays at the cap and does not count as the widest (a lone
        // spike would otherwise open the whole pyramid for its cell).
        float row_min[kConeCell], row_max[kConeCell];
        bool live[kConeCell][kConeCell];
        float cell_min = std::numeric_limits<float>::infinity();
        double cell_max = 0;
        for (int r = 0; r < kConeCell; ++r) {
          row_min[r] = std::numeric_limits<float>::infinity();
          row_max[r] = 0.0f;
          for (int l = 0; l < kConeCell; ++l) {
            const bool real = r < h && l < w;
            c.apex[r][l] = real ? apex[std::size_t(c.y0 + r) * W + c.x0 + l] : std::numeric_limits<float>::infinity();
            c.best[r][l] = cap2;
            live[r][l] = real && c.apex[r][l] < summit;
            if (live[r][l]) row_max[r] = cap2;
            row_min[r] = std::min(row_min[r], c.apex[r][l]);
          }
          cell_min = std::min(cell_min, row_min[r]);
          cell_max = std::max(cell_max, double(row_max[r]));
        }
        // Which apex rows the block [bx0, bx1] x [by0, by1] of height M may narrow.
        bool rows[kConeCell];
        auto select_rows = [&](int gap_x, int by0, int by1, float M) {
          const double gx = shrunk(gap_x);
          bool any = false;
          for (int r = 0; r < kConeCell; ++r) {
            rows[r] = false;
            if (r >= h || !(M > row_min[r])) continue;
            const double gy = shrunk(detail::cone_axis_distance(c.y0 + r, by0, by1, H, repeat));
            const double dh = double(M) - row_min[r];
            rows[r] = gx * gx * m.sx + gy * gy * m.sy <= row_max[r] * kPruneSlack * m.dd * dh * dh;
            any = any || rows[r];
          }
          return any;
        };
        auto refresh = [&] {
          cell_max = 0;
          for (int r = 0; r < h; ++r) {
            if (!rows[r]) {
              cell_max = std::max(cell_max, double(row_max[r]));
              continue;
            }
            float mx = 0;
            for (int l = 0; l < w; ++l) mx = live[r][l] ? std::max(mx, c.best[r][l]) : mx;
            row_max[r] = mx;
            cell_max = std::max(cell_max, double(mx));
          }
        };
        bool all_rows[kConeCell];
        for (int r = 0; r < kConeCell; ++r) all_rows[r] = r < h;
        auto refresh_all = [&] {
          std::copy(all_rows, all_rows + kConeCell, rows);
          refresh();
        };
        // Whether child block (ux, uy) at level s, texels [bx0, bx1] x [by0, by1],
        // can narrow no cone of the cell: each apex with its own cone and
        // distance, and where the block climbs away from the cell along an axis
        // (side != 0: the child loop keeps a side only where every apex sees
        // the block on it), the slope bound (cone_cells.h; classic cones only:
        // the shrunk distances of --bilinear-safe do not add up so).
        auto clear = [&](int s, int ux, int uy, int bx0, int bx1, int by0, int by1, float Mc, int side_x, int side_y) {
          if (detail::cone_cell_clear(g, c, bx0, bx1, by0, by1, Mc, 0, 0.0f, 0)) return true;
          if (slopes.rise[0].empty() || s < SlopePyramid::kBase) return false;
          const std::size_t at = std::size_t(uy) * pyr.w[std::size_t(s)] + ux;
          for (int axis = 0; axis < 2; ++axis) {
            const int side = axis == 0 ? side_x : side_y;
            if (side == 0) continue;
            const float E = slopes.rise[axis * 2 + (side > 0 ? 0 : 1)][std::size_t(s - SlopePyramid::kBase)][at];
            if (!(E > 0.0f)) continue;
            const int extent = axis == 0 ? bx1 - bx0 : by1 - by0;
            if (detail::cone_cell_clear(g, c, bx0, bx1, by0, by1, Mc, axis, E, extent)) return true;
          }
          return false;
        };
        stack.clear();
        if (cell_max > 0) stack.push_back({top, 0, 0, 0.0, 0, 0, summit});
        while (!stack.empty()) {
          const Node n = stack.back();
          stack.pop_back();
          if (n.bound > cell_max) continue;  // the cones narrowed since it was pushed
          const int k = n.level;
          const int bx0 = n.x << k, bx1 = std::min((n.x + 1) << k, W) - 1;
          const int by0 = n.y << k, by1 = std::min((n.y + 1) << k, H) - 1;
          const float M = n.M;
          // --fast: the blocks next to the cell are scanned, farther ones
          // opened only until they are reach of their sizes away.
          const int gap = reach > 0 ? std::max(n.gx, n.gy) : 0;
          if (reach > 0 && gap >= kConeCell && (k == 0 || gap >= std::max(reach << k, shrink + 1))) {
            // One obstacle costs less than choosing its rows: all rows.
            if (M > cell_min && detail::cone_cell_block(g, c, bx0, bx1, by0, by1, M, all_rows)) refresh_all();
            continue;
          }
          if (k <= kScanLevel && gap < kConeCell) {
            if (select_rows(n.gx, by0, by1, M) && detail::cone_cell_texels(g, heights.data(), c, bx0, bx1, by0, by1, rows)) {
              refresh();
            }
            continue;
          }
          // Children that may narrow a cone, nearest pushed last (searched first).
          Node kids[4];
          int count = 0;
          const int s = k - 1;
          const int kw = pyr.w[std::size_t(s)], kh = pyr.h[std::size_t(s)];
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
              const int ux = 2 * n.x + i, uy = 2 * n.y + j;
              if (ux >= kw || uy >= kh) continue;
              if (pyr.level(s)[std::size_t(uy) * kw + ux] <= cell_min) continue;
              int side_x = 0, side_y = 0;
              const int ux0 = ux << s, ux1 = std::min((ux + 1) << s, W) - 1;
              const int uy0 = uy << s, uy1 = std::min((uy + 1) << s, H) - 1;
              const int gx = range_gap(c.x0, x1, ux0, ux1, W, repeat, &side_x);
              const int gy = range_gap(c.y0, y1, uy0, uy1, H, repeat, &side_y);
              // With repeat, a side holds for every apex only well within half the
              // map (the exit pyramids and the slope bound rely on it).
              if (repeat && 2 * (gx + (x1 - c.x0) + (ux1 - ux0)) >= W) side_x = 0;
              if (repeat && 2 * (gy + (y1 - c.y0) + (uy1 - uy0)) >= H) side_y = 0;
              const float Mc = bound_height(s, ux, uy, side_x, side_y);
              if (Mc <= cell_min) continue;
              const double sgx = shrunk(gx), sgy = shrunk(gy), dh = double(Mc) - cell_min;
              const double num = sgx * sgx * m.sx + sgy * sgy * m.sy, den = m.dd * dh * dh;
              if (num > cell_max * kPruneSlack * den) continue;
              // Each apex with its own cone, where the child would be opened or
              // scanned (a --fast obstacle costs about as much as this test).
              const bool obstacle = reach > 0 && std::max(gx, gy) >= kConeCell && std::max(gx, gy) >= std::max(reach << s, shrink + 1);
              if (!obstacle) {
                // --fast's blocks are near the cell, where the cheaper cell-gap test does as well.
                if (reach > 0 ? num > double(detail::cone_cell_reach(c, Mc)) * m.dd * kPruneSlack
                              : clear(s, ux, uy, ux0, ux1, uy0, uy1, Mc, side_x, side_y)) {
                  continue;
                }
              }
              kids[count++] = {s, ux, uy, num / (den * kPruneSlack), gx, gy, Mc};
            }
          for (int a = 1; a < count; ++a)
            for (int b = a; b > 0 && kids[b - 1].bound < kids[b].bound; --b) std::swap(kids[b - 1], kids[b]);
          for (int q = 0; q < count; ++q) stack.push_back(kids[q]);
        }
        for (int r = 0; r < h; ++r)
          for (int l = 0; l < w; ++l) out[std::size_t(c.y0 + r) * W + c.x0 + l] = c.best[r][l];
      }
  }, o.progress);
  return out;
}

// --bilinear-safe. A renderer samples height and ratio bilinearly, so the
// apex of a cone sits anywhere between texel centres, on the bilinear
// surface, with the ratio interpolated from the four texels around it. The
// ratio stored at p is therefore made safe for every apex x in the square
// S_p = p +- 1 texel (the four bilinear cells that p weighs in): then the
// interpolated ratio, a mix of four such values, is safe at x too. For x in
// S_p and a surface point y:
//  - y within Q_p = p +- 3 texels: the bilinear surface is Lipschitz there,
//    H(y) - H(x) <= L |y - x| with L from the largest height step between
//    4-neighbours in Q_p's 7x7 texels, so a ratio of 1 / (depth L) is safe;
//  - y outside Q_p: y lies in a bilinear cell whose corners are all at least
//    3 texels from p along some axis; H(y) is at most its highest corner q,
//    H(x) at least the lowest of p's 3x3 texels, m_p, and |y - x| at least
//    the distance from p to q with 2 texels taken off each axis: the
//    classic search from apex height m_p with distances shrunk by 2, where
//    the texels within 2 of p (shrunk distance 0) are left to the first case.
// The ratio is the smaller of the two.
constexpr int kBilinearShrink = 2;

// out(p) = op over the texels p + [x_lo, x_hi] x [y_lo, y_hi] (wrapped, or
// clipped to the map), separably.
template <typename Op>
std::vector<float> window_reduce(const std::vector<float>& v, int W, int H, bool repeat, int x_lo, int x_hi, int y_lo,
                                 int y_hi, float init, Op op) {
  std::vector<float> rows(v.size()), out(v.size());
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      float a = init;
      for (int i = x + x_lo; i <= x + x_hi; ++i) {
        if (!repeat && (i < 0 || i >= W)) continue;
        a = op(a, v[std::size_t(y) * W + std::size_t((i % W + W) % W)]);
      }
      rows[std::size_t(y) * W + x] = a;
    }
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      float a = init;
      for (int j = y + y_lo; j <= y + y_hi; ++j) {
        if (!repeat && (j < 0 || j >= H)) continue;
        a = op(a, rows[std::size_t((j % H + H) % H) * W + x]);
      }
      out[std::size_t(y) * W + x] = a;
    }
  return out;
}

std::vector<float> bilinear_apex(const std::vector<float>& heights, int W, int H, bool repeat) {
  return window_reduce(heights, W, H, repeat, -1, 1, -1, 1, std::numeric_limits<float>::infinity(),
                       [](float a, float b) { return std::min(a, b); });
}

// Narrows the shrunk-distance cones (squared, in `r2`) to the local
// Lipschitz bound where a point of Q_p may rise above the apex.
void bilinear_local(const std::vector<float>& heights, const std::vector<float>& apex, int W, int H,
                    const ConeMapOptions& o, std::vector<float>& r2) {
  const bool repeat = o.wrap == WrapMode::repeat;
  const auto mx = [](float a, float b) { return std::max(a, b); };
  std::vector<float> ex(heights.size(), 0.0f), ey(heights.size(), 0.0f);  // steps to the +x and +y neighbours
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const float h = heights[std::size_t(y) * W + x];
      if (repeat || x + 1 < W) ex[std::size_t(y) * W + x] = std::abs(heights[std::size_t(y) * W + (x + 1) % W] - h);
      if (repeat || y + 1 < H) ey[std::size_t(y) * W + x] = std::abs(heights[std::size_t((y + 1) % H) * W + x] - h);
    }
  const int R = kBilinearShrink + 1;
  const std::vector<float> gx = window_reduce(ex, W, H, repeat, -R, R - 1, -R, R, 0.0f, mx);
  const std::vector<float> gy = window_reduce(ey, W, H, repeat, -R, R, -R, R - 1, 0.0f, mx);
  const std::vector<float> top = window_reduce(heights, W, H, repeat, -R, R, -R, R, 0.0f, mx);
  for (std::size_t i = 0; i < r2.size(); ++i) {
    if (!(top[i] > apex[i])) continue;
    const double lx = double(gx[i]) * W, ly = double(gy[i]) * H;
    const double bound = 1.0 / (double(o.depth) * o.depth * (lx * lx + ly * ly));
    float b = float(bound);
    if (double(b) > bound) b = std::nextafter(b, 0.0f);
    r2[i] = std::min(r2[i], b);
  }
}
std::vector<float> square_roots(std::vector<float> r2) {
  const int rows = int((r2.size() + 4095) / 4096);
  for_each_row_block(rows, 16, [&](int r0, int r1) {
    for (std::size_t i = std::size_t(r0) * 4096; i < std::min(r2.size(), std::size_t(r1) * 4096); ++i) r2[i] = std::sqrt(r2[i]);
  });
  return r2;
}

}  // namespace

std::vector<float> cone_ratios(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o) {
  check(heights, W, H, o);
  const Pyramid pyr = build_pyramid(heights, W, H);
  if (o.mode == ConeMode::relaxed) {
    const RelaxedBounds rb = relaxed_bounds(heights, W, H, o.wrap == WrapMode::repeat);
    return square_roots(cell_cones(heights, heights, W, H, o, pyr, 0, &rb));
  }
  if (!o.bilinear_safe) return square_roots(cell_cones(heights, heights, W, H, o, pyr, 0));
  const std::vector<float> apex = bilinear_apex(heights, W, H, o.wrap == WrapMode::repeat);
  std::vector<float> r2 = cell_cones(heights, apex, W, H, o, pyr, kBilinearShrink);
  bilinear_local(heights, apex, W, H, o, r2);
  return square_roots(std::move(r2));
}

std::vector<float> cone_ratios_brute_force(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o) {
  check(heights, W, H, o);
  const bool repeat = o.wrap == WrapMode::repeat;
  const bool relaxed = o.mode == ConeMode::relaxed;
  const std::vector<float> apex = o.bilinear_safe ? bilinear_apex(heights, W, H, repeat) : heights;
  const detail::ConeGeometry g = geometry(W, H, o, o.bilinear_safe ? kBilinearShrink : 0);
  const Behind behind{heights, W, H, repeat};
  std::vector<float> r2(heights.size());
  for_each_row_block(H, 1, [&](int y0, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = 0; px < W; ++px) {
        const float hp = apex[std::size_t(py) * W + px];
        float best = o.max_ratio * o.max_ratio;
        for (int qy = 0; qy < H; ++qy)
          for (int qx = 0; qx < W; ++qx) {
            const float hq = heights[std::size_t(qy) * W + qx];
            const float d2 = detail::cone_d2(g, texel_distance(px, qx, W, repeat), texel_distance(py, qy, H, repeat));
            if (!(hq > hp && d2 > 0.0f)) continue;
            if (relaxed && !behind.exits(px, py, qx, qy, hq)) continue;
            best = std::min(best, detail::cone_r2(g, d2, hq - hp));
          }
        r2[std::size_t(py) * W + px] = best;
      }
  }, o.progress);
  if (o.bilinear_safe) bilinear_local(heights, apex, W, H, o, r2);
  return square_roots(std::move(r2));
}

Image cone_map_image(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                     const ConeMapOptions& o, PixelType type, int channels) {
  if (channels < 2 || channels > 4) throw Error(ErrorCode::bad_arguments, "a cone map has 2, 3 or 4 channels");
  Image img = Image::uninitialized(W, H, channels, type);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = std::size_t(y) * W + x;
      const double g = std::sqrt(std::min(1.0, double(ratios[i]) / o.max_ratio));
      const double h = std::clamp(double(heights[i]), 0.0, 1.0);
      // B = 0, A = 1 where asked for.
      auto put = [&](auto* p, double scale, bool integer) {
        using T = std::remove_pointer_t<decltype(p)>;
        p[0] = T(integer ? std::round(h * scale) : h);
        // G rounded down: quantization never widens a cone.
        double gq = integer ? std::floor(g * scale) : g;
        if (!integer && double(T(gq)) > g) gq = std::nextafter(float(gq), 0.0f);
        p[1] = T(gq);
        if (channels > 2) p[2] = T(0);
        if (channels > 3) p[3] = T(scale);
      };
      switch (type) {
        case PixelType::u8: put(img.row<std::uint8_t>(y) + channels * x, 255.0, true); break;
        case PixelType::u16: put(img.row<std::uint16_t>(y) + channels * x, 65535.0, true); break;
        case PixelType::f32: put(img.row<float>(y) + channels * x, 1.0, false); break;
      }
    }
  return img;
}

}  // namespace texproc
