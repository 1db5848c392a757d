// decode_texture_rows: a band of a level decoded on its own. Blocks (and
// uncompressed texels) are decoded independently of their neighbours, so
// the band of block rows that covers the rows asked for, decoded as a
// texture of its own, gives the bytes the whole level gives there.
#include <algorithm>
#include <cstring>

#include "texproc/block_decode.h"
#include "texproc/error.h"

namespace texproc {

void decode_texture_rows(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face, PixelType type,
                         int y0, int y1, void* dst, std::size_t row_stride) {
  const FormatInfo& info = format_info(t.format);
  const int w = int(t.level_width(level)), h = int(t.level_height(level));
  if (y0 < 0 || y1 > h || y0 >= y1) {
    throw Error(ErrorCode::bad_arguments, "decode_texture_rows: rows " + std::to_string(y0) + " to " +
                                              std::to_string(y1) + " of a level of " + std::to_string(h));
  }
  const int bh = info.block_height;
  const std::size_t band_row_bytes = info.compressed
                                         ? std::size_t((w + info.block_width - 1) / info.block_width) * info.block_bytes
                                         : std::size_t(w) * info.block_bytes;
  const int first = y0 / bh, last = (y1 + bh - 1) / bh;  // block rows
  const PixelBytes& data = t.image(level, layer, face);
  if (data.size() < band_row_bytes * std::size_t(last)) {
    throw Error(ErrorCode::bad_arguments, "decode_texture_rows: the level holds too few bytes");
  }
  Texture band;
  band.format = t.format;
  band.width = std::uint32_t(w);
  band.height = std::uint32_t(std::min(h, last * bh) - first * bh);
  band.images.emplace_back(data.begin() + std::ptrdiff_t(band_row_bytes * first),
                           data.begin() + std::ptrdiff_t(band_row_bytes * last));
  const Image rows = decode_texture_image(band, 0, 0, 0, type);
  if (rows.channels() != info.channels) {
    throw Error(ErrorCode::runtime, std::string("decode_texture_rows: ") + info.name + " decoded to " +
                                        std::to_string(rows.channels()) + " channels");
  }
  const std::size_t bytes = std::size_t(rows.width()) * rows.channels() * bytes_per_channel(rows.type());
  for (int y = y0; y < y1; ++y) {
    std::memcpy(static_cast<std::uint8_t*>(dst) + std::size_t(y - y0) * row_stride,
                rows.row<const std::uint8_t>(y - first * bh), bytes);
  }
}

}  // namespace texproc
