// texproc pack: channels of several images in one, moved exactly, as an
// image or block-compressed; sizes that disagree refused.
#include <gtest/gtest.h>

#include <string>

#include "support/images.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;

namespace {
std::string q(const std::string& s) { return "'" + s + "'"; }
}  // namespace

TEST(Pack, ChannelsMoveExactly) {
  const std::string dir = temp_dir("pack_cli");
  const Image ao = random_image(20, 12, 1, PixelType::u8, 1);
  const Image mr = random_image(20, 12, 4, PixelType::u8, 2);
  write_image(dir + "/ao.png", ao.view());
  write_image(dir + "/mr.tga", mr.view());
  RunResult r = run_texproc("pack -r " + q(dir + "/ao.png") + " -g " + q(dir + "/mr.tga:b") + " -b " +
                            q(dir + "/mr.tga") + " -a 1 -o " + q(dir + "/orm.png") + " -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Image orm = read_image(dir + "/orm.png");
  ASSERT_EQ(orm.channels(), 4);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 20; ++x) {
      const std::uint8_t* p = orm.row<std::uint8_t>(y) + 4 * x;
      ASSERT_EQ(p[0], ao.row<std::uint8_t>(y)[x]);
      ASSERT_EQ(p[1], mr.row<std::uint8_t>(y)[4 * x + 2]);  // mr:b
      ASSERT_EQ(p[2], mr.row<std::uint8_t>(y)[4 * x + 2]);  // -b mr: its own blue
      ASSERT_EQ(p[3], 255);
    }
  // Block-compressed: the bytes compress gives the packed image.
  r = run_texproc("pack -r " + q(dir + "/ao.png") + " -g " + q(dir + "/mr.tga:b") + " -b " + q(dir + "/mr.tga") +
                  " -a 1 -o " + q(dir + "/orm.dds") + " --format bc7 --quality fast -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("compress " + q(dir + "/orm.png") + " -o " + q(dir + "/want.dds") +
                  " --format bc7 --quality fast --linear -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/orm.dds"), slurp(dir + "/want.dds"));
  // Sizes must agree, or be made to; a channel letter must be one.
  write_image(dir + "/big.png", random_image(40, 24, 1, PixelType::u8, 3).view());
  r = run_texproc("pack -r " + q(dir + "/ao.png") + " -g " + q(dir + "/big.png") + " -o " + q(dir + "/x.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("one size (--resize WxH makes them)"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.png"));
  r = run_texproc("pack -r " + q(dir + "/ao.png") + " -g " + q(dir + "/big.png") + " -o " + q(dir + "/x.png") +
                  " --resize 10x6 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(probe_image(dir + "/x.png").width, 10);
  r = run_texproc("pack -r " + q(dir + "/ao.png:q") + " -o " + q(dir + "/y.png"));
  EXPECT_EQ(r.exit_code, 1);
  r = run_texproc("pack -g " + q(dir + "/ao.png") + " -o " + q(dir + "/y.png"));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("-r is missing"), std::string::npos) << r.err;
}
