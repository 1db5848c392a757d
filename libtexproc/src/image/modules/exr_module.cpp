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

#include "image/modules/image_module.h"
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

// The header as the OpenEXR file layout has it (magic, version, then per part
// a list of attributes: name, type name, int32 size, value; an empty name
// ends a header, and in a multi-part file an empty header ends the list),
// walked before OpenEXR opens the file: OpenEXR allocates each attribute's
// declared size first, so a 1.6 KB file declaring a 1.9 GB attribute made
// it take 1.9 GB (found by fuzz_images). An attribute larger than the rest
// of the file is refused here. OpenEXR reads some values by their own
// structure, not by their declared size (a channel list until its empty
// name, a preview's width x height pixels, fixed-size types as they are):
// a value whose structure disagrees with its size would make OpenEXR read
// the following bytes as other attributes (a 893-byte file made it take
// 1.7 GB, found by fuzz_images), so each must end where its size says.
std::int64_t fixed_size_of(const std::string& type) {
  static const std::pair<const char*, int> kSizes[] = {
      {"box2i", 16},      {"box2f", 16},   {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
      {"double", 8},      {"envmap", 1},   {"float", 4},           {"int", 4},         {"keycode", 28},
      {"lineOrder", 1},   {"m33f", 36},    {"m33d", 72},           {"m44f", 64},       {"m44d", 128},
      {"rational", 8},    {"tiledesc", 9}, {"timecode", 8},        {"v2i", 8},         {"v2f", 8},
      {"v2d", 16},        {"v3i", 12},     {"v3f", 12},            {"v3d", 24}};
  for (const auto& [name, size] : kSizes) {
    if (type == name) return size;
  }
  return -1;
}

// What a part's header declares that OpenEXR allocates for when it opens
// the file: its data window, its tiles, its chunk offset table.
struct DeclaredWork {
  std::int64_t width = 64, height = 64;  // without a data window, OpenEXR's default header's
  std::int64_t tile_x = 0, tile_y = 0;  // 0: scanlines
  int compression = 0;
};

std::int64_t le32(const std::uint8_t* p) {
  return std::int32_t(std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 |
                      std::uint32_t(p[3]) << 24);
}

// Refuses a header whose buffers OpenEXR would size past any real file: a
// data window over 2^20 a side, a tile larger than its image needs (and
// over 1024), a chunk offset table larger than the whole file.
template <typename Fail>
void check_declared_work(const DeclaredWork& d, std::uint64_t file_size, Fail&& fail) {
  if (d.width <= 0 || d.height <= 0) return;  // OpenEXR reports an empty window
  constexpr std::int64_t kMaxSide = std::int64_t(1) << 20;
  const std::string size = std::to_string(d.width) + "x" + std::to_string(d.height);
  if (d.width > kMaxSide || d.height > kMaxSide) fail("data window " + size + " is over 1048576 a side");
  std::int64_t chunks = 0;
  if (d.tile_x > 0 && d.tile_y > 0) {
    if (d.tile_x > std::max<std::int64_t>(1024, d.width) || d.tile_y > std::max<std::int64_t>(1024, d.height)) {
      fail("tile " + std::to_string(d.tile_x) + "x" + std::to_string(d.tile_y) + " is larger than its " + size +
           " image needs");
    }
    chunks = ((d.width + d.tile_x - 1) / d.tile_x) * ((d.height + d.tile_y - 1) / d.tile_y);
  } else {
    // Scanlines a chunk by compression (OpenEXR's table): none, RLE, ZIPS 1; ZIP, PXR24 16;
    // PIZ, B44, B44A, DWAA 32; DWAB 256.
    static const int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    const int lines = d.compression >= 0 && d.compression < 10 ? kLines[d.compression] : 1;
    chunks = (d.height + lines - 1) / lines;
  }
  if (std::uint64_t(chunks) * 8 > file_size) {
    fail(size + " in " + std::to_string(chunks) + " chunks needs an offset table of " + std::to_string(chunks * 8) +
         " bytes, more than the whole file (" + std::to_string(file_size) + ")");
  }
}

void check_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw texproc::Error(texproc::ErrorCode::io, path + ": cannot open");
  in.seekg(0, std::ios::end);
  const std::uint64_t size = std::uint64_t(in.tellg());
  in.seekg(0);
  std::uint8_t head[8] = {};
  if (!in.read(reinterpret_cast<char*>(head), 8)) return;  // OpenEXR says what is wrong
  const bool multipart = (head[5] & 0x10) != 0;  // version flags: bit 12 multi-part
  auto fail = [&](const std::string& what) {
    throw texproc::Error(texproc::ErrorCode::invalid_file, path + ": not a valid OpenEXR file: " + what); };
  auto read_name = [&](std::string& out) {
    out.clear();
    for (int i = 0; i < 256; ++i) {
      const int c = in.get();
      if (c == EOF) fail("truncated header");
      if (c == 0) return;
      out.push_back(char(c));
    }
    fail("an attribute name longer than 255 bytes");
  };
  for (int part = 0;; ++part) {
    std::string name, type;
    DeclaredWork work;
    read_name(name);
    if (name.empty()) {
      if (!multipart || part > 0) return;  // single part: its header ended; multi-part: the empty header
      fail("an empty header");
    }
    for (; !name.empty(); read_name(name)) {
      read_name(type);
      std::uint8_t b[4];
      if (!in.read(reinterpret_cast<char*>(b), 4)) fail("truncated header");
      const std::int32_t n = std::int32_t(std::uint32_t(b[0]) | std::uint32_t(b[1]) << 8 | std::uint32_t(b[2]) << 16 |
                                          std::uint32_t(b[3]) << 24);
      const std::uint64_t at = std::uint64_t(in.tellg());
      if (n < 0 || std::uint64_t(n) > size - at) {
        fail("attribute '" + name + "' (" + type + ") declares " + std::to_string(n) + " bytes, " +
             std::to_string(size - at) + " follow it in the file");
      }
      const std::string what = "attribute '" + name + "' (" + type + ") of " + std::to_string(n) + " bytes";
      if (const std::int64_t fixed = fixed_size_of(type); fixed >= 0 && fixed != n) {
        fail(what + ": a " + type + " has " + std::to_string(fixed));
      }
      if ((name == "dataWindow" && type == "box2i") || (name == "tiles" && type == "tiledesc") ||
          (name == "compression" && type == "compression")) {
        std::uint8_t v[16] = {};
        if (!in.read(reinterpret_cast<char*>(v), n)) fail("truncated header");
        in.seekg(-std::streamoff(n), std::ios::cur);
        if (type == "box2i") {
          work.width = le32(v + 8) - le32(v) + 1;
          work.height = le32(v + 12) - le32(v + 4) + 1;
        } else if (type == "tiledesc") {
          work.tile_x = std::uint32_t(le32(v));
          work.tile_y = std::uint32_t(le32(v + 4));
        } else {
          work.compression = v[0];
        }
      }
      if (type == "chlist") {  // entries (name, 16 bytes) up to an empty name, all inside the value
        std::uint64_t used = 0;
        for (std::string channel;;) {
          read_name(channel);
          used += channel.size() + 1;
          if (channel.empty()) break;
          in.seekg(16, std::ios::cur);
          used += 16;
          if (used > std::uint64_t(n)) break;
        }
        if (used != std::uint64_t(n)) fail(what + ": its channel list does not end where its size says");
        continue;
      }
      if (type == "preview") {  // width and height, then width x height RGBA bytes
        std::uint8_t wh[8] = {};
        if (n < 8 || !in.read(reinterpret_cast<char*>(wh), 8)) fail(what + ": too short for a preview");
        auto u32 = [&](const std::uint8_t* p) {
          return std::uint64_t(p[0]) | std::uint64_t(p[1]) << 8 | std::uint64_t(p[2]) << 16 | std::uint64_t(p[3]) << 24;
        };
        if (u32(wh) * u32(wh + 4) * 4 + 8 != std::uint64_t(n)) fail(what + ": its pixels do not fill its size");
        in.seekg(std::streamoff(n - 8), std::ios::cur);
        continue;
      }
      in.seekg(std::streamoff(n), std::ios::cur);
    }
    check_declared_work(work, size, fail);
    if (!multipart) return;
    // Multi-part: another header follows unless the next byte ends the list.
    if (in.peek() == 0) return;
  }
}

void probe(const std::string& path, TpImageSpec& out) {
  check_header(path);
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
  check_header(path);
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

using texproc::Error;
using texproc::ErrorCode;
using texproc::ConstImageView;
using texproc::ImageView;
using texproc::PixelType;
using texproc::WriteOptions;

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
const char* const kNamesRG[] = {"R", "G"};
const char* const kNames3[] = {"R", "G", "B"};
const char* const kNames4[] = {"R", "G", "B", "A"};
const char* const* names_for(int channels, bool red_green) {
  switch (channels) {
    case 1: return kNames1;
    case 2: return red_green ? kNamesRG : kNames2;
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
      d[i] = v.type == PixelType::u8 ? v.row<const std::uint8_t>(y)[i] / 255.0f : v.row<const std::uint16_t>(y)[i] / 65535.0f;
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
  std::string failed;         // after a failed write: its message (OpenEXR must not be called again)
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
                      out.levelWidth(level), height, w.channels, PixelType::f32, row_stride};
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
      views.push_back({levels[i].data, levels[i].width, levels[i].height, levels[i].channels,
                       PixelType(levels[i].type), levels[i].row_stride});
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
      throw Error(ErrorCode::runtime, w->path + ": " + std::to_string(w->bands_left) + " bands of the MIP file were not given");
    }
    w->out.reset();  // writes the tile offsets and closes the file
  });
}

const TpImageModule kModule = {TP_IMAGE_MODULE_ABI, probe_c, read_c, write_c, mip_open_c, mip_band_c, mip_close_c};

}  // namespace

extern "C" __attribute__((visibility("default"))) const TpImageModule* texproc_exr_module(void) { return &kModule; }
