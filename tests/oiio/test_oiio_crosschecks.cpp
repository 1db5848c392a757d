// Cross-checks against OpenImageIO, a reader and writer no one here wrote:
// its DDS, TIFF and OpenEXR readers on texproc's files. In a binary of
// their own because OpenImageIO brings about 250 shared libraries, which
// every test process would otherwise map at start-up.
#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "support/images.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

// A 2D texture of `levels` levels of random bytes in an uncompressed format.
Texture random_levels(TexelFormat f, std::uint32_t w, std::uint32_t h, std::uint32_t levels, unsigned seed) {
  Texture t;
  t.format = f;
  t.width = w;
  t.height = h;
  t.levels = levels;
  std::mt19937 rng(seed);
  for (std::uint32_t l = 0; l < levels; ++l) {
    std::vector<std::uint8_t> b(image_bytes(f, t.level_width(l), t.level_height(l)));
    for (auto& v : b) v = std::uint8_t(rng());
    t.images.push_back(std::move(b));
  }
  return t;
}

}  // namespace

// OpenImageIO's DDS reader on texproc's legacy DDS files of random BC1-BC5
// blocks (DXT1, DXT3, DXT5, ATI1, ATI2): the same texels within the
// rounding of BC1's interpolated colours and of BC4/BC5's 8-bit output.
TEST(BcDecode, OpenImageIoAgreesOnLegacyDds) {
  const std::string dir = temp_dir("bc_oiio");
  std::mt19937 rng(8);
  for (TexelFormat f : {TexelFormat::bc1_rgba_unorm, TexelFormat::bc2_unorm, TexelFormat::bc3_unorm,
                        TexelFormat::bc4_unorm, TexelFormat::bc5_unorm}) {
    Texture t;
    t.format = f;
    t.width = 12;
    t.height = 8;
    std::vector<std::uint8_t> data(image_bytes(f, 12, 8));
    for (auto& b : data) b = std::uint8_t(rng());
    t.images.push_back(data);
    const std::string path = dir + "/" + format_info(f).name + ".dds";
    write_texture(path, t);
    const Image ours = decode_texture_image(t, 0, 0, 0, PixelType::u8);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    ASSERT_TRUE(in) << OIIO::geterror();
    const int C = in->spec().nchannels;
    std::vector<std::uint8_t> px(std::size_t(12) * 8 * C);
    ASSERT_TRUE(in->read_image(0, 0, 0, C, OIIO::TypeDesc::UINT8, px.data()));
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 12; ++x)
        for (int c = 0; c < std::min(C, ours.channels()); ++c) {
          const int a = px[(std::size_t(y) * 12 + x) * C + c], b = ours.row<std::uint8_t>(y)[x * ours.channels() + c];
          ASSERT_LE(std::abs(a - b), 1) << format_info(f).name << " at " << x << "," << y << " c" << c;
        }
  }
  fs::remove_all(dir);
}

// OpenImageIO's DDS reader (which no one here wrote) reads texproc's legacy
// DDS files back with the same pixels: RGBA8, BGRA8, L8 (r8), L8A8 (rg8).
TEST(Container, OpenImageIoReadsLegacyDds) {
  const std::string dir = temp_dir("dds_oiio");
  for (TexelFormat f :
       {TexelFormat::rgba8_unorm, TexelFormat::bgra8_unorm, TexelFormat::r8_unorm, TexelFormat::rg8_unorm}) {
    const Texture t = random_levels(f, 13, 6, 3, 21);
    const std::string path = dir + "/" + format_info(f).name + ".dds";
    write_texture(path, t);
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    ASSERT_TRUE(in) << OIIO::geterror();
    for (std::uint32_t l = 0; l < t.levels; ++l) {
      ASSERT_TRUE(in->seek_subimage(0, int(l)));
      const Image want = image_from_texture(t, l);
      const int C = in->spec().nchannels;
      std::vector<std::uint8_t> px(std::size_t(in->spec().width) * in->spec().height * C);
      ASSERT_TRUE(in->read_image(0, int(l), 0, C, OIIO::TypeDesc::UINT8, px.data()));
      ASSERT_EQ(in->spec().width, want.width());
      for (int y = 0; y < want.height(); ++y)
        for (int x = 0; x < want.width(); ++x) {
          // OIIO reads L8 as one channel, L8A8 as two (gray, alpha).
          for (int c = 0; c < want.channels(); ++c) {
            ASSERT_EQ(px[(std::size_t(y) * want.width() + x) * C + c],
                      want.row<std::uint8_t>(y)[x * want.channels() + c])
                << format_info(f).name << " level " << l << " at " << x << "," << y << " c" << c;
          }
        }
    }
  }
  fs::remove_all(dir);
}

// Two-channel data (BC5, EAC RG11, RG8) decompressed: PNG and TGA get RGB
// with blue 0 (a grey+alpha file would be shown as transparency), OpenEXR
// keeps two channels named R and G.
TEST(ImageCodecs, RedGreenDataIsNotGreyAndAlpha) {
  const std::string dir = temp_dir("redgreen");
  const Image img = random_image(32, 16, 3, PixelType::u8, 9);
  write_image(dir + "/n.png", img.view());
  ASSERT_EQ(run_texproc("compress '" + dir + "/n.png' -o '" + dir + "/n.ktx2' --format bc5 -q").exit_code, 0);
  for (const char* out : {"d.png", "d.tga", "d.exr"}) {
    const RunResult r = run_texproc("decompress '" + dir + "/n.ktx2' -o '" + dir + "/" + out + "' -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const Texture t = read_texture(dir + "/n.ktx2");
  const Image rg = decode_texture_image(t, 0, 0, 0, PixelType::u8);
  for (const char* out : {"d.png", "d.tga"}) {
    const Image d = read_image(dir + "/" + out);
    ASSERT_EQ(d.channels(), 3) << out;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 32; ++x) {
        EXPECT_EQ(d.row<std::uint8_t>(y)[3 * x + 2], 0) << out;
        EXPECT_EQ(d.row<std::uint8_t>(y)[3 * x + 1], rg.row<std::uint8_t>(y)[2 * x + 1]) << out;
      }
  }
  ReadOptions through_oiio;
  through_oiio.io_path = ImageIoPath::oiio;  // OpenImageIO sees the channel names
  const ImageFileInfo e = probe_image(dir + "/d.exr", through_oiio);
  EXPECT_EQ(e.channels, 2);
  auto in = OIIO::ImageInput::open(dir + "/d.exr");
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().channelnames, (std::vector<std::string>{"R", "G"}));
  fs::remove_all(dir);
}

// OpenImageIO must read our TIFF and EXR MIP files back as MIP levels, with
// the levels' pixels intact.
TEST(ImageIo, MipFilesReadBackAsMipLevels) {
  const std::string dir = temp_dir("mipfile");
  const Image img = random_image(40, 24, 4, PixelType::u8, 8);
  const MipChain chain = generate_mips(img.view(), MipOptions{});
  MipOptions fo;
  fo.output_type = PixelType::f32;
  const MipChain fchain = generate_mips(img.view(), fo);
  for (const char* name : {"/m.tif", "/m.exr"}) {
    const std::string path = dir + name;
    const bool exr = std::string(name) == "/m.exr";
    const MipChain& c = exr ? fchain : chain;
    write_mip_file(path, c.levels);
    OIIO::ImageSpec config;  // our alpha is straight; keep OpenImageIO from premultiplying it
    config.attribute("oiio:UnassociatedAlpha", 1);
    auto in = OIIO::ImageInput::open(path, &config);
    ASSERT_TRUE(in) << OIIO::geterror();
    for (std::size_t l = 0; l < c.levels.size(); ++l) {
      ASSERT_TRUE(in->seek_subimage(0, int(l))) << path << " level " << l;
      EXPECT_EQ(in->spec().width, c.levels[l].width());
      EXPECT_EQ(in->spec().height, c.levels[l].height());
      std::vector<float> px(std::size_t(in->spec().width) * in->spec().height * 4);
      ASSERT_TRUE(in->read_image(0, int(l), 0, 4, OIIO::TypeDesc::FLOAT, px.data()));
      for (int y = 0; y < c.levels[l].height(); ++y)
        for (int x = 0; x < c.levels[l].width(); ++x)
          ASSERT_NEAR(px[(y * c.levels[l].width() + x) * 4 + 1], c.levels[l].get(x, y, 1), exr ? 1e-3 : 1e-6);
    }
    EXPECT_FALSE(in->seek_subimage(0, int(c.levels.size())));
  }
  // OpenEXR MIP files hold the whole chain.
  std::vector<Image> partial(chain.levels.begin(), chain.levels.begin() + 2);
  EXPECT_THROW(write_mip_file(dir + "/partial.exr", partial), Error);
  fs::remove_all(dir);
}

// OpenImageIO's DDS reader (which no one here wrote) sees a cube map with
// the faces texproc wrote, in order (it reads legacy headers only: RGBA8 UNORM).
TEST(CubemapCli, OpenImageIoReadsTheDdsCube) {
  const std::string dir = temp_dir("cubeoiio");
  Image p(128, 64, 3, PixelType::u8);
  for (std::size_t k = 0; k < p.byte_size(); ++k) p.data()[k] = std::uint8_t((k * 13) ^ (k >> 7));
  write_image(dir + "/pano.png", p.view());
  const RunResult r =
      run_texproc("cubemap '" + dir + "/pano.png' -o '" + dir + "/env.dds' --mips --linear --dds-header dx9");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture t = read_texture(dir + "/env.dds");
  ASSERT_EQ(t.format, TexelFormat::rgba8_unorm);
  auto in = OIIO::ImageInput::open(dir + "/env.dds");
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().get_string_attribute("textureformat"), "CubeFace Environment");
  EXPECT_EQ(in->spec().full_width, 32);
  ASSERT_EQ(in->spec().height, 6 * 32);  // the six faces stacked, +X first
  std::vector<std::uint8_t> px(std::size_t(32) * 6 * 32 * 4);
  ASSERT_TRUE(in->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, px.data()));
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < 32; y += 5)
      for (int x = 0; x < 32; x += 3)
        for (int c = 0; c < 3; ++c)
          ASSERT_EQ(px[((std::size_t(f) * 32 + y) * 32 + x) * 4 + c],
                    t.image(0, 0, f)[(std::size_t(y) * 32 + x) * 4 + c])
              << "face " << f << " at " << x << "," << y;
  fs::remove_all(dir);
}
