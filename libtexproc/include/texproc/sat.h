// texproc/sat.h: summed-area tables (Crow 1984) with stated precision, and
// the box filters built on them.
//
// A table holds inclusive prefix sums S(x, y) = sum of v(i, j) over i <= x,
// j <= y, per channel, row-major. A box [x0, x1) x [y0, y1) (x1, y1
// exclusive) sums to S(x1-1, y1-1) - S(x0-1, y1-1) - S(x1-1, y0-1) +
// S(x0-1, y0-1), with S = 0 left of column 0 and above row 0.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "texproc/filters.h"
#include "texproc/image.h"

namespace texproc {

enum class SatPrecision {
  u32,  // integers modulo 2^32: box sums exact while the true sum < 2^32
  u64,  // integers modulo 2^64: exact for any box of 8- or 16-bit input
  f32,  // float of S minus a block-mean model's sums (Hensley et al. 2005, made local); bound below
  f64   // double: exact for integer input while S < 2^53
};

const char* to_string(SatPrecision p);
SatPrecision parse_sat_precision(std::string_view name);  // throws Error{bad_arguments}

// The largest box, in texels, whose sum a `p` table of `input` values gives
// exactly (u32 of 8-bit input: 16843009 texels, a 4104x4104 box, whatever the
// image size; u32 of 16-bit: 65537). 0 means no exactness promise (float
// input, f32 tables): see SummedAreaTable::error_bound.
std::uint64_t sat_max_exact_box(SatPrecision p, PixelType input);

// The smallest precision that is exact for every box of a width x height
// image of `input` (u32, else u64 for integers; f64 for float input).
SatPrecision default_sat_precision(PixelType input, int width, int height);

struct SummedAreaTable {
  int width = 0, height = 0, channels = 0;
  SatPrecision precision = SatPrecision::u32;
  PixelType source = PixelType::u8;  // u8/u16: sums of the integer codes; f32: of the values
  // f32 tables hold R = S - M, where M is the summed-area table of the
  // block-mean image (each texel replaced by the mean of its block x block
  // block). Hensley et al. subtract one global mean; subtracting local means
  // keeps R small on real images (a bright sky over dark ground no longer
  // accumulates), so rounding R to float costs well under half an 8-bit step.
  // M is rebuilt exactly from the block means (double) at query time.
  static constexpr int kBlock = 16;
  int block = 0;                    // kBlock for f32 tables, 0 for the others
  std::vector<double> block_means;  // ceil(W/block) * ceil(H/block) * channels, row-major
  // The largest |entry| and the largest |M|, which bound the rounding error.
  double max_abs_entry = 0.0;
  double max_abs_model = 0.0;
  PixelBytes data;

  std::size_t element_bytes() const;
  // The sum over [x0, x1) x [y0, y1) for each channel into out[channels]
  // (integer tables: exact within max_exact_box(), modulo 2^32 or 2^64
  // beyond). Asserts 0 <= x0 <= x1 <= width and likewise for y.
  void box_sum(int x0, int y0, int x1, int y1, double* out) const;
  std::uint64_t max_exact_box() const { return sat_max_exact_box(precision, source); }
  // An upper bound on |box_sum - true sum| for any box: 0 for integer tables
  // within their box limit; for f32, four entries each rounded once from
  // exact values: 4 * ulp(max_abs_entry) / 2, plus M's double rounding.
  double error_bound() const;

  // M at inclusive (x, y), channel c (0 for tables without a model).
  double model(int x, int y, int c) const;
  // model(x, y, c) for every x and c of row y into out[width * channels].
  void model_row(int y, double* out) const;

 private:
  friend void build_sat(const ConstImageView& image, SatPrecision precision, SummedAreaTable& table);
  friend SummedAreaTable read_sat_file(const std::string& path);
  // Derives the prefix arrays model() reads from block_means.
  void prepare_model();

  std::vector<double> full_, col_, row_;  // (BW + 1) * (BH + 1) * channels each
};

// Builds the table of every channel of `image`. Integer precisions need
// integer input (Error{bad_arguments} otherwise). Bytes never depend on the
// thread count.
SummedAreaTable build_sat(const ConstImageView& image, SatPrecision precision);
// The same into `table`, reusing its memory when the size allows (a batch,
// or a table rebuilt every frame, then touches no fresh pages).
void build_sat(const ConstImageView& image, SatPrecision precision, SummedAreaTable& table);

// The .sat file (docs/sat.md): a 64-byte header, the offsets, the data.
void write_sat_file(const std::string& path, const SummedAreaTable& table);
// Checks every header field against the file size; throws Error{io} or
// Error{invalid_file} naming the file and the field.
SummedAreaTable read_sat_file(const std::string& path);

struct BoxBlurOptions {
  float radius = 4.0f;                         // half-width in texels: a box of 2r + 1 (fractional r blends)
  const ConstImageView* radius_map = nullptr;  // optional: per texel r = radius * map (first channel, [0, 1])
  WrapMode wrap = WrapMode::clamp;
  std::string color_space;  // "" : srgb for 8/16-bit, linear for float input
};

// A box blur at constant cost per texel, from a double-precision table of
// the linear, alpha-premultiplied image padded by the largest radius with
// `wrap`. A fractional radius r blends the boxes of floor(r) and floor(r)+1.
// The result has the input's size, type and color space.
Image box_blur(const ConstImageView& image, const BoxBlurOptions& options);

}  // namespace texproc
