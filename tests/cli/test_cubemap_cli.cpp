// texproc cubemap from the command line: every input layout and output,
// IBL files, and malformed inputs named in the error.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "support/images.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/cubemap.h"
#include "texproc/image_io.h"

namespace fs = std::filesystem;

namespace texproc {
namespace {

using test::run_texproc;
using test::temp_dir;

// A float panorama: colour = 0.5 + 0.5 * direction.
Image direction_panorama(int w) {
  Image p(w, w / 2, 3, PixelType::f32);
  for (int y = 0; y < w / 2; ++y)
    for (int x = 0; x < w; ++x) {
      double d[3];
      equirect_direction(x + 0.5, y + 0.5, w, w / 2, d);
      for (int c = 0; c < 3; ++c) p.row<float>(y)[3 * x + c] = float(0.5 + 0.5 * d[c]);
    }
  return p;
}

TEST(CubemapCli, PanoramaToAKtx2CubeWithSeamlessMips) {
  const std::string dir = temp_dir("cubecli");
  write_image(dir + "/pano.exr", direction_panorama(256).view());
  const test::RunResult r = run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/env.ktx2' --mips");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("equirect 256x128 -> cube 64, 7 levels"), std::string::npos) << r.out;
  const Texture t = read_texture(dir + "/env.ktx2");
  EXPECT_EQ(t.faces, 6u);
  EXPECT_EQ(t.width, 64u);  // 256 / 4
  EXPECT_EQ(t.levels, 7u);
  EXPECT_EQ(t.format, TexelFormat::rgba16_float);
  // +X face centre looks along +X: colour (1, 0.5, 0.5).
  const Image px = image_from_texture(t, 0, 0, 0);
  EXPECT_NEAR(px.get(32, 32, 0), 1.0f, 0.01f);
  EXPECT_NEAR(px.get(32, 32, 1), 0.5f, 0.01f);
  const Image ny = image_from_texture(t, 0, 0, 3);  // -Y
  EXPECT_NEAR(ny.get(32, 32, 1), 0.0f, 0.01f);
  fs::remove_all(dir);
}

TEST(CubemapCli, EveryLayoutInAndOut) {
  const std::string dir = temp_dir("cubelayouts");
  write_image(dir + "/pano.exr", direction_panorama(128).view());
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/cross.exr' -q").exit_code, 0);
  ImageFileInfo info = probe_image(dir + "/cross.exr");
  EXPECT_EQ(info.width, 128);
  EXPECT_EQ(info.height, 96);
  for (const char* to : {"vcross", "strip", "vstrip"}) {
    ASSERT_EQ(
        run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/" + to + ".exr' --to " + to + " -q").exit_code, 0)
        << to;
  }
  // Each layout comes back to the same cube (the faces are copied exactly).
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/ref.ktx2' --format rgba32f -q").exit_code, 0);
  const Texture ref = read_texture(dir + "/ref.ktx2");
  for (const char* l : {"cross", "vcross", "strip", "vstrip"}) {
    const test::RunResult r =
        run_texproc("cubemap '" + dir + "/" + l + ".exr' -o '" + dir + "/" + l + ".ktx2' --format rgba32f -q");
    ASSERT_EQ(r.exit_code, 0) << l << r.err;
    const Texture t = read_texture(dir + "/" + l + ".ktx2");
    ASSERT_EQ(t.width, 32u) << l;
    for (int f = 0; f < 6; ++f) {
      const Image a = image_from_texture(t, 0, 0, f), b = image_from_texture(ref, 0, 0, f);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(a.get(5, 20, c), b.get(5, 20, c), 1e-3) << l << " face " << f;  // EXR half
    }
  }
  // Six faces out (DIR/) and back in (--faces).
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/faces/' -q").exit_code, 0);
  std::string faces;
  for (const char* f : {"px", "nx", "py", "ny", "pz", "nz"}) {
    ASSERT_TRUE(fs::exists(dir + "/faces/pano_" + f + ".exr")) << f;
    faces += " '" + dir + "/faces/pano_" + f + ".exr'";
  }
  const test::RunResult r = run_texproc("cubemap --faces" + faces + " -o '" + dir + "/f.ktx2' --format rgba32f");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture t = read_texture(dir + "/f.ktx2");
  EXPECT_NEAR(image_from_texture(t, 0, 0, 4).get(3, 9, 2), image_from_texture(ref, 0, 0, 4).get(3, 9, 2), 1e-3);
  // Back to a panorama.
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/f.ktx2' -o '" + dir + "/back.exr' --to equirect -q").exit_code, 0);
  const Image back = read_image(dir + "/back.exr"), orig = read_image(dir + "/pano.exr");
  EXPECT_EQ(back.width(), 128);
  EXPECT_NEAR(back.get(40, 30, 0), orig.get(40, 30, 0), 0.02);
  // An existing cube texture (the corpus' DDS) is read as six faces.
  if (test::have_corpus()) {
    const std::string dds = test::corpus_dir() + "/hdr/qt3d_default_specular_cube_rgba16f.dds";
    const test::RunResult d = run_texproc("cubemap '" + dds + "' -o '" + dir + "/dds_cross.exr'");
    EXPECT_EQ(d.exit_code, 0) << d.err;
    EXPECT_NE(d.out.find("cube 128 -> cube 128"), std::string::npos) << d.out;
  }
  fs::remove_all(dir);
}

TEST(CubemapCli, IblFilesShAndPreview) {
  const std::string dir = temp_dir("cubeibl");
  write_image(dir + "/pano.exr", direction_panorama(128).view());
  const test::RunResult r = run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/spec.ktx2' --ibl both --sh '" +
                                        dir + "/sh.json' --preview '" + dir + "/p.png' --irradiance-size 8");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture spec = read_texture(dir + "/spec.ktx2");
  EXPECT_EQ(spec.width, 32u);
  EXPECT_EQ(spec.levels, 3u);  // 32, 16, 8: roughness 0, 0.5, 1
  const Texture irr = read_texture(dir + "/spec_irradiance.ktx2");
  EXPECT_EQ(irr.width, 8u);
  EXPECT_EQ(irr.faces, 6u);
  // Irradiance / pi of colour 0.5 + 0.5 d at +Y: 0.5 + 0.5 * (2/3) * 1 ... the
  // cosine lobe's mean of d.y over the hemisphere, 2/3.
  EXPECT_NEAR(image_from_texture(irr, 0, 0, 2).get(4, 4, 1), 0.5 + 0.5 * 2.0 / 3.0, 0.02);
  const std::string sh = test::slurp(dir + "/sh.json");
  EXPECT_NE(sh.find("\"radiance\""), std::string::npos);
  EXPECT_NE(sh.find("\"irradiance_over_pi\""), std::string::npos);
  ImageFileInfo info = probe_image(dir + "/p.png");
  EXPECT_EQ(info.width, 8 * 32 + 16);
  // --ibl irradiance alone: -o is the map.
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/pano.exr' -o '" + dir + "/irr.dds' --ibl irradiance -q").exit_code, 0);
  EXPECT_EQ(read_texture(dir + "/irr.dds").width, 32u);
  fs::remove_all(dir);
}

TEST(CubemapCli, LdrPanoramaStaysSrgbAndClippingIsNamed) {
  const std::string dir = temp_dir("cubeldr");
  Image p(64, 32, 3, PixelType::u8);
  for (std::size_t k = 0; k < p.byte_size(); ++k) p.data()[k] = std::uint8_t(k * 7);
  write_image(dir + "/pano.png", p.view());
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/pano.png' -o '" + dir + "/env.ktx2' --mips -q").exit_code, 0);
  EXPECT_EQ(read_texture(dir + "/env.ktx2").format, TexelFormat::rgba8_srgb);
  // HDR into 8 bits: a warning naming the input and what keeps the values.
  Image hdr(64, 32, 3, PixelType::f32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64 * 3; ++x) hdr.row<float>(y)[x] = 4.0f;
  write_image(dir + "/hdr.exr", hdr.view());
  const test::RunResult r = run_texproc("cubemap '" + dir + "/hdr.exr' -o '" + dir + "/h.ktx2' --format rgba8");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("hdr.exr"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("rgba16f"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(CubemapCli, MalformedInputsNameTheFileAndTheProblem) {
  const std::string dir = temp_dir("cubebad");
  write_image(dir + "/odd.png", Image(100, 60, 3, PixelType::u8).view());
  test::RunResult r = run_texproc("cubemap '" + dir + "/odd.png' -o '" + dir + "/o.ktx2'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("odd.png: 100x60 is no cube map layout"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/o.ktx2"));
  // Forced as a panorama or a cross, the proportions are named.
  r = run_texproc("cubemap '" + dir + "/odd.png' -o '" + dir + "/o.ktx2' --layout equirect");
  EXPECT_NE(r.err.find("odd.png: 100x60 is not a 2:1 panorama"), std::string::npos) << r.err;
  r = run_texproc("cubemap '" + dir + "/odd.png' -o '" + dir + "/o.ktx2' --layout hcross");
  EXPECT_NE(r.err.find("odd.png: 100x60 does not fit a hcross layout"), std::string::npos) << r.err;
  // Six faces of different sizes.
  std::string faces;
  for (int f = 0; f < 6; ++f) {
    const int n = f == 3 ? 8 : 16;
    const std::string name = dir + "/f" + std::to_string(f) + ".png";
    write_image(name, Image(n, n, 3, PixelType::u8).view());
    faces += " '" + name + "'";
  }
  r = run_texproc("cubemap --faces" + faces + " -o '" + dir + "/o.ktx2'");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("f3.png: 8x8, but"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("must be one size"), std::string::npos) << r.err;
  r = run_texproc("cubemap --faces '" + dir + "/f0.png' -o '" + dir + "/o.ktx2'");
  EXPECT_NE(r.exit_code, 0);
  // A chain cannot go into one PNG; an unknown --to is listed.
  write_image(dir + "/p.png", Image(32, 16, 3, PixelType::u8).view());
  r = run_texproc("cubemap '" + dir + "/p.png' -o '" + dir + "/c.png' --mips");
  EXPECT_NE(r.err.find("needs .exr or .tif"), std::string::npos) << r.err;
  r = run_texproc("cubemap '" + dir + "/p.png' -o '" + dir + "/c.png' --to sphere");
  EXPECT_NE(r.err.find("valid: auto, cube"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/c.png"));
  fs::remove_all(dir);
}

}  // namespace
// Compressed IBL: every map in the block format asked for, each level within
// the format's error of the float maps (measured here against an rgba32f run
// of the same options, and reported per level by the tool).
TEST(CubemapCli, CompressedIblEveryMapEveryLevel) {
  const std::string dir = temp_dir("cubecompressed");
  // An HDR sky: the direction panorama with a bright spot (values above 1).
  Image pano = direction_panorama(128);
  for (int y = 10; y < 14; ++y)
    for (int x = 40; x < 44; ++x)
      for (int c = 0; c < 3; ++c) pano.row<float>(y)[3 * x + c] = 40.0f;
  write_image(dir + "/sky.exr", pano.view());
  const std::string common = " --ibl both --size 32 --samples 64";
  ASSERT_EQ(run_texproc("cubemap '" + dir + "/sky.exr' -o '" + dir + "/f.ktx2' --format rgba32f -q" + common).exit_code,
            0);
  struct Case {
    const char* format;
    TexelFormat want;
    double max_log2_rmse;
  };
  for (const Case& c :
       {Case{"bc6h", TexelFormat::bc6h_ufloat, 0.05}, Case{"astc-4x4-hdr", TexelFormat::astc_4x4_sfloat, 0.05}}) {
    const std::string out = dir + "/" + c.format + ".ktx2";
    const test::RunResult r =
        run_texproc("cubemap '" + dir + "/sky.exr' -o '" + out + "' --format " + c.format + common);
    ASSERT_EQ(r.exit_code, 0) << c.format << ": " << r.err;
    EXPECT_NE(r.out.find(std::string(c.format) + " error per level (log2 RMSE):"), std::string::npos) << r.out;
    for (const char* suffix : {"", "_irradiance"}) {
      const Texture got = read_texture(dir + "/" + c.format + suffix + ".ktx2");
      const Texture ref = read_texture(dir + "/f" + suffix + ".ktx2");
      EXPECT_EQ(got.format, c.want) << c.format << suffix;
      ASSERT_EQ(got.levels, ref.levels) << c.format << suffix;
      ASSERT_EQ(got.faces, 6u);
      for (std::uint32_t l = 0; l < got.levels; ++l) {
        double sum = 0;
        std::size_t n = 0;
        for (std::uint32_t f = 0; f < 6; ++f) {
          const Image a = image_from_texture(ref, l, 0, f);
          const Image b = decode_texture_image(got, l, 0, f, PixelType::f32);
          for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x)
              for (int ch = 0; ch < 3; ++ch) {
                const double u = a.get(x, y, ch), v = b.get(x, y, ch);
                const double du = std::log2(1 + std::abs(u)) - std::log2(1 + std::abs(v));
                sum += du * du;
                ++n;
              }
        }
        EXPECT_LT(std::sqrt(sum / double(n)), c.max_log2_rmse) << c.format << suffix << " level " << l;
      }
    }
  }
  // A block format is a texture format; one of fewer than three channels holds no colour.
  test::RunResult r = run_texproc("cubemap '" + dir + "/sky.exr' -o '" + dir + "/x.exr' --format bc6h");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("write a cube texture"), std::string::npos) << r.err;
  r = run_texproc("cubemap '" + dir + "/sky.exr' -o '" + dir + "/x.ktx2' --format bc5");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("needs RGB"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/x.ktx2"));
  fs::remove_all(dir);
}

// --irradiance, --sh and --preview take templates as -o does: one set of
// files for each input.
TEST(CubemapCli, LightingOutputsTakeTemplates) {
  const std::string dir = temp_dir("cubetemplates");
  write_image(dir + "/a.exr", direction_panorama(64).view());
  write_image(dir + "/b.exr", direction_panorama(32).view());
  const test::RunResult r = run_texproc("cubemap '" + dir + "/a.exr' '" + dir + "/b.exr' -o '" + dir +
                                        "/out/{stem}.ktx2' --ibl both --size 8 --samples 16 --irradiance '" + dir +
                                        "/out/{stem}_diffuse.ktx2' --sh '" + dir + "/out/{stem}_sh.json' --preview '" +
                                        dir + "/out/{stem}_preview.png' -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* stem : {"a", "b"})
    for (const char* suffix : {".ktx2", "_diffuse.ktx2", "_sh.json", "_preview.png"})
      EXPECT_TRUE(fs::exists(dir + "/out/" + stem + suffix)) << stem << suffix;
  fs::remove_all(dir);
}

}  // namespace texproc
