#include "texproc/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

double psnr_from_mse(double mse) {
  if (mse <= 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / mse);
}
double ImageDifference::psnr() const { return psnr_from_mse(mse); }
double ImageDifference::psnr_rgb() const { return psnr_from_mse(mse_rgb); }
double ImageDifference::psnr_channel(int c) const { return psnr_from_mse(channel.at(std::size_t(c)).mse); }
double ImageDifference::log_rmse_rgb() const { return std::sqrt(log_mse_rgb); }

namespace {

// One row (`n` values of `type`) as doubles on the [0, 1] scale.
void load_values(const void* row, PixelType type, std::size_t n, std::vector<double>& out) {
  out.resize(n);
  switch (type) {
    case PixelType::u8: {
      const auto* p = static_cast<const std::uint8_t*>(row);
      for (std::size_t i = 0; i < n; ++i) out[i] = p[i] / 255.0;
      break;
    }
    case PixelType::u16: {
      const auto* p = static_cast<const std::uint16_t*>(row);
      for (std::size_t i = 0; i < n; ++i) out[i] = p[i] / 65535.0;
      break;
    }
    case PixelType::f32: {
      const auto* p = static_cast<const float*>(row);
      for (std::size_t i = 0; i < n; ++i) out[i] = p[i];
      break;
    }
  }
}

void load_row(const ConstImageView& v, int y, std::vector<double>& out) {
  load_values(v.row<const void>(y), v.type, std::size_t(v.width) * std::size_t(v.channels), out);
}

// The rows of one block of an image: its own, or made by its source.
class BlockRows {
 public:
  BlockRows(const ImageRows& image, int y0, int y1) : image_(image), y0_(y0) {
    if (!image.rows) return;
    stride_ = std::size_t(image.shape.width) * image.shape.channels * bytes_per_channel(image.shape.type);
    made_.resize(stride_ * std::size_t(y1 - y0));
    image.rows(y0, y1, made_.data(), stride_);
  }
  void load(int y, std::vector<double>& out) const {
    const void* row = image_.rows ? made_.data() + std::size_t(y - y0_) * stride_ : image_.shape.row<const void>(y);
    load_values(row, image_.shape.type, std::size_t(image_.shape.width) * std::size_t(image_.shape.channels), out);
  }

 private:
  const ImageRows& image_;
  int y0_;
  std::size_t stride_ = 0;
  std::vector<std::uint8_t> made_;
};

void check_same_shape(const ConstImageView& a, const ConstImageView& b) {
  if (a.width != b.width || a.height != b.height) {
    throw Error(ErrorCode::bad_arguments, "the images differ in size: " + std::to_string(a.width) + "x" +
                                              std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                                              std::to_string(b.height));
  }
  if (a.channels != b.channels) {
    throw Error(ErrorCode::bad_arguments, "the images differ in channel count: " + std::to_string(a.channels) +
                                              " and " + std::to_string(b.channels));
  }
}

// Values closer than this are the same value (8-bit and float forms of one
// code differ by float rounding only).
constexpr double kSameValue = 1e-6;

struct Partial {
  std::vector<double> sq, abs, max;
  double log_sq = 0;  // over RGB
  bool outside = false;
  std::uint64_t differing = 0, nonfinite = 0;
};

bool all_finite(const double* a, const double* b, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(a[i]) || !std::isfinite(b[i])) return false;
  }
  return true;
}

double log_value(double v) { return std::copysign(std::log2(1.0 + std::fabs(v)), v); }

}  // namespace

ImageDifference compare_images(const ConstImageView& a, const ConstImageView& b) {
  check_same_shape(a, b);
  return compare_image_rows(ImageRows{a, {}}, ImageRows{b, {}}, a.channels);
}

ImageDifference compare_image_rows(const ImageRows& ia, const ImageRows& ib, int channels) {
  const ConstImageView& a = ia.shape;
  const ConstImageView& b = ib.shape;
  if (a.width != b.width || a.height != b.height) check_same_shape(a, b);
  if (channels < 1 || channels > a.channels || channels > b.channels) {
    throw Error(ErrorCode::bad_arguments, "cannot compare " + std::to_string(channels) + " channels of images of " +
                                              std::to_string(a.channels) + " and " + std::to_string(b.channels));
  }
  const std::size_t ca = std::size_t(a.channels), cb = std::size_t(b.channels);
  const bool floats = a.type == PixelType::f32 || b.type == PixelType::f32;
  const int rgb = std::min(3, channels);
  constexpr int kBlockRows = 32;
  const int blocks = (a.height + kBlockRows - 1) / kBlockRows;
  std::vector<Partial> partial(std::size_t(std::max(blocks, 0)));
  for_each_row_block(a.height, kBlockRows, [&](int y0, int y1) {
    Partial& p = partial[std::size_t(y0 / kBlockRows)];
    p.sq.assign(std::size_t(channels), 0.0);
    p.abs.assign(std::size_t(channels), 0.0);
    p.max.assign(std::size_t(channels), 0.0);
    const BlockRows rows_a(ia, y0, y1), rows_b(ib, y0, y1);
    std::vector<double> ra, rb;
    for (int y = y0; y < y1; ++y) {
      rows_a.load(y, ra);
      rows_b.load(y, rb);
      for (int x = 0; x < a.width; ++x) {
        const double* pa = ra.data() + std::size_t(x) * ca;
        const double* pb = rb.data() + std::size_t(x) * cb;
        if (floats && !all_finite(pa, pb, channels)) {
          ++p.nonfinite;  // a difference that no figure can measure
          ++p.differing;
          continue;
        }
        bool differs = false;
        for (int c = 0; c < channels; ++c) {
          const double d = std::fabs(pa[c] - pb[c]);
          p.sq[std::size_t(c)] += d * d;
          p.abs[std::size_t(c)] += d;
          if (d > p.max[std::size_t(c)]) p.max[std::size_t(c)] = d;
          differs |= d > kSameValue;
          if (floats) {
            p.outside = p.outside || pa[c] < 0.0 || pa[c] > 1.0 || pb[c] < 0.0 || pb[c] > 1.0;
            if (c < rgb) {
              const double ld = log_value(pa[c]) - log_value(pb[c]);
              p.log_sq += ld * ld;
            }
          }
        }
        p.differing += differs;
      }
    }
  });
  ImageDifference r;
  r.width = a.width;
  r.height = a.height;
  r.channels = channels;
  r.channel.resize(std::size_t(channels));
  for (const Partial& p : partial) {  // in block order: the same sums for any thread count
    for (int c = 0; c < channels; ++c) {
      r.channel[std::size_t(c)].mse += p.sq[std::size_t(c)];
      r.channel[std::size_t(c)].mean_abs += p.abs[std::size_t(c)];
      r.channel[std::size_t(c)].max_abs = std::max(r.channel[std::size_t(c)].max_abs, p.max[std::size_t(c)]);
    }
    r.differing_texels += p.differing;
    r.nonfinite_texels += p.nonfinite;
    r.log_mse_rgb += p.log_sq;
    r.hdr = r.hdr || p.outside;
  }
  const double texels = double(a.width) * double(a.height);
  if (texels > 0 && rgb > 0) r.log_mse_rgb /= texels * rgb;
  for (int c = 0; c < channels; ++c) {
    ChannelDifference& d = r.channel[std::size_t(c)];
    if (texels > 0) {
      d.mse /= texels;
      d.mean_abs /= texels;
    }
    r.mse += d.mse / channels;
    if (c < rgb) r.mse_rgb += d.mse / rgb;
    r.max_abs = std::max(r.max_abs, d.max_abs);
  }
  if (r.nonfinite_texels > 0) {  // the distance is not defined: NaN, and an infinite largest error
    const double nan = std::numeric_limits<double>::quiet_NaN();
    r.mse = r.mse_rgb = r.log_mse_rgb = nan;
    r.max_abs = std::numeric_limits<double>::infinity();
    for (ChannelDifference& d : r.channel) d = {nan, nan, r.max_abs};
  }
  return r;
}

namespace {

// One channel as doubles, and the separable Gaussian blur SSIM uses.
std::vector<double> channel_plane(const ConstImageView& v, int c) {
  std::vector<double> out(std::size_t(v.width) * std::size_t(v.height));
  std::vector<double> row;
  for (int y = 0; y < v.height; ++y) {
    load_row(v, y, row);
    for (int x = 0; x < v.width; ++x) out[std::size_t(y) * v.width + x] = row[std::size_t(x) * v.channels + c];
  }
  return out;
}

std::vector<double> gaussian_blur(const std::vector<double>& in, int w, int h) {
  constexpr int kRadius = 5;
  double k[2 * kRadius + 1], sum = 0;
  for (int i = -kRadius; i <= kRadius; ++i) sum += k[i + kRadius] = std::exp(-(i * i) / (2.0 * 1.5 * 1.5));
  for (double& v : k) v /= sum;
  // One pass along x (step 1, n = w) or y (step w, n = h), edges repeated.
  auto pass = [&](const std::vector<double>& src, std::vector<double>& dst, bool along_x) {
    const std::size_t step = along_x ? 1 : std::size_t(w);
    const int n = along_x ? w : h;
    for_each_row_block(h, 32, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const int at = along_x ? x : y;
          const std::size_t base = std::size_t(y) * w + x - std::size_t(at) * step;
          double acc = 0;
          for (int i = -kRadius; i <= kRadius; ++i)
            acc += k[i + kRadius] * src[base + std::size_t(std::clamp(at + i, 0, n - 1)) * step];
          dst[std::size_t(y) * w + x] = acc;
        }
    });
  };
  std::vector<double> tmp(in.size()), out(in.size());
  pass(in, tmp, true);
  pass(tmp, out, false);
  return out;
}

}  // namespace

std::vector<double> ssim_per_channel(const ConstImageView& a, const ConstImageView& b) {
  check_same_shape(a, b);
  const int w = a.width, h = a.height;
  const double c1 = 0.01 * 0.01, c2 = 0.03 * 0.03;
  std::vector<double> result;
  for (int c = 0; c < a.channels; ++c) {
    const std::vector<double> x = channel_plane(a, c), y = channel_plane(b, c);
    std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      xx[i] = x[i] * x[i];
      yy[i] = y[i] * y[i];
      xy[i] = x[i] * y[i];
    }
    const auto mx = gaussian_blur(x, w, h), my = gaussian_blur(y, w, h);
    const auto sxx = gaussian_blur(xx, w, h), syy = gaussian_blur(yy, w, h), sxy = gaussian_blur(xy, w, h);
    double sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
      sum += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
    }
    result.push_back(x.empty() ? 1.0 : sum / double(x.size()));
  }
  return result;
}

}  // namespace texproc
