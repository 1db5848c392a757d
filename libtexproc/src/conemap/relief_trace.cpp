// Relief ray tracing in texture space, for the preview and the safety tests:
// a dense linear search (the reference) and Dummer's cone stepping, both
// refined by a binary search. Heights are sampled at the nearest texel, the
// surface the cone map describes.
#include <algorithm>
#include <cmath>

#include "texproc/conemap.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

struct Field {
  const std::vector<float>& h;
  const std::vector<float>* ratios;
  int W, H;
  bool repeat;
  // Nearest texel of (u, v); false if outside the texture with clamp.
  bool texel(float u, float v, int& x, int& y) const {
    float fx = std::floor(u * W), fy = std::floor(v * H);
    if (!repeat && (fx < 0 || fy < 0 || fx >= W || fy >= H)) return false;
    x = wrap_index(int(fx), W, WrapMode::repeat);
    y = wrap_index(int(fy), H, WrapMode::repeat);
    return true;
  }
};

// Binary search between a point above the surface (z0 at t0) and one below
// (z1 at t1) along the ray; returns the first point found below.
ReliefHit refine(const Field& f, float u, float v, float du, float dv, float z_above, float z_below, int steps,
                 int binary_steps) {
  ReliefHit hit;
  hit.hit = true;
  hit.steps = steps;
  for (int i = 0; i < binary_steps; ++i) {
    const float z = 0.5f * (z_above + z_below);
    int x, y;
    ++hit.steps;
    if (f.texel(u + (1.0f - z) * du, v + (1.0f - z) * dv, x, y) && z <= f.h[std::size_t(y) * f.W + x]) {
      z_below = z;
    } else {
      z_above = z;
    }
  }
  hit.u = u + (1.0f - z_below) * du;
  hit.v = v + (1.0f - z_below) * dv;
  hit.height = z_below;
  return hit;
}

}  // namespace

namespace {
// Grid traversal (Amanatides and Woo) from ray parameter t_start: t in [0, 1]
// runs from the top plane (z = 1) to the bottom (z = 0); X(t) = (u + t du) W,
// Y(t) = (v + t dv) H. Visits every texel the ray crosses, so it finds the
// exact first hit on the nearest-texel surface after t_start.
ReliefHit traverse(const std::vector<float>& heights, int W, int H, bool repeat, float u, float v, float du, float dv,
                   double t_start, int steps) {
  const double X0 = double(u) * W, Y0 = double(v) * H, DX = double(du) * W, DY = double(dv) * H;
  const double XS = X0 + t_start * DX, YS = Y0 + t_start * DY;
  long long cx = (long long)std::floor(XS), cy = (long long)std::floor(YS);
  const int sx = DX > 0 ? 1 : -1, sy = DY > 0 ? 1 : -1;
  const double inf = 1e300;
  double t_next_x = DX != 0 ? ((sx > 0 ? double(cx + 1) : double(cx)) - X0) / DX : inf;
  double t_next_y = DY != 0 ? ((sy > 0 ? double(cy + 1) : double(cy)) - Y0) / DY : inf;
  if (t_next_x < t_start) t_next_x = t_start;  // rounding at a cell edge
  if (t_next_y < t_start) t_next_y = t_start;
  const double step_x = DX != 0 ? std::abs(1.0 / DX) : inf, step_y = DY != 0 ? std::abs(1.0 / DY) : inf;
  double t_in = t_start;
  ReliefHit hit;
  hit.steps = steps;
  while (t_in <= 1.0) {
    if (!repeat && (cx < 0 || cy < 0 || cx >= W || cy >= H)) return hit;
    const int x = wrap_index(int(((cx % W) + W) % W), W, WrapMode::repeat);
    const int y = wrap_index(int(((cy % H) + H) % H), H, WrapMode::repeat);
    const double hc = heights[std::size_t(y) * W + x];
    const double t_out = std::min({t_next_x, t_next_y, 1.0});
    ++hit.steps;
    if (1.0 - t_out <= hc) {  // the ray is at or below this texel's top before leaving it
      const double t = std::max(t_in, 1.0 - hc);
      hit.hit = true;
      hit.u = float(u + t * du);
      hit.v = float(v + t * dv);
      hit.height = float(1.0 - t);
      return hit;
    }
    if (t_out >= 1.0) break;
    t_in = t_out;
    if (t_next_x < t_next_y) {
      cx += sx;
      t_next_x += step_x;
    } else {
      cy += sy;
      t_next_y += step_y;
    }
  }
  return hit;
}
}  // namespace

ReliefHit trace_exact(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o, float u, float v,
                      float du, float dv) {
  return traverse(heights, W, H, o.wrap == WrapMode::repeat, u, v, du, dv, 0.0, 0);
}

ReliefHit trace_linear(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o, float u, float v,
                       float du, float dv, int linear_steps, int binary_steps) {
  const Field f{heights, nullptr, W, H, o.wrap == WrapMode::repeat};
  const float dz = 1.0f / float(std::max(1, linear_steps));
  float z_prev = 1.0f;
  int steps = 0;
  for (int i = 0; i <= linear_steps; ++i) {
    const float z = std::max(0.0f, 1.0f - float(i) * dz);
    int x, y;
    ++steps;
    if (!f.texel(u + (1.0f - z) * du, v + (1.0f - z) * dv, x, y)) return {0, 0, 0, steps, false};
    if (z <= heights[std::size_t(y) * W + x]) return refine(f, u, v, du, dv, z_prev, z, steps, binary_steps);
    z_prev = z;
  }
  return {0, 0, 0, steps, false};
}

namespace {
// Cone stepping, conservative or relaxed (GPU Gems 3, chapter 18).
ReliefHit step_cones(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                     const ConeMapOptions& o, float u, float v, float du, float dv, bool relaxed, int binary_steps) {
  const Field f{heights, &ratios, W, H, o.wrap == WrapMode::repeat};
  // Horizontal speed in texture widths per unit of height descended, and the
  // cone's horizontal reach per unit height: ratio * depth.
  const float s = std::sqrt(du * du + dv * dv);
  // Cones are exact at texel centres, but the nearest-texel surface is made
  // of squares: the current point may sit half a texel diagonal from the
  // centre its cone stands on, and a higher texel's square reaches half a
  // diagonal closer than its centre. Stepping keeps both margins (one full
  // texel diagonal) inside the cone, so no step crosses a texel's top.
  const float margin = std::sqrt(1.0f / (float(W) * W) + 1.0f / (float(H) * H));
  // Near the surface the cone steps shrink towards zero: below a tenth of a
  // texel of travel, finish with the grid traversal, which is exact, so the
  // hit is the true first hit whenever the cone steps never crossed the
  // surface (what the tests check).
  const float texel_uv = std::min(1.0f / W, 1.0f / H);
  const float min_dz = s > 0 ? 0.1f * texel_uv / s : 1.0f / 4096.0f;
  float z = 1.0f;
  int steps = 0;
  for (int i = 0; i < 4096; ++i) {
    int x, y;
    ++steps;
    if (!f.texel(u + (1.0f - z) * du, v + (1.0f - z) * dv, x, y)) return {0, 0, 0, steps, false};
    const std::size_t t = std::size_t(y) * W + x;
    const float h = heights[t];
    const float c = ratios[t] * o.depth;
    const float dz = (c * (z - h) - margin) / (s + c);
    if (z <= h || !(dz > min_dz)) break;
    const float z_next = std::max(0.0f, z - dz);
    if (relaxed) {
      // A relaxed step may end past the surface (its cone holds one
      // crossing): then the binary search between the two points finds it.
      int nx, ny;
      ++steps;
      if (!f.texel(u + (1.0f - z_next) * du, v + (1.0f - z_next) * dv, nx, ny)) break;  // leaving a clamped texture
      if (z_next <= heights[std::size_t(ny) * W + nx]) return refine(f, u, v, du, dv, z, z_next, steps, binary_steps);
    }
    z = z_next;
  }
  return traverse(heights, W, H, f.repeat, u, v, du, dv, 1.0 - double(z), steps);
}
}  // namespace

ReliefHit trace_cones(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                      const ConeMapOptions& o, float u, float v, float du, float dv, int binary_steps) {
  return step_cones(heights, ratios, W, H, o, u, v, du, dv, false, binary_steps);
}

ReliefHit trace_relaxed(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                        const ConeMapOptions& o, float u, float v, float du, float dv, int binary_steps) {
  return step_cones(heights, ratios, W, H, o, u, v, du, dv, true, binary_steps);
}

Image render_preview(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                     const ConeMapOptions& o, int size, float view_angle_deg, const std::vector<float>& relaxed) {
  const int columns = relaxed.empty() ? 2 : 3;
  Image img(columns * size, 2 * size, 3, PixelType::u8);
  const float theta = view_angle_deg * 3.14159265f / 180.0f, phi = 0.6f;
  // Horizontal texture-space travel per unit of height: depth * tan(theta).
  const float du = o.depth * std::tan(theta) * std::cos(phi), dv = o.depth * std::tan(theta) * std::sin(phi);
  const float light[3] = {-0.5f, -0.4f, 0.77f};
  auto shade = [&](const ReliefHit& hit, std::uint8_t* p) {
    if (!hit.hit) {
      p[0] = p[1] = p[2] = 0;
      return;
    }
    const int x = wrap_index(int(std::floor(hit.u * W)), W, WrapMode::repeat);
    const int y = wrap_index(int(std::floor(hit.v * H)), H, WrapMode::repeat);
    auto h = [&](int i, int j) {
      return heights[std::size_t(wrap_index(j, H, o.wrap)) * W + wrap_index(i, W, o.wrap)];
    };
    const float gx = (h(x + 1, y) - h(x - 1, y)) * 0.5f * W * o.depth,
                gy = (h(x, y + 1) - h(x, y - 1)) * 0.5f * H * o.depth;
    const float len = std::sqrt(gx * gx + gy * gy + 1.0f);
    const float lambert = std::max(0.0f, (-gx * light[0] - gy * light[1] + light[2]) / len);
    const float base[3] = {0.55f + 0.4f * hit.height, 0.45f + 0.3f * hit.height, 0.35f};
    for (int c = 0; c < 3; ++c)
      p[c] = std::uint8_t(std::clamp(255.0f * base[c] * (0.25f + 0.75f * lambert), 0.0f, 255.0f));
  };
  auto heat = [](int steps, std::uint8_t* p) {
    const float t = std::clamp(std::log2(float(std::max(steps, 1))) / 10.0f, 0.0f, 1.0f);  // 1 .. 1024 lookups
    p[0] = std::uint8_t(255 * t);
    p[1] = std::uint8_t(255 * (1.0f - std::abs(2.0f * t - 1.0f)));
    p[2] = std::uint8_t(255 * (1.0f - t));
  };
  for_each_row_block(size, 8, [&](int y0, int y1) {
    for (int j = y0; j < y1; ++j)
      for (int i = 0; i < size; ++i) {
        const float u = (i + 0.5f) / size, v = (j + 0.5f) / size;
        const ReliefHit a = trace_linear(heights, W, H, o, u, v, du, dv);
        const ReliefHit b = trace_cones(heights, ratios, W, H, o, u, v, du, dv);
        shade(a, img.row<std::uint8_t>(j) + 3 * i);
        shade(b, img.row<std::uint8_t>(j) + 3 * (size + i));
        heat(a.steps, img.row<std::uint8_t>(size + j) + 3 * i);
        heat(b.steps, img.row<std::uint8_t>(size + j) + 3 * (size + i));
        if (columns == 3) {
          const ReliefHit c = trace_relaxed(heights, relaxed, W, H, o, u, v, du, dv);
          shade(c, img.row<std::uint8_t>(j) + 3 * (2 * size + i));
          heat(c.steps, img.row<std::uint8_t>(size + j) + 3 * (2 * size + i));
        }
      }
  });
  return img;
}

}  // namespace texproc
