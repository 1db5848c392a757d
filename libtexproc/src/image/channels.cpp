// Channel maps (texproc/channels.h): swizzles, constants and inversion,
// exact for every pixel type.
#include "texproc/channels.h"

#include <cctype>
#include <cstring>

#include "texproc/error.h"

namespace texproc {
namespace {

std::int8_t source_of(char c) {
  switch (std::tolower(static_cast<unsigned char>(c))) {
    case 'r':
    case 'x':
      return 0;
    case 'g':
    case 'y':
      return 1;
    case 'b':
    case 'z':
      return 2;
    case 'a':
    case 'w':
      return 3;
    case '0':
      return ChannelMap::kZero;
    case '1':
      return ChannelMap::kOne;
    default:
      return 99;
  }
}

// Channel c (0-3) of pixel x of a row, read as RGBA.
template <typename T>
T rgba_channel(const T* row, int x, int channels, int c, T one) {
  const T* p = row + std::size_t(x) * channels;
  if (channels >= 3) return c < channels ? p[c] : one;  // RGB: alpha 1
  if (c < 3) return p[0];                               // grey fills RGB
  return channels == 2 ? p[1] : one;
}

template <typename T>
void map_rows(const ConstImageView& in, const ImageView& out, const ChannelMap& m, T one) {
  const int n = out.channels;
  for (int y = 0; y < in.height; ++y) {
    const T* src = in.row<const T>(y);
    T* dst = out.row<T>(y);
    for (int x = 0; x < in.width; ++x)
      for (int k = 0; k < n; ++k) {
        const std::int8_t f = m.from[k];
        T v = f == ChannelMap::kZero ? T(0) : f == ChannelMap::kOne ? one : rgba_channel(src, x, in.channels, f, one);
        if (m.invert[k]) v = T(one - v);
        dst[std::size_t(x) * n + k] = v;
      }
  }
}

}  // namespace

bool ChannelMap::identity() const {
  if (channels != 0) return false;
  for (int k = 0; k < 4; ++k)
    if (from[k] != k || invert[k]) return false;
  return true;
}

ChannelMap parse_swizzle(std::string_view spec) {
  if (spec.empty() || spec.size() > 4) {
    throw Error(ErrorCode::bad_arguments, "--swizzle '" + std::string(spec) +
                                              "': one to four of r, g, b, a, 0, 1 (one per output channel, "
                                              "e.g. bgra, rrr1, gggr)");
  }
  ChannelMap m;
  m.channels = int(spec.size());
  for (std::size_t k = 0; k < spec.size(); ++k) {
    const std::int8_t f = source_of(spec[k]);
    if (f == 99) {
      throw Error(ErrorCode::bad_arguments, "--swizzle '" + std::string(spec) + "': '" + std::string(1, spec[k]) +
                                                "' is not one of r, g, b, a, 0, 1");
    }
    m.from[k] = f;
  }
  return m;
}

void add_inverted_channels(ChannelMap& map, std::string_view channels) {
  if (channels.empty()) throw Error(ErrorCode::bad_arguments, "--invert: name channels, e.g. g or rgb");
  for (char c : channels) {
    const std::int8_t k = source_of(c);
    if (k < 0 || k > 3) {
      throw Error(ErrorCode::bad_arguments,
                  "--invert '" + std::string(channels) + "': '" + std::string(1, c) + "' is not one of r, g, b, a");
    }
    map.invert[k] = true;
  }
}

int mapped_channels(const ChannelMap& map, int input_channels) {
  return map.channels > 0 ? map.channels : input_channels;
}

void map_channels(const ConstImageView& in, const ImageView& out, const ChannelMap& map) {
  if (out.width != in.width || out.height != in.height || out.type != in.type ||
      out.channels != mapped_channels(map, in.channels)) {
    throw Error(ErrorCode::bad_arguments, "map_channels: the output's size, type or channel count does not match");
  }
  for (int k = out.channels; k < 4; ++k)
    if (map.invert[k]) {
      throw Error(ErrorCode::bad_arguments, std::string("cannot invert ") + "rgba"[k] + ": the image has " +
                                                std::to_string(out.channels) + " channel(s)");
    }
  switch (in.type) {
    case PixelType::u8:
      return map_rows<std::uint8_t>(in, out, map, 255);
    case PixelType::u16:
      return map_rows<std::uint16_t>(in, out, map, 65535);
    case PixelType::f32:
      return map_rows<float>(in, out, map, 1.0f);
  }
}

Image map_channels(const ConstImageView& in, const ChannelMap& map) {
  Image out = Image::uninitialized(in.width, in.height, mapped_channels(map, in.channels), in.type);
  map_channels(in, out.view(), map);
  return out;
}

}  // namespace texproc
