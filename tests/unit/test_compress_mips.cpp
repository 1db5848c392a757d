// A chain block-compressed as it is filtered (compress_texture_mips) has the
// bytes of the chain filtered whole and then compressed (generate_mips, then
// compress_texture): every block format, odd sizes, layouts, surfaces and
// thread counts.
#include <gtest/gtest.h>

#include <cstring>

#include "support/images.h"
#include "texproc/block_encode.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;

namespace {

Texture whole(const std::vector<Image>& surfaces, const MipOptions& m, std::uint32_t faces, TexelFormat f, Quality q,
              const TextureEncodeOptions& o) {
  std::vector<std::vector<Image>> chains;
  for (const Image& s : surfaces) chains.push_back(generate_mips(s.view(), m).levels);
  return compress_texture(chains, {.faces = faces}, f, q, o);
}

::testing::AssertionResult same(const Texture& a, const Texture& b) {
  if (a.levels != b.levels || a.images.size() != b.images.size()) return ::testing::AssertionFailure() << "shape";
  for (std::size_t i = 0; i < a.images.size(); ++i) {
    if (!(a.images[i] == b.images[i])) return ::testing::AssertionFailure() << "image " << i << " differs";
  }
  return ::testing::AssertionSuccess();
}

std::vector<Image> copies(const std::vector<Image>& v) {
  std::vector<Image> out;
  for (const Image& i : v) out.emplace_back(i);
  return out;
}

}  // namespace

TEST(CompressMips, SameBytesAsWholeChainsForEveryBlockFormat) {
  const TexelFormat formats[] = {
      TexelFormat::bc1_rgb_srgb,    TexelFormat::bc1_rgba_unorm, TexelFormat::bc2_unorm,
      TexelFormat::bc3_srgb,        TexelFormat::bc4_unorm,      TexelFormat::bc5_snorm,
      TexelFormat::bc7_srgb,        TexelFormat::etc1_rgb,       TexelFormat::etc2_rgba8_unorm,
      TexelFormat::etc2_rgba1_srgb, TexelFormat::eac_r11_unorm,  TexelFormat::eac_rg11_unorm};
  const int sizes[][2] = {{37, 21}, {8, 130}, {1, 5}};
  for (const auto& wh : sizes) {
    const std::vector<Image> in{random_image(wh[0], wh[1], 4, PixelType::u8, unsigned(wh[0] + wh[1]))};
    for (TexelFormat f : formats) {
      SCOPED_TRACE(std::string(format_info(f).name) + " " + std::to_string(wh[0]) + "x" + std::to_string(wh[1]));
      MipOptions m;
      m.color_space = format_info(f).srgb ? "srgb" : "linear";
      m.wrap = WrapMode::repeat;
      std::vector<Image> s = copies(in);
      const Texture streamed = compress_texture_mips(s, m, {}, f, Quality::fast);
      EXPECT_TRUE(same(streamed, whole(in, m, 1, f, Quality::fast, {})));
    }
  }
}

TEST(CompressMips, SameBytesForHdrLayoutsSurfacesAndThreads) {
  // BC6H from floats.
  {
    const std::vector<Image> in{random_image(45, 19, 3, PixelType::f32, 2)};
    std::vector<Image> s = copies(in);
    MipOptions m;
    EXPECT_TRUE(same(compress_texture_mips(s, m, {}, TexelFormat::bc6h_ufloat, Quality::fast),
                     whole(in, m, 1, TexelFormat::bc6h_ufloat, Quality::fast, {})));
  }
  // DXT5nm normal maps, the transparent colour set to zero, six faces.
  std::vector<Image> faces;
  for (unsigned i = 0; i < 6; ++i) faces.push_back(random_image(24, 24, 4, PixelType::u8, 10 + i));
  TextureEncodeOptions nm;
  nm.normal_map = true;
  MipOptions mn;
  mn.normal_map = true;
  mn.color_space = "linear";
  TextureEncodeOptions zero;
  zero.transparent = TransparentColor::zero;
  MipOptions mz;
  mz.color_space = "srgb";
  for (int threads : {1, 3}) {
    ThreadLimit limit(threads);
    std::vector<Image> a = copies(faces), b = copies(faces);
    EXPECT_TRUE(same(compress_texture_mips(a, mn, {.faces = 6}, TexelFormat::bc3_unorm, Quality::normal, nm),
                     whole(faces, mn, 6, TexelFormat::bc3_unorm, Quality::normal, nm)));
    EXPECT_TRUE(same(compress_texture_mips(b, mz, {.faces = 6}, TexelFormat::bc7_srgb, Quality::fast, zero),
                     whole(faces, mz, 6, TexelFormat::bc7_srgb, Quality::fast, zero)));
  }
}

// On return the images hold level 0 as encoded (what --report measures),
// and progress rises to 1.
TEST(CompressMips, LeavesLevelZeroAsEncodedAndReportsProgress) {
  const std::vector<Image> in{random_image(40, 40, 4, PixelType::u8, 7)};
  std::vector<Image> s = copies(in);
  TextureEncodeOptions o;
  o.normal_map = true;
  double last = 0.0;
  bool rising = true;
  o.encode.progress = [&](double f) {
    rising = rising && f >= last;
    last = f;
  };
  MipOptions m;
  m.normal_map = true;
  compress_texture_mips(s, m, {}, TexelFormat::bc3_unorm, Quality::fast, o);
  const Image expected = dxt5nm_layout(in[0].view());
  ASSERT_EQ(s[0].byte_size(), expected.byte_size());
  EXPECT_EQ(std::memcmp(s[0].data(), expected.data(), expected.byte_size()), 0);
  EXPECT_TRUE(rising);
  EXPECT_DOUBLE_EQ(last, 1.0);
}
