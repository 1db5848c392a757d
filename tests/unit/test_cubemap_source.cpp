// read_cubemap and read_cubemap_faces (image_io.h), and block_format_for
// (texture.h): what the CLI's cubemap and compress commands call.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <filesystem>
#include <string>

#include "support/images.h"
#include "texproc/cubemap.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/texture.h"

using namespace texproc;
using namespace texproc::test;

namespace {

// Six 8-bit faces of `n` texels, each a colour of its own with a gradient,
// written as PNG files.
std::array<std::string, 6> write_faces(const std::string& dir, int n) {
  std::array<std::string, 6> paths;
  for (int f = 0; f < 6; ++f) {
    Image img(n, n, 3, PixelType::u8);
    for (int y = 0; y < n; ++y) {
      for (int x = 0; x < n; ++x) {
        std::uint8_t* p = img.row<std::uint8_t>(y) + 3 * x;
        p[0] = std::uint8_t(40 * f + x);
        p[1] = std::uint8_t(200 - 30 * f + y);
        p[2] = std::uint8_t(17 * f);
      }
    }
    paths[f] = dir + "/face" + std::to_string(f) + ".png";
    write_image(paths[f], img.view());
  }
  return paths;
}

bool same_cube(const Cubemap& a, const Cubemap& b) {
  if (a.size() != b.size()) return false;
  for (int f = 0; f < 6; ++f) {
    const Image& x = a.levels[0].faces[f];
    const Image& y = b.levels[0].faces[f];
    if (x.byte_size() != y.byte_size() || std::memcmp(x.data(), y.data(), x.byte_size()) != 0) return false;
  }
  return true;
}

}  // namespace

// Six faces and the horizontal cross made of them read as the same cube.
TEST(CubemapSource, FacesAndTheirCrossReadTheSame) {
  const std::string dir = temp_dir("cube_source");
  const auto faces = write_faces(dir, 8);
  const CubemapSource from_faces = read_cubemap_faces(faces);
  EXPECT_EQ(from_faces.layout, "faces");
  EXPECT_EQ(from_faces.cube.size(), 8);
  EXPECT_EQ(from_faces.files.size(), 6u);
  EXPECT_FALSE(from_faces.hdr);
  EXPECT_FALSE(from_faces.alpha);
  EXPECT_TRUE(from_faces.color_space.is_srgb());
  // The cross, as 8-bit sRGB: the same codes as the faces.
  Image cross = cubemap_to_layout(from_faces.cube, CubeLayout::cross_horizontal);
  Image cross8 = from_linear_rgba(cross.view(), ColorSpace::srgb(), 3, PixelType::u8);
  write_image(dir + "/cross.png", cross8.view());
  const CubemapSource from_cross = read_cubemap(dir + "/cross.png");
  EXPECT_EQ(from_cross.layout, "hcross 32x24");
  EXPECT_TRUE(same_cube(from_faces.cube, from_cross.cube));
  // Options: a size, and a layout named instead of detected.
  CubemapReadOptions o;
  o.size = 4;
  o.layout = CubeLayout::cross_horizontal;
  EXPECT_EQ(read_cubemap(dir + "/cross.png", o).cube.size(), 4);
  std::filesystem::remove_all(dir);
}

TEST(CubemapSource, RefusesWhatIsNoCube) {
  const std::string dir = temp_dir("cube_source_bad");
  auto faces = write_faces(dir, 8);
  write_image(dir + "/wide.png", checkerboard(12, 8, 3).view());
  faces[3] = dir + "/wide.png";
  try {
    read_cubemap_faces(faces);
    ADD_FAILURE() << "a face of 12x8 was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_arguments);
    EXPECT_NE(std::string(e.what()).find("wide.png: a face is square"), std::string::npos) << e.what();
  }
  CubemapReadOptions o;
  o.layout = CubeLayout::equirect;
  try {
    read_cubemap(dir + "/wide.png", o);
    ADD_FAILURE() << "a 3:2 panorama was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::bad_arguments);
    EXPECT_NE(std::string(e.what()).find("is not a 2:1 panorama"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

TEST(BlockFormatNames, FamiliesAliasesAndFullNames) {
  EXPECT_EQ(block_format_for("bc7", true), TexelFormat::bc7_srgb);
  EXPECT_EQ(block_format_for("BC7", false), TexelFormat::bc7_unorm);
  EXPECT_EQ(block_format_for("bc4", true), TexelFormat::bc4_unorm);  // data: no sRGB form
  EXPECT_EQ(block_format_for("dxt5", true), TexelFormat::bc3_srgb);
  EXPECT_EQ(block_format_for("3dc", false), TexelFormat::bc5_unorm);
  EXPECT_EQ(block_format_for("etc2a1", true), TexelFormat::etc2_rgba1_srgb);
  EXPECT_EQ(block_format_for("astc_6x6", true), astc_format(6, 6, true, false));
  EXPECT_EQ(block_format_for("astc-8x5-hdr", true), astc_format(8, 5, false, true));
  // A full name is that format, sRGB or not.
  EXPECT_EQ(block_format_for("BC7_UNORM", true), TexelFormat::bc7_unorm);
  EXPECT_EQ(block_format_for("VK_FORMAT_BC1_RGB_SRGB_BLOCK", false), TexelFormat::bc1_rgb_srgb);
  EXPECT_EQ(exact_block_format("bc7_srgb"), TexelFormat::bc7_srgb);
  EXPECT_FALSE(exact_block_format("bc7").has_value());
  EXPECT_FALSE(exact_block_format("rgba8_srgb").has_value());  // not a block format
  for (const char* bad : {"bc9", "astc-7x7", "astc-6x6-ldr", ""}) {
    try {
      block_format_for(bad, true);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::bad_arguments);
      EXPECT_NE(std::string(e.what()).find("(valid: bc1, bc1a"), std::string::npos) << e.what();
    }
  }
}
