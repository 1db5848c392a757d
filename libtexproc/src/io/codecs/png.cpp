// PNG. libspng decodes (every colour type and bit depth, CRCs checked, chunk
// sizes bounded). The writer is texproc's own, because no PNG library
// deflates on more than one thread: rows are filtered (each row the filter
// with the least sum of absolute values, libpng's heuristic) and deflated in
// strips of a fixed number of rows, one zlib stream ended by a sync flush
// per strip, so the bytes do not depend on the thread count.
#include <spng.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

#include "core/fd_writer.h"
#include "io/codecs/codecs.h"
#include "texproc/error.h"
#include "texproc/runtime.h"
#include "texproc/tools.h"

namespace texproc::codecs {
namespace {

struct SpngFree {
  void operator()(spng_ctx* c) const { spng_ctx_free(c); }
};
using Spng = std::unique_ptr<spng_ctx, SpngFree>;

[[noreturn]] void spng_failed(const std::string& path, int rc) {
  invalid(path, std::string("not a valid PNG: ") + spng_strerror(rc));
}

struct PngLayout {
  spng_ihdr ihdr{};
  int channels = 0;  // after palette expansion and tRNS
  bool sixteen = false;
  int fmt = 0;  // spng_format to decode to
};

Spng open_png(const std::string& path, const FileBytes& f, PngLayout& L) {
  Spng ctx(spng_ctx_new(0));
  if (!ctx) throw Error(ErrorCode::runtime, path + ": out of memory");
  // Sizes are checked against image_read_limits() by check_size, which says so.
  spng_set_image_limits(ctx.get(), 0x7fffffffu, 0x7fffffffu);
  spng_set_chunk_limits(ctx.get(), 64u << 20, 64u << 20);  // text and ancillary chunks: 64 MiB at most
  spng_set_png_buffer(ctx.get(), f.data(), f.size());
  if (int rc = spng_get_ihdr(ctx.get(), &L.ihdr)) spng_failed(path, rc);
  spng_trns trns{};
  const bool has_trns = spng_get_trns(ctx.get(), &trns) == 0;
  L.sixteen = L.ihdr.bit_depth == 16;
  switch (L.ihdr.color_type) {
    case SPNG_COLOR_TYPE_GRAYSCALE:
      L.channels = has_trns ? 2 : 1;
      L.fmt = has_trns ? (L.sixteen ? SPNG_FMT_GA16 : SPNG_FMT_GA8) : (L.sixteen ? SPNG_FMT_PNG : SPNG_FMT_G8);
      break;
    case SPNG_COLOR_TYPE_TRUECOLOR:
      L.channels = has_trns ? 4 : 3;
      L.fmt = has_trns ? (L.sixteen ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8) : (L.sixteen ? SPNG_FMT_PNG : SPNG_FMT_RGB8);
      break;
    case SPNG_COLOR_TYPE_INDEXED:
      L.channels = has_trns ? 4 : 3;
      L.fmt = has_trns ? SPNG_FMT_RGBA8 : SPNG_FMT_RGB8;
      break;
    case SPNG_COLOR_TYPE_GRAYSCALE_ALPHA:  // libspng's GA formats are for grey + tRNS; this is the stored layout
      L.channels = 2;
      L.fmt = SPNG_FMT_PNG;
      break;
    default:
      L.channels = 4;
      L.fmt = L.sixteen ? SPNG_FMT_RGBA16 : SPNG_FMT_RGBA8;
      break;
  }
  return ctx;
}

ImageFileInfo info_of(const std::string& path, spng_ctx* ctx, const PngLayout& L, const ReadLimits& limits) {
  ImageFileInfo info;
  info.format = "png";
  info.width = int(L.ihdr.width);
  info.height = int(L.ihdr.height);
  info.channels = L.channels;
  info.file_type = L.sixteen ? "uint16" : "uint8";
  info.type = L.sixteen ? PixelType::u16 : PixelType::u8;
  // As OpenImageIO 2.4 tags PNG files: sRGB by default and with an sRGB
  // chunk, "GammaX.Y" with a gAMA chunk that is not 1, "linear" for gamma 1.
  std::uint8_t intent = 0;
  std::uint32_t gamma = 0;
  info.color_space_tag = "sRGB";
  struct spng_iccp iccp {};
  info.color_space_tagged = spng_get_srgb(ctx, &intent) == 0 || spng_get_iccp(ctx, &iccp) == 0;
  if (spng_get_srgb(ctx, &intent) != 0 && spng_get_gama_int(ctx, &gamma) == 0 && gamma > 0) {
    info.color_space_tagged = true;
    const float g = std::round(100.0f * float(100000.0 / double(gamma))) / 100.0f;
    if (g == 1.0f) {
      info.color_space_tag = "linear";
    } else {
      char buf[32];
      std::snprintf(buf, sizeof buf, "Gamma%.2g", double(g));
      info.color_space_tag = buf;
    }
  }
  info.level_sizes.emplace_back(info.width, info.height);
  check_size(path, info.width, info.height, info.channels, limits);
  return info;
}

}  // namespace

ImageFileInfo png_probe(const std::string& path, const FileBytes& f, const ReadLimits& limits) {
  PngLayout L;
  Spng ctx = open_png(path, f, L);
  return info_of(path, ctx.get(), L, limits);
}

Image png_read(const std::string& path, const FileBytes& f, ImageFileInfo& info, const ReadLimits& limits) {
  PngLayout L;
  Spng ctx = open_png(path, f, L);
  info = info_of(path, ctx.get(), L, limits);
  Image img = Image::uninitialized(info.width, info.height, info.channels, info.type);
  std::size_t need = 0;
  if (int rc = spng_decoded_image_size(ctx.get(), L.fmt, &need)) spng_failed(path, rc);
  if (need != img.byte_size()) invalid(path, "decoded size does not match the header");
  const int flags = L.fmt == SPNG_FMT_PNG ? 0 : SPNG_DECODE_TRNS;
  if (int rc = spng_decode_image(ctx.get(), img.data(), need, L.fmt, flags)) spng_failed(path, rc);
  // The chunks after the pixels, through IEND: a cut file is refused.
  if (int rc = spng_decode_chunks(ctx.get())) spng_failed(path, rc);
  return img;
}

// ---- writing ------------------------------------------------------------

namespace {

void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out.push_back(std::uint8_t(v >> s));
}

void chunk(std::vector<std::uint8_t>& out, const char type[4], const std::uint8_t* data, std::size_t n) {
  put32(out, std::uint32_t(n));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data, data + n);
  put32(out, std::uint32_t(crc32(0, out.data() + start, uInt(n + 4))));
}

// PNG's filters on byte i of a row: x the byte, a the one bpp bytes left, b
// the one above, c above-left (0 outside the image).
inline int paeth(int a, int b, int c) {
  const int pa = std::abs(b - c), pb = std::abs(a - c), pc = std::abs(a + b - 2 * c);
  return pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
}
inline unsigned magnitude(int filtered) {  // the byte read as signed, libpng's measure
  const int v = std::int8_t(std::uint8_t(filtered));
  return unsigned(v < 0 ? -v : v);
}

// The five filters' scores over a row (loops the compiler vectorizes).
void score_filters(const std::uint8_t* x, const std::uint8_t* b, std::size_t n, std::size_t B, std::uint64_t s[5]) {
  unsigned none = 0, sub = 0, up = 0, avg = 0, pae = 0;
  for (std::size_t i = 0; i < std::min(B, n); ++i) {  // no left neighbour
    none += magnitude(x[i]);
    sub += magnitude(x[i]);
    up += magnitude(x[i] - b[i]);
    avg += magnitude(x[i] - (b[i] >> 1));
    pae += magnitude(x[i] - b[i]);
  }
  s[0] = none;
  s[1] = sub;
  s[2] = up;
  s[3] = avg;
  s[4] = pae;
  // Chunks keep the unsigned sums from overflowing.
  for (std::size_t i0 = B; i0 < n; i0 += 1 << 16) {
    const std::size_t i1 = std::min(n, i0 + (std::size_t(1) << 16));
    none = sub = up = avg = pae = 0;
    for (std::size_t i = i0; i < i1; ++i) none += magnitude(x[i]);
    for (std::size_t i = i0; i < i1; ++i) sub += magnitude(x[i] - x[i - B]);
    for (std::size_t i = i0; i < i1; ++i) up += magnitude(x[i] - b[i]);
    for (std::size_t i = i0; i < i1; ++i) avg += magnitude(x[i] - ((x[i - B] + b[i]) >> 1));
    for (std::size_t i = i0; i < i1; ++i) pae += magnitude(x[i] - paeth(x[i - B], b[i], b[i - B]));
    s[0] += none;
    s[1] += sub;
    s[2] += up;
    s[3] += avg;
    s[4] += pae;
  }
}

// Filters one row of `n` bytes (`prev` the row above, all zeros for the
// first row) into out[0] (the filter type) and out[1..n]: the filter with
// the least score, libpng's heuristic.
void filter_row(const std::uint8_t* row, const std::uint8_t* prev, std::size_t n, int bpp, std::uint8_t* out) {
  const std::size_t B = std::size_t(bpp);
  std::uint64_t s[5];
  score_filters(row, prev, n, B, s);
  int best = 0;
  for (int k = 1; k < 5; ++k)
    if (s[k] < s[best]) best = k;
  out[0] = std::uint8_t(best);
  std::uint8_t* o = out + 1;
  const std::size_t head = std::min(B, n);
  for (std::size_t i = 0; i < head; ++i) {
    const int x = row[i], b = prev[i];
    o[i] = std::uint8_t(best == 0 || best == 1 ? x : best == 3 ? x - (b >> 1) : x - b);
  }
  switch (best) {
    case 0:
      std::memcpy(o + head, row + head, n - head);
      break;
    case 1:
      for (std::size_t i = B; i < n; ++i) o[i] = std::uint8_t(row[i] - row[i - B]);
      break;
    case 2:
      for (std::size_t i = B; i < n; ++i) o[i] = std::uint8_t(row[i] - prev[i]);
      break;
    case 3:
      for (std::size_t i = B; i < n; ++i) o[i] = std::uint8_t(row[i] - ((row[i - B] + prev[i]) >> 1));
      break;
    default:
      for (std::size_t i = B; i < n; ++i) o[i] = std::uint8_t(row[i] - paeth(row[i - B], prev[i], prev[i - B]));
      break;
  }
}

struct Deflate {
  int level, strategy;
};

// The default is zlib's run-length strategy: on filtered rows it is both the
// fastest and, on the corpus, the smallest (4096x4096 16-bit normal map:
// 59.1 MB in 1.8 s against level 1's 66.0 MB in 2.2 s and level 6's 63.8 MB
// in 5.0 s; 2048x2048 albedo 3.66 MB against 4.55 and 3.92 MB). zip:N asks
// for zlib's usual matching at level N.
Deflate png_level(const std::string& path, const std::string& c) {
  if (c.empty()) return {1, Z_RLE};
  if (c == "none") return {0, Z_DEFAULT_STRATEGY};
  if (c.rfind("zip:", 0) == 0) {
    const int level = std::atoi(c.c_str() + 4);
    if (level >= 0 && level <= 9 && c.size() > 4) return {level, Z_DEFAULT_STRATEGY};
  }
  if (c == "zip" || c == "deflate") return {6, Z_DEFAULT_STRATEGY};
  throw Error(ErrorCode::bad_arguments, path + ": PNG compression '" + c + "' (valid: zip:0 to zip:9, zip, none)");
}

}  // namespace

void png_write(const std::string& file, const std::string& path, const ConstImageView& v, const WriteOptions& o) {
  png_write(file, path, v, RowSource{}, o);
}

void png_write(const std::string& file, const std::string& path, const ConstImageView& v, const RowSource& source,
               const WriteOptions& o) {
  const Deflate level = png_level(path, o.compression);
  const bool sixteen = v.type != PixelType::u8;
  const int bps = sixteen ? 2 : 1;
  const int bpp = v.channels * bps;
  const std::size_t row_bytes = std::size_t(v.width) * bpp;
  // Rows as PNG stores them (big-endian 16-bit; float clamped and rounded
  // to 16 bits, as OpenImageIO writes float to PNG).
  auto png_row = [&](const void* src, std::uint8_t* dst) {
    if (v.type == PixelType::u8) {
      std::memcpy(dst, src, row_bytes);
    } else if (v.type == PixelType::u16) {
      const auto* s = static_cast<const std::uint16_t*>(src);
      for (std::size_t i = 0; i < std::size_t(v.width) * v.channels; ++i) {
        dst[2 * i] = std::uint8_t(s[i] >> 8);
        dst[2 * i + 1] = std::uint8_t(s[i]);
      }
    } else {
      const auto* s = static_cast<const float*>(src);
      for (std::size_t i = 0; i < std::size_t(v.width) * v.channels; ++i) {
        const float c = std::clamp(s[i], 0.0f, 1.0f);
        const auto q = std::uint16_t(std::lround(c * 65535.0f));
        dst[2 * i] = std::uint8_t(q >> 8);
        dst[2 * i + 1] = std::uint8_t(q);
      }
    }
  };
  // Strips of at least 256 KiB of pixels: fixed by the image, not by threads.
  const int strip_rows = int(std::max<std::size_t>(1, (std::size_t(256) << 10) / std::max<std::size_t>(row_bytes, 1)));
  const int strips = (v.height + strip_rows - 1) / strip_rows;
  // The file's head, then the strips, each deflated on any thread and
  // written (and freed) in order as soon as those before it are: the
  // compressed image is never held whole.
  std::vector<std::uint8_t> head;
  static const std::uint8_t kSig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  head.insert(head.end(), kSig, kSig + 8);
  std::uint8_t ihdr[13];
  for (int i = 0; i < 4; ++i) ihdr[i] = std::uint8_t(std::uint32_t(v.width) >> (24 - 8 * i));
  for (int i = 0; i < 4; ++i) ihdr[4 + i] = std::uint8_t(std::uint32_t(v.height) >> (24 - 8 * i));
  ihdr[8] = std::uint8_t(8 * bps);
  static const std::uint8_t kColorType[5] = {0, 0, 4, 2, 6};
  ihdr[9] = kColorType[v.channels];
  ihdr[10] = ihdr[11] = ihdr[12] = 0;
  chunk(head, "IHDR", ihdr, 13);
  if (o.color_space == "srgb") {
    const std::uint8_t intent = 0;  // perceptual
    chunk(head, "sRGB", &intent, 1);
  } else if (o.color_space == "linear") {
    const std::uint8_t gama[4] = {0, 1, 0x86, 0xA0};  // 100000: gamma 1.0
    chunk(head, "gAMA", gama, 4);
  }
  static const char kSoftware[] = "Software\0texproc";
  chunk(head, "tEXt", reinterpret_cast<const std::uint8_t*>(kSoftware), sizeof kSoftware - 1);
  FdWriter w(file, path);
  w.write(head.data(), head.size());

  struct Strip {
    std::vector<std::uint8_t> deflated;
    uLong adler = 1, length = 0;
  };
  std::vector<Strip> out(static_cast<std::size_t>(strips));
  uLong total_adler = 1;  // of every filtered row so far, for the zlib trailer
  for_each_in_order(
      std::size_t(strips), std::size_t(std::max(1, thread_limit())),
      [&](std::size_t index) {
        const int s = int(index);
        std::vector<std::uint8_t> prev(row_bytes, 0), cur(row_bytes);
        const int y0 = s * strip_rows, y1 = std::min(v.height, y0 + strip_rows);
        std::vector<std::uint8_t> filtered(std::size_t(y1 - y0) * (row_bytes + 1));
        // Rows made on demand: the strip's and the one above it.
        const int f0 = std::max(0, y0 - 1);
        const std::size_t pixel_row = std::size_t(v.width) * v.channels * bytes_per_channel(v.type);
        std::vector<std::uint8_t> made;
        if (source) {
          made.resize(std::size_t(y1 - f0) * pixel_row);
          source(f0, y1, made.data(), pixel_row);
        }
        auto src = [&](int y) -> const void* {
          return source ? made.data() + std::size_t(y - f0) * pixel_row : v.row<const void>(y);
        };
        if (y0 > 0) png_row(src(y0 - 1), prev.data());
        for (int y = y0; y < y1; ++y) {
          png_row(src(y), cur.data());
          filter_row(cur.data(), prev.data(), row_bytes, bpp, filtered.data() + std::size_t(y - y0) * (row_bytes + 1));
          std::swap(prev, cur);
        }
        Strip& strip = out[index];
        strip.adler = adler32(1, filtered.data(), uInt(filtered.size()));
        strip.length = uLong(filtered.size());
        z_stream z{};
        if (deflateInit2(&z, level.level, Z_DEFLATED, -15, 8, level.strategy) != Z_OK) {
          throw Error(ErrorCode::runtime, path + ": zlib could not start");
        }
        std::vector<std::uint8_t>& dst = strip.deflated;
        dst.resize(deflateBound(&z, uLong(filtered.size())) + 16);
        z.next_in = filtered.data();
        z.avail_in = uInt(filtered.size());
        z.next_out = dst.data();
        z.avail_out = uInt(dst.size());
        const int rc = deflate(&z, s + 1 == strips ? Z_FINISH : Z_SYNC_FLUSH);
        const bool ok = s + 1 == strips ? rc == Z_STREAM_END : rc == Z_OK && z.avail_in == 0;
        dst.resize(z.total_out);
        deflateEnd(&z);
        if (!ok) throw Error(ErrorCode::runtime, path + ": zlib could not compress");
      },
      [&](std::size_t index) {
        // IDAT chunks: the zlib header with the first strip, one chunk per
        // strip, the Adler-32 of all filtered rows with the last.
        const int s = int(index);
        Strip& strip = out[index];
        total_adler = s == 0 ? strip.adler : adler32_combine(total_adler, strip.adler, z_off_t(strip.length));
        std::vector<std::uint8_t> idat;
        if (s == 0) {
          const int flevel = level.level <= 1 ? 0 : level.level < 6 ? 1 : level.level == 6 ? 2 : 3;
          std::uint16_t h = std::uint16_t((0x78 << 8) | (flevel << 6));
          h = std::uint16_t(h + (31 - h % 31) % 31);
          idat.push_back(std::uint8_t(h >> 8));
          idat.push_back(std::uint8_t(h));
        }
        idat.insert(idat.end(), strip.deflated.begin(), strip.deflated.end());
        strip.deflated = std::vector<std::uint8_t>();  // freed
        if (s + 1 == strips) put32(idat, std::uint32_t(total_adler));
        std::vector<std::uint8_t> c;
        chunk(c, "IDAT", idat.data(), idat.size());
        w.write(c.data(), c.size());
        return true;
      });
  std::vector<std::uint8_t> tail;
  chunk(tail, "IEND", nullptr, 0);
  w.write(tail.data(), tail.size());
  w.close();
}

}  // namespace texproc::codecs
