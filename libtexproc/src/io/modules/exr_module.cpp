// texproc_exr: OpenEXR through its own C++ API, behind the C boundary of
// image_module.h (loaded on first use: OpenEXR's four libraries cost every
// process about 3 ms to map). Scan-line and tiled files, any compression,
// chunks decoded and encoded on OpenEXR's thread pool. Channels come in
// OpenImageIO's order (colour, luminance, alpha, depth, then the rest as
// stored), as f32; the data window is the image.
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
#include <fstream>
#include <iterator>
#include <memory>
#include <mutex>
#include <vector>

#include <cstdint>
#include <cstring>
#include <string>
#include <thread>

#include "io/modules/exr_header.h"
#include "io/modules/image_module.h"
#include "texproc/error.h"
#include "texproc/image.h"
#include "texproc/image_io.h"

namespace {

// texproc::ErrorCode values (error.h).
enum : int { kOk = 0, kBadArguments = 1, kIo = 2, kInvalidFile = 3 };

struct Failure {
  int code;
  std::string message;
};

void start_threads() {
  static std::once_flag once;
  std::call_once(once, [] { Imf::setGlobalThreadCount(int(std::max(1u, std::thread::hardware_concurrency()))); });
}

void copy_string(char* dst, size_t size, const std::string& s) {
  const size_t n = std::min(size - 1, s.size());
  std::memcpy(dst, s.data(), n);
  dst[n] = '\0';
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
    static const char* const kOrder[][2] = {{"r", "red"},     {"g", "green"},   {"b", "blue"},  {"y", "y"},
                                            {"real", "real"}, {"imag", "imag"}, {"a", "alpha"}, {"ar", "ra"},
                                            {"ag", "ga"},     {"ab", "ba"},     {"z", "depth"}, {"zback", "zback"}};
    for (int i = 0; i < int(std::size(kOrder)); ++i)
      if (n == kOrder[i][0] || n == kOrder[i][1]) return i;
    return int(std::size(kOrder));
  };
  std::stable_sort(all.begin(), all.end(),
                   [&](const Channel& a, const Channel& b) { return rank(a.name) < rank(b.name); });
  return all;
}

std::string file_type_of(const std::vector<Channel>& ch) {
  bool fl = false, ui = false;
  for (const Channel& c : ch) {
    fl |= c.type == Imf::FLOAT;
    ui |= c.type == Imf::UINT;
  }
  return fl ? "float" : ui ? "uint" : "half";
}

void info_of(const Imf::Header& h, TpImageSpec& out) {
  const Imath::Box2i dw = h.dataWindow();
  const std::vector<Channel> ch = ordered_channels(h);
  out = TpImageSpec{};
  copy_string(out.format, sizeof out.format, "openexr");
  out.width = dw.max.x - dw.min.x + 1;
  out.height = dw.max.y - dw.min.y + 1;
  out.channels = int(ch.size());
  copy_string(out.file_type, sizeof out.file_type, file_type_of(ch));
  out.type = TP_F32;
  copy_string(out.color_space, sizeof out.color_space, "Linear");
  out.subimages = 1;
  out.mip_levels = 1;
  out.level_width[0] = out.width;
  out.level_height[0] = out.height;
}

void probe(const std::string& path, TpImageSpec& out) {
  texproc::exr::check_header(path);
  start_threads();
  Imf::InputFile in(path.c_str());
  info_of(in.header(), out);
  if (in.header().hasTileDescription() && in.header().tileDescription().mode == Imf::MIPMAP_LEVELS) {
    Imf::TiledInputFile tiled(path.c_str());
    out.mip_levels = tiled.numLevels();
    for (int l = 1; l < std::min(tiled.numLevels(), int(TP_IMAGE_MAX_LEVELS)); ++l) {
      out.level_width[l] = tiled.levelWidth(l);
      out.level_height[l] = tiled.levelHeight(l);
    }
  }
}

void read(const std::string& path, int C, void* data, size_t row_stride) {
  texproc::exr::check_header(path);
  start_threads();
  Imf::InputFile in(path.c_str());
  const std::vector<Channel> ch = ordered_channels(in.header());
  const Imath::Box2i dw = in.header().dataWindow();
  Imf::FrameBuffer fb;
  for (int c = 0; c < std::min(C, int(ch.size())); ++c) {
    auto* base = static_cast<char*>(data) + sizeof(float) * c;
    fb.insert(ch[std::size_t(c)].name, Imf::Slice::Make(Imf::FLOAT, base, dw, sizeof(float) * C, row_stride));
  }
  in.setFrameBuffer(fb);
  in.readPixels(dw.min.y, dw.max.y);
}

}  // namespace

using texproc::ConstImageView;
using texproc::Error;
using texproc::ErrorCode;
using texproc::ImageView;
using texproc::PixelType;
using texproc::WriteOptions;

namespace {

Imf::Compression compression_of(const std::string& path, const std::string& c) {
  static const std::pair<const char*, Imf::Compression> kNames[] = {
      {"none", Imf::NO_COMPRESSION},  {"rle", Imf::RLE_COMPRESSION},   {"zips", Imf::ZIPS_COMPRESSION},
      {"zip", Imf::ZIP_COMPRESSION},  {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
      {"b44", Imf::B44_COMPRESSION},  {"b44a", Imf::B44A_COMPRESSION}, {"dwaa", Imf::DWAA_COMPRESSION},
      {"dwab", Imf::DWAB_COMPRESSION}};
  if (c.empty()) return Imf::ZIP_COMPRESSION;
  const std::string name = c.substr(0, c.find(':'));  // "zip:4": OpenEXR 3.1's zip has no level to set
  for (const auto& [n, v] : kNames)
    if (name == n) return v;
  throw Error(ErrorCode::bad_arguments, path + ": OpenEXR compression '" + c +
                                            "' (valid: none, rle, zips, zip, piz, pxr24, b44, b44a, dwaa, dwab)");
}

const char* const kNames1[] = {"Y"};
const char* const kNames2[] = {"Y", "A"};
const char* const kNamesRG[] = {"R", "G"};
const char* const kNames3[] = {"R", "G", "B"};
const char* const kNames4[] = {"R", "G", "B", "A"};
const char* const* names_for(int channels, bool red_green) {
  switch (channels) {
    case 1:
      return kNames1;
    case 2:
      return red_green ? kNamesRG : kNames2;
    case 3:
      return kNames3;
    default:
      return kNames4;
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

std::vector<float> as_float(const ConstImageView& v);

// Float images are converted row by row (no whole float copy of a level
// beside its half copy).
Stored stored(const ConstImageView& v, bool as_half) {
  Stored s;
  const std::size_t n = std::size_t(v.width) * v.channels;
  if (v.type == PixelType::f32) {
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
    s.f = std::vector<float>();  // freed, not just emptied
    s.data = reinterpret_cast<const char*>(s.h.data());
    s.stride = n * sizeof(half);
    s.pixel = sizeof(half) * v.channels;
    s.type = Imf::HALF;
  }
  return s;
}

std::vector<float> as_float(const ConstImageView& v) {
  std::vector<float> out(std::size_t(v.width) * v.height * v.channels);
  for (int y = 0; y < v.height; ++y) {
    float* d = out.data() + std::size_t(y) * v.width * v.channels;
    for (int i = 0; i < v.width * v.channels; ++i) {
      if (v.type == PixelType::f32) {
        d[i] = v.row<const float>(y)[i];
        continue;
      }
      d[i] = v.type == PixelType::u8 ? v.row<const std::uint8_t>(y)[i] / 255.0f
                                     : v.row<const std::uint16_t>(y)[i] / 65535.0f;
    }
  }
  return out;
}

Imf::Header header_for(const ConstImageView& v, const WriteOptions& o, Imf::Compression comp) {
  Imf::Header h(v.width, v.height);
  h.compression() = comp;
  const char* const* names = names_for(v.channels, o.red_green);
  for (int c = 0; c < v.channels; ++c) h.channels().insert(names[c], Imf::Channel(o.half ? Imf::HALF : Imf::FLOAT));
  h.insert("software", Imf::StringAttribute("texproc"));
  return h;
}

void fill_frame_buffer(Imf::FrameBuffer& fb, const ConstImageView& v, const Stored& s, bool red_green) {
  const char* const* names = names_for(v.channels, red_green);
  const std::size_t sample = s.type == Imf::HALF ? sizeof(half) : sizeof(float);
  for (int c = 0; c < v.channels; ++c) {
    fb.insert(names[c], Imf::Slice(s.type, const_cast<char*>(s.data + sample * c), s.pixel, s.stride));
  }
}

// Rows [y0, y1) of `v` as the file stores them, addressed as OpenEXR
// addresses a frame buffer (by the image's row, from the slice's base).
struct Band {
  Stored stored;
  ConstImageView rows;
};
Band band_of(const ConstImageView& v, int y0, int y1, bool as_half) {
  Band b;
  b.rows = v;
  b.rows.height = y1 - y0;
  b.rows.data = static_cast<const char*>(v.data) + std::size_t(y0) * v.row_stride;
  b.stored = stored(b.rows, as_half);
  b.stored.data -= std::ptrdiff_t(y0) * std::ptrdiff_t(b.stored.stride);  // row y at base + y * stride
  return b;
}

}  // namespace

namespace {

void write(const std::string& file, const std::string& path, const std::vector<ConstImageView>& levels, bool mip_file,
           const WriteOptions& o) {
  start_threads();
  const Imf::Compression comp = compression_of(path, o.compression);
  try {
    // Level by level and band by band: a converted copy of a band, never of
    // a whole level, beside the image.
    constexpr int kBandRows = 64;
    if (!mip_file) {
      const ConstImageView& v = levels[0];
      Imf::OutputFile out(file.c_str(), header_for(v, o, comp));
      for (int y0 = 0; y0 < v.height; y0 += kBandRows) {
        const int y1 = std::min(v.height, y0 + kBandRows);
        const Band b = band_of(v, y0, y1, o.half);
        Imf::FrameBuffer fb;
        fill_frame_buffer(fb, v, b.stored, o.red_green);
        out.setFrameBuffer(fb);
        out.writePixels(y1 - y0);
      }
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
      const ConstImageView& v = levels[std::size_t(l)];
      const int tile_rows = out.numYTiles(l);
      for (int ty = 0; ty < tile_rows; ++ty) {  // a band of one row of 64x64 tiles
        const int y0 = ty * 64, y1 = std::min(v.height, y0 + 64);
        const Band b = band_of(v, y0, y1, o.half);
        Imf::FrameBuffer fb;
        fill_frame_buffer(fb, v, b.stored, o.red_green);
        out.setFrameBuffer(fb);
        out.writeTiles(0, out.numXTiles(l) - 1, ty, ty, l);
      }
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorCode::io, path + ": cannot write: " + e.what());
  }
}

// The streamed MIP file: the same header, tiles and order as write()'s
// (OpenEXR keeps a tile that arrives before its turn, compressed, until
// the tiles before it are in the file).
struct MipWriter {
  std::string path;
  WriteOptions options;
  int channels = 0;
  long long bands_left = 0;  // bands not yet given
  std::string failed;        // after a failed write: its message (OpenEXR must not be called again)
  std::unique_ptr<Imf::TiledOutputFile> out;
};

MipWriter* mip_open(const std::string& file, const std::string& path, int width, int height, int channels,
                    const WriteOptions& o) {
  start_threads();
  auto w = std::make_unique<MipWriter>();
  w->path = path;
  w->options = o;
  w->channels = channels;
  try {
    const ConstImageView shape{nullptr, width, height, channels, PixelType::f32, 0};
    Imf::Header h = header_for(shape, o, compression_of(path, o.compression));
    h.setTileDescription(Imf::TileDescription(64, 64, Imf::MIPMAP_LEVELS, Imf::ROUND_DOWN));
    w->out = std::make_unique<Imf::TiledOutputFile>(file.c_str(), h);
    for (int l = 0; l < w->out->numLevels(); ++l) w->bands_left += w->out->numYTiles(l);
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(ErrorCode::io, path + ": cannot write: " + e.what());
  }
  return w.release();
}

void mip_band(MipWriter& w, int level, int band, const void* rows, std::size_t row_stride) {
  if (!w.failed.empty()) throw Error(ErrorCode::io, w.failed);
  Imf::TiledOutputFile& out = *w.out;
  if (level < 0 || level >= out.numLevels() || band < 0 || band >= out.numYTiles(level))
    throw Error(ErrorCode::bad_arguments, w.path + ": band " + std::to_string(band) + " is outside the file");
  try {
    const int height = out.levelHeight(level);
    const int y0 = band * 64, y1 = std::min(height, y0 + 64);
    // The band's rows, addressed as the level's rows y0 .. y1-1.
    const ConstImageView v{static_cast<const char*>(rows) - std::ptrdiff_t(y0) * std::ptrdiff_t(row_stride),
                           out.levelWidth(level),
                           height,
                           w.channels,
                           PixelType::f32,
                           row_stride};
    const Band b = band_of(v, y0, y1, w.options.half);
    Imf::FrameBuffer fb;
    fill_frame_buffer(fb, v, b.stored, w.options.red_green);
    out.setFrameBuffer(fb);
    out.writeTiles(0, out.numXTiles(level) - 1, band, band, level);
    --w.bands_left;
  } catch (const std::exception& e) {
    // A failed write leaves the file's tile buffers waiting: no more calls.
    const auto* known = dynamic_cast<const Error*>(&e);
    w.failed = known ? e.what() : w.path + ": cannot write: " + e.what();
    throw Error(known ? known->code() : ErrorCode::io, w.failed);
  }
}

int report(int code, const std::string& message, char* err, size_t err_size) {
  if (err && err_size) copy_string(err, err_size, message);
  return code;
}

template <typename Fn>
int guarded(const std::string& path, const char* what, char* err, size_t err_size, Fn&& fn) {
  try {
    fn();
    return kOk;
  } catch (const Error& e) {
    return report(int(e.code()), e.what(), err, err_size);
  } catch (const std::exception& e) {
    return report(kInvalidFile, path + ": " + what + ": " + e.what(), err, err_size);
  }
}

int probe_c(const char* path, TpImageSpec* spec, char* err, size_t err_size) {
  return guarded(path, "not a valid OpenEXR file", err, err_size, [&] { probe(path, *spec); });
}
int read_c(const char* path, int channels, int type, void* data, size_t row_stride, char* err, size_t err_size) {
  return guarded(path, "cannot decode OpenEXR", err, err_size, [&] {
    if (type != TP_F32) throw Error(ErrorCode::runtime, std::string(path) + ": OpenEXR reads as f32 only");
    read(path, channels, data, row_stride);
  });
}
WriteOptions options_of(const TpWriteOptions* o) {
  WriteOptions w;
  w.half = o->half != 0;
  w.compression = o->compression ? o->compression : "";
  w.color_space = o->color_space ? o->color_space : "";
  w.quality = o->quality;
  w.red_green = o->red_green != 0;
  return w;
}

int write_c(const char* file, const char* path, const TpImageLevel* levels, int count, int mip_file,
            const TpWriteOptions* o, char* err, size_t err_size) {
  return guarded(path, "cannot write", err, err_size, [&] {
    std::vector<ConstImageView> views;
    for (int i = 0; i < count; ++i) {
      views.push_back({levels[i].data, levels[i].width, levels[i].height, levels[i].channels, PixelType(levels[i].type),
                       levels[i].row_stride});
    }
    write(file, path, views, mip_file != 0, options_of(o));
  });
}

int mip_open_c(const char* file, const char* path, int width, int height, int channels, const TpWriteOptions* o,
               void** writer, char* err, size_t err_size) {
  *writer = nullptr;
  return guarded(path, "cannot write", err, err_size,
                 [&] { *writer = mip_open(file, path, width, height, channels, options_of(o)); });
}
int mip_band_c(void* writer, int level, int band, const void* rows, size_t row_stride, char* err, size_t err_size) {
  MipWriter& w = *static_cast<MipWriter*>(writer);
  return guarded(w.path, "cannot write", err, err_size, [&] { mip_band(w, level, band, rows, row_stride); });
}
int mip_close_c(void* writer, int commit, char* err, size_t err_size) {
  std::unique_ptr<MipWriter> w(static_cast<MipWriter*>(writer));
  return guarded(w->path, "cannot write", err, err_size, [&] {
    if (commit && w->bands_left != 0) {
      throw Error(ErrorCode::runtime,
                  w->path + ": " + std::to_string(w->bands_left) + " bands of the MIP file were not given");
    }
    w->out.reset();  // writes the tile offsets and closes the file
  });
}

const TpImageModule kModule = {TP_IMAGE_MODULE_ABI, probe_c, read_c, write_c, mip_open_c, mip_band_c, mip_close_c};

}  // namespace

extern "C" __attribute__((visibility("default"))) const TpImageModule* texproc_exr_module(void) { return &kModule; }
