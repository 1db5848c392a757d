// The CLI through its real output: exit codes, messages, files.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <unistd.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <csignal>
#include <thread>
#include <map>
#include <fstream>

#include "support/images.h"
#include "support/json.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

TEST(Cli, VersionAndHelp) {
  RunResult r = run_texproc("--version");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("texproc 0."), std::string::npos);
  r = run_texproc("--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("mip"), std::string::npos);
  EXPECT_NE(r.out.find("Exit codes"), std::string::npos);
  r = run_texproc("mip --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--filter", "--sigma", "--wrap", "--colorspace", "--linear", "--levels", "--min-size",
                          "--alpha-coverage", "--normal-map", "--threads", "--force", "--type"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
}

TEST(Cli, UsageErrorsExitOneWithHint) {
  RunResult r = run_texproc("mip");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("texproc mip: error:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("See 'texproc mip --help'."), std::string::npos) << r.err;
  r = run_texproc("frobnicate");
  EXPECT_EQ(r.exit_code, 1);
}

// A library error about one file reaches the user with that file in front
// and in the command line's terms (the library names MipOptions::normal_map).
TEST(Cli, LibraryErrorsNameTheFileAndTheFlag) {
  const std::string dir = temp_dir("cli_liberr");
  write_image(dir + "/gray.png", checkerboard(8, 8, 1).view());
  write_image(dir + "/rgb.png", checkerboard(8, 8, 3).view());
  RunResult r = run_texproc("mip '" + dir + "/gray.png' '" + dir + "/rgb.png' -o '" + dir + "/out/' --normal-map");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("texproc mip: error: " + dir + "/gray.png: --normal-map needs an RGB or RGBA image"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(r.err.find("MipOptions"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/out/rgb.dds"));  // the other file went on
  r = run_texproc("normalmap '" + dir + "/gray.png' -o '" + dir + "/n.png' --height-channel b");
  EXPECT_NE(r.err.find("gray.png: --height-channel b: the image has only 1 channel"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, MipErrorsNameTheFileAndProblem) {
  const std::string dir = temp_dir("cli_err");
  const Image img = checkerboard(8, 8, 3);
  write_image(dir + "/in.png", img.view());

  RunResult r = run_texproc("mip " + dir + "/missing.png -o " + dir + "/o.tif");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.png: no such file"), std::string::npos) << r.err;

  r = run_texproc("mip " + dir + "/in.png -o " + dir + "/o.tif --filter bicubic");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown filter 'bicubic' (valid: box, triangle, gaussian"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/o.tif"));

  write_image(dir + "/in.tif", img.view());
  r = run_texproc("mip " + dir + "/in.tif -o " + dir + "/./in.tif --force");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("would overwrite the input"), std::string::npos) << r.err;

  { std::ofstream(dir + "/garbage.png") << "not an image"; }
  r = run_texproc("mip " + dir + "/garbage.png -o " + dir + "/g.tif");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("garbage.png"), std::string::npos) << r.err;

  r = run_texproc("mip " + dir + "/in.png -o " + dir + "/o.tif -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("mip " + dir + "/in.png -o " + dir + "/o.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("output exists (use --force"), std::string::npos) << r.err;
  r = run_texproc("mip " + dir + "/in.png -o " + dir + "/o.tif --force -q");
  EXPECT_EQ(r.exit_code, 0);

  r = run_texproc("mip " + dir + "/in.png -o " + dir + "/o.xyz");
  EXPECT_EQ(r.exit_code, 5);
  fs::remove_all(dir);
}

// The checkerboard through the real command: one PNG per level, 187-188 below level 0.
TEST(Cli, MipCheckerboardPerLevelPngs) {
  const std::string dir = temp_dir("cli_mip");
  write_image(dir + "/cb.png", checkerboard(16, 16, 3).view());
  RunResult r = run_texproc("mip " + dir + "/cb.png -o " + dir + "/out/cb.png --wrap repeat -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (int l = 0; l < 5; ++l) {
    const std::string p = dir + "/out/cb_mip" + std::to_string(l) + ".png";
    ASSERT_TRUE(fs::exists(p)) << p;
    const Image lv = read_image(p);
    EXPECT_EQ(lv.width(), 16 >> l);
    if (l == 0) continue;
    for (int y = 0; y < lv.height(); ++y)
      for (int x = 0; x < lv.width() * 3; ++x) {
        const int v = lv.row<std::uint8_t>(y)[x];
        EXPECT_TRUE(v == 187 || v == 188) << v;
      }
  }
  EXPECT_FALSE(fs::exists(dir + "/out/cb_mip5.png"));
  // The same bytes with 1 and 2 threads, as a TIFF MIP file.
  r = run_texproc("mip " + dir + "/cb.png -o " + dir + "/t1.tif -j 1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("mip " + dir + "/cb.png -o " + dir + "/t2.tif -j 2 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(slurp(dir + "/t1.tif") == slurp(dir + "/t2.tif")) << "TIFF bytes depend on the thread count";
  EXPECT_EQ(probe_image(dir + "/t1.tif").mip_levels, 5);
  fs::remove_all(dir);
}

TEST(Cli, NormalmapOutputsAndErrors) {
  const std::string dir = temp_dir("cli_nm");
  Image h(32, 16, 1, PixelType::u16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) h.set(x, y, 0, 0.01f * x);
  write_image(dir + "/h.png", h.view());

  RunResult r = run_texproc("normalmap --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* opt : {"--kernel", "--height-channel", "--invert", "--height-scale", "--strength", "--wrap", "--y",
                          "--channels", "--multiscale-weights", "--mips", "--threads"}) {
    EXPECT_NE(r.out.find(opt), std::string::npos) << opt;
  }
  r = run_texproc("normalmap " + dir + "/h.png -o " + dir + "/n.png --kernel laplace");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown kernel 'laplace' (valid: gather2x2, central, sobel3"), std::string::npos) << r.err;

  // 16-bit input gives 16-bit output; xyzh has four channels with the height in A.
  r = run_texproc("normalmap " + dir + "/h.png -o " + dir + "/n.png --channels xyzh -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ImageFileInfo info;
  const Image n = read_image(dir + "/n.png", &info);
  EXPECT_EQ(n.channels(), 4);
  EXPECT_EQ(n.type(), PixelType::u16);
  EXPECT_EQ(n.get(5, 5, 3), h.get(5, 5, 0));
  // A ramp of 0.01 per texel at height scale 100 is 45 degrees: x = -sin 45.
  r = run_texproc("normalmap " + dir + "/h.png -o " + dir + "/n45.exr --height-scale 100 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image n45 = read_image(dir + "/n45.exr");
  EXPECT_NEAR(n45.get(10, 8, 0) * 2 - 1, -std::sqrt(0.5), 2e-3);  // stored as half
  EXPECT_NEAR(n45.get(10, 8, 2) * 2 - 1, std::sqrt(0.5), 2e-3);

  // --mips --channels xy: a chain of two-channel levels, renormalized.
  r = run_texproc("normalmap " + dir + "/h.png -o " + dir + "/m.tif --mips --channels xy --type u8 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const ImageFileInfo mi = probe_image(dir + "/m.tif");
  EXPECT_EQ(mi.mip_levels, 6);
  EXPECT_EQ(mi.channels, 2);
  // Into a container: rg8 (two channels for BC5-style shaders), the whole chain.
  r = run_texproc("normalmap " + dir + "/h.png -o " + dir + "/n.ktx2 --mips --channels xy --type u8 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture t = read_texture(dir + "/n.ktx2");
  EXPECT_EQ(t.format, TexelFormat::rg8_unorm);
  EXPECT_EQ(t.levels, 6u);
  fs::remove_all(dir);
}

TEST(Cli, SatBuildQueryBlurAndInfo) {
  const std::string dir = temp_dir("cli_sat");
  Image img(10, 6, 2, PixelType::u8);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 10; ++x) {
      img.row<std::uint8_t>(y)[2 * x] = std::uint8_t(x + 10 * y);
      img.row<std::uint8_t>(y)[2 * x + 1] = 200;
    }
  write_image(dir + "/in.png", img.view());
  RunResult r = run_texproc("sat " + dir + "/in.png -o " + dir + "/t.sat -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Box [2, 5) x [1, 3): the values x + 10y for x = 2..4, y = 1..2 (sum 108, mean 18).
  double want = 0;
  for (int y = 1; y < 3; ++y)
    for (int x = 2; x < 5; ++x) want += x + 10 * y;
  r = run_texproc("sat query " + dir + "/t.sat 2 1 5 3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  {
    const Json::Value q = parse_json(r.out);
    EXPECT_EQ(q["sum"][0].asDouble(), want) << r.out;
    EXPECT_EQ(q["sum"][1].asDouble(), 1200.0) << r.out;
    EXPECT_EQ(q["mean"][0].asDouble(), want / 6) << r.out;
    EXPECT_EQ(q["mean"][1].asDouble(), 200.0) << r.out;
    EXPECT_EQ(q["texels"].asInt(), 6);
    EXPECT_EQ(q["box"][2].asInt(), 5);
    // The CLI's one JSON layout: sorted keys, two-space indent, number arrays on one line.
    EXPECT_EQ(r.out.rfind("{\n  \"box\": [2, 1, 5, 3],\n  \"error_bound\": 0.0,\n", 0), 0u) << r.out;
  }
  r = run_texproc("sat query " + dir + "/t.sat 0 0 11 1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("outside the 10x6 table"), std::string::npos) << r.err;
  r = run_texproc("sat query " + dir + "/missing.sat 0 0 1 1");
  EXPECT_EQ(r.exit_code, 2);
  { std::ofstream(dir + "/junk.sat") << "not a table"; }
  r = run_texproc("sat query " + dir + "/junk.sat 0 0 1 1");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("junk.sat: not a valid .sat file"), std::string::npos) << r.err;
  r = run_texproc("sat " + dir + "/in.png -o " + dir + "/t.sat --precision f16");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("(valid: u32, u64, f32, f64)"), std::string::npos) << r.err;

  r = run_texproc("info --json " + dir + "/t.sat " + dir + "/in.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  {
    const Json::Value files = parse_json(r.out);
    ASSERT_EQ(files.size(), 2u) << r.out;
    EXPECT_EQ(files[0]["container"].asString(), "sat");
    EXPECT_EQ(files[0]["width"].asInt(), 10);
    EXPECT_EQ(files[0]["height"].asInt(), 6);
    EXPECT_EQ(files[0]["channels"].asInt(), 2);
    EXPECT_EQ(files[0]["precision"].asString(), "u32");
    EXPECT_EQ(files[1]["container"].asString(), "png");
  }
  r = run_texproc("info " + dir + "/nope.png " + dir + "/in.png");
  EXPECT_EQ(r.exit_code, 2);  // the failure is reported, the good file still described
  EXPECT_NE(r.out.find("in.png: png, 10x6"), std::string::npos) << r.out;

  r = run_texproc("sat blur " + dir + "/in.png -o " + dir + "/b.png --radius 2 --wrap repeat -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_image(dir + "/b.png").width(), 10);
  fs::remove_all(dir);
}

TEST(Cli, MipIntoContainersAndInfo) {
  const std::string dir = temp_dir("cli_containers");
  write_image(dir + "/a.png", checkerboard(16, 8, 4).view());
  for (const char* ext : {".dds", ".ktx2", ".ktx"}) {
    RunResult r = run_texproc("mip " + dir + "/a.png -o " + dir + "/a" + ext + " -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    r = run_texproc("info --json " + dir + "/a" + ext);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json::Value info = parse_json(r.out)[0];
    EXPECT_EQ(info["format"].asString(), "rgba8_srgb") << r.out;
    EXPECT_EQ(info["levels"][0]["width"].asInt(), 16) << r.out;
    EXPECT_EQ(info["levels"][0]["height"].asInt(), 8) << r.out;
    EXPECT_EQ(info["levels"][0]["bytes"].asInt(), 512) << r.out;
  }
  // sRGB needs the DX10 header: asking for a legacy one is refused, by name.
  RunResult r = run_texproc("mip " + dir + "/a.png -o " + dir + "/b.dds --dds-header dx9");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_NE(r.err.find("b.dds: a legacy (DX9) DDS header cannot say rgba8_srgb"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/b.dds"));
  r = run_texproc("mip " + dir + "/a.png -o " + dir + "/c.dds --dds-header dx9 --linear -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("mip " + dir + "/a.png -o " + dir + "/d.dds --dds-header dx11");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("(valid: auto, dx9, dx10)"), std::string::npos) << r.err;
  { std::ofstream(dir + "/bad.ktx2", std::ios::binary) << std::string("\xABKTX 20\xBB\r\n\x1A\n", 12) << "short"; }
  r = run_texproc("info " + dir + "/bad.ktx2");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_NE(r.err.find("bad.ktx2: truncated: typeSize needs bytes 16..20 of 17"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, ConemapWritesMapAndPreview) {
  const std::string dir = temp_dir("cli_cone");
  Image h(24, 24, 1, PixelType::u8);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) h.set(x, y, 0, (x / 6 + y / 6) % 2 ? 0.8f : 0.1f);
  write_image(dir + "/h.png", h.view());
  RunResult r =
      run_texproc("conemap " + dir + "/h.png -o " + dir + "/c.png --preview " + dir + "/p.png --preview-size 32 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image c = read_image(dir + "/c.png");
  EXPECT_EQ(c.channels(), 3);
  EXPECT_EQ(c.get(3, 3, 0), h.get(3, 3, 0));           // R is the height
  EXPECT_EQ(read_image(dir + "/p.png").width(), 96);   // linear, cones, relaxed cones
  EXPECT_EQ(read_image(dir + "/p.png").height(), 64);  // renders over heat maps
  // The fast generator and the brute force write the same bytes.
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/b.png --brute-force -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(slurp(dir + "/b.png") == slurp(dir + "/c.png"));
  // --fast: never a wider cone than the exact map, texel for texel.
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/f.png --fast --fast-reach 1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image f = read_image(dir + "/f.png");
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) EXPECT_LE(f.get(x, y, 1), c.get(x, y, 1)) << x << "," << y;
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/x.png --fast --brute-force");
  EXPECT_EQ(r.exit_code, 1);
  // Relaxed cones: never narrower than conservative ones; an unknown mode is refused.
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/r.png --mode relaxed -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image rx = read_image(dir + "/r.png");
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) EXPECT_GE(rx.get(x, y, 1), c.get(x, y, 1)) << x << "," << y;
  // --bilinear-safe: never wider than the classic cones, and with the
  // preview (whose relaxed panel uses texel-centre cones); not with relaxed.
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/s.png --bilinear-safe --preview " + dir +
                  "/sp.png --preview-size 16 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image sb = read_image(dir + "/s.png");
  int narrower = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      EXPECT_LE(sb.get(x, y, 1), c.get(x, y, 1)) << x << "," << y;
      narrower += sb.get(x, y, 1) < c.get(x, y, 1);
    }
  EXPECT_GT(narrower, 0);
  // --channels: RG for two-channel textures, RGBA with an opaque alpha; the same cones.
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/rg.tif --channels rg -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/rgba.png --channels rgba -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image rg = read_image(dir + "/rg.tif"), rgba = read_image(dir + "/rgba.png");
  ASSERT_EQ(rg.channels(), 2);
  ASSERT_EQ(rgba.channels(), 4);
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x)
      for (int ch = 0; ch < 2; ++ch) {
        EXPECT_EQ(rg.get(x, y, ch), c.get(x, y, ch));
        EXPECT_EQ(rgba.get(x, y, ch), c.get(x, y, ch));
        EXPECT_EQ(rgba.get(x, y, 2), 0.0f);
        EXPECT_EQ(rgba.get(x, y, 3), 1.0f);
      }
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/x.png --channels rgb0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown --channels 'rgb0' (valid: rg, rgb, rgba)"), std::string::npos) << r.err;
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/x.png --bilinear-safe --mode relaxed");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--bilinear-safe makes conservative cones"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/x.png"));
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/x.png --mode loose");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown --mode 'loose' (valid: conservative, relaxed)"), std::string::npos) << r.err;
  r = run_texproc("conemap " + dir + "/h.png -o " + dir + "/x.png --depth 0");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--depth: 0 is outside the valid range (0, 1000000]"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, DecompressContainers) {
  const std::string dir = temp_dir("cli_decompress");
  write_image(dir + "/a.png", checkerboard(8, 8, 4).view());
  RunResult r = run_texproc("mip " + dir + "/a.png -o " + dir + "/a.ktx2 --wrap repeat -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("decompress " + dir + "/a.ktx2 -o " + dir + "/out/a.png --all-levels -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image l0 = read_image(dir + "/out/a_mip0.png");
  EXPECT_EQ(l0.get(1, 0, 0), 1.0f);
  const int v = read_image(dir + "/out/a_mip1.png").row<std::uint8_t>(0)[0];
  EXPECT_TRUE(v == 187 || v == 188) << v;  // gamma-correct average, through the container
  EXPECT_TRUE(fs::exists(dir + "/out/a_mip3.png"));
  // A BC5 SNORM texture to float: values in [-1, 1].
  Texture t;
  t.format = TexelFormat::bc5_snorm;
  t.width = t.height = 4;
  t.images.push_back(std::vector<std::uint8_t>(16, 0x81));  // endpoints -127: every texel -1
  write_texture(dir + "/n.dds", t);
  r = run_texproc("decompress " + dir + "/n.dds -o " + dir + "/n.exr -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_image(dir + "/n.exr").get(2, 2, 1), -1.0f);
  r = run_texproc("decompress " + dir + "/n.dds -o " + dir + "/n2.png --level 3");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--level 3 (valid: 0 to 0)"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Cli, CompressBc4Bc5IntoContainers) {
  const std::string dir = temp_dir("cli_compress");
  Image h(30, 18, 1, PixelType::u8);
  for (int y = 0; y < 18; ++y)
    for (int x = 0; x < 30; ++x) h.set(x, y, 0, 0.5f + 0.45f * std::sin(x * 0.3f + y * 0.2f));
  write_image(dir + "/h.png", h.view());
  RunResult r = run_texproc("compress " + dir + "/h.png -o " + dir + "/h.dds --format bc4 --mips --quality high -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture t = read_texture(dir + "/h.dds");
  EXPECT_EQ(t.format, TexelFormat::bc4_unorm);
  EXPECT_EQ(t.levels, 5u);  // 30x18 -> 15x9 -> 7x4 -> 3x2 -> 1x1
  r = run_texproc("decompress " + dir + "/h.dds -o " + dir + "/back.png -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image back = read_image(dir + "/back.png");
  double se = 0;
  for (int y = 0; y < 18; ++y)
    for (int x = 0; x < 30; ++x) se += std::pow(back.get(x, y, 0) - h.get(x, y, 0), 2);
  // A steep field (0.45 * 0.3 of the range per texel: ~100 levels across a
  // block, so palette steps of ~14 levels): PSNR well above 30 dB.
  EXPECT_GT(10 * std::log10(1.0 / (se / (30 * 18))), 33.0);
  r = run_texproc("compress " + dir + "/h.png -o " + dir + "/n.ktx2 --format bc5s -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_texture(dir + "/n.ktx2").format, TexelFormat::bc5_snorm);
  // ETC has no DDS format (Direct3D has none): the error says where it fits.
  r = run_texproc("compress " + dir + "/h.png -o " + dir + "/x.dds --format etc1");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_NE(r.err.find("DDS cannot hold etc1_rgb (Direct3D has no ETC formats): write .ktx2, .ktx or .pkm"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir + "/x.dds"));
  for (const char* f : {"etc1", "etc2", "etc2a1", "etc2a", "eac-r11", "eac-r11s", "eac-rg11", "eac-rg11s"}) {
    r = run_texproc("compress " + dir + "/h.png -o " + dir + "/e_" + f + ".ktx2 --format " + f + " --mips -q");
    ASSERT_EQ(r.exit_code, 0) << f << r.err;
    r = run_texproc("decompress " + dir + "/e_" + f + ".ktx2 -o " + dir + "/e_" + f + ".png -q");
    ASSERT_EQ(r.exit_code, 0) << f << r.err;
  }
  r = run_texproc("compress " + dir + "/h.png -o " + dir + "/e.pkm --format etc1 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_texture(dir + "/e.pkm").format, TexelFormat::etc1_rgb);
  r = run_texproc("compress " + dir + "/h.png -o " + dir + "/x.dds --format bc9");
  EXPECT_EQ(r.exit_code, 1);
  r = run_texproc("compress " + dir + "/h.png -o " + dir + "/x.png --format bc4");
  EXPECT_EQ(r.exit_code, 5);
  fs::remove_all(dir);
}

// BC7 from the CLI: sRGB for 8-bit colour (UNORM with --linear), DDS (DX10)
// and KTX2 with mips, decompress back close to the source, alpha kept on a
// cutout; float input outside [0, 1] warns, as every LDR format does.
TEST(Cli, CompressBc7IntoContainers) {
  const std::string dir = temp_dir("cli_bc7");
  const std::string albedo = std::string(TEXPROC_SAMPLES_DIR) + "/albedo_desert_512.png";
  RunResult r = run_texproc("compress " + albedo + " -o " + dir + "/a.dds --format bc7 --mips --quality fast -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Texture t = read_texture(dir + "/a.dds");
  EXPECT_EQ(t.format, TexelFormat::bc7_srgb);
  EXPECT_EQ(t.levels, 10u);
  r = run_texproc("compress " + albedo + " -o " + dir + "/a.ktx2 --format BC7 --linear -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_texture(dir + "/a.ktx2").format, TexelFormat::bc7_unorm);
  r = run_texproc("info " + dir + "/a.dds");
  EXPECT_NE(r.out.find("bc7_srgb"), std::string::npos) << r.out;
  r = run_texproc("decompress " + dir + "/a.dds -o " + dir + "/back.png -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image src = read_image(albedo), back = read_image(dir + "/back.png");
  double se = 0;
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x)
      for (int c = 0; c < 3; ++c) se += std::pow(back.get(x, y, c) - src.get(x, y, c), 2);
  EXPECT_GT(10 * std::log10(1.0 / (se / (3.0 * src.width() * src.height()))), 40.0);
  const std::string cutout = std::string(TEXPROC_SAMPLES_DIR) + "/cutout_fence_512x256.png";
  r = run_texproc("compress " + cutout + " -o " + dir + "/c.dds --format bc7 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("decompress " + dir + "/c.dds -o " + dir + "/c.png -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image csrc = read_image(cutout), cback = read_image(dir + "/c.png");
  ASSERT_EQ(cback.channels(), 4);
  double ase = 0;
  for (int y = 0; y < csrc.height(); ++y)
    for (int x = 0; x < csrc.width(); ++x) ase += std::pow(cback.get(x, y, 3) - csrc.get(x, y, 3), 2);
  EXPECT_GT(10 * std::log10(1.0 / (ase / (double(csrc.width()) * csrc.height()))), 35.0);
  const std::string sky = std::string(TEXPROC_SAMPLES_DIR) + "/sky_forest_512x256.exr";
  r = run_texproc("compress " + sky + " -o " + dir + "/s.dds --format bc7 --quality fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sky_forest_512x256.exr: values from"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("clipped to [0, 1] by bc7_unorm"), std::string::npos) << r.err;
  r = run_texproc("compress " + sky + " -o " + dir + "/s2.dds --format bc7 --quality fast --clip");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("clipped"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// BC6H from the HDR formats texproc reads (OpenEXR, float TIFF, Radiance
// HDR, a half-float DDS cubemap) into DDS, KTX2 and KTX1, with a float mip
// chain; values above 1 come back through decompress (OpenEXR by default
// into a folder), compare's HDR metric is small, and no clip warning is
// given (an LDR format warns about the same file; 8-bit input never warns).
// (`fast` reaches 0.064 on this sky; astc-encoder at -thorough, astc-4x4-hdr
// at the same bits, 0.062.)
TEST(Cli, CompressBc6hFromHdrInputs) {
  const std::string dir = temp_dir("cli_bc6h");
  const std::string sky = std::string(TEXPROC_SAMPLES_DIR) + "/sky_forest_512x256.exr";
  RunResult r = run_texproc("compress " + sky + " -o " + dir + "/s.dds --format bc6h --mips --quality fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("clipped"), std::string::npos) << r.err;
  Texture t = read_texture(dir + "/s.dds");
  EXPECT_EQ(t.format, TexelFormat::bc6h_ufloat);
  EXPECT_EQ(t.levels, 10u);
  r = run_texproc("info " + dir + "/s.dds");
  EXPECT_NE(r.out.find("bc6h_ufloat"), std::string::npos) << r.out;
  r = run_texproc("decompress " + dir + "/s.dds -o " + dir + "/out/ -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image src = read_image(sky), back = read_image(dir + "/out/s.exr");
  float src_max = 0, back_max = 0;
  for (int y = 0; y < src.height(); ++y)
    for (int x = 0; x < src.width(); ++x)
      for (int c = 0; c < 3; ++c)
        src_max = std::max(src_max, src.get(x, y, c)), back_max = std::max(back_max, back.get(x, y, c));
  ASSERT_GT(src_max, 2.0f);
  EXPECT_GT(back_max, 0.9f * src_max);
  r = run_texproc("compare " + sky + " " + dir + "/out/s.exr --max-log-rmse 0.08");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("log2 RMSE"), std::string::npos) << r.out;
  r = run_texproc("compare " + sky + " " + dir + "/out/s.exr --max-log-rmse 0.0001 -q");
  EXPECT_EQ(r.exit_code, 7);
  const std::string png = std::string(TEXPROC_SAMPLES_DIR) + "/albedo_desert_512.png";
  r = run_texproc("compare " + png + " " + png + " --max-log-rmse 0.01");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--max-log-rmse: " + png), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("not floats"), std::string::npos) << r.err;
  // Float TIFF and Radiance HDR of the same sky, SF16 into KTX2 and KTX1.
  WriteOptions w;
  write_image(dir + "/sky.tif", src.view(), w);
  write_image(dir + "/sky.hdr", src.view(), w);
  r = run_texproc("compress " + dir + "/sky.tif -o " + dir + "/t.ktx2 --format bc6hs -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_texture(dir + "/t.ktx2").format, TexelFormat::bc6h_sfloat);
  r = run_texproc("compress " + dir + "/sky.hdr -o " + dir + "/h.ktx --format BC6H_UF16 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_texture(dir + "/h.ktx").format, TexelFormat::bc6h_ufloat);
  // A half-float DDS cubemap keeps its six faces.
  const std::string cube = corpus_dir() + "/hdr/qt3d_default_specular_cube_rgba16f.dds";
  if (have_corpus()) {
    r = run_texproc("compress " + cube + " -o " + dir + "/cube.dds --format bc6h -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(read_texture(dir + "/cube.dds").faces, 6u);
  }
  // The same float file to an LDR format warns; 8-bit input does not.
  r = run_texproc("compress " + sky + " -o " + dir + "/s1.dds --format bc1 --quality fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("an HDR format keeps them (bc6h"), std::string::npos) << r.err;
  r = run_texproc("compress " + std::string(TEXPROC_SAMPLES_DIR) + "/albedo_desert_512.png -o " + dir +
                  "/a.dds --format bc6h --quality fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("clipped"), std::string::npos) << r.err;
  r = run_texproc("compress " + std::string(TEXPROC_SAMPLES_DIR) + "/albedo_desert_512.png -o " + dir +
                  "/a7.dds --format bc7 --quality fast");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("clipped"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

namespace {
std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

}  // namespace

// --depfile: a Make rule "outputs: inputs", with spaces and '#' escaped as
// gcc -MD escapes them, the OpenColorIO config included; nothing on failure.
TEST(Cli, DepfileListsOutputsAndInputs) {
  const std::string dir = temp_dir("cli_depfile");
  fs::create_directories(dir + "/in put");
  write_image(dir + "/in put/a#1.png", random_image(8, 8, 3, PixelType::u8, 5).view());
  write_text(dir + "/cfg.ocio", kTestOcioConfig);
  RunResult r = run_texproc("mip '" + dir + "/in put/a#1.png' -o " + dir + "/out/a.png --levels 2 --depfile " + dir +
                            "/deps/a.d -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir + "/deps/a.d"),
            dir + "/out/a_mip0.png " + dir + "/out/a_mip1.png: \\\n  " + dir + "/in\\ put/a\\#1.png\n");
  // The config is a dependency when a space came from it.
  const std::string env = "OCIO=" + dir + "/cfg.ocio ";
  const int status = std::system((env + TEXPROC_CLI_PATH + " mip '" + dir + "/in put/a#1.png' -o " + dir +
                                  "/out/g.tif --colorspace gamma22 --depfile " + dir + "/g.d -q")
                                     .c_str());
  ASSERT_EQ(status, 0);
  EXPECT_EQ(read_text(dir + "/g.d"),
            dir + "/out/g.tif: \\\n  " + dir + "/cfg.ocio \\\n  " + dir + "/in\\ put/a\\#1.png\n");
  // A failed run writes no depfile.
  r = run_texproc("mip " + dir + "/missing.png -o " + dir + "/out/m.png --depfile " + dir + "/m.d");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir + "/m.d"));
  // A depfile that names an output or an input is refused before any work.
  r = run_texproc("mip " + dir + "/out/g.tif -o " + dir + "/out/h.tif --depfile " + dir + "/out/h.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("h.tif: --depfile names an output of the command"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out/h.tif"));
  r = run_texproc("mip " + dir + "/out/g.tif -o " + dir + "/out/h.tif --depfile " + dir + "/out/g.tif");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("g.tif: --depfile would overwrite the input"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// Make reads the depfile: nothing to do after a build; touching the input
// or the OpenColorIO config (which the Makefile does not name) rebuilds.
TEST(Cli, DepfileDrivesMake) {
  if (std::system("command -v make >/dev/null 2>&1") != 0) GTEST_SKIP() << "no make";
  const std::string dir = temp_dir("cli_depfile_make");
  write_image(dir + "/h.png", random_image(8, 8, 3, PixelType::u8, 5).view());
  write_text(dir + "/cfg.ocio", kTestOcioConfig);
  write_text(dir + "/Makefile", std::string("out.tif:\n\tOCIO=cfg.ocio ") + TEXPROC_CLI_PATH +
                                    " mip h.png -o out.tif --colorspace gamma22 -f -q --depfile out.d\n"
                                    "-include out.d\n");
  auto make_q = [&] { return WEXITSTATUS(std::system(("make -s -q -C " + dir + " out.tif").c_str())); };
  // Times in the past, so nothing is in the future for Make: everything a
  // minute old, then the changed file half a minute old.
  auto later = [&](const std::string& f) {
    const auto now = fs::file_time_type::clock::now();
    for (const char* g : {"h.png", "cfg.ocio", "out.tif", "out.d", "Makefile"})
      fs::last_write_time(dir + "/" + g, now - std::chrono::seconds(60));
    fs::last_write_time(dir + "/" + f, now - std::chrono::seconds(30));
  };
  ASSERT_EQ(std::system(("make -s -C " + dir + " out.tif").c_str()), 0);
  ASSERT_TRUE(fs::exists(dir + "/out.d"));
  EXPECT_EQ(make_q(), 0) << "up to date after a build";
  later("h.png");
  EXPECT_EQ(make_q(), 1) << "the input changed";
  ASSERT_EQ(std::system(("make -s -C " + dir + " out.tif").c_str()), 0);
  EXPECT_EQ(make_q(), 0);
  later("cfg.ocio");
  EXPECT_EQ(make_q(), 1) << "the OCIO config changed";
  fs::remove_all(dir);
}

// --write-if-changed: replaces an output when its bytes change, leaves it
// (and its time stamp) alone when they do not; for Ninja's restat.
TEST(Cli, WriteIfChangedKeepsIdenticalOutputs) {
  const std::string dir = temp_dir("cli_write_if_changed");
  write_image(dir + "/in.png", random_image(16, 16, 3, PixelType::u8, 7).view());
  const std::string base = "mip " + dir + "/in.png -o " + dir + "/out.dds -q";
  ASSERT_EQ(run_texproc(base).exit_code, 0);
  const auto old_time = fs::file_time_type::clock::now() - std::chrono::seconds(100);
  fs::last_write_time(dir + "/out.dds", old_time);
  const std::string first = slurp(dir + "/out.dds");
  // Same options: same bytes, the file is not touched.
  RunResult r = run_texproc(base + " --write-if-changed");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(fs::last_write_time(dir + "/out.dds"), old_time);
  // Other options: other bytes, the file is replaced.
  r = run_texproc(base + " --write-if-changed --filter box");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(fs::last_write_time(dir + "/out.dds"), old_time);
  EXPECT_FALSE(slurp(dir + "/out.dds") == first);
  // No temporary files are left behind either way.
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 2);
  // Without it (or --force) an existing output is still an error.
  r = run_texproc(base);
  EXPECT_EQ(r.exit_code, 1);
  fs::remove_all(dir);
}

// --dry-run: the outputs, one a line, after every check; nothing written.
TEST(Cli, DryRunListsOutputsAndWritesNothing) {
  const std::string dir = temp_dir("cli_dry_run");
  write_image(dir + "/in.png", random_image(4, 2, 3, PixelType::u8, 3).view());
  RunResult r = run_texproc("mip " + dir + "/in.png -o " + dir + "/o/a.png --dry-run --depfile " + dir + "/a.d");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, dir + "/o/a_mip0.png\n" + dir + "/o/a_mip1.png\n" + dir + "/o/a_mip2.png\n");
  EXPECT_FALSE(fs::exists(dir + "/o/a_mip0.png"));
  EXPECT_FALSE(fs::exists(dir + "/a.d"));
  r = run_texproc("compress " + dir + "/in.png -o " + dir + "/c.dds --format bc1 -n");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, dir + "/c.dds\n");
  EXPECT_FALSE(fs::exists(dir + "/c.dds"));
  // The same checks as a real run: a missing input, an existing output.
  r = run_texproc("compress " + dir + "/nope.png -o " + dir + "/c.dds --format bc1 -n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.png: no such file"), std::string::npos) << r.err;
  r = run_texproc("conemap " + dir + "/in.png -o " + dir + "/in.png -n");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("output would overwrite the input"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// samples/Makefile with its depfiles: a build cooks every sample; then
// nothing is out of date; after one input changes, exactly its output is
// cooked again.
TEST(Cli, SamplesMakefileRebuildsExactlyWhatChanged) {
  if (std::system("command -v make >/dev/null 2>&1") != 0) GTEST_SKIP() << "no make";
  const std::string dir = temp_dir("cli_samples_make");
  for (const auto& e : fs::directory_iterator(TEXPROC_SAMPLES_DIR)) {
    if (e.path().extension() == ".png" || e.path().filename() == "Makefile") {
      fs::copy_file(e.path(), dir + "/" + e.path().filename().string());
    }
  }
  const std::string make = std::string("make -s -C ") + dir + " TEXPROC=" + TEXPROC_CLI_PATH + " OUT=cooked";
  ASSERT_EQ(std::system(make.c_str()), 0);
  std::vector<std::string> outputs;
  for (const auto& e : fs::directory_iterator(dir + "/cooked")) {
    if (e.path().extension() != ".d") outputs.push_back(e.path().filename().string());
  }
  ASSERT_EQ(outputs.size(), 5u);
  EXPECT_EQ(WEXITSTATUS(std::system((make + " -q").c_str())), 0) << "up to date after a build";
  // Everything a minute old, then one input half a minute old.
  const auto now = fs::file_time_type::clock::now();
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) fs::last_write_time(e.path(), now - std::chrono::seconds(60));
  }
  fs::last_write_time(dir + "/normal_stein_256.png", now - std::chrono::seconds(30));
  ASSERT_EQ(std::system(make.c_str()), 0);
  for (const auto& name : outputs) {
    const bool rebuilt = fs::last_write_time(dir + "/cooked/" + name) > now - std::chrono::seconds(45);
    EXPECT_EQ(rebuilt, name == "normal_stein_256.ktx2") << name;
  }
  EXPECT_EQ(WEXITSTATUS(std::system((make + " -q").c_str())), 0);
  fs::remove_all(dir);
}

// samples/CMakeLists.txt (texproc_add_textures) under the Ninja and the
// Makefile generators: a build cooks every sample; changing one input
// cooks exactly that texture again.
TEST(Cli, SamplesCMakeRebuildsExactlyWhatChanged) {
  if (std::system("command -v cmake >/dev/null 2>&1") != 0) GTEST_SKIP() << "no cmake";
  std::vector<std::string> generators{"Unix Makefiles"};
  if (std::system("command -v ninja >/dev/null 2>&1") == 0) generators.push_back("Ninja");
  for (const std::string& generator : generators) {
    const std::string dir = temp_dir("cli_samples_cmake");
    fs::create_directories(dir + "/src");
    for (const auto& e : fs::directory_iterator(TEXPROC_SAMPLES_DIR)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() == ".png" || name == "CMakeLists.txt" || name == "TexprocTextures.cmake") {
        fs::copy_file(e.path(), dir + "/src/" + name);
      }
    }
    const std::string quiet = " >" + dir + "/log.txt 2>&1";
    ASSERT_EQ(std::system(("cmake -S " + dir + "/src -B " + dir + "/build -G '" + generator +
                           "' -DTEXPROC_EXECUTABLE=" + TEXPROC_CLI_PATH + quiet)
                              .c_str()),
              0)
        << generator;
    const std::string build = "cmake --build " + dir + "/build" + quiet;
    ASSERT_EQ(std::system(build.c_str()), 0) << generator;
    std::map<std::string, fs::file_time_type> before;
    for (const auto& e : fs::directory_iterator(dir + "/build/cooked")) {
      if (e.path().extension() != ".d") before[e.path().filename().string()] = e.last_write_time();
    }
    ASSERT_EQ(before.size(), 5u) << generator;
    // New content (texproc_add_textures uses --write-if-changed: a touch
    // alone leaves the output's bytes and time stamp as they were).
    fs::copy_file(dir + "/src/height_mount_250.png", dir + "/src/height_stein_256.png",
                  fs::copy_options::overwrite_existing);
    fs::last_write_time(dir + "/src/height_stein_256.png", fs::file_time_type::clock::now());
    ASSERT_EQ(std::system(build.c_str()), 0) << generator;
    for (const auto& [name, time] : before) {
      const bool rebuilt = fs::last_write_time(dir + "/build/cooked/" + name) != time;
      EXPECT_EQ(rebuilt, name == "height_stein_256_n.dds") << generator << ": " << name;
    }
    fs::remove_all(dir);
  }
}

// A run killed with SIGKILL at any moment leaves either no file under the
// final name or the whole file (never part of one): outputs are written to
// a temporary name and renamed.
TEST(Cli, KilledRunLeavesNoPartialOutput) {
  const std::string dir = temp_dir("cli_sigkill");
  write_image(dir + "/in.tif", random_image(2048, 2048, 4, PixelType::u8, 11).view());
  const std::string out = dir + "/out.tif";
  auto spawn = [&] {
    const pid_t pid = fork();
    if (pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      dup2(null, 1);
      dup2(null, 2);
      execl(TEXPROC_CLI_PATH, "texproc", "mip", (dir + "/in.tif").c_str(), "-o", out.c_str(), "-f", "-q",
            static_cast<char*>(nullptr));
      _exit(127);
    }
    return pid;
  };
  int status = 0;
  const auto t0 = std::chrono::steady_clock::now();
  waitpid(spawn(), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const auto full_run = std::chrono::steady_clock::now() - t0;
  const std::string reference = slurp(out);
  ASSERT_FALSE(reference.empty());
  int killed_before = 0, killed_after = 0;
  for (int i = 0; i < 12; ++i) {
    fs::remove(out);
    const pid_t pid = spawn();
    std::this_thread::sleep_for(full_run * (i + 0.5) / 12);
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    if (fs::exists(out)) {
      EXPECT_TRUE(slurp(out) == reference) << "partial output after a kill at step " << i;
      ++killed_after;
    } else {
      ++killed_before;
    }
  }
  EXPECT_GT(killed_before, 0) << "no kill landed before the output was in place";
  fs::remove_all(dir);
}

// --normal-map with bc3: the DXT5nm layout (X in alpha, Y in green, red 1,
// blue 0), for platforms without BC5.
TEST(Cli, CompressBc3NormalMapIsDxt5nm) {
  const std::string dir = temp_dir("cli_dxt5nm");
  Image n(32, 32, 3, PixelType::u8);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const float nx = 0.6f * std::sin(x * 0.3f), ny = 0.5f * std::cos(y * 0.2f);
      const float nz = std::sqrt(std::max(0.0f, 1.0f - nx * nx - ny * ny));
      n.set(x, y, 0, nx * 0.5f + 0.5f);
      n.set(x, y, 1, ny * 0.5f + 0.5f);
      n.set(x, y, 2, nz * 0.5f + 0.5f);
    }
  write_image(dir + "/n.png", n.view());
  RunResult r = run_texproc("compress " + dir + "/n.png -o " + dir + "/n.dds --format bc3 --normal-map -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture t = read_texture(dir + "/n.dds");
  EXPECT_EQ(t.format, TexelFormat::bc3_unorm);  // normals are data: never sRGB
  const Image d = decode_texture_image(t, 0, 0, 0, PixelType::f32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      ASSERT_NEAR(d.get(x, y, 3), n.get(x, y, 0), 4.5 / 255) << x << "," << y;  // X from alpha
      ASSERT_NEAR(d.get(x, y, 1), n.get(x, y, 1), 6.0 / 255) << x << "," << y;  // Y from green
      ASSERT_EQ(d.get(x, y, 0), 1.0f);
      ASSERT_EQ(d.get(x, y, 2), 0.0f);
    }
  fs::remove_all(dir);
}

// --alpha-coverage with --mips: a cutout (thin leaves of alpha 1 on 0)
// keeps its level-0 coverage at alpha >= 0.5 through the chain's levels
// after BC3 (without it the coverage falls as the leaves blur away); an
// error without --mips.
TEST(Cli, CompressKeepsAlphaCoverage) {
  const std::string dir = temp_dir("cli_compress_coverage");
  Image img(64, 64, 4, PixelType::u8);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = img.row<std::uint8_t>(y) + 4 * x;
      p[0] = 60;
      p[1] = 140;
      p[2] = 40;
      p[3] = (x % 8 == 0 || (x + y) % 11 == 0) ? 255 : 0;  // thin strokes
    }
  write_image(dir + "/leaves.png", img.view());
  auto coverage = [](const Image& d) {
    double n = 0;
    for (int y = 0; y < d.height(); ++y)
      for (int x = 0; x < d.width(); ++x) n += d.get(x, y, 3) >= 0.5f ? 1.0 : 0.0;
    return n / (double(d.width()) * d.height());
  };
  double level3[2] = {};
  for (int keep = 0; keep < 2; ++keep) {
    const std::string out = dir + "/leaves" + std::to_string(keep) + ".dds";
    RunResult r = run_texproc("compress " + dir + "/leaves.png -o " + out + " --format bc3 --mips -q" +
                              (keep ? " --alpha-coverage 0.5" : ""));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Texture t = read_texture(out);
    level3[keep] = coverage(decode_texture_image(t, 3, 0, 0, PixelType::f32));
    if (keep) {
      const double c0 = coverage(decode_texture_image(t, 0, 0, 0, PixelType::f32));
      for (int l = 1; l < 4; ++l)
        EXPECT_NEAR(coverage(decode_texture_image(t, l, 0, 0, PixelType::f32)), c0, 0.06) << l;
    }
  }
  EXPECT_GT(level3[1], level3[0] + 0.05);
  RunResult bad = run_texproc("compress " + dir + "/leaves.png -o " + dir + "/x.dds --format bc3 --alpha-coverage 0.5");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--mips"), std::string::npos) << bad.err;
  fs::remove_all(dir);
}

// --no-premultiply with --mips: an alpha channel that holds data leaves the
// colour alone (a colour under alpha 0 keeps its weight in level 1; the
// default weighs it by alpha, so level 1 is the opaque texels' colour).
TEST(Cli, CompressNoPremultiply) {
  const std::string dir = temp_dir("cli_compress_nopremul");
  Image img(8, 8, 4, PixelType::u8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      std::uint8_t* p = img.row<std::uint8_t>(y) + 4 * x;
      const bool left = x < 4;
      p[0] = left ? 255 : 0;
      p[1] = 0;
      p[2] = left ? 0 : 255;
      p[3] = left ? 255 : 0;
    }
  write_image(dir + "/data.png", img.view());
  double blue[2] = {};
  for (int plain = 0; plain < 2; ++plain) {
    const std::string out = dir + "/d" + std::to_string(plain) + ".ktx2";
    RunResult r = run_texproc("compress " + dir + "/data.png -o " + out +
                              " --format bc3 --linear --mips --filter box -q" + (plain ? " --no-premultiply" : ""));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Image d = decode_texture_image(read_texture(out), 3, 0, 0, PixelType::f32);  // 1x1: the average
    blue[plain] = d.get(0, 0, 2);
  }
  EXPECT_LT(blue[0], 0.05);         // weighed by alpha: only the opaque red half counts
  EXPECT_NEAR(blue[1], 0.5, 0.05);  // data: both halves
  RunResult bad = run_texproc("compress " + dir + "/data.png -o " + dir + "/x.dds --format bc3 --no-premultiply");
  EXPECT_EQ(bad.exit_code, 1);
  fs::remove_all(dir);
}

// --bc1-black: opaque BC1 only (an error naming the flag otherwise); on line
// art it lowers the error of what is written.
TEST(Cli, Bc1BlackFlag) {
  const std::string dir = temp_dir("cli_bc1_black");
  Image img(64, 32, 3, PixelType::u8);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool ink = (x + y) % 7 == 0 || x % 9 == 0;
      img.row<std::uint8_t>(y)[3 * x] = ink ? 0 : std::uint8_t(150 + x);
      img.row<std::uint8_t>(y)[3 * x + 1] = ink ? 0 : std::uint8_t(80 + 2 * y);
      img.row<std::uint8_t>(y)[3 * x + 2] = ink ? 0 : 60;
    }
  write_image(dir + "/art.png", img.view());
  RunResult bad = run_texproc("compress " + dir + "/art.png -o " + dir + "/a.dds --format bc3 --bc1-black");
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("--bc1-black"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir + "/a.dds"));
  double se[2] = {};
  for (int black = 0; black < 2; ++black) {
    const std::string out = dir + "/art" + std::to_string(black) + ".ktx2";
    RunResult r = run_texproc("compress " + dir + "/art.png -o " + out + " --format bc1 --linear -q" +
                              (black ? " --bc1-black" : ""));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Image d = decode_texture_image(read_texture(out), 0, 0, 0, PixelType::u8);
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < 3; ++c) {
          const double e = double(d.row<std::uint8_t>(y)[d.channels() * x + c]) - img.row<std::uint8_t>(y)[3 * x + c];
          se[black] += e * e;
        }
  }
  EXPECT_LT(se[1], se[0] * 0.8);
  fs::remove_all(dir);
}

// NVIDIA Texture Tools' nvdecompress (Debian's libnvtt-bin 2.0) decodes
// texproc's legacy-header BC1-BC5 files to the texels texproc's decoder gives,
// within one 8-bit level (BC1's interpolation rounding; NVTT rounds RGTC to
// 8 bits, texproc returns the exact values). NVTT 2.0 predates the DX10
// header and SNORM formats, so those are checked with OpenImageIO, Pillow
// and nvddsinfo elsewhere.
TEST(Cli, NvdecompressAgreesOnLegacyDds) {
  if (std::system("command -v nvdecompress >/dev/null 2>&1") != 0) GTEST_SKIP() << "nvdecompress not installed";
  const std::string dir = temp_dir("cli_nvdecompress");
  write_image(dir + "/in.png", random_image(64, 48, 4, PixelType::u8, 31).view());
  for (const char* f : {"bc1", "bc1a", "bc2", "bc3", "bc4", "bc5"}) {
    const std::string dds = dir + "/" + f + ".dds";
    RunResult r =
        run_texproc("compress " + dir + "/in.png -o " + dds + " --format " + f + " --linear --dds-header dx9 -q");
    ASSERT_EQ(r.exit_code, 0) << f << r.err;
    ASSERT_EQ(std::system(("cd '" + dir + "' && nvdecompress " + std::string(f) + ".dds >/dev/null 2>&1").c_str()), 0)
        << f;
    const Image nv = read_image(dir + "/" + f + ".tga");
    const Image ours = decode_texture_image(read_texture(dds), 0, 0, 0, PixelType::f32);
    const int channels = ours.channels();
    ASSERT_EQ(nv.width(), 64);
    for (int y = 0; y < 48; ++y)
      for (int x = 0; x < 64; ++x)
        for (int c = 0; c < std::min(channels, 3); ++c) {
          // One-channel BC4 comes back from NVTT as gray in R, G and B.
          ASSERT_NEAR(nv.get(x, y, c), ours.get(x, y, c), 1.0 / 255 + 1e-6) << f << " " << x << "," << y << " c" << c;
        }
  }
  fs::remove_all(dir);
}
