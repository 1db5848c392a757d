#include "io/modules/exr_header.h"

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <utility>

#include "texproc/error.h"

namespace texproc::exr {
namespace {

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
  static const std::pair<const char*, int> kSizes[] = {{"box2i", 16},
                                                       {"box2f", 16},
                                                       {"chromaticities", 32},
                                                       {"compression", 1},
                                                       {"deepImageState", 1},
                                                       {"double", 8},
                                                       {"envmap", 1},
                                                       {"float", 4},
                                                       {"int", 4},
                                                       {"keycode", 28},
                                                       {"lineOrder", 1},
                                                       {"m33f", 36},
                                                       {"m33d", 72},
                                                       {"m44f", 64},
                                                       {"m44d", 128},
                                                       {"rational", 8},
                                                       {"tiledesc", 9},
                                                       {"timecode", 8},
                                                       {"v2i", 8},
                                                       {"v2f", 8},
                                                       {"v2d", 16},
                                                       {"v3i", 12},
                                                       {"v3f", 12},
                                                       {"v3d", 24}};
  for (const auto& [name, size] : kSizes) {
    if (type == name) return size;
  }
  return -1;
}

// What a part's header declares that OpenEXR allocates for when it opens
// the file: its data window, its tiles, its chunk offset table.
struct DeclaredWork {
  std::int64_t width = 64, height = 64;  // without a data window, OpenEXR's default header's
  std::int64_t tile_x = 0, tile_y = 0;   // 0: scanlines
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

}  // namespace

void check_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw texproc::Error(texproc::ErrorCode::io, path + ": cannot open");
  in.seekg(0, std::ios::end);
  const std::uint64_t size = std::uint64_t(in.tellg());
  in.seekg(0);
  std::uint8_t head[8] = {};
  if (!in.read(reinterpret_cast<char*>(head), 8)) return;  // OpenEXR says what is wrong
  const bool multipart = (head[5] & 0x10) != 0;            // version flags: bit 12 multi-part
  auto fail = [&](const std::string& what) {
    throw texproc::Error(texproc::ErrorCode::invalid_file, path + ": not a valid OpenEXR file: " + what);
  };
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

}  // namespace texproc::exr
