// resize_image and apply_size_rule (mip.h): an image filtered to any size
// as a mip level is, in linear premultiplied float with polyphase weights.
#include <algorithm>
#include <cmath>
#include <vector>

#include "mip/resample.h"
#include "texproc/error.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

constexpr int kRowBlock = 16;

bool has_alpha(int channels) { return channels == 2 || channels == 4; }

// A row decoded to linear floats, colour premultiplied by alpha.
void load_row(const ConstImageView& in, int y, const ColorSpace& cs, bool premultiply, float* out) {
  const int n = in.channels;
  cs.decode_row(in.row<const std::uint8_t>(y), in.type, n, in.width, out);
  if (!premultiply) return;
  for (int x = 0; x < in.width; ++x) {
    float* p = out + std::size_t(x) * n;
    const float a = p[n - 1];
    for (int c = 0; c < n - 1; ++c) p[c] *= a;
  }
}

// The inverse of load_row's premultiplication, and a normal map's
// vectors renormalized; then encoded to the output row.
void store_row(float* row, int width, int n, const ColorSpace& cs, const ResizeOptions& o, bool premultiplied,
               const ImageView& out, int y) {
  for (int x = 0; x < width; ++x) {
    float* p = row + std::size_t(x) * n;
    if (premultiplied) {
      const float a = p[n - 1];
      const float inv = a > 0.0f ? 1.0f / a : 0.0f;
      for (int c = 0; c < n - 1; ++c) p[c] *= inv;
    }
    if (o.normal_map) {
      const float v[3] = {p[0] * 2 - 1, p[1] * 2 - 1, p[2] * 2 - 1};
      const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      const float inv = len > 0.0f ? 1.0f / len : 0.0f;
      for (int c = 0; c < 3; ++c) p[c] = len > 0.0f ? v[c] * inv * 0.5f + 0.5f : (c == 2 ? 1.0f : 0.5f);
    }
  }
  cs.encode_row(row, n, width, out.row<std::uint8_t>(y), out.type);
}

int round_pow2(int v, const std::string& mode) {
  int lo = 1;
  while (lo * 2 <= v) lo *= 2;
  if (lo == v) return v;
  const int hi = lo * 2;
  if (mode == "down") return lo;
  if (mode == "up") return hi;
  return v - lo < hi - v ? lo : hi;  // nearest; a tie goes up
}

}  // namespace

Image resize_image(const ConstImageView& in, int width, int height, const ResizeOptions& o) {
  if (width < 1 || height < 1) throw Error(ErrorCode::bad_arguments, "resize: the size must be at least 1x1");
  if (o.normal_map && in.channels < 3)
    throw Error(ErrorCode::bad_arguments, "resize: a normal map has 3 or 4 channels");
  const ColorSpace cs = o.normal_map || (o.color_space.empty() && in.type == PixelType::f32) ? ColorSpace::linear()
                        : o.color_space.empty()                                              ? ColorSpace::srgb()
                                                : ColorSpace::from_name(o.color_space);
  const int n = in.channels;
  const bool premultiply = o.premultiplied_alpha && has_alpha(n) && !o.normal_map;
  const AxisWeights wx = compute_axis_weights(in.width, width, o.filter);
  const AxisWeights wy = compute_axis_weights(in.height, height, o.filter);
  // Every source row filtered across: in.height rows of width texels.
  std::vector<float> across(std::size_t(in.height) * width * n);
  for_each_row_block(in.height, kRowBlock, [&](int y0, int y1) {
    const int padded = wx.pad_before + in.width + wx.pad_after;
    std::vector<float> row(std::size_t(in.width) * n), pad(std::size_t(padded) * n);
    for (int y = y0; y < y1; ++y) {
      load_row(in, y, cs, premultiply, row.data());
      for (int i = 0; i < padded; ++i) {
        const int sx = wrap_index(i - wx.pad_before, in.width, o.wrap);
        std::copy_n(row.data() + std::size_t(sx) * n, n, pad.data() + std::size_t(i) * n);
      }
      horizontal_pass(pad.data() + std::size_t(wx.pad_before) * n, n, wx.first.data(), wx.weights.data(), wx.taps,
                      width, across.data() + std::size_t(y) * width * n);
    }
  });
  Image out = Image::uninitialized(width, height, n, in.type);
  for_each_row_block(height, kRowBlock, [&](int y0, int y1) {
    std::vector<const float*> rows(wy.taps);
    std::vector<float> line(std::size_t(width) * n);
    for (int y = y0; y < y1; ++y) {
      for (int k = 0; k < wy.taps; ++k)
        rows[k] = across.data() + std::size_t(wrap_index(wy.first[y] + k, in.height, o.wrap)) * width * n;
      vertical_pass(rows.data(), wy.weights.data() + std::size_t(y) * wy.taps, wy.taps, width * n, line.data());
      store_row(line.data(), width, n, cs, o, premultiply, out.view(), y);
    }
  });
  return out;
}

void apply_size_rule(const SizeRule& r, int& width, int& height) {
  if (r.resize_width > 0 || r.resize_height > 0) {
    const double aspect = double(width) / height;
    const int w = r.resize_width > 0 ? r.resize_width : std::max(1, int(std::lround(r.resize_height * aspect)));
    const int h = r.resize_height > 0 ? r.resize_height : std::max(1, int(std::lround(r.resize_width / aspect)));
    width = w;
    height = h;
  }
  if (r.max_size > 0 && std::max(width, height) > r.max_size) {
    const double k = double(r.max_size) / std::max(width, height);
    width = std::max(1, std::min(r.max_size, int(std::lround(width * k))));
    height = std::max(1, std::min(r.max_size, int(std::lround(height * k))));
  }
  if (!r.pow2.empty()) {
    if (r.pow2 != "up" && r.pow2 != "down" && r.pow2 != "nearest")
      throw Error(ErrorCode::bad_arguments, "--pow2 " + r.pow2 + ": valid: up, down, nearest");
    width = round_pow2(width, r.pow2);
    height = round_pow2(height, r.pow2);
  }
  if (r.multiple_of > 1) {
    width = (width + r.multiple_of - 1) / r.multiple_of * r.multiple_of;
    height = (height + r.multiple_of - 1) / r.multiple_of * r.multiple_of;
  }
}

}  // namespace texproc
