// OpenEXR through its own C++ API: scan-line and tiled files, any
// compression, chunks decoded and encoded on OpenEXR's thread pool. Channels
// come in OpenImageIO's order (R, G, B, A first, then the rest as stored),
// as f32; the data window is the image.
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>
#include <OpenEXR/ImfTiledInputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include <algorithm>
#include <cctype>
#include <iterator>
#include <mutex>
#include <vector>

#include "image/codecs/codecs.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc::codecs {
namespace {

void start_threads() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(std::max(1, hardware_threads())); });
}

struct Channel {
  std::string name;
  Imf::PixelType type;
};

// OpenImageIO's order: colour, then luminance, then alpha, then depth (each
// name in any case), then the rest as stored (alphabetically).
std::vector<Channel> ordered_channels(const Imf::Header& h) {
  std::vector<Channel> all;
  for (auto it = h.channels().begin(); it != h.channels().end(); ++it) all.push_back({it.name(), it.channel().type});
  auto rank = [](std::string n) {
    for (auto& c : n) c = char(std::tolower(static_cast<unsigned char>(c)));
    static const char* const kOrder[][2] = {{"r", "red"}, {"g", "green"}, {"b", "blue"}, {"y", "y"}, {"real", "real"},
                                            {"imag", "imag"}, {"a", "alpha"}, {"ar", "ra"}, {"ag", "ga"}, {"ab", "ba"},
                                            {"z", "depth"}, {"zback", "zback"}};
    for (int i = 0; i < int(std::size(kOrder)); ++i)
      if (n == kOrder[i][0] || n == kOrder[i][1]) return i;
    return int(std::size(kOrder));
  };
  std::stable_sort(all.begin(), all.end(), [&](const Channel& a, const Channel& b) { return rank(a.name) < rank(b.name); });
  return all;
}

std::string file_type_of(const std::vector<Channel>& ch) {
  bool fl = false, ui = false;
  for (const Channel& c : ch) fl |= c.type == Imf::FLOAT, ui |= c.type == Imf::UINT;
  return fl ? "float" : ui ? "uint" : "half";
}

ImageFileInfo info_of(const std::string& path, const Imf::Header& h) {
  const Imath::Box2i dw = h.dataWindow();
  const std::vector<Channel> ch = ordered_channels(h);
  ImageFileInfo info;
  info.format = "openexr";
  info.width = dw.max.x - dw.min.x + 1;
  info.height = dw.max.y - dw.min.y + 1;
  info.channels = int(ch.size());
  info.file_type = file_type_of(ch);
  info.type = PixelType::f32;
  info.color_space_tag = "Linear";
  check_size(path, info.width, info.height, info.channels);
  return info;
}

template <typename Fn>
auto guarded(const std::string& path, const char* what, Fn&& fn) -> decltype(fn()) {
  try {
    return fn();
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorCode::invalid_file, path + ": " + what + ": " + e.what());
  }
}

}  // namespace

ImageFileInfo exr_probe(const std::string& path) {
  start_threads();
  return guarded(path, "not a valid OpenEXR file", [&] {
    Imf::InputFile in(path.c_str());
    ImageFileInfo info = info_of(path, in.header());
    info.level_sizes.emplace_back(info.width, info.height);
    if (in.header().hasTileDescription() && in.header().tileDescription().mode == Imf::MIPMAP_LEVELS) {
      Imf::TiledInputFile tiled(path.c_str());
      info.mip_levels = tiled.numLevels();
      for (int l = 1; l < tiled.numLevels(); ++l) info.level_sizes.emplace_back(tiled.levelWidth(l), tiled.levelHeight(l));
    }
    return info;
  });
}

Image exr_read(const std::string& path, ImageFileInfo& info) {
  start_threads();
  return guarded(path, "cannot decode OpenEXR", [&] {
    Imf::InputFile in(path.c_str());
    info = info_of(path, in.header());
    info.level_sizes.emplace_back(info.width, info.height);
    const std::vector<Channel> ch = ordered_channels(in.header());
    const int C = std::min(int(ch.size()), 4);
    Image img = Image::uninitialized(info.width, info.height, C, PixelType::f32);
    const Imath::Box2i dw = in.header().dataWindow();
    Imf::FrameBuffer fb;
    for (int c = 0; c < C; ++c) {
      auto* base = reinterpret_cast<char*>(img.data() + sizeof(float) * c);
      fb.insert(ch[std::size_t(c)].name,
                Imf::Slice::Make(Imf::FLOAT, base, dw, sizeof(float) * C, img.row_stride()));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    return img;
  });
}

namespace {

Imf::Compression compression_of(const std::string& path, const std::string& c) {
  static const std::pair<const char*, Imf::Compression> kNames[] = {
      {"none", Imf::NO_COMPRESSION},     {"rle", Imf::RLE_COMPRESSION},     {"zips", Imf::ZIPS_COMPRESSION},
      {"zip", Imf::ZIP_COMPRESSION},     {"piz", Imf::PIZ_COMPRESSION},     {"pxr24", Imf::PXR24_COMPRESSION},
      {"b44", Imf::B44_COMPRESSION},     {"b44a", Imf::B44A_COMPRESSION},   {"dwaa", Imf::DWAA_COMPRESSION},
      {"dwab", Imf::DWAB_COMPRESSION}};
  if (c.empty()) return Imf::ZIP_COMPRESSION;
  const std::string name = c.substr(0, c.find(':'));  // "zip:4": OpenEXR 3.1's zip has no level to set
  for (const auto& [n, v] : kNames)
    if (name == n) return v;
  throw Error(ErrorCode::bad_arguments,
              path + ": OpenEXR compression '" + c + "' (valid: none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab)");
}

const char* const kNames1[] = {"Y"};
const char* const kNames2[] = {"Y", "A"};
const char* const kNames3[] = {"R", "G", "B"};
const char* const kNames4[] = {"R", "G", "B", "A"};
const char* const* names_for(int channels) {
  switch (channels) {
    case 1: return kNames1;
    case 2: return kNames2;
    case 3: return kNames3;
    default: return kNames4;
  }
}

// Pixels as the file stores them: f32, or half when asked (OpenEXR converts
// nothing on output); u8/u16 are scaled to [0, 1].
struct Stored {
  std::vector<float> f;
  std::vector<half> h;
  const char* data = nullptr;
  std::size_t stride = 0, pixel = 0;
  Imf::PixelType type = Imf::FLOAT;
};

std::vector<float> as_float(const ImageView& v);

Stored stored(const ImageView& v, bool as_half) {
  Stored s;
  const std::size_t n = std::size_t(v.width) * v.channels;
  if (!as_half && v.type == PixelType::f32) {
    s.data = static_cast<const char*>(v.data);
    s.stride = v.row_stride;
  } else {
    s.f = as_float(v);
    s.data = reinterpret_cast<const char*>(s.f.data());
    s.stride = n * sizeof(float);
  }
  s.pixel = sizeof(float) * v.channels;
  if (as_half) {
    s.h.resize(n * v.height);
    for (int y = 0; y < v.height; ++y) {
      const float* row = reinterpret_cast<const float*>(s.data + std::size_t(y) * s.stride);
      for (std::size_t i = 0; i < n; ++i) s.h[std::size_t(y) * n + i] = half(row[i]);
    }
    s.f.clear();
    s.data = reinterpret_cast<const char*>(s.h.data());
    s.stride = n * sizeof(half);
    s.pixel = sizeof(half) * v.channels;
    s.type = Imf::HALF;
  }
  return s;
}

std::vector<float> as_float(const ImageView& v) {
  std::vector<float> out(std::size_t(v.width) * v.height * v.channels);
  for (int y = 0; y < v.height; ++y) {
    float* d = out.data() + std::size_t(y) * v.width * v.channels;
    for (int i = 0; i < v.width * v.channels; ++i) {
      if (v.type == PixelType::f32) {
        d[i] = v.row<const float>(y)[i];
        continue;
      }
      d[i] = v.type == PixelType::u8 ? v.row<const std::uint8_t>(y)[i] / 255.0f : v.row<const std::uint16_t>(y)[i] / 65535.0f;
    }
  }
  return out;
}

Imf::Header header_for(const ImageView& v, const WriteOptions& o, Imf::Compression comp) {
  Imf::Header h(v.width, v.height);
  h.compression() = comp;
  const char* const* names = names_for(v.channels);
  for (int c = 0; c < v.channels; ++c) h.channels().insert(names[c], Imf::Channel(o.half ? Imf::HALF : Imf::FLOAT));
  h.insert("software", Imf::StringAttribute("texproc"));
  return h;
}

void fill_frame_buffer(Imf::FrameBuffer& fb, const ImageView& v, const Stored& s) {
  const char* const* names = names_for(v.channels);
  const std::size_t sample = s.type == Imf::HALF ? sizeof(half) : sizeof(float);
  for (int c = 0; c < v.channels; ++c) {
    fb.insert(names[c], Imf::Slice(s.type, const_cast<char*>(s.data + sample * c), s.pixel, s.stride));
  }
}

}  // namespace

void exr_write(const std::string& file, const std::string& path, const std::vector<ImageView>& levels, bool mip_file,
               const WriteOptions& o) {
  start_threads();
  const Imf::Compression comp = compression_of(path, o.compression);
  try {
    if (!mip_file) {
      const ImageView& v = levels[0];
      const Stored s = stored(v, o.half);
      Imf::OutputFile out(file.c_str(), header_for(v, o, comp));
      Imf::FrameBuffer fb;
      fill_frame_buffer(fb, v, s);
      out.setFrameBuffer(fb);
      out.writePixels(v.height);
      return;
    }
    Imf::Header h = header_for(levels[0], o, comp);
    h.setTileDescription(Imf::TileDescription(64, 64, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    Imf::TiledOutputFile out(file.c_str(), h);
    if (out.numLevels() != int(levels.size())) {
      throw Error(ErrorCode::bad_arguments, path + ": an OpenEXR MIP file holds " + std::to_string(out.numLevels()) +
                                                " levels, given " + std::to_string(levels.size()));
    }
    for (int l = 0; l < out.numLevels(); ++l) {
      const ImageView& v = levels[std::size_t(l)];
      const Stored s = stored(v, o.half);
      Imf::FrameBuffer fb;
      fill_frame_buffer(fb, v, s);
      out.setFrameBuffer(fb);
      out.writeTiles(0, out.numXTiles(l) - 1, 0, out.numYTiles(l) - 1, l);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    write_error(path, e.what());
  }
}

}  // namespace texproc::codecs
