// texproc/metrics.h: how far two images are apart (PSNR and friends), for
// `texproc compare`, `compress --report` and the benchmarks.
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/image.h"

namespace texproc {

struct ChannelDifference {
  double mse = 0;       // mean squared difference
  double mean_abs = 0;  // mean absolute difference
  double max_abs = 0;   // largest absolute difference
};

struct ImageDifference {
  int width = 0, height = 0, channels = 0;
  std::vector<ChannelDifference> channel;
  double mse = 0;                      // over every channel
  double mse_rgb = 0;                  // over the first min(3, channels) channels (color without alpha)
  double max_abs = 0;                  // over every channel
  std::uint64_t differing_texels = 0;  // texels where any channel differs (by more than 1e-6)
  // Texels where either image holds NaN or an infinity in any channel. Each
  // is a differing texel; when there is one, the distance is not defined:
  // every mse, mean_abs and the log error are NaN (so PSNR is NaN and fails
  // any limit), and every max_abs is +infinity.
  std::uint64_t nonfinite_texels = 0;
  // HDR: whether either image holds a value outside [0, 1] (float images
  // only), and the mean over RGB (the first min(3, channels) channels) of
  // the squared difference of L(v) = sign(v) log2(1 + |v|), for float
  // images (0 otherwise). L is about log2 (stops) for bright values, so an
  // error counts relative to the light around it, and about v / ln 2 near
  // 0, so noise in the blacks is not blown up as a plain log would.
  bool hdr = false;
  double log_mse_rgb = 0;
  double log_rmse_rgb() const;
  // 10 log10(1 / mse): values are compared on a [0, 1] scale, so the peak is
  // 1. +infinity for identical images.
  double psnr() const;
  double psnr_rgb() const;
  double psnr_channel(int c) const;
};

double psnr_from_mse(double mse);

// Mean structural similarity (Wang, Bovik, Sheikh and Simoncelli 2004) per
// channel on the [0, 1] scale: an 11x11 Gaussian window of sigma 1.5 (edge
// texels repeated), C1 = 0.01^2, C2 = 0.03^2. 1 for identical images.
// Same size and channel count required (Error{bad_arguments}).
std::vector<double> ssim_per_channel(const ConstImageView& a, const ConstImageView& b);

// Compares two images of the same size and channel count, texel by texel,
// on a [0, 1] scale (8-bit codes / 255, 16-bit / 65535, floats as they are;
// the types may differ). Sums are in double over fixed row blocks: the
// result is the same for any thread count. Throws Error{bad_arguments} when
// the sizes or channel counts differ.
ImageDifference compare_images(const ConstImageView& a, const ConstImageView& b);

// An image compared without being held whole: `shape` gives its width,
// height, channels and type; `rows`, where set, makes its rows on demand
// (a block of 32 at a time), else they are shape's.
struct ImageRows {
  ConstImageView shape;
  RowSource rows;
};

// compare_images of the first `channels` channels of each image (a BC1
// texture's RGB against an RGBA image's), reading a block of rows of each
// at a time: the same figures. Throws Error{bad_arguments} when the sizes
// differ or either image has fewer channels.
ImageDifference compare_image_rows(const ImageRows& a, const ImageRows& b, int channels);

}  // namespace texproc
