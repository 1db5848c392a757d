// Truevision TGA (the TGA 2.0 specification): colour-mapped, true-colour and
// grey images, raw or run-length encoded, 8/15/16/24/32 bits, any origin.
// No Debian library reads TGA on its own (OpenImageIO and SDL_image carry
// their own readers), and the format is a header and rows.
#include <algorithm>
#include <cstring>
#include <vector>

#include "core/fd_writer.h"
#include "io/codecs/codecs.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc::codecs {
namespace {

struct TgaHeader {
  int id_length, cmap_type, image_type;
  int cmap_first, cmap_length, cmap_bits;
  int width, height, bits, descriptor;
  int alpha_bits() const { return descriptor & 15; }
  bool right_to_left() const { return descriptor & 0x10; }
  bool top_down() const { return descriptor & 0x20; }
  bool rle() const { return image_type >= 9; }
  int base_type() const { return image_type & 7; }  // 1 colour-mapped, 2 true colour, 3 grey
};

int le16(const std::uint8_t* p) { return p[0] | (p[1] << 8); }

TgaHeader parse(const std::string& path, const FileBytes& f) {
  if (f.size() < 18)
    invalid(path, "not a TGA file: " + std::to_string(f.size()) + " bytes, shorter than its 18-byte header");
  const std::uint8_t* b = f.data();
  TgaHeader h{b[0], b[1], b[2], le16(b + 3), le16(b + 5), b[7], le16(b + 12), le16(b + 14), b[16], b[17]};
  const int t = h.image_type;
  if (!(t == 1 || t == 2 || t == 3 || t == 9 || t == 10 || t == 11)) {
    invalid(path, "not a TGA file: image type " + std::to_string(t) + " (valid: 1, 2, 3, 9, 10, 11)");
  }
  if (h.cmap_type > 1) invalid(path, "TGA colour map type " + std::to_string(h.cmap_type) + " (valid: 0, 1)");
  if (h.base_type() == 1) {
    if (h.cmap_type != 1) invalid(path, "colour-mapped TGA without a colour map");
    if (h.bits != 8 && h.bits != 16)
      invalid(path, "colour-mapped TGA with " + std::to_string(h.bits) + "-bit indices (valid: 8, 16)");
    if (h.cmap_bits != 15 && h.cmap_bits != 16 && h.cmap_bits != 24 && h.cmap_bits != 32) {
      invalid(path, "TGA colour map entries of " + std::to_string(h.cmap_bits) + " bits (valid: 15, 16, 24, 32)");
    }
  } else if (h.base_type() == 2) {
    if (h.bits != 15 && h.bits != 16 && h.bits != 24 && h.bits != 32) {
      invalid(path, "true-colour TGA of " + std::to_string(h.bits) + " bits a pixel (valid: 15, 16, 24, 32)");
    }
  } else if (h.bits != 8 && h.bits != 16) {
    invalid(path, "grey TGA of " + std::to_string(h.bits) + " bits a pixel (valid: 8, 16)");
  }
  if (h.width == 0 || h.height == 0)
    invalid(path, "TGA of " + std::to_string(h.width) + "x" + std::to_string(h.height) + " pixels");
  return h;
}

int channels_of(const TgaHeader& h) {
  switch (h.base_type()) {
    case 3:
      return h.bits == 16 ? 2 : 1;
    case 1:
      return h.cmap_bits == 32 || (h.cmap_bits == 16 && h.alpha_bits() > 0) ? 4 : 3;
    default:
      return h.bits == 32 || (h.bits == 16 && h.alpha_bits() > 0) ? 4 : 3;
  }
}

ImageFileInfo info_of(const std::string& path, const TgaHeader& h, const ReadLimits& limits) {
  ImageFileInfo info;
  info.format = "targa";
  info.width = h.width;
  info.height = h.height;
  info.channels = channels_of(h);
  info.file_type = "uint8";
  info.type = PixelType::u8;  // no colour-space tag: OpenImageIO gives TGA none
  info.level_sizes.emplace_back(h.width, h.height);
  check_size(path, h.width, h.height, info.channels, limits);
  return info;
}

// One stored pixel (little-endian, BGR(A) or 5:5:5:1) to `channels` bytes.
inline void unpack(const std::uint8_t* p, int bits, int channels, bool alpha16, std::uint8_t* out) {
  if (bits == 8) {
    out[0] = p[0];
  } else if (bits == 15 || bits == 16) {
    const int v = p[0] | (p[1] << 8);
    auto five = [](int x) { return std::uint8_t((x << 3) | (x >> 2)); };
    out[0] = five((v >> 10) & 31);
    out[1] = five((v >> 5) & 31);
    out[2] = five(v & 31);
    if (channels == 4) out[3] = alpha16 ? ((v & 0x8000) ? 255 : 0) : 255;
  } else {
    out[0] = p[2];
    out[1] = p[1];
    out[2] = p[0];
    if (channels == 4) out[3] = bits == 32 ? p[3] : 255;
  }
}

}  // namespace

ImageFileInfo tga_probe(const std::string& path, const FileBytes& f, const ReadLimits& limits) {
  return info_of(path, parse(path, f), limits);
}

Image tga_read(const std::string& path, const FileBytes& f, ImageFileInfo& info, const ReadLimits& limits) {
  const TgaHeader h = parse(path, f);
  info = info_of(path, h, limits);
  const int C = info.channels;
  std::size_t pos = 18 + std::size_t(h.id_length);
  std::vector<std::uint8_t> palette;  // entries unpacked to C bytes
  if (h.cmap_type == 1) {
    const std::size_t entry = std::size_t(h.cmap_bits + 7) / 8;
    const std::size_t bytes = entry * std::size_t(h.cmap_length);
    if (pos + bytes > f.size()) invalid(path, "TGA colour map runs past the end of the file");
    if (h.base_type() == 1) {
      palette.resize(std::size_t(h.cmap_length) * C);
      for (int i = 0; i < h.cmap_length; ++i) {
        unpack(f.data() + pos + entry * std::size_t(i), h.cmap_bits, C, h.alpha_bits() > 0,
               &palette[std::size_t(i) * C]);
      }
    }
    pos += bytes;
  }
  const int stored = (h.bits + 7) / 8;
  const std::size_t count = std::size_t(h.width) * h.height;
  // Raw data: use it where it lies; RLE: expand it first.
  std::vector<std::uint8_t> expanded;
  const std::uint8_t* src = f.data() + pos;
  if (h.rle()) {
    expanded.resize(count * stored);
    std::size_t n = 0;
    while (n < count) {
      if (pos >= f.size())
        invalid(path,
                "TGA run-length data ends after " + std::to_string(n) + " of " + std::to_string(count) + " pixels");
      const int packet = f.data()[pos++];
      const std::size_t run = std::min<std::size_t>(std::size_t(packet & 0x7f) + 1, count - n);
      if (packet & 0x80) {
        if (pos + stored > f.size()) invalid(path, "TGA run-length data ends inside a packet");
        for (std::size_t i = 0; i < run; ++i)
          std::memcpy(&expanded[(n + i) * stored], f.data() + pos, std::size_t(stored));
        pos += std::size_t(stored);
      } else {
        if (pos + run * stored > f.size()) invalid(path, "TGA run-length data ends inside a packet");
        std::memcpy(&expanded[n * stored], f.data() + pos, run * stored);
        pos += run * stored;
      }
      n += run;
    }
    src = expanded.data();
  } else if (pos + count * stored > f.size()) {
    invalid(path, "TGA pixel data is " + std::to_string(f.size() - std::min(f.size(), pos)) + " bytes, " +
                      std::to_string(count * stored) + " expected");
  }
  Image img = Image::uninitialized(h.width, h.height, C, PixelType::u8);
  const bool alpha16 = h.alpha_bits() > 0;
  const int entries = h.cmap_length;
  bool bad_index = false;
  for_each_row_block(h.height, 64, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const int sy = h.top_down() ? y : h.height - 1 - y;
      const std::uint8_t* s = src + std::size_t(sy) * h.width * stored;
      std::uint8_t* d = img.row<std::uint8_t>(y);
      for (int x = 0; x < h.width; ++x) {
        const int sx = h.right_to_left() ? h.width - 1 - x : x;
        const std::uint8_t* p = s + std::size_t(sx) * stored;
        std::uint8_t* o = d + std::size_t(x) * C;
        if (h.base_type() == 1) {
          const int index = (stored == 1 ? p[0] : p[0] | (p[1] << 8)) - h.cmap_first;
          if (index < 0 || index >= entries) {
            bad_index = true;
            std::memset(o, 0, std::size_t(C));
            continue;
          }
          std::memcpy(o, &palette[std::size_t(index) * C], std::size_t(C));
        } else if (h.base_type() == 3) {
          o[0] = p[0];
          if (C == 2) o[1] = p[1];
        } else {
          unpack(p, h.bits, C, alpha16, o);
        }
      }
    }
    if (!h.rle()) {  // the rows' file bytes are pixels now: out of resident memory
      const int s0 = h.top_down() ? y0 : h.height - y1;
      const std::size_t row_bytes = std::size_t(h.width) * stored;
      f.release(src + std::size_t(s0) * row_bytes, std::size_t(y1 - y0) * row_bytes);
    }
  });
  if (bad_index) invalid(path, "TGA colour index outside its colour map of " + std::to_string(entries) + " entries");
  return img;
}

void tga_write(const std::string& file, const std::string& path, const ConstImageView& v, const WriteOptions&) {
  if (v.width > 65535 || v.height > 65535) write_error(path, "TGA holds at most 65535 pixels a side");
  // Grey (8 bits), grey + alpha (16), BGR (24), BGRA (32); top-left origin;
  // 16-bit and float are rounded to 8 bits (float clamped to [0, 1]).
  const int C = v.channels;
  const int type = C <= 2 ? 3 : 2;
  std::uint8_t hdr[18] = {};
  hdr[2] = std::uint8_t(type);
  hdr[12] = std::uint8_t(v.width);
  hdr[13] = std::uint8_t(v.width >> 8);
  hdr[14] = std::uint8_t(v.height);
  hdr[15] = std::uint8_t(v.height >> 8);
  hdr[16] = std::uint8_t(8 * C);
  hdr[17] = std::uint8_t(0x20 | (C == 2 || C == 4 ? 8 : 0));
  std::vector<std::uint8_t> body(std::size_t(v.width) * v.height * C);
  for_each_row_block(v.height, 64, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      std::uint8_t* d = body.data() + std::size_t(y) * v.width * C;
      for (int x = 0; x < v.width; ++x) {
        std::uint8_t px[4];
        for (int c = 0; c < C; ++c) px[c] = sample_u8(v, y, std::size_t(x) * C + c);
        std::uint8_t* o = d + std::size_t(x) * C;
        if (C >= 3) {
          o[0] = px[2], o[1] = px[1], o[2] = px[0];
          if (C == 4) o[3] = px[3];
        } else {
          std::memcpy(o, px, std::size_t(C));
        }
      }
    }
  });
  FdWriter w(file, path);
  w.write(hdr, sizeof hdr);
  w.write(body.data(), body.size());
  w.close();
}

}  // namespace texproc::codecs
