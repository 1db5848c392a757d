// The scalar reference of cone_cells.h (namespace ref): what cone_cells_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "conemap/cone_cells.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace texproc::detail::ref {

namespace {
bool update(const ConeGeometry& g, float hq, float d2, float hp, float& best) {
  if (hq > hp && d2 > 0.0f) {
    const float r2 = cone_r2(g, d2, hq - hp);
    if (r2 < best) {
      best = r2;
      return true;
    }
  }
  return false;
}
}  // namespace

bool cone_cell_texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                      const bool rows[kConeCell]) {
  bool improved = false;
  for (int r = 0; r < kConeCell; ++r) {
    if (!rows[r]) continue;
    const int py = c.y0 + r;
    for (int qy = by0; qy <= by1; ++qy) {
      const int dy = cone_axis_distance(py, qy, qy, g.H, g.repeat);
      const float* hrow = heights + std::size_t(qy) * g.W;
      for (int qx = bx0; qx <= bx1; ++qx)
        for (int l = 0; l < kConeCell; ++l) {
          if (g.exit_bits && !(hrow[qx] > c.apex[r][l] && cone_exits(g, c.x0 + l, py, qx, qy))) continue;
          const float d2 = cone_d2(g, cone_axis_distance(c.x0 + l, qx, qx, g.W, g.repeat), dy);
          improved |= update(g, hrow[qx], d2, c.apex[r][l], c.best[r][l]);
        }
    }
  }
  return improved;
}

bool cone_cell_block(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M,
                     const bool rows[kConeCell]) {
  bool improved = false;
  for (int r = 0; r < kConeCell; ++r) {
    if (!rows[r]) continue;
    const int dy = cone_axis_distance(c.y0 + r, by0, by1, g.H, g.repeat);
    for (int l = 0; l < kConeCell; ++l) {
      const float d2 = cone_d2(g, cone_axis_distance(c.x0 + l, bx0, bx1, g.W, g.repeat), dy);
      improved |= update(g, M, d2, c.apex[r][l], c.best[r][l]);
    }
  }
  return improved;
}

bool cone_cell_clear(const ConeGeometry& g, const ConeCell& c, int bx0, int bx1, int by0, int by1, float M, int axis,
                     float rise, int extent) {
  const float slack = 1.0f + 1.0f / 65536;
  const float M0 = rise > 0.0f ? M - float(extent) * rise : M;
  for (int r = 0; r < kConeCell; ++r)
    for (int l = 0; l < kConeCell; ++l) {
      const float hp = c.apex[r][l];
      if (!(M > hp)) continue;
      int dx = cone_axis_distance(c.x0 + l, bx0, bx1, g.W, g.repeat),
          dy = cone_axis_distance(c.y0 + r, by0, by1, g.H, g.repeat);
      dx = dx > g.shrink ? dx - g.shrink : 0;
      dy = dy > g.shrink ? dy - g.shrink : 0;
      const float vx = float(dx) / float(g.W), vy = float(dy) / float(g.H);
      const float len2 = vx * vx + vy * vy;
      const float lim = c.best[r][l] * g.dd * slack;
      // a = 0: the whole block at M0 (M without a rise), at the nearest distance.
      const float dh0 = M0 - hp;
      if (dh0 > 0.0f && !(len2 > lim * (dh0 * dh0))) return false;
      if (rise > 0.0f) {
        // a = extent: the far edge at M, at the projected far distance.
        const float len = std::sqrt(len2);
        if (!(len > 0.0f)) return false;
        const float far = len + (axis == 0 ? vx : vy) / len * (float(extent) / float(axis == 0 ? g.W : g.H));
        const float dh = M - hp;
        if (!(far * far > lim * (dh * dh))) return false;
      }
    }
  return true;
}

float cone_cell_reach(const ConeCell& c, float M) {
  float most = 0.0f;
  for (int r = 0; r < kConeCell; ++r)
    for (int l = 0; l < kConeCell; ++l) {
      const float dh = M - c.apex[r][l];
      if (dh > 0.0f) most = std::max(most, c.best[r][l] * (dh * dh));
    }
  return most;
}

}  // namespace texproc::detail::ref
