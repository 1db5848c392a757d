// compress --role ROLE --target T: the same bytes as the options the role
// table in docs/compression.md names, for every role and target.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/images.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/texture.h"

using namespace texproc;
using namespace texproc::test;

namespace {
std::string q(const std::string& s) { return "'" + s + "'"; }
}  // namespace

TEST(Roles, EachRoleIsItsTableRow) {
  const std::string dir = temp_dir("roles");
  write_image(dir + "/rgba.png", random_image(16, 12, 4, PixelType::u8, 6).view());
  write_image(dir + "/sky.exr", random_image(16, 12, 3, PixelType::f32, 7).view());
  struct Case {
    const char* role;
    const char* target;
    const char* input;
    const char* same_as;  // the explicit options
    const char* ext;
  };
  const Case cases[] = {
      {"color", "desktop", "rgba.png", "--format bc7 --mips", ".dds"},
      {"color", "mobile", "rgba.png", "--format astc-6x6 --mips --quality fast", ".ktx2"},
      {"color-alpha", "web", "rgba.png", "--format bc7 --mips --zstd 19", ".ktx2"},
      {"cutout", "desktop", "rgba.png", "--format bc7 --mips --alpha-coverage 0.5", ".dds"},
      {"normal", "desktop", "rgba.png", "--format bc5 --mips --normal-map --linear", ".dds"},
      {"normal", "mobile", "rgba.png", "--format eac-rg11 --mips --normal-map --linear", ".ktx2"},
      {"mask", "desktop", "rgba.png", "--format bc7 --mips --linear", ".dds"},
      {"height", "mobile", "rgba.png", "--format eac-r11 --mips --linear", ".ktx2"},
      {"hdr", "desktop", "sky.exr", "--format bc6h --mips", ".dds"},
      {"ui", "mobile", "rgba.png", "--format astc-4x4 --quality fast", ".ktx2"},
  };
  for (const Case& c : cases) {
    const std::string in = q(dir + "/" + c.input);
    const std::string a = dir + "/a" + c.ext, b = dir + "/b" + c.ext;
    const std::string quality = std::string(c.same_as).find("--quality") == std::string::npos ? "" : " --quality fast";
    RunResult r = run_texproc("compress " + in + " -o " + q(a) + " --role " + c.role + " --target " + c.target +
                              quality + " -f -q");
    ASSERT_EQ(r.exit_code, 0) << c.role << " " << c.target << ": " << r.err;
    r = run_texproc("compress " + in + " -o " + q(b) + " " + c.same_as + " -f -q");
    ASSERT_EQ(r.exit_code, 0) << c.same_as << ": " << r.err;
    EXPECT_EQ(slurp(a), slurp(b)) << c.role << " " << c.target;
  }
  // The options given win over the role's; the default output of --target web is KTX2.
  RunResult r = run_texproc("compress " + q(dir + "/rgba.png") + " -o " + q(dir + "/n.dds") +
                            " --role color --format bc1 --no-mips -f -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture t = read_texture(dir + "/n.dds");
  EXPECT_EQ(t.levels, 1u);
  EXPECT_EQ(std::string(format_info(t.format).name).substr(0, 4), "bc1_") << format_info(t.format).name;
  EXPECT_TRUE(format_info(t.format).srgb);
  r = run_texproc("compress " + q(dir + "/rgba.png") + " -o " + q(dir + "/out/") + " --role color --target web -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/rgba.ktx2"));
  // Unknown names are named with the valid ones; --target alone has nothing to choose for.
  r = run_texproc("compress " + q(dir + "/rgba.png") + " -o " + q(dir + "/x.dds") + " --role albedo");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("valid: color, color-alpha, cutout, normal, mask, height, hdr, ui"), std::string::npos);
  r = run_texproc("compress " + q(dir + "/rgba.png") + " -o " + q(dir + "/x.dds") + " --target mobile");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("add --role"), std::string::npos) << r.err;
}

// A normal map about to be stored as sRGB colour, and alpha a format drops,
// are warned about, naming the file; not when the options say so.
TEST(Roles, NormalMapAsColourAndDroppedAlphaAreNamed) {
  const std::string dir = temp_dir("roles_warnings");
  Image normals(32, 32, 3, PixelType::u8);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) {
      const double nx = 0.4 * std::sin(x * 0.3), ny = 0.4 * std::cos(y * 0.2);
      const double nz = std::sqrt(1 - nx * nx - ny * ny);
      normals.set(x, y, 0, float(nx * 0.5 + 0.5));
      normals.set(x, y, 1, float(ny * 0.5 + 0.5));
      normals.set(x, y, 2, float(nz * 0.5 + 0.5));
    }
  write_image(dir + "/n.png", normals.view());
  write_image(dir + "/rgba.png", random_image(16, 16, 4, PixelType::u8, 9).view());
  write_image(dir + "/rgb.png", random_image(16, 16, 3, PixelType::u8, 9).view());
  auto warnings = [&](const std::string& args) {
    const RunResult r = run_texproc("compress " + args + " -f");
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
    return r.err;
  };
  const std::string as_colour = warnings(q(dir + "/n.png") + " -o " + q(dir + "/n.dds") + " --format bc7");
  EXPECT_NE(as_colour.find(dir + "/n.png: looks like a tangent-space normal map"), std::string::npos) << as_colour;
  EXPECT_EQ(warnings(q(dir + "/n.png") + " -o " + q(dir + "/n.dds") + " --format bc5 --normal-map"), "");
  EXPECT_EQ(warnings(q(dir + "/rgb.png") + " -o " + q(dir + "/c.dds") + " --format bc7"), "");
  const std::string dropped = warnings(q(dir + "/rgba.png") + " -o " + q(dir + "/a.dds") + " --format bc1");
  EXPECT_NE(dropped.find(dir + "/rgba.png: alpha is below 1 in"), std::string::npos) << dropped;
  EXPECT_NE(dropped.find("bc1_rgb_srgb has no alpha"), std::string::npos) << dropped;
  EXPECT_EQ(warnings(q(dir + "/rgba.png") + " -o " + q(dir + "/a.ktx2") + " --format etc2a"), "");
}
