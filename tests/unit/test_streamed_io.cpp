// Images written from rows made on demand, and texture levels decoded band
// by band: the bytes of the whole-image paths.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <filesystem>

#include "support/images.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/texture.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

Texture one_level(TexelFormat f, const Image& img, Quality q = Quality::fast) {
  Texture t;
  t.format = f;
  t.width = std::uint32_t(img.width());
  t.height = std::uint32_t(img.height());
  t.images.emplace_back(compress_image(img.view(), f, q));
  return t;
}

}  // namespace

TEST(StreamedIo, DecodedRowsAreTheWholeLevelsRows) {
  const Image rgba = random_image(37, 21, 4, PixelType::u8, 1);
  const Image hdr = random_image(19, 13, 3, PixelType::f32, 2);
  std::vector<Texture> textures = {one_level(TexelFormat::bc1_rgb_srgb, rgba),   one_level(TexelFormat::bc3_unorm, rgba),
                                   one_level(TexelFormat::bc4_snorm, rgba),      one_level(TexelFormat::bc5_unorm, rgba),
                                   one_level(TexelFormat::bc7_srgb, rgba),       one_level(TexelFormat::etc2_rgba8_unorm, rgba),
                                   one_level(TexelFormat::eac_rg11_snorm, rgba), one_level(TexelFormat::bc6h_sfloat, hdr)};
  textures.push_back(texture_from_levels({Image(rgba)}, true, false));  // uncompressed rgba8
  for (const Texture& t : textures) {
    for (PixelType type : {PixelType::u8, PixelType::u16, PixelType::f32}) {
      SCOPED_TRACE(std::string(format_info(t.format).name) + " " + to_string(type));
      const Image whole = decode_texture_image(t, 0, 0, 0, type);
      ASSERT_EQ(whole.channels(), format_info(t.format).channels);
      const std::size_t bytes = std::size_t(whole.width()) * whole.channels() * bytes_per_channel(type);
      for (const auto& r : {std::pair{0, 1}, std::pair{3, 9}, std::pair{5, 6}, std::pair{0, int(t.height)},
                            std::pair{int(t.height) - 2, int(t.height)}}) {
        std::vector<std::uint8_t> rows(bytes * std::size_t(r.second - r.first) + 7, 0xCD);
        decode_texture_rows(t, 0, 0, 0, type, r.first, r.second, rows.data() + 7, bytes);
        for (int y = r.first; y < r.second; ++y) {
          EXPECT_EQ(std::memcmp(rows.data() + 7 + std::size_t(y - r.first) * bytes, whole.row<const void>(y), bytes), 0)
              << "row " << y << " of " << r.first << ".." << r.second;
        }
      }
    }
  }
  EXPECT_THROW(decode_texture_rows(textures[0], 0, 0, 0, PixelType::u8, 20, 22, nullptr, 0), Error);
}

TEST(StreamedIo, RowSourceWritesTheBytesOfTheWholeImage) {
  const fs::path dir = temp_dir("rows");
  for (PixelType type : {PixelType::u8, PixelType::u16, PixelType::f32}) {
    for (int channels = 1; channels <= 4; ++channels) {
      // Tall enough for several strips of the PNG writer.
      const Image img = random_image(300, 700, channels, type, unsigned(channels) + 10 * int(type));
      for (const char* ext : {".png", ".tga"}) {
        SCOPED_TRACE(std::string(ext) + " " + to_string(type) + " " + std::to_string(channels));
        const std::string a = (dir / (std::string("a") + ext)).string(), b = (dir / (std::string("b") + ext)).string();
        write_image(a, img.view());
        std::atomic<long> asked{0};
        ImageView shape = img.view();
        shape.data = nullptr;
        write_image(b, shape, [&](int y0, int y1, void* dst, std::size_t stride) {
          EXPECT_TRUE(y0 >= 0 && y0 < y1 && y1 <= img.height());
          asked += y1 - y0;
          for (int y = y0; y < y1; ++y) {
            std::memcpy(static_cast<std::uint8_t*>(dst) + std::size_t(y - y0) * stride, img.row<const void>(y),
                        std::size_t(img.width()) * channels * bytes_per_channel(type));
          }
        });
        EXPECT_EQ(slurp_file(a), slurp_file(b));
        EXPECT_GE(asked.load(), img.height());
      }
    }
  }
  fs::remove_all(dir);
}
