// The cone map's search over the maximum pyramid, a cell of apex texels at a
// time: cone_search.h.
#include "conemap/cone_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "conemap/cone_cells.h"
#include "texproc/runtime.h"

namespace texproc::cone {
namespace {

// The terms of a squared ratio, (dx^2 sx + dy^2 sy) / (dd dh^2), in double
// for the search's bounds (candidates are in float: cone_cells.h).
struct Metric {
  double sx, sy, dd;  // 1 / W^2, 1 / H^2, depth^2
};

}  // namespace

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

namespace {

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
    if (g2 < g) {
      g = g2;
      sd = s2;
    }
    g2 = gap(n, s2);
    if (g2 < g) {
      g = g2;
      sd = s2;
    }
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
    const int pw = pyr.w[std::size_t(k - 1)], ph = pyr.h[std::size_t(k - 1)], nw = pyr.w[std::size_t(k)],
              nh = pyr.h[std::size_t(k)];
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

}  // namespace

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

namespace {

// What every cell's search reads: the map, its pyramids and bounds.
struct CellContext {
  const std::vector<float>& heights;
  const std::vector<float>& apex;
  int W, H;
  const Pyramid& pyr;
  int shrink;
  const RelaxedBounds* relaxed;
  detail::ConeGeometry g;
  Metric m;
  bool repeat;
  int top, reach;
  float summit, cap2;
  SlopePyramid slopes;

  int shrunk(int gap) const { return gap > shrink ? gap - shrink : 0; }
  // The bound height of block (x, y) at level k, on sides (sx, sy) of the cell.
  float bound_height(int k, int x, int y, int sx, int sy) const {
    const std::size_t at = std::size_t(y) * pyr.w[std::size_t(k)] + x;
    if (!relaxed) return pyr.level(k)[at];
    float M = -1.0f;
    if (sx >= 0) M = std::max(M, relaxed->exit_pyr[0].level(k)[at]);
    if (sx <= 0) M = std::max(M, relaxed->exit_pyr[1].level(k)[at]);
    if (sy >= 0) M = std::max(M, relaxed->exit_pyr[2].level(k)[at]);
    if (sy <= 0) M = std::max(M, relaxed->exit_pyr[3].level(k)[at]);
    return M;
  }
};

// One cell's search (a thread's, reused cell after cell): the cell's apexes
// and their cones so far, the rows' and the cell's bounds, and the walk.
struct CellSearch {
  static constexpr int kScanLevel = 3;  // 8x8-texel blocks are scanned
  static constexpr int kCell = detail::kConeCell;
  const CellContext& x;
  std::vector<Node> stack;
  detail::ConeCell c;
  int w = 0, h = 0, x1 = 0, y1 = 0;
  // Bounds: the lowest apex and the widest cone of each row and of the cell.
  float row_min[kCell], row_max[kCell];
  bool live[kCell][kCell];
  float cell_min = 0;
  double cell_max = 0;
  bool rows[kCell], all_rows[kCell];

  explicit CellSearch(const CellContext& context) : x(context) {}

  // Cell (cx, cy)'s apexes at the cap. An apex at the summit of the map has
  // nothing above it: its cone stays at the cap and does not count as the
  // widest (a lone spike would otherwise open the whole pyramid for its cell).
  void begin(int cx, int cy) {
    c.x0 = cx * kCell;
    c.y0 = cy * kCell;
    w = std::min(kCell, x.W - c.x0);
    h = std::min(kCell, x.H - c.y0);
    x1 = c.x0 + w - 1;
    y1 = c.y0 + h - 1;
    cell_min = std::numeric_limits<float>::infinity();
    cell_max = 0;
    for (int r = 0; r < kCell; ++r) {
      row_min[r] = std::numeric_limits<float>::infinity();
      row_max[r] = 0.0f;
      for (int l = 0; l < kCell; ++l) {
        const bool real = r < h && l < w;
        c.apex[r][l] = real ? x.apex[std::size_t(c.y0 + r) * x.W + c.x0 + l] : std::numeric_limits<float>::infinity();
        c.best[r][l] = x.cap2;
        live[r][l] = real && c.apex[r][l] < x.summit;
        if (live[r][l]) row_max[r] = x.cap2;
        row_min[r] = std::min(row_min[r], c.apex[r][l]);
      }
      cell_min = std::min(cell_min, row_min[r]);
      cell_max = std::max(cell_max, double(row_max[r]));
    }
    for (int r = 0; r < kCell; ++r) all_rows[r] = r < h;
  }

  // Which apex rows the block [bx0, bx1] x [by0, by1] of height M may narrow.
  bool select_rows(int gap_x, int by0, int by1, float M) {
    const double gx = x.shrunk(gap_x);
    bool any = false;
    for (int r = 0; r < kCell; ++r) {
      rows[r] = false;
      if (r >= h || !(M > row_min[r])) continue;
      const double gy = x.shrunk(detail::cone_axis_distance(c.y0 + r, by0, by1, x.H, x.repeat));
      const double dh = double(M) - row_min[r];
      rows[r] = gx * gx * x.m.sx + gy * gy * x.m.sy <= row_max[r] * kPruneSlack * x.m.dd * dh * dh;
      any = any || rows[r];
    }
    return any;
  }
  // The widest cones again, of the rows just scanned.
  void refresh() {
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
  }
  void refresh_all() {
    std::copy(all_rows, all_rows + kCell, rows);
    refresh();
  }

  // Whether child block (ux, uy) at level s, texels [bx0, bx1] x [by0, by1],
  // can narrow no cone of the cell: each apex with its own cone and
  // distance, and where the block climbs away from the cell along an axis
  // (side != 0: the child loop keeps a side only where every apex sees
  // the block on it), the slope bound (cone_cells.h; classic cones only:
  // the shrunk distances of --bilinear-safe do not add up so).
  bool clear(int s, int ux, int uy, int bx0, int bx1, int by0, int by1, float Mc, int side_x, int side_y) const {
    if (detail::cone_cell_clear(x.g, c, bx0, bx1, by0, by1, Mc, 0, 0.0f, 0)) return true;
    if (x.slopes.rise[0].empty() || s < SlopePyramid::kBase) return false;
    const std::size_t at = std::size_t(uy) * x.pyr.w[std::size_t(s)] + ux;
    for (int axis = 0; axis < 2; ++axis) {
      const int side = axis == 0 ? side_x : side_y;
      if (side == 0) continue;
      const float E = x.slopes.rise[axis * 2 + (side > 0 ? 0 : 1)][std::size_t(s - SlopePyramid::kBase)][at];
      if (!(E > 0.0f)) continue;
      const int extent = axis == 0 ? bx1 - bx0 : by1 - by0;
      if (detail::cone_cell_clear(x.g, c, bx0, bx1, by0, by1, Mc, axis, E, extent)) return true;
    }
    return false;
  }

  // Node n's children that may narrow a cone, nearest pushed last (searched first).
  void push_children(const Node& n) {
    Node kids[4];
    int count = 0;
    const int s = n.level - 1;
    const int kw = x.pyr.w[std::size_t(s)], kh = x.pyr.h[std::size_t(s)];
    const int reach = x.reach, shrink = x.shrink;
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) {
        const int ux = 2 * n.x + i, uy = 2 * n.y + j;
        if (ux >= kw || uy >= kh) continue;
        if (x.pyr.level(s)[std::size_t(uy) * kw + ux] <= cell_min) continue;
        int side_x = 0, side_y = 0;
        const int ux0 = ux << s, ux1 = std::min((ux + 1) << s, x.W) - 1;
        const int uy0 = uy << s, uy1 = std::min((uy + 1) << s, x.H) - 1;
        const int gx = range_gap(c.x0, x1, ux0, ux1, x.W, x.repeat, &side_x);
        const int gy = range_gap(c.y0, y1, uy0, uy1, x.H, x.repeat, &side_y);
        // With repeat, a side holds for every apex only well within half the
        // map (the exit pyramids and the slope bound rely on it).
        if (x.repeat && 2 * (gx + (x1 - c.x0) + (ux1 - ux0)) >= x.W) side_x = 0;
        if (x.repeat && 2 * (gy + (y1 - c.y0) + (uy1 - uy0)) >= x.H) side_y = 0;
        const float Mc = x.bound_height(s, ux, uy, side_x, side_y);
        if (Mc <= cell_min) continue;
        const double sgx = x.shrunk(gx), sgy = x.shrunk(gy), dh = double(Mc) - cell_min;
        const double num = sgx * sgx * x.m.sx + sgy * sgy * x.m.sy, den = x.m.dd * dh * dh;
        if (num > cell_max * kPruneSlack * den) continue;
        // Each apex with its own cone, where the child would be opened or
        // scanned (a --fast obstacle costs about as much as this test).
        const bool obstacle =
            reach > 0 && std::max(gx, gy) >= kCell && std::max(gx, gy) >= std::max(reach << s, shrink + 1);
        if (!obstacle) {
          // --fast's blocks are near the cell, where the cheaper cell-gap test does as well.
          if (reach > 0 ? num > double(detail::cone_cell_reach(c, Mc)) * x.m.dd * kPruneSlack
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

  // The walk of the pyramid for the cell, nearest block first.
  void search() {
    const int reach = x.reach;
    stack.clear();
    if (cell_max > 0) stack.push_back({x.top, 0, 0, 0.0, 0, 0, x.summit});
    while (!stack.empty()) {
      const Node n = stack.back();
      stack.pop_back();
      if (n.bound > cell_max) continue;  // the cones narrowed since it was pushed
      const int k = n.level;
      const int bx0 = n.x << k, bx1 = std::min((n.x + 1) << k, x.W) - 1;
      const int by0 = n.y << k, by1 = std::min((n.y + 1) << k, x.H) - 1;
      const float M = n.M;
      // --fast: the blocks next to the cell are scanned, farther ones
      // opened only until they are reach of their sizes away.
      const int gap = reach > 0 ? std::max(n.gx, n.gy) : 0;
      if (reach > 0 && gap >= kCell && (k == 0 || gap >= std::max(reach << k, x.shrink + 1))) {
        // One obstacle costs less than choosing its rows: all rows.
        if (M > cell_min && detail::cone_cell_block(x.g, c, bx0, bx1, by0, by1, M, all_rows)) refresh_all();
        continue;
      }
      if (k <= kScanLevel && gap < kCell) {
        if (select_rows(n.gx, by0, by1, M) &&
            detail::cone_cell_texels(x.g, x.heights.data(), c, bx0, bx1, by0, by1, rows)) {
          refresh();
        }
        continue;
      }
      push_children(n);
    }
  }
};

}  // namespace

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
struct CellCones::State {
  std::vector<float> row_max8;
  std::unique_ptr<CellContext> context;
};

CellCones::CellCones(const std::vector<float>& heights, const std::vector<float>& apex, int W, int H,
                     const ConeMapOptions& o, const Pyramid& pyr, int shrink, const RelaxedBounds* relaxed)
    : s_(std::make_unique<State>()) {
  using detail::kConeCell;
  detail::ConeGeometry g = geometry(W, H, o, shrink);
  const int runs = (W + kConeCell - 1) / kConeCell;
  std::vector<float>& row_max8 = s_->row_max8;
  row_max8.resize(std::size_t(runs) * H);
  for_each_row_block(H, 64, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < W; ++x) {
        float& v = row_max8[std::size_t(y) * runs + std::size_t(x / kConeCell)];
        v = x % kConeCell == 0 ? heights[std::size_t(y) * W + x] : std::max(v, heights[std::size_t(y) * W + x]);
      }
  });
  g.row_max8 = row_max8.data();
  const int top = pyr.levels() - 1;
  float summit = pyr.level(top)[0];
  if (relaxed) {
    g.exit_bits = relaxed->exit_bits.data();
    summit = -1.0f;
    for (const Pyramid& e : relaxed->exit_pyr) summit = std::max(summit, e.level(top)[0]);
  }
  // (--fast does not use the slope bound: its blocks are near the cell.)
  // (Nor do relaxed cones: their bound heights are not the slope's anchor.)
  const bool repeat = g.repeat;
  s_->context.reset(new CellContext{
      heights, apex, W, H, pyr, shrink, relaxed, g,
      Metric{1.0 / (double(W) * W), 1.0 / (double(H) * H), double(o.depth) * o.depth}, repeat, top, o.fast_reach,
      summit, o.max_ratio * o.max_ratio,
      shrink > 0 || o.fast_reach > 0 || relaxed ? SlopePyramid{} : build_slopes(heights, W, H, repeat, pyr)});
}

CellCones::~CellCones() = default;

int CellCones::cell_rows() const { return (s_->context->H + detail::kConeCell - 1) / detail::kConeCell; }

void CellCones::rows(int cy0, int cy1, float* out, const std::function<void(double)>& progress) const {
  using detail::kConeCell;
  const CellContext& context = *s_->context;
  const int W = context.W;
  const int cw = (W + kConeCell - 1) / kConeCell;
  const std::size_t first = std::size_t(cy0) * kConeCell;
  for_each_row_block(
      cy1 - cy0, 1,
      [&](int r0, int r1) {
        CellSearch cell(context);
        for (int cy = cy0 + r0; cy < cy0 + r1; ++cy)
          for (int cx = 0; cx < cw; ++cx) {
            cell.begin(cx, cy);
            cell.search();
            for (int r = 0; r < cell.h; ++r)
              for (int l = 0; l < cell.w; ++l)
                out[(std::size_t(cell.c.y0 + r) - first) * W + std::size_t(cell.c.x0 + l)] = cell.c.best[r][l];
          }
      },
      progress);
}

std::vector<float> cell_cones(const std::vector<float>& heights, const std::vector<float>& apex, int W, int H,
                              const ConeMapOptions& o, const Pyramid& pyr, int shrink, const RelaxedBounds* relaxed) {
  const CellCones cones(heights, apex, W, H, o, pyr, shrink, relaxed);
  std::vector<float> out(heights.size());
  cones.rows(0, cones.cell_rows(), out.data(), o.progress);
  return out;
}

}  // namespace texproc::cone
