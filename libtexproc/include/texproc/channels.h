// texproc/channels.h: channels rearranged, set to constants and inverted:
// swizzles (bgra, rrr1, gggr), OpenGL <-> DirectX normal maps (green
// inverted), and what channel packing builds on.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "texproc/image.h"

namespace texproc {

// Where each output channel comes from, and which output channels are
// inverted (v becomes max - v: 255 - v, 65535 - v, 1 - v for floats).
// Sources are the input's channels read as RGBA: grey is (l, l, l, 1),
// grey+alpha (l, l, l, a), RGB (r, g, b, 1).
struct ChannelMap {
  static constexpr std::int8_t kZero = -1;                    // the constant 0
  static constexpr std::int8_t kOne = -2;                     // the constant 1 (255, 65535, 1.0)
  std::array<std::int8_t, 4> from = {0, 1, 2, 3};             // per output channel: 0-3 (r, g, b, a), kZero or kOne
  int channels = 0;                                           // output channels (1-4); 0: the input's count
  std::array<bool, 4> invert = {false, false, false, false};  // per output channel, after `from`

  // Whether the map leaves every image as it is.
  bool identity() const;
};

// A swizzle of one to four of r, g, b, a, 0, 1 (in any case; x y z w too),
// one per output channel: "bgra", "rrr1", "gggr", "rg". Throws
// Error{bad_arguments} naming the spec and what is wrong.
ChannelMap parse_swizzle(std::string_view spec);

// Sets `map` to invert the output channels named in `channels` (a subset of
// "rgba", e.g. "g" or "rgb"). Throws Error{bad_arguments}.
void add_inverted_channels(ChannelMap& map, std::string_view channels);

// The output channel count `map` gives an image of `input_channels`.
int mapped_channels(const ChannelMap& map, int input_channels);

// `in` through `map` into `out` (same size and type as `in`,
// mapped_channels(map, in.channels) channels; rows may be a band of an
// image). Exact: values are moved or inverted, never converted.
void map_channels(const ConstImageView& in, const ImageView& out, const ChannelMap& map);
Image map_channels(const ConstImageView& in, const ChannelMap& map);

}  // namespace texproc
