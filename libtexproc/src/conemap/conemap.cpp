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
#include <memory>
#include <type_traits>

#include "conemap/cone_cells.h"
#include "conemap/cone_search.h"
#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

using cone::Behind;
using cone::build_pyramid;
using cone::cell_cones;
using cone::geometry;
using cone::Pyramid;
using cone::relaxed_bounds;
using cone::RelaxedBounds;

void check(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o) {
  if (width <= 0 || height <= 0 || heights.size() != std::size_t(width) * height) {
    throw Error(ErrorCode::bad_arguments, "heights do not match the size");
  }
  if (!(o.depth > 0.0f) || !std::isfinite(o.depth))
    throw Error(ErrorCode::bad_arguments, "ConeMapOptions::depth must be > 0");
  if (!(o.max_ratio > 0.0f) || !std::isfinite(o.max_ratio))
    throw Error(ErrorCode::bad_arguments, "ConeMapOptions::max_ratio must be > 0");
  if (o.wrap == WrapMode::mirror) throw Error(ErrorCode::bad_arguments, "ConeMapOptions::wrap: valid: repeat, clamp");
  if (o.fast_reach < 0)
    throw Error(ErrorCode::bad_arguments, "ConeMapOptions::fast_reach must be >= 1 (0: exact cones)");
  if (o.bilinear_safe && o.mode == ConeMode::relaxed) {
    throw Error(ErrorCode::bad_arguments,
                "ConeMapOptions::bilinear_safe makes conservative cones (use it without ConeMode::relaxed)");
  }
}

int texel_distance(int p, int q, int n, bool repeat) {
  const int d = p > q ? p - q : q - p;
  return repeat ? std::min(d, n - d) : d;
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
    for (std::size_t i = std::size_t(r0) * 4096; i < std::min(r2.size(), std::size_t(r1) * 4096); ++i)
      r2[i] = std::sqrt(r2[i]);
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
  for_each_row_block(
      H, 1,
      [&](int y0, int y1) {
        for (int py = y0; py < y1; ++py)
          for (int px = 0; px < W; ++px) {
            const float hp = apex[std::size_t(py) * W + px];
            float best = o.max_ratio * o.max_ratio;
            for (int qy = 0; qy < H; ++qy)
              for (int qx = 0; qx < W; ++qx) {
                const float hq = heights[std::size_t(qy) * W + qx];
                const float d2 =
                    detail::cone_d2(g, texel_distance(px, qx, W, repeat), texel_distance(py, qy, H, repeat));
                if (!(hq > hp && d2 > 0.0f)) continue;
                if (relaxed && !behind.exits(px, py, qx, qy, hq)) continue;
                best = std::min(best, detail::cone_r2(g, d2, hq - hp));
              }
            r2[std::size_t(py) * W + px] = best;
          }
      },
      o.progress);
  if (o.bilinear_safe) bilinear_local(heights, apex, W, H, o, r2);
  return square_roots(std::move(r2));
}

namespace {

// Rows of a cone map from the heights and ratios of those rows (W per row).
void quantize_rows(const float* heights, const float* ratios, int W, const ConeMapOptions& o, PixelType type,
                   int channels, int rows, void* dst, std::size_t row_stride) {
  for (int y = 0; y < rows; ++y) {
    std::uint8_t* row = static_cast<std::uint8_t*>(dst) + std::size_t(y) * row_stride;
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
        case PixelType::u8:
          put(row + channels * x, 255.0, true);
          break;
        case PixelType::u16:
          put(reinterpret_cast<std::uint16_t*>(row) + channels * x, 65535.0, true);
          break;
        case PixelType::f32:
          put(reinterpret_cast<float*>(row) + channels * x, 1.0, false);
          break;
      }
    }
  }
}

void check_map_rows(int channels, int y0, int y1, int H) {
  if (channels < 2 || channels > 4) throw Error(ErrorCode::bad_arguments, "a cone map has 2, 3 or 4 channels");
  if (y0 < 0 || y1 > H || y0 > y1) throw Error(ErrorCode::bad_arguments, "cone map rows outside the map");
}

}  // namespace

void cone_map_rows(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                   const ConeMapOptions& o, PixelType type, int channels, int y0, int y1, void* dst,
                   std::size_t row_stride) {
  check_map_rows(channels, y0, y1, H);
  if (heights.size() != std::size_t(W) * H || ratios.size() != heights.size()) {
    throw Error(ErrorCode::bad_arguments, "cone_map_rows: heights or ratios do not match the size");
  }
  const std::size_t first = std::size_t(y0) * W;
  quantize_rows(heights.data() + first, ratios.data() + first, W, o, type, channels, y1 - y0, dst, row_stride);
}

struct ConeRatioSearch::State {
  const std::vector<float>& heights;
  int W, H;
  ConeMapOptions o;
  Pyramid pyr;
  RelaxedBounds relaxed;
  std::unique_ptr<cone::CellCones> cells;
  std::vector<float> whole;  // bilinear_safe: every ratio, computed at construction
};

ConeRatioSearch::ConeRatioSearch(const std::vector<float>& heights, int W, int H, const ConeMapOptions& o) {
  check(heights, W, H, o);
  s_.reset(new State{heights, W, H, o, {}, {}, {}, {}});
  if (o.bilinear_safe) {
    s_->whole = cone_ratios(heights, W, H, o);
    return;
  }
  s_->pyr = build_pyramid(heights, W, H);
  const RelaxedBounds* rb = nullptr;
  if (o.mode == ConeMode::relaxed) {
    s_->relaxed = relaxed_bounds(heights, W, H, o.wrap == WrapMode::repeat);
    rb = &s_->relaxed;
  }
  s_->cells = std::make_unique<cone::CellCones>(heights, heights, W, H, s_->o, s_->pyr, 0, rb);
}

ConeRatioSearch::~ConeRatioSearch() = default;

void ConeRatioSearch::rows(int y0, int y1, float* out) const {
  const State& s = *s_;
  if (y0 < 0 || y1 > s.H || y0 > y1)
    throw Error(ErrorCode::bad_arguments, "ConeRatioSearch::rows: rows outside the map");
  if (y0 == y1) return;
  const std::size_t W = std::size_t(s.W);
  if (!s.whole.empty()) {
    std::copy(s.whole.begin() + std::ptrdiff_t(y0 * W), s.whole.begin() + std::ptrdiff_t(y1 * W), out);
    return;
  }
  using detail::kConeCell;
  const int cy0 = y0 / kConeCell, cy1 = (y1 + kConeCell - 1) / kConeCell;
  const int first = cy0 * kConeCell, last = std::min(s.H, cy1 * kConeCell);
  // Whole cells when the band is aligned; otherwise the cells' rows, then the band's.
  const bool aligned = first == y0 && last == y1;
  std::vector<float> cells(aligned ? 0 : std::size_t(last - first) * W);
  float* r2 = aligned ? out : cells.data();
  std::function<void(double)> progress;
  if (s.o.progress) {
    progress = [&s, y0, y1](double done) { s.o.progress((y0 + done * (y1 - y0)) / s.H); };
  }
  s.cells->rows(cy0, cy1, r2, progress);
  const std::size_t n = std::size_t(y1 - y0) * W, skip = std::size_t(y0 - first) * W;
  for (std::size_t i = 0; i < n; ++i) out[i] = std::sqrt(r2[skip + i]);
}

void ConeRatioSearch::map_rows(PixelType type, int channels, int y0, int y1, void* dst, std::size_t row_stride,
                               double* ratio_sum) const {
  const State& s = *s_;
  check_map_rows(channels, y0, y1, s.H);
  // Bands of whole cells, enough of them to keep every thread busy.
  const int band = detail::kConeCell * std::max(16, 4 * thread_limit());
  std::vector<float> ratios;
  for (int b0 = y0; b0 < y1;) {
    const int b1 = std::min(y1, (b0 / band + 1) * band);
    ratios.resize(std::size_t(b1 - b0) * s.W);
    rows(b0, b1, ratios.data());
    if (ratio_sum)
      for (float v : ratios) *ratio_sum += v;
    quantize_rows(s.heights.data() + std::size_t(b0) * s.W, ratios.data(), s.W, s.o, type, channels, b1 - b0,
                  static_cast<std::uint8_t*>(dst) + std::size_t(b0 - y0) * row_stride, row_stride);
    b0 = b1;
  }
}

Image cone_map_image(const std::vector<float>& heights, const std::vector<float>& ratios, int W, int H,
                     const ConeMapOptions& o, PixelType type, int channels) {
  if (channels < 2 || channels > 4) throw Error(ErrorCode::bad_arguments, "a cone map has 2, 3 or 4 channels");
  Image img = Image::uninitialized(W, H, channels, type);
  cone_map_rows(heights, ratios, W, H, o, type, channels, 0, H, img.data(), img.row_stride());
  return img;
}

}  // namespace texproc
