// Images written from rows made on demand, and texture levels decoded band
// by band: the bytes of the whole-image paths.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <filesystem>

#include "support/images.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"
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
  std::vector<Texture> textures = {
      one_level(TexelFormat::bc1_rgb_srgb, rgba),   one_level(TexelFormat::bc3_unorm, rgba),
      one_level(TexelFormat::bc4_snorm, rgba),      one_level(TexelFormat::bc5_unorm, rgba),
      one_level(TexelFormat::bc7_srgb, rgba),       one_level(TexelFormat::etc2_rgba8_unorm, rgba),
      one_level(TexelFormat::eac_rg11_snorm, rgba), one_level(TexelFormat::bc6h_sfloat, hdr)};
  textures.push_back(texture_from_levels({Image(rgba)}, {.srgb = true}));  // uncompressed rgba8
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
        ConstImageView shape = img.view();
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

// A MIP file fed row by row, in a scrambled order from several threads, has
// the bytes of write_mip_file; one not committed, or missing a row, leaves
// nothing.
TEST(StreamedIo, MipFileWriterWritesTheBytesOfWriteMipFile) {
  if (!MipFileWriter::supports("x.exr")) GTEST_SKIP() << "OpenEXR is written through OpenImageIO here";
  const std::string dir = temp_dir("mipfile");
  const Image img = random_image(150, 70, 3, PixelType::f32, 4);
  const MipChain chain = generate_mips(img.view(), MipOptions{});
  for (bool half : {true, false}) {
    WriteOptions w;
    w.half = half;
    const std::string a = dir + "/a.exr", b = dir + "/b.exr";
    write_mip_file(a, chain.levels, w);
    {
      MipFileWriter f(b, img.width(), img.height(), 3, w);
      std::vector<std::pair<int, int>> rows;
      for (std::size_t l = 0; l < chain.levels.size(); ++l)
        for (int y = 0; y < chain.levels[l].height(); ++y) rows.emplace_back(int(l), y);
      std::reverse(rows.begin(), rows.end());
      for (std::size_t i = 0; i + 7 < rows.size(); i += 7) std::swap(rows[i], rows[i + 7]);
      for_each_row_block(int(rows.size()), 5, [&](int i0, int i1) {
        for (int i = i0; i < i1; ++i) {
          const auto [l, y] = rows[std::size_t(i)];
          const Image& level = chain.levels[std::size_t(l)];
          std::memcpy(f.row(l, y), level.row<const float>(y), std::size_t(level.width()) * 3 * sizeof(float));
          f.row_done(l, y);
        }
      });
      f.commit();
    }
    EXPECT_EQ(slurp_file(a), slurp_file(b)) << "half " << half;
  }
  const std::string c = dir + "/c.exr";
  {
    MipFileWriter f(c, 20, 10, 1);
    *f.row(0, 0) = 1.0f;
    f.row_done(0, 0);
  }
  EXPECT_FALSE(fs::exists(c));
  {
    MipFileWriter f(c, 2, 2, 1);
    for (int y = 0; y < 2; ++y) {
      float* r = f.row(0, y);
      r[0] = r[1] = 0.5f;
      f.row_done(0, y);
    }
    EXPECT_THROW(f.commit(), Error);  // level 1 (1x1) never given
  }
  EXPECT_FALSE(fs::exists(c));
  fs::remove_all(dir);
}
