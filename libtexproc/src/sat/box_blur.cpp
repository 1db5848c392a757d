// A box blur of any radius at constant cost per texel: the image is decoded
// to linear premultiplied float, padded by the largest radius (with the wrap
// mode), summed into a double table, and every texel averages its box with
// four lookups. A fractional radius r blends the boxes of floor(r) and
// floor(r) + 1, so a radius map varies smoothly.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "texproc/color.h"
#include "texproc/error.h"
#include "texproc/runtime.h"
#include "texproc/sat.h"

namespace texproc {
namespace {

float map_value(const ConstImageView& m, int x, int y) {
  switch (m.type) {
    case PixelType::u8:
      return m.row<const std::uint8_t>(y)[x * m.channels] / 255.0f;
    case PixelType::u16:
      return m.row<const std::uint16_t>(y)[x * m.channels] / 65535.0f;
    case PixelType::f32:
      return m.row<const float>(y)[x * m.channels];
  }
  return 0.0f;
}

}  // namespace

Image box_blur(const ConstImageView& img, const BoxBlurOptions& o) {
  if (!(o.radius >= 0.0f) || !std::isfinite(o.radius)) {
    throw Error(ErrorCode::bad_arguments, "BoxBlurOptions::radius must be a number >= 0");
  }
  if (o.radius_map && (o.radius_map->width != img.width || o.radius_map->height != img.height)) {
    throw Error(ErrorCode::bad_arguments, "BoxBlurOptions::radius_map is " + std::to_string(o.radius_map->width) + "x" +
                                              std::to_string(o.radius_map->height) + ", the image " +
                                              std::to_string(img.width) + "x" + std::to_string(img.height) +
                                              " (they must match)");
  }
  const int W = img.width, H = img.height, C = img.channels;
  const bool alpha = C == 2 || C == 4;
  const ColorSpace cs = !o.color_space.empty() ? ColorSpace::from_name(o.color_space)
                        : is_float(img.type)   ? ColorSpace::linear()
                                               : ColorSpace::srgb();
  // Radii past twice the image's size change nothing that matters; capping
  // them bounds the padding.
  const float cap = 2.0f * std::max(W, H);
  float rmax = o.radius;
  if (o.radius_map) {
    float m = 0.0f;
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) m = std::max(m, std::clamp(map_value(*o.radius_map, x, y), 0.0f, 1.0f));
    rmax *= m;
  }
  rmax = std::min(rmax, cap);
  const int P = int(std::floor(rmax)) + 1;
  const int PW = W + 2 * P, PH = H + 2 * P;

  // Linear, premultiplied, padded.
  Image padded = Image::uninitialized(PW, PH, C, PixelType::f32);
  std::vector<float> decoded(std::size_t(H) * W * C);
  for_each_row_block(H, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* d = decoded.data() + std::size_t(y) * W * C;
      cs.decode_row(img.row<const void>(y), img.type, C, W, d);
      if (alpha) {
        for (int x = 0; x < W; ++x)
          for (int c = 0; c < C - 1; ++c) d[x * C + c] *= d[x * C + C - 1];
      }
    }
  });
  for_each_row_block(PH, 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const float* s = decoded.data() + std::size_t(wrap_index(y - P, H, o.wrap)) * W * C;
      float* d = padded.row<float>(y);
      for (int x = 0; x < PW; ++x) std::memcpy(d + x * C, s + wrap_index(x - P, W, o.wrap) * C, C * sizeof(float));
    }
  });
  decoded = {};
  const SummedAreaTable table = build_sat(padded.view(), SatPrecision::f64);
  padded = Image{};

  Image out = Image::uninitialized(W, H, C, img.type);
  for_each_row_block(H, 16, [&](int y0, int y1) {
    std::vector<float> row(std::size_t(W) * C);
    double a[4], b[4];
    for (int y = y0; y < y1; ++y) {
      for (int x = 0; x < W; ++x) {
        float r = o.radius;
        if (o.radius_map) r *= std::clamp(map_value(*o.radius_map, x, y), 0.0f, 1.0f);
        r = std::min(r, rmax);
        const int r0 = int(std::floor(r));
        const double f = double(r) - r0;
        const int cx = x + P, cy = y + P;
        table.box_sum(cx - r0, cy - r0, cx + r0 + 1, cy + r0 + 1, a);
        const double area0 = double(2 * r0 + 1) * (2 * r0 + 1);
        if (f > 0.0) {
          const int r1 = r0 + 1;
          table.box_sum(cx - r1, cy - r1, cx + r1 + 1, cy + r1 + 1, b);
          const double area1 = double(2 * r1 + 1) * (2 * r1 + 1);
          for (int c = 0; c < C; ++c) row[x * C + c] = float((1.0 - f) * a[c] / area0 + f * b[c] / area1);
        } else {
          for (int c = 0; c < C; ++c) row[x * C + c] = float(a[c] / area0);
        }
        if (alpha) {
          const float al = row[x * C + C - 1];
          for (int c = 0; c < C - 1; ++c) row[x * C + c] = al > 0.0f ? row[x * C + c] / al : 0.0f;
        }
      }
      cs.encode_row(row.data(), C, W, out.row<void>(y), out.type());
    }
  });
  return out;
}

}  // namespace texproc
