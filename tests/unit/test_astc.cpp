// ASTC through ARM's astc-encoder: every footprint, edge blocks, HDR, normal
// maps, containers, threads, and astc-encoder's own CLI (`astcenc`, Debian's
// package of the same library) as the independent check: it must write the
// bytes texproc writes and decode texproc's files to texproc's pixels.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "support/images.h"
#include "support/run.h"
#include "support/threads.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/metrics.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

const std::pair<int, int> kFootprints[] = {{4, 4}, {5, 4},  {5, 5},  {6, 5},  {6, 6},   {8, 5},   {8, 6},
                                           {8, 8}, {10, 5}, {10, 6}, {10, 8}, {10, 10}, {12, 10}, {12, 12}};

// A smooth RGBA gradient with a soft alpha ramp: what ASTC codes well.
Image gradient(int w, int h, int channels = 4) {
  Image img(w, h, channels, PixelType::u8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float u = w > 1 ? float(x) / float(w - 1) : 0.5f, v = h > 1 ? float(y) / float(h - 1) : 0.5f;
      const float c[4] = {0.2f + 0.3f * u, 0.3f + 0.3f * v, 0.4f + 0.2f * (u + v), 1.0f - 0.2f * u};
      for (int k = 0; k < channels; ++k) img.set(x, y, k, c[k]);
    }
  return img;
}

bool have_astcenc_cli() { return std::system("command -v astcenc >/dev/null 2>&1") == 0; }

std::string file_bytes(const std::string& p) { return slurp(p); }

}  // namespace

// Every footprint, at sizes that are not multiples of it and at 1x1: the
// block count is the rounded-up one and the decoded image is close.
TEST(Astc, EveryFootprintCodesEdgeBlocksAndOneTexel) {
  for (auto [bw, bh] : kFootprints) {
    for (auto [w, h] : {std::pair{1, 1}, {13, 7}, {17, 19}}) {
      const Image src = gradient(w, h);
      const TexelFormat f = astc_format(bw, bh, false, false);
      const std::vector<std::uint8_t> blocks = compress_image(src.view(), f, Quality::fast);
      ASSERT_EQ(blocks.size(), image_bytes(f, std::uint32_t(w), std::uint32_t(h))) << bw << "x" << bh;
      ASSERT_EQ(blocks.size(), std::size_t((w + bw - 1) / bw) * ((h + bh - 1) / bh) * 16);
      const Image back = decompress_image(blocks, w, h, f, PixelType::u8);
      ASSERT_EQ(back.width(), w);
      ASSERT_EQ(back.channels(), 4);
      // 22 dB: a 12x12 block (0.89 bit a texel) over a four-channel ramp at
      // -fast; misplaced or misdecoded blocks give under 12.
      EXPECT_GT(compare_images(src.view(), back.view()).psnr(), 22.0) << bw << "x" << bh << " " << w << "x" << h;
    }
  }
}

// Gray, gray+alpha and RGB inputs fill RGBA as for BC1-BC3 (gray to RGB,
// alpha 1 when absent). Constant images code exactly (to 8 bits).
TEST(Astc, ChannelLayoutsFillRgba) {
  const float value[4] = {0.4f, 0.7f, 0.2f, 0.9f};
  for (int channels : {1, 2, 3, 4}) {
    const Image src = constant_image(10, 6, channels, PixelType::u8, value);
    const Image back = decompress_image(compress_image(src.view(), TexelFormat::astc_4x4_unorm, Quality::fast), 10, 6,
                                        TexelFormat::astc_4x4_unorm, PixelType::u8);
    const float want[4][4] = {
        {0.4f, 0.4f, 0.4f, 1.0f}, {0.4f, 0.4f, 0.4f, 0.7f}, {0.4f, 0.7f, 0.2f, 1.0f}, {0.4f, 0.7f, 0.2f, 0.9f}};
    for (int c = 0; c < 4; ++c)
      EXPECT_NEAR(back.get(9, 5, c), want[channels - 1][c], 1.5f / 255.0f) << channels << " " << c;
  }
}

// HDR: values far above 1 survive, within ASTC's HDR precision.
TEST(Astc, HdrRoundTripKeepsValuesAboveOne) {
  Image src(30, 18, 3, PixelType::f32);
  for (int y = 0; y < 18; ++y)
    for (int x = 0; x < 30; ++x)
      for (int c = 0; c < 3; ++c)
        src.row<float>(y)[x * 3 + c] = std::exp2(float(x) / 29.0f * 6.0f - 1.0f) * (1.0f + 0.2f * c);
  const TexelFormat f = TexelFormat::astc_6x6_sfloat;
  const Image back = decompress_image(compress_image(src.view(), f, Quality::normal), 30, 18, f, PixelType::f32);
  float top = 0.0f;
  double log_err = 0.0;
  for (int y = 0; y < 18; ++y)
    for (int x = 0; x < 30; ++x)
      for (int c = 0; c < 3; ++c) {
        const float a = src.row<float>(y)[x * 3 + c], b = back.row<float>(y)[x * 4 + c];
        top = std::max(top, b);
        log_err = std::max(log_err, std::abs(std::log2(double(b) / double(a))));
      }
  EXPECT_GT(top, 30.0f);
  EXPECT_LT(log_err, 0.1);  // within 7% everywhere
  // An LDR format clamps the same input to [0, 1].
  const Image ldr = decompress_image(compress_image(src.view(), TexelFormat::astc_6x6_unorm, Quality::fast), 30, 18,
                                     TexelFormat::astc_6x6_unorm, PixelType::f32);
  EXPECT_LE(ldr.get(29, 0, 0), 1.0f);
}

// Normal maps: X in RGB, Y in alpha (astc-encoder's rrrg), as documented.
TEST(Astc, NormalMapStoresXInRgbAndYInAlpha) {
  Image n(20, 20, 3, PixelType::u8);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) {
      const float nx = (float(x) - 9.5f) / 25.0f, ny = (float(y) - 9.5f) / 25.0f;
      const float nz = std::sqrt(1.0f - nx * nx - ny * ny);
      n.set(x, y, 0, nx * 0.5f + 0.5f);
      n.set(x, y, 1, ny * 0.5f + 0.5f);
      n.set(x, y, 2, nz * 0.5f + 0.5f);
    }
  EncodeOptions o;
  o.normal_map = true;
  const Image back = decompress_image(compress_image(n.view(), TexelFormat::astc_5x5_unorm, Quality::normal, o), 20, 20,
                                      TexelFormat::astc_5x5_unorm, PixelType::f32);
  for (int y = 0; y < 20; y += 3)
    for (int x = 0; x < 20; x += 3) {
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.get(x, y, c), n.get(x, y, 0), 0.02f);
      EXPECT_NEAR(back.get(x, y, 3), n.get(x, y, 1), 0.02f);
    }
  o.normal_map = true;
  EXPECT_THROW(compress_image(n.view(), TexelFormat::astc_5x5_sfloat, Quality::fast, o), Error);
}

// The bytes do not depend on the thread count (astc-encoder searches each
// block on its own; texproc's threads only take blocks from it).
TEST(Astc, SameBytesForAnyThreadCount) {
  const Image src = random_image(70, 45, 4, PixelType::u8, 5);
  for (TexelFormat f : {TexelFormat::astc_4x4_srgb, TexelFormat::astc_8x5_unorm}) {
    const auto one = with_threads(1, [&] { return compress_image(src.view(), f, Quality::normal); });
    EXPECT_EQ(with_threads(2, [&] { return compress_image(src.view(), f, Quality::normal); }), one);
    EXPECT_EQ(with_threads(7, [&] { return compress_image(src.view(), f, Quality::normal); }), one);
  }
}

// Effort: the preset each quality names, or astc-encoder's number.
TEST(Astc, EffortOverridesThePreset) {
  const Image src = random_image(32, 32, 3, PixelType::u8, 9);
  EncodeOptions o;
  o.astc_effort = 60.0f;  // -medium
  EXPECT_EQ(compress_image(src.view(), TexelFormat::astc_6x6_unorm, Quality::fast, o),
            compress_image(src.view(), TexelFormat::astc_6x6_unorm, Quality::normal));
  o.astc_effort = 101.0f;
  EXPECT_THROW(compress_image(src.view(), TexelFormat::astc_6x6_unorm, Quality::fast, o), Error);
}

// KTX2: the VkFormat, every level's size and the DFD libktx writes
// (KHR_DF_MODEL_ASTC, the footprint, one 128-bit sample; SFLOAT float and
// signed with bounds -1, 1), for every footprint and profile.
TEST(Astc, Ktx2LevelSizesAndDfdForEveryFootprint) {
  for (auto [bw, bh] : kFootprints) {
    for (int p = 0; p < 3; ++p) {
      const TexelFormat f = astc_format(bw, bh, p == 1, p == 2);
      const FormatInfo& fi = format_info(f);
      Texture t;
      t.format = f;
      t.width = 37;
      t.height = 21;
      t.levels = 6;
      for (std::uint32_t l = 0; l < t.levels; ++l) {
        const Image level = gradient(int(t.level_width(l)), int(t.level_height(l)));
        t.images.emplace_back(compress_image(level.view(), f, Quality::fast));
        ASSERT_EQ(t.images.back().size(),
                  std::size_t((t.level_width(l) + bw - 1) / bw) * ((t.level_height(l) + bh - 1) / bh) * 16);
      }
      const std::vector<std::uint8_t> file = encode_ktx2(t);
      auto u32 = [&](std::size_t at) {
        std::uint32_t v;
        std::memcpy(&v, file.data() + at, 4);
        return v;
      };
      EXPECT_EQ(u32(12), fi.vk_format);
      EXPECT_EQ(u32(16), 1u) << "typeSize";
      EXPECT_EQ(u32(40), 6u) << "levelCount";
      for (std::uint32_t l = 0; l < t.levels; ++l) {
        std::uint64_t length;
        std::memcpy(&length, file.data() + 80 + 24 * l + 8, 8);
        EXPECT_EQ(length, t.images[l].size()) << "level " << l;
      }
      const std::size_t dfd = u32(48);
      EXPECT_EQ(u32(dfd), 44u);                                   // dfdTotalSize: one block, one sample
      EXPECT_EQ(u32(dfd + 12) & 0xFF, 162u);                      // KHR_DF_MODEL_ASTC
      EXPECT_EQ((u32(dfd + 12) >> 16) & 0xFF, p == 1 ? 2u : 1u);  // transfer sRGB / linear
      EXPECT_EQ(u32(dfd + 16), std::uint32_t(bw - 1) | std::uint32_t(bh - 1) << 8);
      EXPECT_EQ(u32(dfd + 20), 16u);  // bytesPlane0
      EXPECT_EQ(u32(dfd + 28), 127u << 16 | (p == 2 ? 0xC0u : 0u) << 24);
      EXPECT_EQ(u32(dfd + 36), p == 2 ? 0xBF800000u : 0u);
      EXPECT_EQ(u32(dfd + 40), p == 2 ? 0x3F800000u : 0xFFFFFFFFu);
      const Texture back = decode_ktx2(file.data(), file.size(), "t.ktx2");
      EXPECT_EQ(back.format, f);
      EXPECT_TRUE(back.images == t.images);
    }
  }
}

// KTX1 and .astc have one code for LDR and HDR: the reader tells them apart
// by the blocks.
TEST(Astc, ProfilelessContainersTellHdrByTheBlocks) {
  Image hdr(16, 16, 3, PixelType::f32);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x)
      for (int c = 0; c < 3; ++c) hdr.row<float>(y)[x * 3 + c] = 4.0f + float(x + c);
  const Image ldr = gradient(16, 16);
  for (bool is_hdr : {false, true}) {
    const TexelFormat f = astc_format(8, 8, false, is_hdr);
    Texture t;
    t.format = f;
    t.width = t.height = 16;
    t.images.emplace_back(compress_image(is_hdr ? hdr.view() : ldr.view(), f, Quality::fast));
    const std::vector<std::uint8_t> k1 = encode_ktx1(t), a = encode_astc(t);
    EXPECT_EQ(decode_ktx1(k1.data(), k1.size(), "t.ktx").format, f);
    EXPECT_EQ(decode_astc(a.data(), a.size(), "t.astc").format, f);
  }
}

// Malformed .astc files: every truncation, zero and huge sizes, block sizes
// ASTC does not have, 3D: Error, never a crash.
TEST(Astc, MalformedAstcFilesAreRejected) {
  Texture t;
  t.format = TexelFormat::astc_5x4_unorm;
  t.width = 11;
  t.height = 9;
  t.images.emplace_back(compress_image(gradient(11, 9).view(), t.format, Quality::fast));
  const std::vector<std::uint8_t> good = encode_astc(t);
  ASSERT_EQ(good.size(), 16u + 3 * 3 * 16);
  EXPECT_EQ(good[0], 0x13);
  EXPECT_EQ(good[3], 0x5C);
  EXPECT_EQ(decode_astc(good.data(), good.size(), "g.astc").images, t.images);
  for (std::size_t n = 0; n < good.size(); ++n) {
    EXPECT_THROW(decode_astc(good.data(), n, "cut.astc"), Error) << n;
  }
  auto with = [&](std::size_t at, std::initializer_list<std::uint8_t> bytes) {
    std::vector<std::uint8_t> b = good;
    std::size_t i = at;
    for (std::uint8_t v : bytes) b[i++] = v;
    return b;
  };
  auto code_of = [](const std::vector<std::uint8_t>& b) {
    try {
      decode_astc(b.data(), b.size(), "bad.astc");
    } catch (const Error& e) {
      return e.code();
    }
    return ErrorCode::success;
  };
  EXPECT_EQ(code_of(with(7, {0, 0, 0})), ErrorCode::invalid_file);           // width 0
  EXPECT_EQ(code_of(with(10, {0, 0, 0})), ErrorCode::invalid_file);          // height 0
  EXPECT_EQ(code_of(with(7, {0xFF, 0xFF, 0xFF})), ErrorCode::invalid_file);  // 16M wide, 144 bytes of blocks
  EXPECT_EQ(code_of(with(4, {7, 7})), ErrorCode::invalid_file);              // no 7x7 footprint
  EXPECT_EQ(code_of(with(4, {0, 4})), ErrorCode::invalid_file);
  EXPECT_EQ(code_of(with(6, {0})), ErrorCode::invalid_file);  // block depth 0
  EXPECT_EQ(code_of(with(6, {4})), ErrorCode::unsupported);   // 3D
  std::vector<std::uint8_t> longer = good;
  longer.push_back(0);
  EXPECT_EQ(code_of(longer), ErrorCode::invalid_file);
}

// Through the CLI: exit 3 and no output for a malformed file.
TEST(Astc, CliRefusesMalformedAstcWithNoOutput) {
  const std::string dir = temp_dir("astc_bad");
  std::vector<std::uint8_t> b = {0x13, 0xAB, 0xA1, 0x5C, 6, 6, 1, 0, 0, 0, 8, 0, 0, 1, 0, 0};
  b.resize(16 + 16, 0);
  std::FILE* f = std::fopen((dir + "/bad.astc").c_str(), "wb");
  std::fwrite(b.data(), 1, b.size(), f);
  std::fclose(f);
  const RunResult r = run_texproc("decompress '" + dir + "/bad.astc' -o '" + dir + "/out.png'");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("bad.astc"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.png"));
  EXPECT_EQ(run_texproc("info '" + dir + "/bad.astc'").exit_code, 3);
  fs::remove_all(dir);
}

// What the CLI refuses, with the way out in the message.
TEST(Astc, CliRefusals) {
  const std::string dir = temp_dir("astc_cli");
  write_image(dir + "/a.png", gradient(20, 12).view());
  const std::string in = "'" + dir + "/a.png' ";
  RunResult r = run_texproc("compress " + in + "-o '" + dir + "/x.ktx2' --format astc-7x7");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("12x12"), std::string::npos) << r.err;
  r = run_texproc("compress " + in + "-o '" + dir + "/x.dds' --format astc-4x4");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_NE(r.err.find(".astc"), std::string::npos) << r.err;
  EXPECT_EQ(run_texproc("compress " + in + "-o '" + dir + "/x.dds' --format bc1 --astc-effort 50").exit_code, 1);
  EXPECT_EQ(run_texproc("compress " + in + "-o '" + dir + "/x.ktx2' --format astc-4x4-hdr --normal-map").exit_code, 1);
  EXPECT_EQ(run_texproc("compress " + in + "-o '" + dir + "/x.ktx2' --format astc-4x4-hdr --srgb").exit_code, 1);
  r = run_texproc("compress " + in + "-o '" + dir + "/x.astc' --format astc-4x4 --mips");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_FALSE(fs::exists(dir + "/x.astc"));
  // The default container for -o DIR/ is KTX2.
  ASSERT_EQ(run_texproc("compress " + in + "-o '" + dir + "/out/' --format ASTC-6x6 -q").exit_code, 0);
  EXPECT_EQ(read_texture(dir + "/out/a.ktx2").format, TexelFormat::astc_6x6_srgb);
  // info and compare read ASTC like any other texture.
  ASSERT_EQ(run_texproc("compress " + in + "-o '" + dir + "/a.astc' --format astc-5x4 --linear -q").exit_code, 0);
  r = run_texproc("info '" + dir + "/a.astc' --json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"container\": \"astc\""), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("astc_5x4_unorm"), std::string::npos) << r.out;
  EXPECT_EQ(run_texproc("compare " + in + "'" + dir + "/a.astc' --min-psnr 30").exit_code, 0);
  EXPECT_EQ(run_texproc("compare " + in + "'" + dir + "/a.astc' --min-psnr 80").exit_code, 7);
  fs::remove_all(dir);
}

// The library is opened on first use only: a BC1 run never maps it, an
// ASTC run does; when it is missing, ASTC fails naming it and BC1 works.
TEST(Astc, LibraryIsLoadedOnFirstUseOnly) {
  const std::string dir = temp_dir("astc_load");
  write_image(dir + "/a.png", gradient(16, 16).view());
  // texproc with `env` set; returns the exit status, stderr in `err`.
  auto run_env = [&](const std::string& env, const std::string& args, std::string& err) {
    const std::string cmd =
        env + " " + TEXPROC_CLI_PATH + " compress '" + dir + "/a.png' " + args + " 2>'" + dir + "/err.txt' >/dev/null";
    const int status = std::system(cmd.c_str());
    err = slurp(dir + "/err.txt");
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  std::string err;
  EXPECT_EQ(run_env("LD_DEBUG=files", "-o '" + dir + "/a.dds' --format bc1", err), 0);
  EXPECT_EQ(err.find("astcenc"), std::string::npos) << "a BC1 run maps libastcenc";
  EXPECT_EQ(run_env("LD_DEBUG=files", "-o '" + dir + "/a.ktx2' --format astc-4x4", err), 0);
  EXPECT_NE(err.find("astcenc"), std::string::npos);
  EXPECT_EQ(
      run_env("TEXPROC_ASTCENC_LIBRARY=/nonexistent/libastcenc.so", "-o '" + dir + "/d.ktx2' --format astc-4x4", err),
      5);
  EXPECT_NE(err.find("astc-encoder"), std::string::npos) << err;
  EXPECT_NE(err.find("/nonexistent/libastcenc.so"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir + "/d.ktx2"));
  EXPECT_EQ(run_env("TEXPROC_ASTCENC_LIBRARY=/nonexistent/libastcenc.so", "-o '" + dir + "/d.dds' --format bc1", err),
            0);
  fs::remove_all(dir);
}

// astcenc, ARM's CLI over the same library, writes the bytes texproc writes
// for the same preset, footprint and profile (LDR linear and sRGB, alpha,
// normal maps, a numeric effort), and decodes texproc's .astc files to the
// pixels texproc decodes.
TEST(Astc, AstcencCliWritesTheSameBytesAndDecodesTheSamePixels) {
  if (!have_astcenc_cli()) GTEST_SKIP() << "no astcenc (Debian: astcenc)";
  const std::string dir = temp_dir("astc_cli_match");
  write_image(dir + "/rgba.png", random_image(45, 29, 4, PixelType::u8, 3).view());
  write_image(dir + "/rgb.png", gradient(64, 40, 3).view());
  struct Case {
    const char* input;
    const char* format;
    const char* texproc_flags;
    const char* astcenc_args;  // profile flag, footprint, preset, extra
  } cases[] = {
      {"rgb.png", "astc-4x4", "--linear --quality fast", "-cl {in} {out} 4x4 -fast"},
      {"rgb.png", "astc-6x6", "--quality normal", "-cs {in} {out} 6x6 -medium"},
      {"rgba.png", "astc-8x8", "--quality fast", "-cs {in} {out} 8x8 -fast"},
      {"rgba.png", "astc-12x10", "--linear --astc-effort 30", "-cl {in} {out} 12x10 30"},
      {"rgb.png", "astc-5x5", "--normal-map --quality fast", "-cl {in} {out} 5x5 -fast -normal"},
  };
  for (const Case& c : cases) {
    const std::string in = dir + "/" + c.input, ours = dir + "/ours.astc", theirs = dir + "/theirs.astc";
    ASSERT_EQ(run_texproc("compress '" + in + "' -o '" + ours + "' --format " + c.format + " " + c.texproc_flags +
                          " -f -q --threads 2")
                  .exit_code,
              0)
        << c.format;
    std::string args = c.astcenc_args;
    args.replace(args.find("{in}"), 4, "'" + in + "'");
    args.replace(args.find("{out}"), 5, "'" + theirs + "'");
    ASSERT_EQ(std::system(("astcenc " + args + " -silent -j 1 >/dev/null 2>&1").c_str()), 0) << args;
    EXPECT_EQ(file_bytes(ours), file_bytes(theirs)) << c.format << " " << c.texproc_flags;
    // astcenc -dl decodes texproc's file to texproc's pixels.
    const std::string png = dir + "/theirs.png", ours_png = dir + "/ours.png";
    ASSERT_EQ(std::system(("astcenc -dl '" + ours + "' '" + png + "' -silent >/dev/null 2>&1").c_str()), 0);
    ASSERT_EQ(run_texproc("decompress '" + ours + "' -o '" + ours_png + "' -f -q").exit_code, 0);
    const Image a = read_image(png), b = read_image(ours_png);
    ASSERT_EQ(a.width(), b.width());
    ASSERT_EQ(a.channels(), 4);
    ASSERT_EQ(b.channels(), 4);
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.byte_size()), 0) << c.format << ": astcenc -dl differs";
  }
  fs::remove_all(dir);
}

// Float input outside [0, 1] to an LDR format warns once, naming the file, the
// range and the HDR way out; --clip silences it; an HDR format keeps the values.
TEST(Astc, LdrFormatsWarnWhenTheyClipFloatInput) {
  const std::string dir = temp_dir("astc_clip");
  Image hdr(12, 8, 3, PixelType::f32);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 12; ++x)
      for (int c = 0; c < 3; ++c) hdr.row<float>(y)[x * 3 + c] = 0.25f * float(x);
  write_image(dir + "/sky.exr", hdr.view());
  const std::string in = "'" + dir + "/sky.exr' ";
  RunResult r = run_texproc("compress " + in + "-o '" + dir + "/a.ktx2' --format astc-4x4");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("sky.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2.75"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("hdr"), std::string::npos) << r.err;
  r = run_texproc("compress " + in + "-o '" + dir + "/b.dds' --format bc1");
  EXPECT_NE(r.err.find("clipped"), std::string::npos) << r.err;
  r = run_texproc("compress " + in + "-o '" + dir + "/c.dds' --format bc1 --clip");
  EXPECT_EQ(r.err.find("clipped"), std::string::npos) << r.err;
  r = run_texproc("compress " + in + "-o '" + dir + "/d.ktx2' --format astc-4x4-hdr");
  EXPECT_EQ(r.err.find("clipped"), std::string::npos) << r.err;
  const Image back = decode_texture_image(read_texture(dir + "/d.ktx2"), 0, 0, 0, PixelType::f32);
  EXPECT_GT(back.get(11, 0, 0), 2.5f);
  fs::remove_all(dir);
}

// Cubemaps keep their faces through ASTC, with a chain per face.
TEST(Astc, CubemapsKeepTheirFaces) {
  const std::string dir = temp_dir("astc_cube");
  std::vector<std::vector<Image>> faces;
  for (int f = 0; f < 6; ++f) {
    faces.emplace_back();
    faces.back().push_back(random_image(16, 16, 4, PixelType::u8, unsigned(40 + f)));
  }
  write_texture(dir + "/cube.dds", texture_from_surfaces(std::move(faces), {.faces = 6}, {.srgb = true}));
  ASSERT_EQ(
      run_texproc("compress '" + dir + "/cube.dds' -o '" + dir + "/cube.ktx2' --format astc-8x8 --mips -q").exit_code,
      0);
  const Texture t = read_texture(dir + "/cube.ktx2");
  EXPECT_EQ(t.format, TexelFormat::astc_8x8_srgb);
  EXPECT_EQ(t.faces, 6u);
  EXPECT_EQ(t.levels, 5u);
  EXPECT_FALSE(t.image(0, 0, 0) == t.image(0, 0, 5));
  fs::remove_all(dir);
}
