// texproc/color.h: transfer functions and color spaces.
//
// Filters only ever see linear floats: rows are decoded at the boundary
// (a 256-entry table for 8-bit sRGB), filtered, and encoded back with correct
// rounding. Alpha is always linear and never goes through a transfer function.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "texproc/image.h"

namespace texproc {

// The IEC 61966-2-1 sRGB transfer functions, in double precision.
double srgb_to_linear(double encoded);
double linear_to_srgb(double linear);

// Exact fast paths. srgb8_to_linear is a table lookup; linear_to_srgb8 returns
// round(255 * linear_to_srgb(x)) exactly (x clamped to [0, 1], NaN gives 0).
float srgb8_to_linear(std::uint8_t v);
std::uint8_t linear_to_srgb8(float x);
float srgb16_to_linear(std::uint16_t v);
std::uint16_t linear_to_srgb16(float x);

// A source or destination color space. Built in: "linear" (also "raw",
// "data": no transfer function) and "srgb" (exact sRGB curve, Rec.709
// primaries). Any other name is looked up in the OpenColorIO config named by
// $OCIO or, without it, texproc's built-in config (see docs/color.md), and
// converted to and from that config's scene_linear role.
class ColorSpace {
 public:
  static ColorSpace linear();
  static ColorSpace srgb();
  // Throws Error{bad_arguments} naming `name` and listing the valid names.
  static ColorSpace from_name(const std::string& name);

  const std::string& name() const;
  bool is_linear() const;
  bool is_srgb() const;
  // The OCIO config file this space came from ("" for built-in ones or the
  // built-in config); build systems list it as a dependency.
  const std::string& config_path() const;

  // Decodes `width` interleaved pixels of `channels` (1 gray, 2 gray+alpha,
  // 3 RGB, 4 RGBA) from `src` (integers scaled to [0, 1]) to linear floats in
  // `dst` (same layout). Alpha is copied unchanged.
  void decode_row(const void* src, PixelType type, int channels, int width, float* dst) const;
  // The inverse of decode_row. Integers are rounded to nearest and clamped;
  // `src` is used as scratch and may be modified.
  void encode_row(float* src, int channels, int width, void* dst, PixelType type) const;

 private:
  struct Impl;
  explicit ColorSpace(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}
  std::shared_ptr<const Impl> impl_;
};

// Names accepted by ColorSpace::from_name in the active config.
std::vector<std::string> color_space_names();

}  // namespace texproc
