// Exact conservative cone maps by branch and bound over a maximum mip
// pyramid (the approach of Valasek and Ban, "Quick Cone Map Generation on
// the GPU", EGS 2022, made exact): for texel p, blocks of the pyramid are
// visited nearest first; a block whose maximum height M at its nearest
// distance d cannot give a ratio below the best so far,
// d / (depth * (M - h_p)) >= best, is skipped with everything in it.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

void check(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o) {
  if (width <= 0 || height <= 0 || heights.size() != std::size_t(width) * height) {
    throw Error(ErrorCode::bad_arguments, "heights do not match the size");
  }
  if (!(o.depth > 0.0f) || !std::isfinite(o.depth)) throw Error(ErrorCode::bad_arguments, "--depth must be > 0");
  if (!(o.max_ratio > 0.0f) || !std::isfinite(o.max_ratio)) throw Error(ErrorCode::bad_arguments, "--max-ratio must be > 0");
  if (o.wrap == WrapMode::mirror) throw Error(ErrorCode::bad_arguments, "--wrap for conemap: valid: repeat, clamp");
  if (o.fast_reach < 0) throw Error(ErrorCode::bad_arguments, "--fast-reach must be >= 1 (0: exact cones)");
}

// Squared ratio of a candidate: (dx^2 / W^2 + dy^2 / H^2) / (D^2 dh^2), in
// double, the same expression in the fast search and the brute force.
struct Metric {
  double sx, sy, dd;
  double ratio2(double dx, double dy, double dh) const { return (dx * dx * sx + dy * dy * sy) / (dd * dh * dh); }
};

// Distance in texels from p to the nearest point of [lo, hi] (texel
// centres), along one axis; with repeat, to the nearest periodic copy.
int axis_distance(int p, int lo, int hi, int n, bool repeat) {
  int d = p < lo ? lo - p : p > hi ? p - hi : 0;
  if (repeat && d > 0) d = std::min({d, lo + n - p, p - hi + n});
  return d;
}

int texel_distance(int p, int q, int n, bool repeat) {
  const int d = p > q ? p - q : q - p;
  return repeat ? std::min(d, n - d) : d;
}

struct Pyramid {
  std::vector<std::vector<float>> max;  // level 0: the heights
  std::vector<int> w, h;
};

Pyramid build_pyramid(const std::vector<float>& heights, int W, int H) {
  Pyramid p;
  p.max.push_back(heights);
  p.w.push_back(W);
  p.h.push_back(H);
  while (p.w.back() > 1 || p.h.back() > 1) {
    const int pw = p.w.back(), ph = p.h.back(), nw = (pw + 1) / 2, nh = (ph + 1) / 2;
    const std::vector<float>& prev = p.max.back();
    std::vector<float> next(std::size_t(nw) * nh);
    for (int y = 0; y < nh; ++y)
      for (int x = 0; x < nw; ++x) {
        float m = prev[std::size_t(2 * y) * pw + 2 * x];
        if (2 * x + 1 < pw) m = std::max(m, prev[std::size_t(2 * y) * pw + 2 * x + 1]);
        if (2 * y + 1 < ph) {
          m = std::max(m, prev[std::size_t(2 * y + 1) * pw + 2 * x]);
          if (2 * x + 1 < pw) m = std::max(m, prev[std::size_t(2 * y + 1) * pw + 2 * x + 1]);
        }
        next[std::size_t(y) * nw + x] = m;
      }
    p.max.push_back(std::move(next));
    p.w.push_back(nw);
    p.h.push_back(nh);
  }
  return p;
}

constexpr int kLeafLevel = 2;  // blocks of 4x4 texels are scanned directly
// Prune only when the bound exceeds the best by more than rounding could
// explain: candidates are >= the true bound, which the computed one matches
// to ~1e-15 relative.
constexpr double kPruneSlack = 1.0 + 1e-9;

struct Node {
  int level, x, y;
  double bound;
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
  // dx, dy: q - p, the shortest way round with repeat (ties: both ways).
  bool exits(int px, int py, int qx, int qy, float hq) const {
    const int ox = signed_offset(px, qx, W), oy = signed_offset(py, qy, H);
    const bool both_x = repeat && 2 * std::abs(ox) == W, both_y = repeat && 2 * std::abs(oy) == H;
    if ((ox >= 0 || both_x) && lower(qx, qy, hq, 1, 0)) return true;
    if ((ox <= 0 || both_x) && lower(qx, qy, hq, -1, 0)) return true;
    if ((oy >= 0 || both_y) && lower(qx, qy, hq, 0, 1)) return true;
    if ((oy <= 0 || both_y) && lower(qx, qy, hq, 0, -1)) return true;
    return false;
  }
  int signed_offset(int p, int q, int n) const {
    int d = q - p;
    if (repeat) {
      if (d > n / 2) d -= n;
      if (d < -n / 2) d += n;
    }
    return d;
  }
};

// --fast, conservative: the texture is cut into cells of kCell x kCell
// texels. Obstacles farther than `near` texels from a cell (Chebyshev, from
// the cell's texel rectangle) are folded into one bound per cell, computed
// once: min over them of dist(cell, q) / (depth (h_q - min height of the
// cell)); every texel of the cell is at least that far and no lower, so the
// bound is <= its true ratio for those obstacles. Each texel then searches
// only the obstacles within `near` of its cell, exactly, starting from the
// cell's bound. The cone is min(exact near, cell bound): never wider.
constexpr int kCell = 8;

// Gap between texel ranges [a0, a1] and [b0, b1] along an axis of n texels
// (with repeat, the nearest periodic copy of b), and the shift used.
int range_gap(int a0, int a1, int b0, int b1, int n, bool repeat, int* shift = nullptr) {
  auto gap = [&](int s) { return std::max({0, b0 + s - a1, a0 - (b1 + s)}); };
  int best = gap(0), bs = 0;
  if (repeat) {
    for (int s : {-n, n}) {
      const int g = gap(s);
      if (g < best) best = g, bs = s;
    }
  }
  if (shift) *shift = bs;
  return best;
}

// The farthest point of [b0, b1] from [a0, a1] (in the copy `shift`).
int range_reach(int a0, int a1, int b0, int b1, int shift) {
  return std::max({0, b1 + shift - a1, a0 - (b0 + shift)});
}

// Pushes the children of node n that may hold a candidate below `best`
// (bound(child) is the squared ratio at its nearest point), nearest first.
template <typename Bound>
void push_children(const Pyramid& pyr, const Node& n, float floor_height, double best, Bound bound,
                   std::vector<Node>& stack) {
  const int k = n.level;
  Node kids[4];
  int count = 0;
  const int kw = pyr.w[std::size_t(k - 1)], kh = pyr.h[std::size_t(k - 1)];
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int ux = 2 * n.x + i, uy = 2 * n.y + j;
      if (ux >= kw || uy >= kh) continue;
      const float M = pyr.max[std::size_t(k - 1)][std::size_t(uy) * kw + ux];
      if (M <= floor_height) continue;
      const double b = bound(k - 1, ux, uy, double(M) - floor_height);
      if (b > best * kPruneSlack) continue;
      kids[count++] = {k - 1, ux, uy, b / kPruneSlack};
    }
  for (int a = 1; a < count; ++a)
    for (int b = a; b > 0 && kids[b - 1].bound < kids[b].bound; --b) std::swap(kids[b - 1], kids[b]);
  for (int c = 0; c < count; ++c) stack.push_back(kids[c]);
}

std::vector<float> cone_ratios_tiled(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o,
                                     const Pyramid& pyr, const Metric& m, bool repeat) {
  const int top = int(pyr.max.size()) - 1;
  const double cap2 = double(o.max_ratio) * o.max_ratio;
  const int near = o.fast_reach * kCell;
  const int cw = (W + kCell - 1) / kCell, ch = (H + kCell - 1) / kCell;
  std::vector<double> far2(std::size_t(cw) * ch, cap2);
  // 1. The far bound of every cell.
  for_each_row_block(ch, 1, [&](int r0, int r1) {
    std::vector<Node> stack;
    for (int cy = r0; cy < r1; ++cy)
      for (int cx = 0; cx < cw; ++cx) {
        const int x0 = cx * kCell, x1 = std::min(W, x0 + kCell) - 1, y0 = cy * kCell, y1 = std::min(H, y0 + kCell) - 1;
        float lo = 2.0f;
        for (int y = y0; y <= y1; ++y)
          for (int x = x0; x <= x1; ++x) lo = std::min(lo, heights[std::size_t(y) * W + x]);
        double best = cap2;
        stack.clear();
        stack.push_back({top, 0, 0, 0.0});
        while (!stack.empty()) {
          const Node n = stack.back();
          stack.pop_back();
          if (n.bound > best) continue;
          const int k = n.level;
          const int bx0 = n.x << k, bx1 = std::min((n.x + 1) << k, W) - 1;
          const int by0 = n.y << k, by1 = std::min((n.y + 1) << k, H) - 1;
          int sx, sy;
          const int gx = range_gap(x0, x1, bx0, bx1, W, repeat, &sx), gy = range_gap(y0, y1, by0, by1, H, repeat, &sy);
          if (range_reach(x0, x1, bx0, bx1, sx) <= near && range_reach(y0, y1, by0, by1, sy) <= near) continue;  // all near
          if (k == 0) {
            if (gx <= near && gy <= near) continue;  // a near texel: the texels' own searches see it
            best = std::min(best, m.ratio2(gx, gy, double(pyr.max[0][std::size_t(by0) * W + bx0]) - lo));
            continue;
          }
          push_children(pyr, n, lo, best, [&](int s, int ux, int uy, double dh) {
            return m.ratio2(range_gap(x0, x1, ux << s, std::min((ux + 1) << s, W) - 1, W, repeat),
                            range_gap(y0, y1, uy << s, std::min((uy + 1) << s, H) - 1, H, repeat), dh);
          }, stack);
        }
        far2[std::size_t(cy) * cw + cx] = best;
      }
  });
  // 2. Every texel: the obstacles near its cell, exactly, from the cell's bound.
  std::vector<float> out(heights.size());
  for_each_row_block(H, 4, [&](int r0, int r1) {
    std::vector<Node> stack;
    for (int py = r0; py < r1; ++py)
      for (int px = 0; px < W; ++px) {
        const int cx = px / kCell, cy = py / kCell;
        const int x0 = cx * kCell, x1 = std::min(W, x0 + kCell) - 1, y0 = cy * kCell, y1 = std::min(H, y0 + kCell) - 1;
        const float hp = heights[std::size_t(py) * W + px];
        double best = far2[std::size_t(cy) * cw + cx];
        stack.clear();
        stack.push_back({top, 0, 0, 0.0});
        while (!stack.empty()) {
          const Node n = stack.back();
          stack.pop_back();
          if (n.bound > best) continue;
          const int k = n.level;
          const int bx0 = n.x << k, bx1 = std::min((n.x + 1) << k, W) - 1;
          const int by0 = n.y << k, by1 = std::min((n.y + 1) << k, H) - 1;
          int sx, sy;
          if (range_gap(x0, x1, bx0, bx1, W, repeat, &sx) > near || range_gap(y0, y1, by0, by1, H, repeat, &sy) > near) {
            continue;  // wholly far: in the cell's bound
          }
          if (k <= kLeafLevel) {
            // Usually the whole block is near: no per-texel test then.
            const bool all_near = range_reach(x0, x1, bx0, bx1, sx) <= near && range_reach(y0, y1, by0, by1, sy) <= near;
            for (int qy = by0; qy <= by1; ++qy) {
              if (!all_near && range_gap(y0, y1, qy, qy, H, repeat) > near) continue;
              const int dy = texel_distance(py, qy, H, repeat);
              const float* row = heights.data() + std::size_t(qy) * W;
              for (int qx = bx0; qx <= bx1; ++qx) {
                const float hq = row[qx];
                if (hq <= hp || (!all_near && range_gap(x0, x1, qx, qx, W, repeat) > near)) continue;
                best = std::min(best, m.ratio2(texel_distance(px, qx, W, repeat), dy, double(hq) - hp));
              }
            }
            continue;
          }
          push_children(pyr, n, hp, best, [&](int s, int ux, int uy, double dh) {
            return m.ratio2(axis_distance(px, ux << s, std::min((ux + 1) << s, W) - 1, W, repeat),
                            axis_distance(py, uy << s, std::min((uy + 1) << s, H) - 1, H, repeat), dh);
          }, stack);
        }
        out[std::size_t(py) * W + px] = float(std::sqrt(best));
      }
  });
  return out;
}

}  // namespace

std::vector<float> cone_ratios(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o) {
  check(heights, W, H, o);
  const bool repeat = o.wrap == WrapMode::repeat;
  const Metric m{1.0 / (double(W) * W), 1.0 / (double(H) * H), double(o.depth) * o.depth};
  const Pyramid pyr = build_pyramid(heights, W, H);
  if (o.fast_reach > 0 && o.mode == ConeMode::conservative) return cone_ratios_tiled(heights, W, H, o, pyr, m, repeat);
  // Relaxed cones: four more pyramids, of the heights of the texels whose
  // +x, -x, +y or -y neighbour is lower (-1 elsewhere). A block wholly on
  // one side of p along an axis can only hold exits that way, so its bound
  // takes the maximum of the matching pyramids.
  std::vector<Pyramid> exit_pyr;
  if (o.mode == ConeMode::relaxed) {
    const Behind b{heights, W, H, repeat};
    const int sx[4] = {1, -1, 0, 0}, sy[4] = {0, 0, 1, -1};
    for (int f = 0; f < 4; ++f) {
      std::vector<float> v(heights.size());
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
          const float hq = heights[std::size_t(y) * W + x];
          v[std::size_t(y) * W + x] = b.lower(x, y, hq, sx[f], sy[f]) ? hq : -1.0f;
        }
      exit_pyr.push_back(build_pyramid(v, W, H));
    }
  }
  // Which side of p a block [lo, hi] lies on along an axis: +1, -1, or 0
  // (both: it holds p's row or column, or straddles the far seam).
  auto side = [&](int p, int lo, int hi, int n) {
    if (!repeat) return lo > p ? 1 : hi < p ? -1 : 0;
    if (2 * (hi - lo + 1) >= n) return 0;
    auto off = [&](int q) {
      int d = q - p;
      if (d > n / 2) d -= n;
      if (d < -n / 2) d += n;
      return d;
    };
    const int a = off(lo), b = off(hi);
    if (b < a || 2 * std::abs(a) == n || 2 * std::abs(b) == n) return 0;  // across the seam, or a tie
    return a > 0 ? 1 : b < 0 ? -1 : 0;
  };
  const int top = int(pyr.max.size()) - 1;
  const double cap2 = double(o.max_ratio) * o.max_ratio;
  const int reach = o.fast_reach;
  const bool relaxed = o.mode == ConeMode::relaxed;
  const Behind behind{heights, W, H, repeat};
  std::vector<float> out(heights.size());

  for_each_row_block(H, 4, [&](int y0, int y1) {
    thread_local std::vector<Node> stack;
    for (int py = y0; py < y1; ++py) {
      // The texel that bounded the previous texel's cone usually bounds this
      // one too, nearly as tightly: starting from it prunes from the start.
      // (Only a starting bound: the search still proves the minimum.)
      int wx = -1, wy = -1;
      for (int px = 0; px < W; ++px) {
        const float hp = heights[std::size_t(py) * W + px];
        double best = cap2;
        if (wx >= 0) {
          const float hq = heights[std::size_t(wy) * W + wx];
          if (hq > hp && (!relaxed || behind.exits(px, py, wx, wy, hq))) {
            const double r2 =
                m.ratio2(texel_distance(px, wx, W, repeat), texel_distance(py, wy, H, repeat), double(hq) - hp);
            best = r2 < best ? r2 : best;
          }
        }
        stack.clear();
        stack.push_back({top, 0, 0, 0.0});
        while (!stack.empty()) {
          const Node n = stack.back();
          stack.pop_back();
          if (n.bound * 1.0 > best) continue;  // the best improved since it was pushed
          const int k = n.level;
          const int x_lo = n.x << k, x_hi = std::min((n.x + 1) << k, W) - 1;
          const int y_lo = n.y << k, y_hi = std::min((n.y + 1) << k, H) - 1;
          if (k <= kLeafLevel) {
            for (int qy = y_lo; qy <= y_hi; ++qy) {
              const float* row = heights.data() + std::size_t(qy) * W;
              const int dy = texel_distance(py, qy, H, repeat);
              for (int qx = x_lo; qx <= x_hi; ++qx) {
                const float hq = row[qx];
                if (hq <= hp) continue;
                const double r2 = m.ratio2(texel_distance(px, qx, W, repeat), dy, double(hq) - hp);
                if (r2 < best && (!relaxed || behind.exits(px, py, qx, qy, hq))) {
                  best = r2;
                  wx = qx;
                  wy = qy;
                }
              }
            }
            continue;
          }
          // Children, farthest pushed first so the nearest is searched first.
          Node kids[4];
          int count = 0;
          const int cw = pyr.w[k - 1], ch = pyr.h[k - 1];
          for (int j = 0; j < 2; ++j)
            for (int i = 0; i < 2; ++i) {
              const int cx = 2 * n.x + i, cy = 2 * n.y + j;
              if (cx >= cw || cy >= ch) continue;
              float M = pyr.max[k - 1][std::size_t(cy) * cw + cx];
              if (M <= hp) continue;
              if (relaxed) {
                const int s1 = k - 1;
                const int xs = side(px, cx << s1, std::min((cx + 1) << s1, W) - 1, W);
                const int ys = side(py, cy << s1, std::min((cy + 1) << s1, H) - 1, H);
                const std::size_t at = std::size_t(cy) * cw + cx;
                float e = -1.0f;
                if (xs >= 0) e = std::max(e, exit_pyr[0].max[k - 1][at]);
                if (xs <= 0) e = std::max(e, exit_pyr[1].max[k - 1][at]);
                if (ys >= 0) e = std::max(e, exit_pyr[2].max[k - 1][at]);
                if (ys <= 0) e = std::max(e, exit_pyr[3].max[k - 1][at]);
                M = e;
                if (M <= hp) continue;
              }
              const int s = k - 1;
              const int dx = axis_distance(px, cx << s, std::min((cx + 1) << s, W) - 1, W, repeat);
              const int dy = axis_distance(py, cy << s, std::min((cy + 1) << s, H) - 1, H, repeat);
              const double bound = m.ratio2(dx, dy, double(M) - hp);
              if (bound > best * kPruneSlack) continue;
              if (reach > 0 && std::max(dx, dy) >= (reach << s)) {  // --fast: the block as one obstacle
                best = bound < best ? bound : best;
                continue;
              }
              kids[count++] = {s, cx, cy, bound / kPruneSlack};
            }
          // At most four: insertion sort, largest bound first.
          for (int a = 1; a < count; ++a)
            for (int b = a; b > 0 && kids[b - 1].bound < kids[b].bound; --b) std::swap(kids[b - 1], kids[b]);
          for (int c = 0; c < count; ++c) stack.push_back(kids[c]);
        }
        out[std::size_t(py) * W + px] = float(std::sqrt(best));
      }
    }
  });
  return out;
}

std::vector<float> cone_ratios_brute_force(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o) {
  check(heights, W, H, o);
  const bool repeat = o.wrap == WrapMode::repeat;
  const Metric m{1.0 / (double(W) * W), 1.0 / (double(H) * H), double(o.depth) * o.depth};
  const bool relaxed = o.mode == ConeMode::relaxed;
  const Behind behind{heights, W, H, repeat};
  std::vector<float> out(heights.size());
  for_each_row_block(H, 1, [&](int y0, int y1) {
    for (int py = y0; py < y1; ++py)
      for (int px = 0; px < W; ++px) {
        const float hp = heights[std::size_t(py) * W + px];
        double best = double(o.max_ratio) * o.max_ratio;
        for (int qy = 0; qy < H; ++qy)
          for (int qx = 0; qx < W; ++qx) {
            const float hq = heights[std::size_t(qy) * W + qx];
            if (hq <= hp) continue;
            if (relaxed && !behind.exits(px, py, qx, qy, hq)) continue;
            const double r2 =
                m.ratio2(texel_distance(px, qx, W, repeat), texel_distance(py, qy, H, repeat), double(hq) - hp);
            best = r2 < best ? r2 : best;
          }
        out[std::size_t(py) * W + px] = float(std::sqrt(best));
      }
  });
  return out;
}

Image cone_map_image(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                     const ConeMapOptions& o, PixelType type) {
  Image img = Image::uninitialized(W, H, 3, type);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t i = std::size_t(y) * W + x;
      const double g = std::sqrt(std::min(1.0, double(ratios[i]) / o.max_ratio));
      switch (type) {
        case PixelType::u8: {
          auto* p = img.row<std::uint8_t>(y) + 3 * x;
          p[0] = std::uint8_t(std::lround(std::clamp(heights[i], 0.0f, 1.0f) * 255.0f));
          p[1] = std::uint8_t(std::floor(g * 255.0));  // rounded down: never a wider cone
          p[2] = 0;
          break;
        }
        case PixelType::u16: {
          auto* p = img.row<std::uint16_t>(y) + 3 * x;
          p[0] = std::uint16_t(std::lround(std::clamp(heights[i], 0.0f, 1.0f) * 65535.0f));
          p[1] = std::uint16_t(std::floor(g * 65535.0));
          p[2] = 0;
          break;
        }
        case PixelType::f32: {
          auto* p = img.row<float>(y) + 3 * x;
          p[0] = heights[i];
          p[1] = float(g);
          p[2] = 0.0f;
          break;
        }
      }
    }
  return img;
}

}  // namespace texproc
