// texproc compress of a texture: every level, face and layer it has is
// encoded as it is (--levels N keeps the first N); --mips makes a new chain
// from level 0 and says so.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/images.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/texture.h"

using namespace texproc;
using namespace texproc::test;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// A level of one colour (RGBA floats).
Image flat_level(int size, const float rgba[4], int channels, PixelType type) {
  Image img(size, size, channels, type);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      for (int c = 0; c < channels; ++c) img.set(x, y, c, rgba[c]);
  return img;
}

// Level l of surface s: a colour no filter of the levels above would make.
void colour_of(int surface, int level, float rgba[4]) {
  rgba[0] = float((surface * 37 + level * 53) % 11) / 10.0f;
  rgba[1] = float((surface * 17 + level * 29 + 3) % 7) / 6.0f;
  rgba[2] = level % 2 ? 0.9f : 0.1f;
  rgba[3] = 1.0f;
}

// The mean of channel c over level `level` of surface (layer, face).
double mean_of(const Texture& t, std::uint32_t level, std::uint32_t face, int c) {
  const Image img = decode_texture_image(t, level, 0, face, PixelType::f32);
  double sum = 0;
  for (int y = 0; y < img.height(); ++y)
    for (int x = 0; x < img.width(); ++x) sum += img.get(x, y, c);
  return sum / (double(img.width()) * img.height());
}

}  // namespace

// A hand-made HDR chain (levels that are not a filter of level 0) to BC6H:
// every level comes through as it is, --levels keeps the first ones, and
// --mips replaces them with a filtered chain and says so.
TEST(CompressChains, TextureInputKeepsEveryLevel) {
  const std::string dir = temp_dir("compress_chains");
  std::vector<Image> levels;
  for (int l = 0, size = 32; size >= 1; ++l, size /= 2) {
    float rgba[4];
    colour_of(0, l, rgba);
    levels.push_back(flat_level(size, rgba, 4, PixelType::f32));
  }
  const std::string in = dir + "/chain.ktx2";
  write_texture(in, texture_from_levels(levels, {.half = true}));
  const std::string out = dir + "/bc6h.ktx2";
  RunResult r = run_texproc("compress " + q(in) + " -o " + q(out) + " --format bc6h");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Texture t = read_texture(out);
  ASSERT_EQ(t.levels, 6u);
  for (std::uint32_t l = 0; l < t.levels; ++l) {
    float want[4];
    colour_of(0, int(l), want);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean_of(t, l, 0, c), want[c], 0.01) << "level " << l << " channel " << c;
  }

  ASSERT_EQ(
      run_texproc("compress " + q(in) + " -o " + q(dir + "/three.ktx2") + " --format bc6h --levels 3 -q").exit_code, 0);
  EXPECT_EQ(read_texture(dir + "/three.ktx2").levels, 3u);

  r = run_texproc("compress " + q(in) + " -o " + q(dir + "/remade.ktx2") + " --format bc6h --mips");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("6 levels replaced by a chain made from its level 0"), std::string::npos) << r.out;
  t = read_texture(dir + "/remade.ktx2");
  ASSERT_EQ(t.levels, 6u);
  float level0[4];
  colour_of(0, 0, level0);
  EXPECT_NEAR(mean_of(t, 2, 0, 0), level0[0], 0.01) << "a chain filtered from a flat level 0 is flat";
}

// A cube map with its chain (an 8-bit texture) to BC7 and ETC2: six faces,
// every level, each surface's own colour.
TEST(CompressChains, CubeKeepsFacesAndLevels) {
  const std::string dir = temp_dir("compress_cube_chain");
  std::vector<std::vector<Image>> chains(6);
  for (int f = 0; f < 6; ++f)
    for (int l = 0, size = 16; size >= 1; ++l, size /= 2) {
      float rgba[4];
      colour_of(f, l, rgba);
      chains[f].push_back(flat_level(size, rgba, 4, PixelType::u8));
    }
  const std::string in = dir + "/cube.dds";
  write_texture(in, texture_from_surfaces(std::move(chains), {.faces = 6}, {}));
  for (const char* format : {"bc7", "etc2"}) {
    const std::string out = dir + "/" + format + ".ktx2";
    const RunResult r = run_texproc("compress " + q(in) + " -o " + q(out) + " --format " + format + " --linear -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Texture t = read_texture(out);
    ASSERT_EQ(t.faces, 6u) << format;
    ASSERT_EQ(t.levels, 5u) << format;
    for (std::uint32_t f = 0; f < 6; ++f)
      for (std::uint32_t l = 0; l < t.levels; ++l) {
        float want[4];
        colour_of(int(f), int(l), want);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(mean_of(t, l, f, c), want[c], 0.02) << format << " face " << f << " level " << l;
      }
  }
}

// --levels without --mips keeps an input chain's levels: an image has one.
TEST(CompressChains, LevelsOfAnImageNeedMips) {
  const std::string dir = temp_dir("compress_levels_image");
  write_image(dir + "/a.png", random_image(16, 16, 4, PixelType::u8, 5).view());
  const RunResult r =
      run_texproc("compress " + q(dir + "/a.png") + " -o " + q(dir + "/a.dds") + " --format bc1 --levels 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("has one level: add --mips"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/a.dds"));
}
