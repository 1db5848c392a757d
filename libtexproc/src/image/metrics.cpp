#include "texproc/metrics.h"

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

namespace {

// One row as doubles on the [0, 1] scale.
void load_row(const ImageView& v, int y, std::vector<double>& out) {
  const std::size_t n = std::size_t(v.width) * std::size_t(v.channels);
  out.resize(n);
  switch (v.type) {
    case PixelType::u8: {
      const auto* p = v.row<const std::uint8_t>(y);
      for (std::size_t i = 0; i < n; ++i) out[i] = p[i] / 255.0;
      break;
    }
    case PixelType::u16: {
      const auto* p = v.row<const std::uint16_t>(y);
      for (std::size_t i = 0; i < n; ++i) out[i] = p[i] / 65535.0;
      break;
    }
    case PixelType::f32: {
      const auto* p = v.row<const float>(y);
      for (std::size_t i = 0; i < n; ++i) out[i] = p[i];
      break;
    }
  }
}

struct Partial {
  std::vector<double> sq, abs, max;
  std::uint64_t differing = 0;
};

}  // namespace

ImageDifference compare_images(const ImageView& a, const ImageView& b) {
  if (a.width != b.width || a.height != b.height) {
    throw Error(ErrorCode::bad_arguments, "the images differ in size: " + std::to_string(a.width) + "x" +
                                              std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                                              std::to_string(b.height));
  }
  if (a.channels != b.channels) {
    throw Error(ErrorCode::bad_arguments, "the images differ in channel count: " + std::to_string(a.channels) +
                                              " and " + std::to_string(b.channels));
  }
  const int channels = a.channels;
  constexpr int kBlockRows = 32;
  const int blocks = (a.height + kBlockRows - 1) / kBlockRows;
  std::vector<Partial> partial(std::size_t(std::max(blocks, 0)));
  for_each_row_block(a.height, kBlockRows, [&](int y0, int y1) {
    Partial& p = partial[std::size_t(y0 / kBlockRows)];
    p.sq.assign(std::size_t(channels), 0.0);
    p.abs.assign(std::size_t(channels), 0.0);
    p.max.assign(std::size_t(channels), 0.0);
    std::vector<double> ra, rb;
    for (int y = y0; y < y1; ++y) {
      load_row(a, y, ra);
      load_row(b, y, rb);
      for (int x = 0; x < a.width; ++x) {
        bool differs = false;
        for (int c = 0; c < channels; ++c) {
          const std::size_t i = std::size_t(x) * std::size_t(channels) + std::size_t(c);
          const double d = std::fabs(ra[i] - rb[i]);
          p.sq[std::size_t(c)] += d * d;
          p.abs[std::size_t(c)] += d;
          if (d > p.max[std::size_t(c)]) p.max[std::size_t(c)] = d;
          differs |= ra[i] != rb[i];
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
  }
  const double texels = double(a.width) * double(a.height);
  const int rgb = std::min(3, channels);
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
  return r;
}

}  // namespace texproc
