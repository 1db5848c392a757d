// OpenImageIO 2.4 writes TIFF tiles one after another on one thread, and a
// 4096x4096 RGBA8 chain takes seconds to deflate that way. Here libtiff lays
// out the file and libdeflate compresses the tiles of each level in parallel;
// tiles are written in order, so the bytes do not depend on the thread count.
#include "io/tiff_mip_writer.h"

#include <libdeflate.h>
#include <tiffio.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>

#include "io/codecs/codecs.h"
#include "texproc/error.h"
#include "texproc/runtime.h"
#include "texproc/tools.h"

namespace texproc {
namespace {

constexpr int kTile = 64;

struct TiffCloser {
  void operator()(TIFF* t) const { TIFFClose(t); }
};
struct CompressorFree {
  void operator()(libdeflate_compressor* c) const { libdeflate_free_compressor(c); }
};

// -1: not deflate; 0: no compression; 1..12: deflate level.
int deflate_level(const std::string& c) {
  if (c.empty()) return kDefaultZipLevel;
  if (c == "none") return 0;
  for (const char* name : {"zip", "deflate"}) {
    const std::string n(name);
    if (c == n) return kDefaultZipLevel;
    if (c.rfind(n + ":", 0) == 0) {
      try {
        const int level = std::stoi(c.substr(n.size() + 1));
        if (level >= 1 && level <= 12) return level;
      } catch (...) {
      }
      throw Error(ErrorCode::bad_arguments, "WriteOptions::compression " + c + ": the deflate level must be 1 to 12");
    }
  }
  return -1;
}

// The OS error when there is one (a full disk, a failed device), else
// libtiff's own message.
[[noreturn]] void fail(const std::string& path, const std::string& what) {
  const int err = errno;
  const std::string why = err ? std::strerror(err) : codecs::libtiff_last_error();
  throw Error(ErrorCode::io, path + ": cannot write: " + what + (why.empty() ? "" : ": " + why));
}

int other_compression(const std::string& c) {
  if (c == "lzw") return COMPRESSION_LZW;
  if (c == "packbits") return COMPRESSION_PACKBITS;
  return -1;
}

void set_level_fields(TIFF* tif, const ConstImageView& im, int level, bool mip_file, int compression_tag) {
  TIFFSetField(tif, TIFFTAG_SUBFILETYPE, level == 0 ? 0 : FILETYPE_REDUCEDIMAGE);
  TIFFSetField(tif, TIFFTAG_IMAGEWIDTH, std::uint32_t(im.width));
  TIFFSetField(tif, TIFFTAG_IMAGELENGTH, std::uint32_t(im.height));
  TIFFSetField(tif, TIFFTAG_TILEWIDTH, std::uint32_t(kTile));
  TIFFSetField(tif, TIFFTAG_TILELENGTH, std::uint32_t(kTile));
  TIFFSetField(tif, TIFFTAG_SAMPLESPERPIXEL, std::uint16_t(im.channels));
  TIFFSetField(tif, TIFFTAG_BITSPERSAMPLE, std::uint16_t(8 * bytes_per_channel(im.type)));
  TIFFSetField(tif, TIFFTAG_SAMPLEFORMAT, is_float(im.type) ? SAMPLEFORMAT_IEEEFP : SAMPLEFORMAT_UINT);
  TIFFSetField(tif, TIFFTAG_PHOTOMETRIC, im.channels >= 3 ? PHOTOMETRIC_RGB : PHOTOMETRIC_MINISBLACK);
  TIFFSetField(tif, TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
  TIFFSetField(tif, TIFFTAG_ORIENTATION, ORIENTATION_TOPLEFT);
  TIFFSetField(tif, TIFFTAG_COMPRESSION, compression_tag);
  if (im.channels == 2 || im.channels == 4) {
    const std::uint16_t extra = EXTRASAMPLE_UNASSALPHA;
    TIFFSetField(tif, TIFFTAG_EXTRASAMPLES, 1, &extra);
  }
  TIFFSetField(tif, TIFFTAG_SOFTWARE, "texproc");
  // What maketx writes, and what tells OpenImageIO the subimages are MIP levels.
  if (mip_file) TIFFSetField(tif, TIFFTAG_PIXAR_TEXTUREFORMAT, "Plain Texture");
  if (compression_tag != COMPRESSION_NONE && !is_float(im.type)) {
    TIFFSetField(tif, TIFFTAG_PREDICTOR, PREDICTOR_HORIZONTAL);
  }
}

// TIFF predictor 2: each sample minus the same channel of the pixel to its
// left, within a tile row (mod 2^bits). Deflate then sees small numbers.
template <typename T>
void horizontal_difference(std::uint8_t* tile, int channels) {
  for (int y = 0; y < kTile; ++y) {
    T* row = reinterpret_cast<T*>(tile) + std::size_t(y) * kTile * channels;
    for (int i = kTile * channels - 1; i >= channels; --i) row[i] = T(row[i] - row[i - channels]);
  }
}

}  // namespace

bool tiff_levels_supported(const std::string& compression) {
  return other_compression(compression) >= 0 || deflate_level(compression) >= 0;
}

void write_tiff_levels(const std::string& file, const std::string& error_path,
                       const std::vector<ConstImageView>& levels, bool mip_file, const std::string& compression) {
  const int other = other_compression(compression);
  const int level_of_deflate = other >= 0 ? -1 : deflate_level(compression);
  codecs::quiet_libtiff();
  errno = 0;
  std::unique_ptr<TIFF, TiffCloser> tif(TIFFOpen(file.c_str(), "w"));
  if (!tif) fail(error_path, "cannot create the file");
  const int tag = other >= 0 ? other : level_of_deflate == 0 ? COMPRESSION_NONE : COMPRESSION_ADOBE_DEFLATE;

  for (std::size_t l = 0; l < levels.size(); ++l) {
    const ConstImageView& im = levels[l];
    set_level_fields(tif.get(), im, int(l), mip_file, tag);
    const int tiles_x = (im.width + kTile - 1) / kTile, tiles_y = (im.height + kTile - 1) / kTile;
    const std::size_t px = std::size_t(im.channels) * bytes_per_channel(im.type);
    const std::size_t tile_bytes = std::size_t(kTile) * kTile * px;
    auto fill_tile = [&](std::vector<std::uint8_t>& raw, int tx, int ty) {
      // Edge tiles are padded with zeros, never with stale memory.
      std::fill(raw.begin(), raw.end(), std::uint8_t(0));
      const int w = std::min(kTile, im.width - tx * kTile), h = std::min(kTile, im.height - ty * kTile);
      for (int y = 0; y < h; ++y) {
        std::memcpy(raw.data() + std::size_t(y) * kTile * px,
                    im.row<std::uint8_t>(ty * kTile + y) + std::size_t(tx) * kTile * px, std::size_t(w) * px);
      }
    };
    if (other >= 0) {  // libtiff's own encoder, one tile after another
      std::vector<std::uint8_t> raw(tile_bytes);
      for (int ty = 0; ty < tiles_y; ++ty) {
        for (int tx = 0; tx < tiles_x; ++tx) {
          fill_tile(raw, tx, ty);
          const ttile_t index = TIFFComputeTile(tif.get(), std::uint32_t(tx * kTile), std::uint32_t(ty * kTile), 0, 0);
          if (TIFFWriteEncodedTile(tif.get(), index, raw.data(), tmsize_t(tile_bytes)) < 0)
            fail(error_path, "tile write failed");
        }
      }
      if (!TIFFWriteDirectory(tif.get())) fail(error_path, "directory write failed");
      continue;
    }
    // A row of tiles a task, deflated on any thread and written (and freed)
    // in order as soon as the rows before it are: the compressed level is
    // never held whole.
    std::vector<std::vector<std::vector<std::uint8_t>>> out(static_cast<std::size_t>(tiles_y));
    for_each_in_order(
        std::size_t(tiles_y), std::size_t(std::max(1, thread_limit())),
        [&](std::size_t row) {
          const int ty = int(row);
          thread_local std::vector<std::uint8_t> raw;
          raw.resize(tile_bytes);
          // A compressor holds large hash tables: one per thread and level.
          thread_local std::unique_ptr<libdeflate_compressor, CompressorFree> comp;
          thread_local int comp_level = -1;
          if (level_of_deflate > 0 && comp_level != level_of_deflate) {
            comp.reset(libdeflate_alloc_compressor(level_of_deflate));
            comp_level = level_of_deflate;
          }
          out[row].resize(std::size_t(tiles_x));
          for (int tx = 0; tx < tiles_x; ++tx) {
            fill_tile(raw, tx, ty);
            std::vector<std::uint8_t>& dst = out[row][std::size_t(tx)];
            if (level_of_deflate == 0) {
              dst = raw;
              continue;
            }
            if (im.type == PixelType::u8) horizontal_difference<std::uint8_t>(raw.data(), im.channels);
            if (im.type == PixelType::u16) horizontal_difference<std::uint16_t>(raw.data(), im.channels);
            dst.resize(libdeflate_zlib_compress_bound(comp.get(), tile_bytes));
            const std::size_t n = libdeflate_zlib_compress(comp.get(), raw.data(), tile_bytes, dst.data(), dst.size());
            dst.resize(n);
          }
        },
        [&](std::size_t row) {
          const int ty = int(row);
          for (int tx = 0; tx < tiles_x; ++tx) {
            auto& t = out[row][std::size_t(tx)];
            const ttile_t index =
                TIFFComputeTile(tif.get(), std::uint32_t(tx * kTile), std::uint32_t(ty * kTile), 0, 0);
            if (TIFFWriteRawTile(tif.get(), index, t.data(), tmsize_t(t.size())) < 0)
              fail(error_path, "tile write failed");
          }
          out[row] = {};  // freed
          return true;
        });
    if (!TIFFWriteDirectory(tif.get())) fail(error_path, "directory write failed");
  }
  TIFF* raw = tif.release();
  TIFFClose(raw);
}

}  // namespace texproc
