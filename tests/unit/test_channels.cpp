// Channel maps: swizzles, constants and inversion, checked texel by texel
// against their definition for every pixel type and channel count.
#include <gtest/gtest.h>

#include <string>

#include "support/images.h"
#include "texproc/channels.h"
#include "texproc/error.h"

using namespace texproc;

namespace {

// The definition: channel c of (x, y) read as RGBA, on the type's scale.
double rgba_of(const Image& img, int x, int y, int c) {
  const int n = img.channels();
  if (n >= 3) return c < n ? img.get(x, y, c) : 1.0;
  if (c < 3) return img.get(x, y, 0);
  return n == 2 ? img.get(x, y, 1) : 1.0;
}

}  // namespace

TEST(Channels, SwizzlesConstantsAndInversionForEveryTypeAndShape) {
  for (PixelType type : {PixelType::u8, PixelType::u16, PixelType::f32})
    for (int channels = 1; channels <= 4; ++channels)
      for (const char* spec : {"bgra", "rrr1", "gggr", "a0b1", "rg", "b", "xyzw", "RGBA"}) {
        const Image in = test::random_image(13, 7, channels, type, 11 + channels);
        ChannelMap m = parse_swizzle(spec);
        const int out_channels = int(std::string(spec).size());
        if (out_channels >= 2) add_inverted_channels(m, "g");
        const Image out = map_channels(in.view(), m);
        ASSERT_EQ(out.channels(), out_channels);
        for (int y = 0; y < in.height(); ++y)
          for (int x = 0; x < in.width(); ++x)
            for (int k = 0; k < out_channels; ++k) {
              const char c = char(std::tolower(spec[k]));
              double want = c == '0'   ? 0.0
                            : c == '1' ? 1.0
                                       : rgba_of(in, x, y,
                                                 int(std::string("rgba").find(c == 'x'   ? 'r'
                                                                              : c == 'y' ? 'g'
                                                                              : c == 'z' ? 'b'
                                                                              : c == 'w' ? 'a'
                                                                                         : c)));
              if (k == 1 && out_channels >= 2) want = 1.0 - want;
              ASSERT_NEAR(out.get(x, y, k), want, 1e-6)  // a wrong 16-bit code is 1.5e-5 off
                  << spec << " " << to_string(type) << " " << channels << " channels at " << x << "," << y << " k "
                  << k;
            }
      }
}

TEST(Channels, IdentityAndBandsAreExact) {
  const Image in = test::random_image(9, 40, 4, PixelType::u16, 3);
  EXPECT_TRUE(ChannelMap{}.identity());
  EXPECT_FALSE(parse_swizzle("rgba").identity());  // four channels asked for, whatever the input has
  ChannelMap m = parse_swizzle("bgr1");
  const Image whole = map_channels(in.view(), m);
  // A band of rows mapped on its own gives those rows of the whole.
  Image band(9, 10, 4, PixelType::u16);
  ConstImageView part = in.view();
  part.data = in.row<std::uint16_t>(20);
  part.height = 10;
  map_channels(part, band.view(), m);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 36; ++x) EXPECT_EQ(band.row<std::uint16_t>(y)[x], whole.row<std::uint16_t>(20 + y)[x]);
}

TEST(Channels, BadSpecsAreNamed) {
  for (const char* bad : {"", "rgbar", "rgq", "r-g"}) {
    try {
      parse_swizzle(bad);
      ADD_FAILURE() << bad;
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::bad_arguments);
      EXPECT_NE(std::string(e.what()).find("--swizzle '" + std::string(bad) + "'"), std::string::npos) << e.what();
    }
  }
  ChannelMap m;
  EXPECT_THROW(add_inverted_channels(m, "q"), Error);
  EXPECT_THROW(add_inverted_channels(m, "1"), Error);
  add_inverted_channels(m, "a");
  const Image grey(4, 4, 1, PixelType::u8);
  EXPECT_THROW(map_channels(grey.view(), m), Error);  // no alpha to invert in a grey image
}
