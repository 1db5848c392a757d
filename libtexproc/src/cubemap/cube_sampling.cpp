// Filtered sampling into and out of cube maps: panorama to faces over each
// texel's footprint, padded faces, the seamless mip chain, trilinear
// lookups, cube to panorama.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>

#include "cubemap/cube_internal.h"
#include "cubemap/pano_map.h"
#include "mip/resample.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {
namespace cube {

namespace {

// Bilinear inside the n x n interior of a padded face, texel coordinates
// (centres at integers) clamped to the interior.
void interior_bilinear(const PaddedLevel& l, int face, double x, double y, float out[4]) {
  const int n = l.n;
  x = std::clamp(x, 0.0, double(n - 1));
  y = std::clamp(y, 0.0, double(n - 1));
  const int x0 = std::min(int(x), n - 1), y0 = std::min(int(y), n - 1);
  const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
  const float tx = float(x - x0), ty = float(y - y0);
  const float* a = l.texel(face, x0, y0);
  const float* b = l.texel(face, x1, y0);
  const float* c = l.texel(face, x0, y1);
  const float* d = l.texel(face, x1, y1);
  for (int k = 0; k < 4; ++k) {
    const float top = a[k] + (b[k] - a[k]) * tx;
    const float bottom = c[k] + (d[k] - c[k]) * tx;
    out[k] = top + (bottom - top) * ty;
  }
}

}  // namespace

PaddedLevel pad_level(const CubeLevel& level) {
  const int n = level.size;
  PaddedLevel p;
  p.n = n;
  for (int f = 0; f < 6; ++f) p.faces[f].resize(std::size_t(n + 2) * (n + 2) * 4);
  for_each_row_block(6 * n, kRowBlock, [&](int r0, int r1) {
    for (int r = r0; r < r1; ++r)
      std::memcpy(p.texel(r / n, 0, r % n), level.faces[r / n].row<float>(r % n), std::size_t(n) * 16);
  });
  for (int f = 0; f < 6; ++f) {
    auto fill = [&](int i, int j) {
      double d[3], u, v;
      cube_direction(f, 2.0 * (i + 0.5) / n - 1.0, 2.0 * (j + 0.5) / n - 1.0, d);
      const int of = cube_face_uv(d, u, v);
      interior_bilinear(p, of, (u + 1.0) * 0.5 * n - 0.5, (v + 1.0) * 0.5 * n - 0.5, p.texel(f, i, j));
    };
    for (int k = -1; k <= n; ++k) {
      fill(k, -1);
      fill(k, n);
    }
    for (int k = 0; k < n; ++k) {
      fill(-1, k);
      fill(n, k);
    }
  }
  return p;
}

void sample_bilinear(const PaddedLevel& l, const double dir[3], float out[4]) {
  double u, v;
  const int f = cube_face_uv(dir, u, v);
  const int n = l.n;
  const double x = std::clamp((u + 1.0) * 0.5 * n - 0.5, -1.0, double(n));
  const double y = std::clamp((v + 1.0) * 0.5 * n - 0.5, -1.0, double(n));
  const int x0 = std::min(int(std::floor(x)), n - 1), y0 = std::min(int(std::floor(y)), n - 1);
  const float tx = float(x - x0), ty = float(y - y0);
  const float* a = l.texel(f, x0, y0);
  const float* b = l.texel(f, x0 + 1, y0);
  const float* c = l.texel(f, x0, y0 + 1);
  const float* d = l.texel(f, x0 + 1, y0 + 1);
  for (int k = 0; k < 4; ++k) {
    const float top = a[k] + (b[k] - a[k]) * tx;
    const float bottom = c[k] + (d[k] - c[k]) * tx;
    out[k] = top + (bottom - top) * ty;
  }
}

}  // namespace cube

using cube::PaddedLevel;

// ---- Panorama to faces ---------------------------------------------------------

namespace {

struct PanoLevel {
  int w = 0, h = 0;
  const float* data = nullptr;
  std::size_t stride = 0;  // floats per row
};

// The panorama and its box-filtered (exact area) pyramid down to one row.
struct PanoPyramid {
  std::vector<Image> owned;
  std::vector<PanoLevel> levels;

  explicit PanoPyramid(const ConstImageView& v) {
    levels.push_back({v.width, v.height, static_cast<const float*>(v.data), v.row_stride / 4});
    const Filter box{FilterKind::box};
    while (levels.back().w > 1 || levels.back().h > 1) {
      const PanoLevel s = levels.back();
      const int w = std::max(1, s.w / 2), h = std::max(1, s.h / 2);
      const AxisWeights ax = compute_axis_weights(s.w, w, box), ay = compute_axis_weights(s.h, h, box);
      Image tmp = Image::uninitialized(w, s.h, 4, PixelType::f32);
      Image out = Image::uninitialized(w, h, 4, PixelType::f32);
      for_each_row_block(s.h, cube::kRowBlock, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          const float* src = s.data + y * s.stride;
          float* dst = tmp.row<float>(y);
          for (int x = 0; x < w; ++x) {
            float acc[4] = {0, 0, 0, 0};
            for (int t = 0; t < ax.taps; ++t) {
              const float wt = ax.weights[std::size_t(x) * ax.taps + t];
              const int sx = std::clamp(ax.first[x] + t, 0, s.w - 1);
              for (int c = 0; c < 4; ++c) acc[c] += wt * src[4 * sx + c];
            }
            std::memcpy(dst + 4 * x, acc, 16);
          }
        }
      });
      for_each_row_block(h, cube::kRowBlock, [&](int y0, int y1) {
        for (int y = y0; y < y1; ++y) {
          float* dst = out.row<float>(y);
          std::fill(dst, dst + std::size_t(w) * 4, 0.0f);
          for (int t = 0; t < ay.taps; ++t) {
            const float wt = ay.weights[std::size_t(y) * ay.taps + t];
            const float* src = tmp.row<float>(std::clamp(ay.first[y] + t, 0, s.h - 1));
            for (int x = 0; x < w * 4; ++x) dst[x] += wt * src[x];
          }
        }
      });
      owned.push_back(std::move(out));
      const Image& o = owned.back();
      levels.push_back({o.width(), o.height(), o.row<float>(0), std::size_t(o.width()) * 4});
    }
  }

  // Bilinear at level k, (x, y) in level-0 texel units; columns wrap, rows clamp.
  void sample(int k, double x, double y, float out[4]) const {
    const PanoLevel& l = levels[k];
    const PanoLevel& l0 = levels[0];
    const double fx = x * (double(l.w) / l0.w) - 0.5, fy = y * (double(l.h) / l0.h) - 0.5;
    const double flx = std::floor(fx);
    int x0 = int(flx);
    if (x0 < 0 || x0 >= l.w) {  // a tap past the seam (rarely more than one width)
      x0 %= l.w;
      if (x0 < 0) x0 += l.w;
    }
    const int x1 = x0 + 1 == l.w ? 0 : x0 + 1;
    const float tx = float(fx - flx);
    int y0, y1;
    float ty;
    if (fy <= 0) {
      y0 = y1 = 0;
      ty = 0;
    } else if (fy >= l.h - 1) {
      y0 = y1 = l.h - 1;
      ty = 0;
    } else {
      y0 = int(fy);
      y1 = y0 + 1;
      ty = float(fy - y0);
    }
    const float* r0 = l.data + y0 * l.stride;
    const float* r1 = l.data + y1 * l.stride;
    for (int c = 0; c < 4; ++c) {
      const float top = r0[4 * x0 + c] + (r0[4 * x1 + c] - r0[4 * x0 + c]) * tx;
      const float bottom = r1[4 * x0 + c] + (r1[4 * x1 + c] - r1[4 * x0 + c]) * tx;
      out[c] += top + (bottom - top) * ty;
    }
  }
};

// d/du and d/dv of cube_direction on each face.
void face_axes(int face, double eu[3], double ev[3]) {
  double o[3], a[3], b[3];
  cube_direction(face, 0, 0, o);
  cube_direction(face, 1, 0, a);
  cube_direction(face, 0, 1, b);
  for (int k = 0; k < 3; ++k) {
    eu[k] = a[k] - o[k];
    ev[k] = b[k] - o[k];
  }
}

void apply_flip(CubeFlip flip, double d[3]) {
  if (flip == CubeFlip::x) d[0] = -d[0];
  if (flip == CubeFlip::y) d[1] = -d[1];
  if (flip == CubeFlip::z) d[2] = -d[2];
}

constexpr int kMaxTaps = 64;  // per texel, past which a coarser level is read

}  // namespace

Cubemap cubemap_from_equirect(const ConstImageView& pano, int size, CubeFlip flip) {
  if (pano.channels != 4 || pano.type != PixelType::f32) {
    throw Error(ErrorCode::bad_arguments, "cubemap_from_equirect needs a linear RGBA f32 panorama (to_linear_rgba)");
  }
  if (size < 1) throw Error(ErrorCode::bad_arguments, "cube face size must be at least 1");
  const PanoPyramid pyr(pano);
  // The pyramid's row-filtered temporaries are cached for images of their
  // sizes, which the faces are not: back to the system before the faces grow.
  release_cached_pixel_memory();
  const int W = pano.width, H = pano.height;
  const int top = int(pyr.levels.size()) - 1;
  Cubemap c;
  c.levels.push_back(cube::make_level(size));
  CubeLevel& out = c.levels[0];
  const double step = 2.0 / size;
  for_each_row_block(6 * size, cube::kRowBlock, [&](int r0, int r1) {
    std::vector<float> buf(std::size_t(size) * 7);
    const cube::FaceRowMap map{buf.data(),
                               buf.data() + size,
                               buf.data() + 2 * size,
                               buf.data() + 3 * size,
                               buf.data() + 4 * size,
                               buf.data() + 5 * size,
                               buf.data() + 6 * size};
    for (int r = r0; r < r1; ++r) {
      const int f = r / size, j = r % size;
      double o[3], eu[3], ev[3];
      cube_direction(f, 0, 0, o);
      face_axes(f, eu, ev);
      apply_flip(flip, o);
      apply_flip(flip, eu);
      apply_flip(flip, ev);
      float axes[9];
      for (int k = 0; k < 3; ++k) axes[k] = float(o[k]), axes[3 + k] = float(eu[k]), axes[6 + k] = float(ev[k]);
      cube::map_face_row(axes, size, j, W, H, map);
      float* row = out.faces[f].row<float>(j);
      const double v = step * (j + 0.5) - 1.0;
      for (int i = 0; i < size; ++i) {
        // The texel's footprint in panorama texels: a along u, b along v.
        const double ax = map.ax[i], ay = map.ay[i], bx = map.bx[i], by = map.by[i];
        const double la = std::sqrt(ax * ax + ay * ay), lb = std::sqrt(bx * bx + by * by);
        const double major = std::max(la, lb);
        const double minor = std::fabs(ax * by - ay * bx) / std::max(major, 1e-30);
        int k = 0;
        if (minor >= 2.0) k = std::min(top, std::ilogb(minor));
        int na, nb;
        for (;;) {
          const double inv_texel = std::ldexp(1.0, -k);
          na = std::clamp(int(std::ceil(la * inv_texel - 1e-3)), 1, kMaxTaps);
          nb = std::clamp(int(std::ceil(lb * inv_texel - 1e-3)), 1, kMaxTaps);
          if (na * nb <= kMaxTaps || k == top) break;
          ++k;
        }
        while (na * nb > kMaxTaps) (na > nb ? na : nb) /= 2;
        // Near the poles (latitude past ~75 degrees) the panorama mapping is
        // far from linear over a texel: each tap is mapped exactly.
        const bool exact = map.cosl[i] < 0.25f && na * nb > 1;
        float acc[4] = {0, 0, 0, 0};
        if (na * nb == 1) {
          pyr.sample(k, map.px[i], std::clamp(double(map.py[i]), 0.0, double(H)), acc);
        } else {
          const double u = step * (i + 0.5) - 1.0;
          for (int b = 0; b < nb; ++b) {
            const double tv = (b + 0.5) / nb - 0.5;
            for (int a = 0; a < na; ++a) {
              const double tu = (a + 0.5) / na - 0.5;
              double x, y;
              if (exact) {
                double dt[3];
                cube_direction(f, u + tu * step, v + tv * step, dt);
                apply_flip(flip, dt);
                direction_to_equirect(dt, W, H, x, y);
              } else {
                x = map.px[i] + tu * ax + tv * bx;
                y = map.py[i] + tu * ay + tv * by;
              }
              pyr.sample(k, x, std::clamp(y, 0.0, double(H)), acc);
            }
          }
        }
        const float inv = 1.0f / float(na * nb);
        for (int ch = 0; ch < 4; ++ch) row[4 * i + ch] = acc[ch] * inv;
      }
    }
  });
  return c;
}

// ---- Seamless mips -----------------------------------------------------------------

namespace {

// Source taps of each destination texel along one axis: indices
// first..first+count-1 in [-1, n] (the padded range), those within a tent
// of radius n / m around the texel's centre.
struct TapRange {
  std::vector<int> first, count;
  int max_count = 0;
};
TapRange tap_range(int n, int m) {
  TapRange t;
  const double s = double(n) / m;
  t.first.resize(m);
  t.count.resize(m);
  for (int i = 0; i < m; ++i) {
    const double c = (i + 0.5) * s - 0.5;
    const int lo = std::max(-1, int(std::ceil(c - s + 1e-9)));
    const int hi = std::min(n, int(std::floor(c + s - 1e-9)));
    t.first[i] = lo;
    t.count[i] = hi - lo + 1;
    t.max_count = std::max(t.max_count, t.count[i]);
  }
  return t;
}

void normalize3(double v[3]) {
  const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  v[0] /= l;
  v[1] /= l;
  v[2] /= l;
}

// The weights of every destination texel's taps, normalized: a separable
// tent one destination texel wide in the tangent plane at the texel's own
// direction (so the filter is centred on that direction on the sphere, not
// on the face plane, which is compressed towards the edges), times each
// source texel's solid angle. Every face has the same table: it is built
// on the face-local plane (u, -v, 1).
std::vector<float> mip_weights(int n, int m, const TapRange& axis) {
  const int stride = axis.max_count * axis.max_count;
  // Unit directions and solid angles of the padded source texels.
  const int p = n + 2;
  std::vector<double> dirs(std::size_t(p) * p * 3), solid(std::size_t(p) * p);
  for_each_row_block(p, cube::kRowBlock, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < p; ++x) {
        const std::size_t k = std::size_t(y) * p + x;
        double* L = dirs.data() + 3 * k;
        L[0] = 2.0 * (x - 1 + 0.5) / n - 1.0;
        L[1] = -(2.0 * (y - 1 + 0.5) / n - 1.0);
        L[2] = 1.0;
        normalize3(L);
        solid[k] = cube_texel_solid_angle(n, x - 1, y - 1);
      }
  });
  std::vector<float> w(std::size_t(m) * m * stride, 0.0f);
  for_each_row_block(m, cube::kRowBlock, [&](int j0, int j1) {
    for (int j = j0; j < j1; ++j)
      for (int i = 0; i < m; ++i) {
        const double u = 2.0 * (i + 0.5) / m - 1.0, v = 2.0 * (j + 0.5) / m - 1.0;
        double D[3] = {u, -v, 1.0};
        const double len = std::sqrt(u * u + v * v + 1.0);
        normalize3(D);
        // d(D)/du and d(D)/dv: the plane axes minus their part along D, over |p|.
        double Tu[3] = {1.0 - D[0] * D[0], -D[1] * D[0], -D[2] * D[0]};
        double Tv[3] = {D[0] * D[1], -1.0 + D[1] * D[1], D[2] * D[1]};
        const double su = std::sqrt(Tu[0] * Tu[0] + Tu[1] * Tu[1] + Tu[2] * Tu[2]) / len * (2.0 / m);
        const double sv = std::sqrt(Tv[0] * Tv[0] + Tv[1] * Tv[1] + Tv[2] * Tv[2]) / len * (2.0 / m);
        normalize3(Tu);
        normalize3(Tv);
        float* out = w.data() + (std::size_t(j) * m + i) * stride;
        double wts[64], sum = 0;
        for (int b = 0; b < axis.count[j]; ++b)
          for (int a = 0; a < axis.count[i]; ++a) {
            const std::size_t k = std::size_t(axis.first[j] + b + 1) * p + (axis.first[i] + a + 1);
            const double* L = dirs.data() + 3 * k;
            const double ld = L[0] * D[0] + L[1] * D[1] + L[2] * D[2];
            const double x = (L[0] * Tu[0] + L[1] * Tu[1] + L[2] * Tu[2]) / ld;
            const double y = (L[0] * Tv[0] + L[1] * Tv[1] + L[2] * Tv[2]) / ld;
            const double wt =
                std::max(0.0, 1.0 - std::fabs(x) / su) * std::max(0.0, 1.0 - std::fabs(y) / sv) * solid[k];
            wts[b * axis.max_count + a] = wt;
            sum += wt;
          }
        for (int b = 0; b < axis.count[j]; ++b)
          for (int a = 0; a < axis.count[i]; ++a)
            out[b * axis.max_count + a] = float(wts[b * axis.max_count + a] / sum);
      }
  });
  return w;
}

}  // namespace

void generate_cube_mips(Cubemap& cube, int max_levels) {
  if (cube.levels.empty()) throw Error(ErrorCode::bad_arguments, "generate_cube_mips: the cube map has no level 0");
  cube.levels.resize(1);
  const int wanted = max_levels > 0 ? max_levels : 1 << 30;
  while (int(cube.levels.size()) < wanted && cube.levels.back().size > 1) {
    const PaddedLevel src = cube::pad_level(cube.levels.back());
    const int n = src.n, m = std::max(1, n / 2);
    const TapRange axis = tap_range(n, m);
    const std::vector<float> weights = mip_weights(n, m, axis);
    const int stride = axis.max_count * axis.max_count;
    CubeLevel dst = cube::make_level(m);
    for_each_row_block(6 * m, cube::kRowBlock, [&](int r0, int r1) {
      for (int r = r0; r < r1; ++r) {
        const int f = r / m, j = r % m;
        float* row = dst.faces[f].row<float>(j);
        for (int i = 0; i < m; ++i) {
          const float* w = weights.data() + (std::size_t(j) * m + i) * stride;
          float acc[4] = {0, 0, 0, 0};
          for (int b = 0; b < axis.count[j]; ++b) {
            const float* t = src.texel(f, axis.first[i], axis.first[j] + b);
            for (int a = 0; a < axis.count[i]; ++a, t += 4) {
              const float wt = w[b * axis.max_count + a];
              for (int c = 0; c < 4; ++c) acc[c] += wt * t[c];
            }
          }
          std::memcpy(row + 4 * i, acc, 16);
        }
      }
    });
    cube.levels.push_back(std::move(dst));
  }
}

namespace cube {
namespace {
int mip_count(int n) {
  int levels = 1;
  while (n > 1) {
    n = std::max(1, n / 2);
    ++levels;
  }
  return levels;
}
}  // namespace

const Cubemap& full_chain(const Cubemap& cube, Cubemap& scratch) {
  if (cube.levels.back().size == 1 && int(cube.levels.size()) == mip_count(cube.size())) return cube;
  scratch.levels.assign(1, cube.levels[0]);
  generate_cube_mips(scratch);
  return scratch;
}
}  // namespace cube

// ---- Trilinear sampling ---------------------------------------------------------------

struct CubeSampler::Impl {
  std::vector<PaddedLevel> levels;
};

CubeSampler::CubeSampler(const Cubemap& cube) : impl_(std::make_unique<Impl>()) {
  for (const CubeLevel& l : cube.levels) impl_->levels.push_back(cube::pad_level(l));
}
CubeSampler::~CubeSampler() = default;
CubeSampler::CubeSampler(CubeSampler&&) noexcept = default;
CubeSampler& CubeSampler::operator=(CubeSampler&&) noexcept = default;
int CubeSampler::levels() const { return int(impl_->levels.size()); }
int CubeSampler::size() const { return impl_->levels.empty() ? 0 : impl_->levels[0].n; }

void CubeSampler::sample(const double dir[3], float lod, float rgba[4]) const {
  const int top = int(impl_->levels.size()) - 1;
  lod = std::clamp(lod, 0.0f, float(top));
  const int l0 = std::min(int(lod), top);
  const float t = lod - l0;
  cube::sample_bilinear(impl_->levels[l0], dir, rgba);
  if (t > 0.0f && l0 < top) {
    float b[4];
    cube::sample_bilinear(impl_->levels[l0 + 1], dir, b);
    for (int c = 0; c < 4; ++c) rgba[c] += (b[c] - rgba[c]) * t;
  }
}

Cubemap resize_cubemap(const Cubemap& cube, int size) {
  if (cube.levels.empty()) throw Error(ErrorCode::bad_arguments, "resize_cubemap: the cube map has no level 0");
  if (size < 1) throw Error(ErrorCode::bad_arguments, "cube face size must be at least 1");
  if (size == cube.size()) {
    Cubemap same;
    same.levels.push_back(cube.levels[0]);
    return same;
  }
  Cubemap scratch;
  const CubeSampler sampler(cube::full_chain(cube, scratch));
  const float lod = std::max(0.0f, float(std::log2(double(cube.size()) / size)));
  Cubemap out;
  out.levels.push_back(cube::make_level(size));
  for_each_row_block(6 * size, cube::kRowBlock, [&](int r0, int r1) {
    for (int r = r0; r < r1; ++r) {
      const int f = r / size, j = r % size;
      float* row = out.levels[0].faces[f].row<float>(j);
      for (int i = 0; i < size; ++i) {
        double d[3];
        cube::texel_direction(f, size, i, j, d);
        sampler.sample(d, lod, row + 4 * i);
      }
    }
  });
  return out;
}

Image cubemap_to_equirect(const Cubemap& cube, int width, int level) {
  if (level < 0 || level >= int(cube.levels.size())) {
    throw Error(ErrorCode::bad_arguments,
                "cubemap_to_equirect: level " + std::to_string(level) + " is not in the cube map");
  }
  if (width < 2) throw Error(ErrorCode::bad_arguments, "a panorama is at least 2 texels wide");
  Cubemap src;
  src.levels.assign(cube.levels.begin() + level, cube.levels.end());
  if (src.levels.size() == 1) generate_cube_mips(src);
  const CubeSampler sampler(src);
  const int w = width, h = width / 2, n = src.size();
  Image out = Image::uninitialized(w, h, 4, PixelType::f32);
  for_each_row_block(h, cube::kRowBlock, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* row = out.row<float>(y);
      for (int x = 0; x < w; ++x) {
        double d[3];
        equirect_direction(x + 0.5, y + 0.5, w, h, d);
        // The panorama texel's larger side (its height, pi / h) against the
        // cube texel's side in this direction.
        double u, v;
        cube_face_uv(d, u, v);
        const double cube_side = (2.0 / n) / std::pow(1.0 + u * u + v * v, 0.75);
        const float lod = float(std::max(0.0, std::log2((std::numbers::pi / h) / cube_side)));
        sampler.sample(d, lod, row + 4 * x);
      }
    }
  });
  return out;
}

}  // namespace texproc
