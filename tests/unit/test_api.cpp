// The shape of the public API: what must not compile, option structs and
// the format table's codec families.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <utility>

#include "texproc/block_encode.h"
#include "texproc/error.h"
#include "texproc/image.h"
#include "texproc/mip.h"
#include "texproc/normalmap.h"
#include "texproc/texture.h"

using namespace texproc;

// Inputs and outputs are told apart by type: a const image gives a read-only
// view, which converts to nothing a call writes through, so swapping an
// input and an output does not compile.
static_assert(std::is_convertible_v<ImageView, ConstImageView>);
static_assert(!std::is_convertible_v<ConstImageView, ImageView>);
static_assert(std::is_same_v<decltype(std::declval<const Image&>().view()), ConstImageView>);
static_assert(std::is_same_v<decltype(std::declval<Image&>().view()), ImageView>);
static_assert(std::is_same_v<decltype(std::declval<const ConstImageView&>().row<float>(0)), const float*>);
static_assert(std::is_invocable_v<decltype(compute_normal_map), ConstImageView, ImageView, const NormalMapOptions&>);
static_assert(
    !std::is_invocable_v<decltype(compute_normal_map), ConstImageView, ConstImageView, const NormalMapOptions&>);

TEST(Api, ConstViewReadsTheSamePixels) {
  Image img(3, 2, 2, PixelType::u16);
  img.set(2, 1, 1, 0.5f);
  const Image& ro = img;
  const ConstImageView v = ro.view();
  EXPECT_EQ(v.data, img.data());
  EXPECT_EQ(v.row_stride, img.row_stride());
  EXPECT_EQ(v.row<std::uint16_t>(1)[2 * 2 + 1], 32768);
  const ConstImageView converted = img.view();  // an output view read as an input
  EXPECT_EQ(converted.row<std::uint16_t>(1), v.row<std::uint16_t>(1));
}

// Every format's family is the one its name says, compress_image goes by
// it, and is_astc agrees with it.
TEST(Api, FormatInfoNamesTheCodecFamily) {
  for (const std::string& name : texel_format_names()) {
    const FormatInfo& f = format_info(parse_texel_format(name));
    const std::string family = to_string(f.family);
    if (f.compressed) {
      EXPECT_EQ(name.rfind(family + "_", 0), 0u) << name << " is in family " << family;
    } else {
      EXPECT_EQ(f.family, CodecFamily::uncompressed) << name;
    }
    EXPECT_EQ(is_astc(f.format), f.family == CodecFamily::astc) << name;
  }
  const Image img(4, 4, 4, PixelType::u8);
  try {
    compress_image(img.view(), TexelFormat::rgba8_unorm, Quality::fast);
    ADD_FAILURE() << "an uncompressed format was block-encoded";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::unsupported);
  }
  EXPECT_EQ(compress_image(img.view(), TexelFormat::eac_r11_unorm, Quality::fast).size(), 8u);
  EXPECT_EQ(compress_image(img.view(), TexelFormat::etc2_rgba8_unorm, Quality::fast).size(), 16u);
}

// Optional settings are unset by default and take effect when set.
TEST(Api, OptionalSettings) {
  Image img(16, 16, 4, PixelType::u8);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) img.set(x, y, 3, (x + y) % 3 ? 1.0f : 0.0f);
  MipOptions o;
  EXPECT_FALSE(o.alpha_coverage_ref.has_value());
  EXPECT_TRUE(generate_mips(img.view(), o).alpha_coverage.empty());
  o.alpha_coverage_ref = 0.5f;
  EXPECT_EQ(generate_mips(img.view(), o).alpha_coverage.size(), 5u);
  o.alpha_coverage_ref = 0.0f;  // set, and outside (0, 1]
  EXPECT_THROW(generate_mips(img.view(), o), Error);
  EXPECT_FALSE(EncodeOptions{}.astc_effort.has_value());
}

// Layouts and storage are named, not runs of bools.
TEST(Api, SurfaceLayoutAndStorage) {
  std::vector<std::vector<Image>> faces;
  for (int f = 0; f < 6; ++f) faces.push_back({Image(4, 4, 4, PixelType::u8)});
  const Texture cube = texture_from_surfaces(std::move(faces), {.faces = 6}, {.srgb = true});
  EXPECT_EQ(cube.faces, 6u);
  EXPECT_EQ(cube.layers, 1u);
  EXPECT_FALSE(cube.is_array);
  EXPECT_EQ(cube.format, TexelFormat::rgba8_srgb);
  std::vector<std::vector<Image>> layers(3, std::vector<Image>{Image(8, 8, 4, PixelType::u8)});
  const Texture arr =
      compress_texture(layers, {.layers = 3, .is_array = true}, TexelFormat::bc1_rgb_unorm, Quality::fast);
  EXPECT_EQ(arr.layers, 3u);
  EXPECT_TRUE(arr.is_array);
  EXPECT_EQ(texture_from_levels({Image(2, 2, 4, PixelType::f32)}, {.half = true}).format, TexelFormat::rgba16_float);
}

// PixelBytes owns its block: copies are deep, moves leave the source empty,
// resize keeps the leading bytes, and Image and Texture pass blocks without
// a copy.
TEST(Api, PixelBytesOwnsItsBlock) {
  PixelBytes a(std::vector<std::uint8_t>{1, 2, 3, 4});
  PixelBytes b = a;
  b[0] = 9;
  EXPECT_EQ(a[0], 1);
  EXPECT_EQ(b, (std::vector<std::uint8_t>{9, 2, 3, 4}));
  const std::uint8_t* block = b.data();
  PixelBytes c = std::move(b);
  EXPECT_EQ(c.data(), block);
  EXPECT_TRUE(b.empty());  // NOLINT(bugprone-use-after-move): a moved-from block is empty
  c.resize(6);
  EXPECT_EQ(c.size(), 6u);
  EXPECT_TRUE(std::equal(c.begin(), c.begin() + 4, std::vector<std::uint8_t>{9, 2, 3, 4}.begin()));
  c.resize(2);
  EXPECT_EQ(std::vector<std::uint8_t>(c), (std::vector<std::uint8_t>{9, 2}));
  const std::uint8_t raw[3] = {7, 7, 7};
  c.assign(raw, raw + 3);
  EXPECT_EQ(c, PixelBytes(3, 7));
  c.clear();
  EXPECT_EQ(c.data(), nullptr);

  // A large block (16 MiB) goes from an image to a texture and back unmoved.
  Image img(2048, 2048, 4, PixelType::u8);
  const std::uint8_t* pixels = img.data();
  std::vector<Image> levels;
  levels.push_back(std::move(img));
  Texture t = texture_from_levels(std::move(levels));
  EXPECT_EQ(t.image(0).data(), pixels);
  EXPECT_EQ(t.image(0).size(), std::size_t(2048) * 2048 * 4);
  EXPECT_EQ(t.image(0)[12345], 0);  // Image(...) zero-fills
  release_cached_pixel_memory();
}
