// Normal maps from heightmaps: separable gradient kernels over rows of
// heights, then unit normals, then the requested channels.
#include "core/pixel_memory.h"
#include "texproc/normalmap.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "normalmap/kernels.h"
#include "normalmap/normalmap_rows.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

namespace ref {
void convolve_row(const float* in, const float* w, int taps, int n, float* out) {
  for (int x = 0; x < n; ++x) {
    float acc = 0.0f;
    for (int k = 0; k < taps; ++k) acc = acc + w[k] * in[x + k];
    out[x] = acc;
  }
}

void vertical_pass2(const float* const* rows, const float* wa, const float* wb, int taps, int n, float* a, float* b) {
  for (int x = 0; x < n; ++x) {
    float acc_a = 0.0f, acc_b = 0.0f;
    for (int k = 0; k < taps; ++k) {
      acc_a = acc_a + wa[k] * rows[k][x];
      acc_b = acc_b + wb[k] * rows[k][x];
    }
    a[x] = acc_a;
    b[x] = acc_b;
  }
}

void convolve_rows2(const float* ina, const float* wa, const float* inb, const float* wb, int taps, int n, float* a,
                    float* b) {
  convolve_row(ina, wa, taps, n, a);
  convolve_row(inb, wb, taps, n, b);
}

void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz) {
  for (int x = 0; x < n; ++x) {
    const float a = sx * gx[x], b = sy * gy[x];
    const float inv = 1.0f / std::sqrt(a * a + b * b + 1.0f);
    nx[x] = a * inv;
    ny[x] = b * inv;
    nz[x] = inv;
  }
}
}  // namespace ref

namespace {
template <typename T>
void write_row(T* dst, int channels, int width, const float* nx, const float* ny, const float* nz, const float* h);
}

namespace ref {
void encode_normals_u8(const float* nx, const float* ny, const float* nz, const float* h, int n, int channels,
                       std::uint8_t* out) {
  write_row(out, channels, n, nx, ny, nz, h);
}

void gradients_to_u8(const float* gx, const float* gy, const float* h, int n, float sx, float sy, int channels,
                     std::uint8_t* out) {
  std::vector<float> nx(n), ny(n), nz(n);
  normals_from_gradients(gx, gy, n, sx, sy, nx.data(), ny.data(), nz.data());
  encode_normals_u8(nx.data(), ny.data(), nz.data(), h, n, channels, out);
}
}  // namespace ref

namespace {

constexpr int kBlockRows = 16;

using FloatBuffer = std::vector<float, detail::DefaultInitAllocator<float>>;

// Rec. 709 luma weights, applied to the stored values (heights are data).
constexpr float kLuma[3] = {0.2126f, 0.7152f, 0.0722f};

int height_source_channel(const ConstImageView& img, HeightChannel ch) {
  const int c = img.channels;
  auto need = [&](int index, const char* name) {
    if (index >= c) {
      throw Error(ErrorCode::bad_arguments, std::string("NormalMapOptions::height_channel ") + name +
                                                ": the image has only " + std::to_string(c) + " channel(s)");
    }
    return index;
  };
  switch (ch) {
    case HeightChannel::automatic:
      return c <= 2 ? 0 : -1;  // -1: luma
    case HeightChannel::r:
      return need(0, "r");
    case HeightChannel::g:
      return need(1, "g");
    case HeightChannel::b:
      return need(2, "b");
    case HeightChannel::a:
      if (c != 2 && c != 4)
        throw Error(ErrorCode::bad_arguments, "NormalMapOptions::height_channel a: the image has no alpha");
      return c - 1;
    case HeightChannel::luma:
      return c >= 3 ? -1 : 0;
  }
  return 0;
}

template <typename T>
void extract_row_t(const T* s, int width, int channels, int source, bool invert, float scale, float* dst) {
  if (source >= 0) {
    for (int x = 0; x < width; ++x) dst[x] = float(s[x * channels + source]) * scale;
  } else {
    for (int x = 0; x < width; ++x) {
      const T* p = s + x * channels;
      dst[x] = (kLuma[0] * float(p[0]) + kLuma[1] * float(p[1]) + kLuma[2] * float(p[2])) * scale;
    }
  }
  if (invert) {
    for (int x = 0; x < width; ++x) dst[x] = 1.0f - dst[x];
  }
}

void extract_row(const ConstImageView& img, int y, int source, bool invert, float* dst) {
  switch (img.type) {
    case PixelType::u8:
      extract_row_t(img.row<const std::uint8_t>(y), img.width, img.channels, source, invert, 1.0f / 255.0f, dst);
      break;
    case PixelType::u16:
      extract_row_t(img.row<const std::uint16_t>(y), img.width, img.channels, source, invert, 1.0f / 65535.0f, dst);
      break;
    case PixelType::f32:
      extract_row_t(img.row<const float>(y), img.width, img.channels, source, invert, 1.0f, dst);
      break;
  }
}

template <typename T>
T quantize(float v);
template <>
std::uint8_t quantize<std::uint8_t>(float v) {
  const float e = (v * 0.5f + 0.5f) * 255.0f + 0.5f;
  return std::uint8_t(e > 0.0f ? (e < 255.0f ? e : 255.0f) : 0.0f);
}
template <>
std::uint16_t quantize<std::uint16_t>(float v) {
  const float e = (v * 0.5f + 0.5f) * 65535.0f + 0.5f;
  return std::uint16_t(e > 0.0f ? (e < 65535.0f ? e : 65535.0f) : 0.0f);
}
template <>
float quantize<float>(float v) {
  return v * 0.5f + 0.5f;
}

template <typename T>
T quantize_height(float h);
template <>
std::uint8_t quantize_height<std::uint8_t>(float h) {
  const float e = h * 255.0f + 0.5f;
  return std::uint8_t(e > 0.0f ? (e < 255.0f ? e : 255.0f) : 0.0f);
}
template <>
std::uint16_t quantize_height<std::uint16_t>(float h) {
  const float e = h * 65535.0f + 0.5f;
  return std::uint16_t(e > 0.0f ? (e < 65535.0f ? e : 65535.0f) : 0.0f);
}
template <>
float quantize_height<float>(float h) {
  return h;
}

template <typename T>
void write_row(T* dst, int channels, int width, const float* nx, const float* ny, const float* nz, const float* h) {
  switch (channels) {
    case 2:
      for (int x = 0; x < width; ++x) {
        dst[2 * x] = quantize<T>(nx[x]);
        dst[2 * x + 1] = quantize<T>(ny[x]);
      }
      break;
    case 3:
      for (int x = 0; x < width; ++x) {
        dst[3 * x] = quantize<T>(nx[x]);
        dst[3 * x + 1] = quantize<T>(ny[x]);
        dst[3 * x + 2] = quantize<T>(nz[x]);
      }
      break;
    default:
      for (int x = 0; x < width; ++x) {
        dst[4 * x] = quantize<T>(nx[x]);
        dst[4 * x + 1] = quantize<T>(ny[x]);
        dst[4 * x + 2] = quantize<T>(nz[x]);
        dst[4 * x + 3] = quantize_height<T>(h[x]);
      }
      break;
  }
}

struct Scratch {
  FloatBuffer heights, vs, vd, gx, gy, nx, ny, nz;
  std::vector<const float*> rows;
};

}  // namespace

std::vector<float> extract_height(const ConstImageView& image, HeightChannel channel, bool invert) {
  const int source = height_source_channel(image, channel);
  std::vector<float> out(std::size_t(image.width) * image.height);
  for (int y = 0; y < image.height; ++y)
    extract_row(image, y, source, invert, out.data() + std::size_t(y) * image.width);
  return out;
}

std::vector<float> extract_height(Image&& image, HeightChannel channel, bool invert) {
  Image consumed = std::move(image);
  const ConstImageView view = consumed.view();
  const int source = height_source_channel(view, channel);
  const std::size_t width = std::size_t(view.width);
  std::vector<float> out;
  out.reserve(width * view.height);  // pages are touched as the bands fill them
  constexpr int kBand = 64;
  for (int y0 = 0; y0 < view.height; y0 += kBand) {
    const int y1 = std::min(view.height, y0 + kBand);
    out.resize(width * y1);
    for (int y = y0; y < y1; ++y) extract_row(view, y, source, invert, out.data() + width * y);
    detail::discard_pages(consumed.data(), view.row_stride * y1);
  }
  return out;
}

void compute_normal_map(const ConstImageView& in, const ImageView& out, const NormalMapOptions& o) {
  assert(in.data && out.data && in.width == out.width && in.height == out.height);
  assert(out.channels == channel_count(o.channels));
  if (!(o.height_scale > 0.0f) || !std::isfinite(o.height_scale)) {
    throw Error(ErrorCode::bad_arguments, "NormalMapOptions::height_scale must be a positive number of texels");
  }
  if (!(o.strength > 0.0f) || !std::isfinite(o.strength)) {
    throw Error(ErrorCode::bad_arguments, "NormalMapOptions::strength must be positive");
  }
  const int source = height_source_channel(in, o.height_channel);
  const SeparableKernel k = make_kernel(o.kernel, o.multiscale_weights);
  const int taps = int(k.deriv.size());
  const int first = k.first, last = k.first + taps - 1;
  const int pad = std::max(-first, last);
  const int W = in.width, H = in.height, PW = W + 2 * pad;
  const float slope = o.height_scale * o.strength;
  // Image rows grow downwards. OpenGL's +Y (green) points up the image, so
  // n.y = -dH/dy_up = +dH/drow; DirectX's +Y points down: n.y = -dH/drow.
  const float sx = -slope, sy = o.y_up ? slope : -slope;

  for_each_row_block(H, kBlockRows, [&](int y0, int y1) {
    thread_local Scratch sc;
    const int lo = y0 + first, hi = y1 - 1 + last;
    sc.heights.resize(std::size_t(hi - lo + 1) * PW);
    sc.rows.resize(hi - lo + 1);
    for (int j = lo; j <= hi; ++j) {
      float* r = sc.heights.data() + std::size_t(j - lo) * PW;
      extract_row(in, wrap_index(j, H, o.wrap), source, o.invert, r + pad);
      for (int p = 1; p <= pad; ++p) {
        r[pad - p] = r[pad + wrap_index(-p, W, o.wrap)];
        r[pad + W - 1 + p] = r[pad + wrap_index(W - 1 + p, W, o.wrap)];
      }
      sc.rows[j - lo] = r;
    }
    for (FloatBuffer* b : {&sc.vs, &sc.vd}) b->resize(PW);
    for (FloatBuffer* b : {&sc.gx, &sc.gy, &sc.nx, &sc.ny, &sc.nz}) b->resize(W);
    for (int y = y0; y < y1; ++y) {
      const float* const* rows = sc.rows.data() + (y + first - lo);
      vertical_pass2(rows, k.smooth.data(), k.deriv.data(), taps, PW, sc.vs.data(), sc.vd.data());
      convolve_rows2(sc.vs.data() + pad + first, k.deriv.data(), sc.vd.data() + pad + first, k.smooth.data(), taps, W,
                     sc.gx.data(), sc.gy.data());
      const float* h = sc.rows[y - lo] + pad;
      if (out.type == PixelType::u8) {
        gradients_to_u8(sc.gx.data(), sc.gy.data(), h, W, sx, sy, out.channels, out.row<std::uint8_t>(y));
        continue;
      }
      normals_from_gradients(sc.gx.data(), sc.gy.data(), W, sx, sy, sc.nx.data(), sc.ny.data(), sc.nz.data());
      switch (out.type) {
        case PixelType::u8:  // handled above
          break;
        case PixelType::u16:
          write_row(out.row<std::uint16_t>(y), out.channels, W, sc.nx.data(), sc.ny.data(), sc.nz.data(), h);
          break;
        case PixelType::f32:
          write_row(out.row<float>(y), out.channels, W, sc.nx.data(), sc.ny.data(), sc.nz.data(), h);
          break;
      }
    }
  });
}

Image normal_map(const ConstImageView& heights, const NormalMapOptions& options, PixelType type) {
  Image out = Image::uninitialized(heights.width, heights.height, channel_count(options.channels), type);
  compute_normal_map(heights, out.view(), options);
  return out;
}

}  // namespace texproc
