// --resize, --max-size, --pow2, --multiple-of on mip, compress, normalmap
// and conemap: level 0 gets the size the rule gives, resampled.
#include <gtest/gtest.h>

#include <string>

#include "support/images.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

using namespace texproc;
using namespace texproc::test;

namespace {
std::string q(const std::string& s) { return "'" + s + "'"; }
}  // namespace

TEST(ResizeOptions, EveryCommandGetsTheRulesSize) {
  const std::string dir = temp_dir("resize_cli");
  write_image(dir + "/a.png", random_image(48, 20, 4, PixelType::u8, 8).view());
  auto ok = [&](const std::string& args) {
    const RunResult r = run_texproc(args + " -q -f");
    EXPECT_EQ(r.exit_code, 0) << args << ": " << r.err;
  };
  ok("mip " + q(dir + "/a.png") + " -o " + q(dir + "/m.dds") + " --max-size 16");
  Texture t = read_texture(dir + "/m.dds");
  EXPECT_EQ(t.width, 16u);
  EXPECT_EQ(t.height, 7u);  // 20 * 16 / 48 rounded
  EXPECT_EQ(t.levels, 5u);
  ok("mip " + q(dir + "/a.png") + " -o " + q(dir + "/m.png") + " --pow2 down --levels 2");
  EXPECT_EQ(probe_image(dir + "/m_mip0.png").width, 32);
  EXPECT_EQ(probe_image(dir + "/m_mip0.png").height, 16);
  EXPECT_EQ(probe_image(dir + "/m_mip1.png").width, 16);
  ok("compress " + q(dir + "/a.png") + " -o " + q(dir + "/c.dds") + " --format bc1 --resize 30x0 --multiple-of 4");
  t = read_texture(dir + "/c.dds");
  EXPECT_EQ(t.width, 32u);   // 30 to a multiple of 4
  EXPECT_EQ(t.height, 16u);  // 30 * 20 / 48 = 12.5 -> 13 -> 16
  ok("normalmap " + q(dir + "/a.png") + " -o " + q(dir + "/n.png") + " --resize 24x10");
  EXPECT_EQ(probe_image(dir + "/n.png").width, 24);
  ok("conemap " + q(dir + "/a.png") + " -o " + q(dir + "/k.png") + " --fast --max-size 12");
  EXPECT_EQ(probe_image(dir + "/k.png").width, 12);
  EXPECT_EQ(probe_image(dir + "/k.png").height, 5);

  // A texture's own chain cannot be resized level by level; a bad rule is named.
  ok("mip " + q(dir + "/a.png") + " -o " + q(dir + "/chain.ktx2"));
  RunResult r =
      run_texproc("compress " + q(dir + "/chain.ktx2") + " -o " + q(dir + "/x.dds") + " --format bc1 --max-size 8");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("add --mips"), std::string::npos) << r.err;
  r = run_texproc("mip " + q(dir + "/a.png") + " -o " + q(dir + "/x.dds") + " --resize 10by3");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--resize 10by3"), std::string::npos) << r.err;
  r = run_texproc("mip " + q(dir + "/a.png") + " -o " + q(dir + "/x.dds") + " --pow2 sideways");
  EXPECT_EQ(r.exit_code, 1);
}
