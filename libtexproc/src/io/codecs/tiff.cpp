// TIFF through libtiff: grey and RGB, 8/16-bit integers, 16/32-bit floats,
// extra channels, strips or tiles, contiguous or planar, top-left origin.
// Deflate and uncompressed contiguous files (what texproc and maketx write)
// are inflated chunk by chunk on all threads with libdeflate; every other
// compression goes through libtiff's codecs one chunk at a time. Layouts
// outside that list (palette, CMYK, YCbCr, 1-bit, other orientations) are
// left to the OpenImageIO module.
#include <libdeflate.h>
#include <tiffio.h>

#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <memory>
#include <mutex>
#include <vector>

#include "io/codecs/codecs.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc::codecs {
namespace {

thread_local std::string t_last_error;

void on_error(const char* module, const char* fmt, va_list ap) {
  char buf[512];
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  t_last_error = module ? std::string(module) + ": " + buf : buf;
}
void on_warning(const char*, const char*, va_list) {}

}  // namespace

void quiet_libtiff() {
  static std::once_flag once;
  std::call_once(once, [] {
    TIFFSetErrorHandler(on_error);
    TIFFSetWarningHandler(on_warning);
  });
}

std::string libtiff_last_error() { return t_last_error; }

namespace {

struct TiffClose {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
using Tiff = std::unique_ptr<TIFF, TiffClose>;

// The largest tile side accepted whatever the image's size.
constexpr std::uint64_t kMaxSmallTile = 1024;

struct Layout {
  std::uint32_t width = 0, height = 0;
  std::uint16_t spp = 1, bits = 8, format = SAMPLEFORMAT_UINT, photometric = PHOTOMETRIC_MINISBLACK;
  std::uint16_t planar = PLANARCONFIG_CONTIG, orientation = ORIENTATION_TOPLEFT, compression = COMPRESSION_NONE;
  std::uint16_t predictor = PREDICTOR_NONE;
  bool tiled = false;
  std::uint32_t tile_w = 0, tile_h = 0, rows_per_strip = 0;
  int bytes() const { return bits / 8; }
};

Tiff open_tiff(const std::string& path) {
  quiet_libtiff();
  t_last_error.clear();
  Tiff tif(TIFFOpen(path.c_str(), "rm"));
  if (!tif)
    invalid(path, "not a valid TIFF: " + (t_last_error.empty() ? std::string("libtiff cannot open it") : t_last_error));
  return tif;
}

Layout layout_of(const std::string& path, TIFF* t, const ReadLimits& limits) {
  Layout L;
  TIFFGetField(t, TIFFTAG_IMAGEWIDTH, &L.width);
  TIFFGetField(t, TIFFTAG_IMAGELENGTH, &L.height);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLESPERPIXEL, &L.spp);
  TIFFGetFieldDefaulted(t, TIFFTAG_BITSPERSAMPLE, &L.bits);
  TIFFGetFieldDefaulted(t, TIFFTAG_SAMPLEFORMAT, &L.format);
  if (!TIFFGetField(t, TIFFTAG_PHOTOMETRIC, &L.photometric))
    L.photometric = L.spp >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK;
  TIFFGetFieldDefaulted(t, TIFFTAG_PLANARCONFIG, &L.planar);
  TIFFGetFieldDefaulted(t, TIFFTAG_ORIENTATION, &L.orientation);
  TIFFGetFieldDefaulted(t, TIFFTAG_COMPRESSION, &L.compression);
  TIFFGetFieldDefaulted(t, TIFFTAG_PREDICTOR, &L.predictor);
  L.tiled = TIFFIsTiled(t);
  if (L.tiled) {
    TIFFGetField(t, TIFFTAG_TILEWIDTH, &L.tile_w);
    TIFFGetField(t, TIFFTAG_TILELENGTH, &L.tile_h);
  } else {
    TIFFGetFieldDefaulted(t, TIFFTAG_ROWSPERSTRIP, &L.rows_per_strip);
    L.rows_per_strip = std::min(L.rows_per_strip, L.height);
  }
  check_size(path, L.width, L.height, L.spp, limits);
  if (L.tiled) {
    // A tile is decoded whole: one far larger than the image (a few bytes of
    // file declaring gigabytes) is refused before anything is allocated.
    // Writers use tiles of 64 to 512 over small images and levels.
    const auto room = [](std::uint64_t side) { return std::max<std::uint64_t>((side + 15) / 16 * 16, kMaxSmallTile); };
    if (L.tile_w > room(L.width) || L.tile_h > room(L.height) ||
        std::uint64_t(L.tile_w) * L.tile_h > std::uint64_t(limits.max_image_pixels)) {
      invalid(path, "TIFF tile " + std::to_string(L.tile_w) + "x" + std::to_string(L.tile_h) +
                        " is larger than its image (" + std::to_string(L.width) + "x" + std::to_string(L.height) +
                        ") needs (a tile is decoded whole): refused before decoding");
    }
  }
  const bool ints = L.format == SAMPLEFORMAT_UINT && (L.bits == 8 || L.bits == 16);
  const bool floats = L.format == SAMPLEFORMAT_IEEEFP && (L.bits == 16 || L.bits == 32);
  const bool photometric = L.photometric == PHOTOMETRIC_MINISBLACK || (L.photometric == PHOTOMETRIC_RGB && L.spp >= 3);
  if (!(ints || floats) || !photometric || L.orientation != ORIENTATION_TOPLEFT ||
      (L.planar != PLANARCONFIG_CONTIG && L.planar != PLANARCONFIG_SEPARATE) || (L.tiled && (!L.tile_w || !L.tile_h)) ||
      (!L.tiled && !L.rows_per_strip)) {
    throw LeaveToModule{"TIFF layout"};
  }
  return L;
}

ImageFileInfo info_of(const Layout& L) {
  ImageFileInfo info;
  info.format = "tiff";
  info.width = int(L.width);
  info.height = int(L.height);
  info.channels = L.spp;
  info.file_type = L.format == SAMPLEFORMAT_IEEEFP ? (L.bits == 16 ? "half" : "float")
                   : L.bits == 8                   ? "uint8"
                                                   : "uint16";
  info.type = L.format == SAMPLEFORMAT_IEEEFP ? PixelType::f32 : L.bits == 8 ? PixelType::u8 : PixelType::u16;
  return info;  // no colour-space tag: OpenImageIO gives TIFF none
}

// MIP levels: a file that says it is a texture (maketx, texproc) holds its
// levels as further directories, as OpenImageIO reads it.
bool is_texture(TIFF* t) {
  const char* tf = nullptr;
  return TIFFGetField(t, TIFFTAG_PIXAR_TEXTUREFORMAT, &tf) && tf;
}

float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = std::uint32_t(h & 0x8000) << 16;
  std::uint32_t exp = (h >> 10) & 31, man = h & 1023, bits;
  if (exp == 0) {
    if (man == 0) {
      bits = sign;
    } else {  // subnormal: normalize
      exp = 127 - 15 + 1;
      while (!(man & 1024)) man <<= 1, --exp;
      bits = sign | (exp << 23) | ((man & 1023) << 13);
    }
  } else if (exp == 31) {
    bits = sign | 0x7f800000u | (man << 13);
  } else {
    bits = sign | ((exp + 127 - 15) << 23) | (man << 13);
  }
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

// One decoded chunk (tile or strip, one plane when planar) into the image.
struct Chunk {
  std::uint32_t x0, y0, w, h;  // where it lands; w x h its full (padded) size
  int plane;                   // -1: all samples (contiguous)
};

void place(const Layout& L, const Chunk& c, const std::uint8_t* data, Image& img) {
  const int C = img.channels();
  const int spp = c.plane < 0 ? L.spp : 1;
  const std::size_t in_px = std::size_t(spp) * L.bytes();
  const std::uint32_t w = std::min(c.w, L.width - c.x0), h = std::min(c.h, L.height - c.y0);
  const bool same_layout = c.plane < 0 && spp == C && !(L.format == SAMPLEFORMAT_IEEEFP && L.bits == 16);
  const int used = std::min(spp, C);  // samples past the fourth are not read
  for (std::uint32_t y = 0; y < h; ++y) {
    const std::uint8_t* s = data + std::size_t(y) * c.w * in_px;
    if (same_layout) {  // the usual case: rows copied as they are
      std::memcpy(img.row<std::uint8_t>(int(c.y0 + y)) + std::size_t(c.x0) * in_px, s, std::size_t(w) * in_px);
      continue;
    }
    for (std::uint32_t x = 0; x < w; ++x) {
      for (int k = 0; k < used; ++k) {
        const int ch = c.plane < 0 ? k : c.plane;
        if (ch >= C) continue;
        const std::uint8_t* p = s + std::size_t(x) * in_px + std::size_t(k) * L.bytes();
        const int X = int(c.x0 + x), Y = int(c.y0 + y);
        if (img.type() == PixelType::u8) {
          img.row<std::uint8_t>(Y)[std::size_t(X) * C + ch] = p[0];
        } else if (img.type() == PixelType::u16) {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          img.row<std::uint16_t>(Y)[std::size_t(X) * C + ch] = v;
        } else if (L.bits == 16) {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          img.row<float>(Y)[std::size_t(X) * C + ch] = half_to_float(v);
        } else {
          float v;
          std::memcpy(&v, p, 4);
          img.row<float>(Y)[std::size_t(X) * C + ch] = v;
        }
      }
    }
  }
}

template <typename T>
void undo_horizontal_predictor(std::uint8_t* data, std::uint32_t w, std::uint32_t h, int spp) {
  for (std::uint32_t y = 0; y < h; ++y) {
    T* row = reinterpret_cast<T*>(data) + std::size_t(y) * w * spp;
    for (std::size_t i = std::size_t(spp); i < std::size_t(w) * spp; ++i) row[i] = T(row[i] + row[i - spp]);
  }
}

template <typename T>
void swap_bytes(std::uint8_t* data, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t* p = data + i * sizeof(T);
    std::reverse(p, p + sizeof(T));
  }
}

struct DecompressorFree {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

}  // namespace

ImageFileInfo tiff_probe(const std::string& path, const ReadLimits& limits) {
  Tiff tif = open_tiff(path);
  const Layout L = layout_of(path, tif.get(), limits);
  ImageFileInfo info = info_of(L);
  info.level_sizes.emplace_back(info.width, info.height);
  const bool texture = is_texture(tif.get());
  int dirs = 1;
  while (TIFFReadDirectory(tif.get())) {
    ++dirs;
    std::uint32_t w = 0, h = 0;
    TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &h);
    if (texture) info.level_sizes.emplace_back(int(w), int(h));
  }
  if (texture) {
    info.mip_levels = dirs;
  } else {
    info.subimages = dirs;
  }
  return info;
}

Image tiff_read(const std::string& path, ImageFileInfo& info, const ReadLimits& limits) {
  Tiff tif = open_tiff(path);
  TIFF* t = tif.get();
  const Layout L = layout_of(path, t, limits);
  info = info_of(L);
  info.level_sizes.emplace_back(info.width, info.height);
  const int C = std::min<int>(L.spp, 4);
  Image img = Image::uninitialized(int(L.width), int(L.height), C, info.type);

  // The chunks, in file order.
  std::vector<Chunk> chunks;
  const int planes = L.planar == PLANARCONFIG_SEPARATE ? L.spp : 1;
  const std::uint32_t cw = L.tiled ? L.tile_w : L.width, ch = L.tiled ? L.tile_h : L.rows_per_strip;
  for (int p = 0; p < planes; ++p)
    for (std::uint32_t y = 0; y < L.height; y += ch)
      for (std::uint32_t x = 0; x < L.width; x += cw) chunks.push_back({x, y, cw, ch, planes > 1 ? p : -1});
  const std::size_t count = L.tiled ? std::size_t(TIFFNumberOfTiles(t)) : std::size_t(TIFFNumberOfStrips(t));
  if (count != chunks.size()) {
    invalid(path, "TIFF holds " + std::to_string(count) + " chunks, its size and layout need " +
                      std::to_string(chunks.size()));
  }
  const std::size_t spp_chunk = planes > 1 ? 1 : L.spp;
  const std::size_t chunk_bytes = std::size_t(cw) * ch * spp_chunk * L.bytes();
  // The samples declared must fit the chunks' bytes: no TIFF compression
  // texproc reads turns a byte into more than 4096 (deflate: at most 1032).
  // A small file declaring thousands of samples per pixel is refused before
  // its chunks are allocated or decoded.
  {
    std::uint64_t* sizes = nullptr;
    if (TIFFGetField(t, L.tiled ? TIFFTAG_TILEBYTECOUNTS : TIFFTAG_STRIPBYTECOUNTS, &sizes) && sizes) {
      std::uint64_t stored = 0;
      for (std::size_t i = 0; i < count; ++i) stored += sizes[i];
      const double declared = double(L.width) * L.height * double(L.spp) * L.bytes();
      if (declared > 4096.0 * double(stored) + 65536.0) {
        invalid(path, "TIFF declares " + std::to_string(std::uint64_t(declared)) + " bytes of samples (" +
                          std::to_string(L.spp) + " a pixel) in " + std::to_string(stored) +
                          " bytes of chunks, more than any compression it may use can hold");
      }
    }
  }

  const bool parallel =
      (L.compression == COMPRESSION_ADOBE_DEFLATE || L.compression == COMPRESSION_DEFLATE ||
       L.compression == COMPRESSION_NONE) &&
      (L.predictor == PREDICTOR_NONE || (L.predictor == PREDICTOR_HORIZONTAL && L.format == SAMPLEFORMAT_UINT));
  if (!parallel) {
    std::vector<std::uint8_t> buf(chunk_bytes);
    for (std::size_t i = 0; i < chunks.size(); ++i) {
      t_last_error.clear();
      const tmsize_t n = L.tiled ? TIFFReadEncodedTile(t, ttile_t(i), buf.data(), tmsize_t(chunk_bytes))
                                 : TIFFReadEncodedStrip(t, tstrip_t(i), buf.data(), tmsize_t(chunk_bytes));
      if (n < 0) invalid(path, "cannot decode TIFF chunk " + std::to_string(i) + ": " + t_last_error);
      if (std::size_t(n) < chunk_bytes) std::memset(buf.data() + n, 0, chunk_bytes - std::size_t(n));
      place(L, chunks[i], buf.data(), img);
    }
    return img;
  }
  // Raw chunks straight from the mapped file, inflated in parallel.
  const FileBytes file(path);
  std::uint64_t* offsets = nullptr;
  std::uint64_t* sizes = nullptr;
  if (!TIFFGetField(t, L.tiled ? TIFFTAG_TILEOFFSETS : TIFFTAG_STRIPOFFSETS, &offsets) ||
      !TIFFGetField(t, L.tiled ? TIFFTAG_TILEBYTECOUNTS : TIFFTAG_STRIPBYTECOUNTS, &sizes) || !offsets || !sizes) {
    invalid(path, "TIFF without chunk offsets or byte counts");
  }
  const bool swapped = TIFFIsByteSwapped(t);
  std::vector<std::uint64_t> off(offsets, offsets + count), len(sizes, sizes + count);
  for (std::size_t i = 0; i < count; ++i) {
    if (off[i] > file.size() || len[i] > file.size() - off[i]) {
      invalid(path, "TIFF chunk " + std::to_string(i) + " at byte " + std::to_string(off[i]) + " (" +
                        std::to_string(len[i]) + " bytes) runs past the end of the file (" +
                        std::to_string(file.size()) + " bytes)");
    }
  }
  std::string failure;
  std::mutex failure_mutex;
  for_each_row_block(int(count), 4, [&](int i0, int i1) {
    thread_local std::unique_ptr<libdeflate_decompressor, DecompressorFree> d(libdeflate_alloc_decompressor());
    std::vector<std::uint8_t> buf(chunk_bytes);
    for (int i = i0; i < i1; ++i) {
      const std::uint8_t* src = file.data() + off[std::size_t(i)];
      const std::size_t n = std::size_t(len[std::size_t(i)]);
      std::size_t got = 0;
      if (L.compression == COMPRESSION_NONE) {
        got = std::min(n, chunk_bytes);
        std::memcpy(buf.data(), src, got);
      } else if (libdeflate_zlib_decompress(d.get(), src, n, buf.data(), chunk_bytes, &got) != LIBDEFLATE_SUCCESS) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (failure.empty()) failure = "TIFF chunk " + std::to_string(i) + " is not valid deflate data";
        continue;
      }
      if (got < chunk_bytes) std::memset(buf.data() + got, 0, chunk_bytes - got);
      if (swapped && L.bytes() == 2) swap_bytes<std::uint16_t>(buf.data(), chunk_bytes / 2);
      if (swapped && L.bytes() == 4) swap_bytes<std::uint32_t>(buf.data(), chunk_bytes / 4);
      if (L.predictor == PREDICTOR_HORIZONTAL) {
        if (L.bytes() == 1) undo_horizontal_predictor<std::uint8_t>(buf.data(), cw, ch, int(spp_chunk));
        if (L.bytes() == 2) undo_horizontal_predictor<std::uint16_t>(buf.data(), cw, ch, int(spp_chunk));
      }
      place(L, chunks[std::size_t(i)], buf.data(), img);
    }
  });
  file.check_intact(path);
  if (!failure.empty()) invalid(path, failure);
  return img;
}

}  // namespace texproc::codecs
