// texproc convert: textures moved between containers with their blocks,
// levels, faces and layers unchanged; what a container cannot hold refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "support/images.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

void expect_same_texture(const Texture& a, const Texture& b, const std::string& what) {
  EXPECT_EQ(a.width, b.width) << what;
  EXPECT_EQ(a.height, b.height) << what;
  EXPECT_EQ(a.levels, b.levels) << what;
  EXPECT_EQ(a.faces, b.faces) << what;
  EXPECT_EQ(a.layers, b.layers) << what;
  EXPECT_TRUE(a.images == b.images) << what << ": the blocks differ";
}

}  // namespace

// Every container pair that can hold the texture: the blocks come through
// byte for byte, and a round trip back to the first container gives the
// first file's bytes (KTX2's Zstandard included).
TEST(Convert, BlocksComeThroughEveryContainerUnchanged) {
  const std::string dir = temp_dir("convert");
  write_image(dir + "/c.png", random_image(36, 20, 4, PixelType::u8, 3).view());
  struct Case {
    const char* args;  // compress options
    const char* first;
    std::vector<const char*> others;
  };
  const std::vector<Case> cases = {
      {"--format bc1 --mips", "bc1.dds", {".ktx2", ".ktx"}},
      {"--format bc3 --mips", "bc3.dds", {".ktx2", ".ktx"}},
      {"--format bc5 --mips --linear", "bc5.dds", {".ktx2", ".ktx"}},
      {"--format bc7 --mips --quality fast", "bc7.ktx2", {".dds", ".ktx"}},
      {"--format etc2a --mips", "etc.ktx2", {".ktx"}},
      {"--format etc2 --linear --quality fast", "etc2.pkm", {".ktx2", ".ktx"}},
      {"--format eac-rg11 --mips --linear", "eac.ktx", {".ktx2"}},
      {"--format astc-6x6 --quality fast", "astc.astc", {".ktx2", ".ktx"}},
  };
  for (const Case& c : cases) {
    const std::string first = dir + "/" + c.first;
    RunResult r = run_texproc("compress " + q(dir + "/c.png") + " -o " + q(first) + " " + c.args + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Texture want = read_texture(first);
    for (const char* ext : c.others) {
      const std::string stem = fs::path(first).stem().string();
      const std::string out = dir + "/" + stem + "_to" + ext;
      r = run_texproc("convert " + q(first) + " -o " + q(out) + " -q");
      ASSERT_EQ(r.exit_code, 0) << c.first << " -> " << ext << ": " << r.err;
      const Texture got = read_texture(out);
      EXPECT_EQ(got.format, want.format) << c.first << " -> " << ext;
      expect_same_texture(want, got, std::string(c.first) + " -> " + ext);
      const std::string back = dir + "/" + stem + "_back" + fs::path(first).extension().string();
      r = run_texproc("convert " + q(out) + " -o " + q(back) + " -f -q");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      EXPECT_EQ(slurp(back), slurp(first)) << c.first << " -> " << ext << " -> back";
    }
  }
  // KTX2 with Zstandard and back: the same DDS bytes.
  ASSERT_EQ(run_texproc("convert " + q(dir + "/bc1.dds") + " -o " + q(dir + "/z.ktx2") + " --zstd 19 -q").exit_code, 0);
  ASSERT_EQ(run_texproc("convert " + q(dir + "/z.ktx2") + " -o " + q(dir + "/z.dds") + " -q").exit_code, 0);
  EXPECT_EQ(slurp(dir + "/z.dds"), slurp(dir + "/bc1.dds"));
  const std::string z = slurp(dir + "/z.ktx2");
  ASSERT_GT(z.size(), 48u);
  EXPECT_EQ(z[44], 2) << "supercompressionScheme: Zstandard";  // KTX2 header, uint32 at byte 44
  fs::remove_all(dir);
}

// A cube map with its chain, and an array, keep their faces and layers.
TEST(Convert, CubesAndArraysKeepTheirSurfaces) {
  const std::string dir = temp_dir("convert_cube");
  write_image(dir + "/p.png", random_image(64, 32, 3, PixelType::u8, 4).view());
  RunResult r = run_texproc("cubemap " + q(dir + "/p.png") + " -o " + q(dir + "/cube.ktx2") + " --mips -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* ext : {".dds", ".ktx"}) {
    const std::string out = dir + "/cube" + ext;
    r = run_texproc("convert " + q(dir + "/cube.ktx2") + " -o " + q(out) + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Texture t = read_texture(out);
    EXPECT_EQ(t.faces, 6u);
    expect_same_texture(read_texture(dir + "/cube.ktx2"), t, ext);
  }
  Texture arr;
  arr.format = TexelFormat::bc4_unorm;
  arr.width = 8;
  arr.height = 8;
  arr.layers = 3;
  arr.is_array = true;
  for (int i = 0; i < 3; ++i) arr.images.push_back(std::vector<std::uint8_t>(32, std::uint8_t(10 * i + 1)));
  write_texture(dir + "/arr.ktx2", arr);
  for (const char* ext : {".dds", ".ktx"}) {
    r = run_texproc("convert " + q(dir + "/arr.ktx2") + " -o " + q(dir + "/arr" + ext) + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    expect_same_texture(arr, read_texture(dir + "/arr" + ext), ext);
  }
  fs::remove_all(dir);
}

// What a container cannot hold is refused with the reason, exit 5, and
// nothing is written; a non-container output is a usage error.
TEST(Convert, RefusesWhatTheTargetCannotHold) {
  const std::string dir = temp_dir("convert_refuse");
  write_image(dir + "/c.png", random_image(16, 16, 4, PixelType::u8, 5).view());
  ASSERT_EQ(
      run_texproc("compress " + q(dir + "/c.png") + " -o " + q(dir + "/bc7.dds") + " --format bc7 --mips -q").exit_code,
      0);
  ASSERT_EQ(
      run_texproc("compress " + q(dir + "/c.png") + " -o " + q(dir + "/etc.ktx2") + " --format etc2 -q").exit_code, 0);
  struct Refusal {
    std::string in, out, says;
  };
  for (const Refusal& c :
       {Refusal{"bc7.dds", "x.pkm", "PKM holds ETC1 and ETC2 RGB only"},
        Refusal{"etc.ktx2", "x.dds", "DDS cannot hold"}, Refusal{"bc7.dds", "x.astc", ".astc holds ASTC blocks"}}) {
    const RunResult r = run_texproc("convert " + q(dir + "/" + c.in) + " -o " + q(dir + "/" + c.out));
    EXPECT_EQ(r.exit_code, 5) << c.in << " -> " << c.out;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.out), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/" + c.out)) << c.out;
  }
  // Allowed, but what .astc cannot say is named.
  ASSERT_EQ(run_texproc("compress " + q(dir + "/c.png") + " -o " + q(dir + "/a.ktx2") +
                        " --format astc-4x4 "
                        "--quality fast -q")
                .exit_code,
            0);
  RunResult r = run_texproc("convert " + q(dir + "/a.ktx2") + " -o " + q(dir + "/a.astc"));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("the sRGB mark"), std::string::npos) << r.err;
  r = run_texproc("convert " + q(dir + "/bc7.dds") + " -o " + q(dir + "/x.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not a texture container"), std::string::npos) << r.err;
  r = run_texproc("convert " + q(dir + "/bc7.dds") + " -o " + q(dir + "/x.dds") + " --zstd 5");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  r = run_texproc("convert " + q(dir + "/c.png") + " -o " + q(dir + "/x.ktx2"));
  EXPECT_EQ(r.exit_code, 3) << r.err;  // not a texture: an invalid input file
  EXPECT_FALSE(fs::exists(dir + "/x.ktx2"));
  fs::remove_all(dir);
}

// Pillow (an independent DDS decoder) reads a BC7 KTX2 converted to DDS as
// texproc decodes the KTX2.
TEST(Convert, PillowDecodesAConvertedDds) {
  if (std::system("/usr/bin/python3 -c 'import PIL' >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3-pil not installed";
  const std::string dir = temp_dir("convert_pil");
  write_image(dir + "/c.png", random_image(32, 24, 4, PixelType::u8, 6).view());
  ASSERT_EQ(run_texproc("compress " + q(dir + "/c.png") + " -o " + q(dir + "/a.ktx2") +
                        " --format bc7 --linear --quality fast -q")
                .exit_code,
            0);
  ASSERT_EQ(run_texproc("convert " + q(dir + "/a.ktx2") + " -o " + q(dir + "/a.dds") + " -q").exit_code, 0);
  const std::string out = dir + "/px.bin";
  const std::string cmd = "/usr/bin/python3 -c \"from PIL import Image; im = Image.open('" + dir +
                          "/a.dds').convert('RGBA'); open('" + out + "', 'wb').write(im.tobytes())\"";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const Image ours = decode_texture_image(read_texture(dir + "/a.ktx2"), 0, 0, 0, PixelType::u8);
  const std::string px = slurp(out);
  ASSERT_EQ(px.size(), ours.byte_size());
  EXPECT_EQ(0, std::memcmp(px.data(), ours.data(), px.size()));
  fs::remove_all(dir);
}
