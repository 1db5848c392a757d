// --swizzle, --flip-green and --invert on compress, mip and decompress: the
// same bytes as the command run on an image with its channels moved first.
#include <gtest/gtest.h>

#include <string>

#include "support/images.h"
#include "support/run.h"
#include "texproc/channels.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;

namespace {

std::string q(const std::string& s) { return "'" + s + "'"; }

// Runs `args` with {in} and {out} replaced; exit 0 expected.
void run_ok(std::string args, const std::string& in, const std::string& out) {
  args.replace(args.find("{in}"), 4, q(in));
  args.replace(args.find("{out}"), 5, q(out));
  const RunResult r = run_texproc(args + " -q");
  ASSERT_EQ(r.exit_code, 0) << args << ": " << r.err;
}

}  // namespace

TEST(ChannelOptions, SameBytesAsAnImageMovedFirst) {
  const std::string dir = temp_dir("channels_cli");
  const Image src = random_image(24, 16, 4, PixelType::u8, 21);
  write_image(dir + "/src.png", src.view());
  struct Case {
    const char* command;  // with {in} and {out}
    const char* options;  // the channel options
    const char* swizzle;  // the same as a map applied beforehand
    const char* invert;
    const char* ext;
  };
  const Case cases[] = {
      {"compress {in} -o {out} --format bc4 --linear", "--swizzle g", "g", "", ".dds"},
      {"compress {in} -o {out} --format bc5 --linear", "--flip-green", "", "g", ".ktx2"},
      {"compress {in} -o {out} --format bc7 --quality fast --mips", "--swizzle bgra --invert a", "bgra", "a", ".dds"},
      {"mip {in} -o {out}", "--swizzle rrr1", "rrr1", "", ".tif"},
  };
  for (const Case& c : cases) {
    ChannelMap m = *c.swizzle ? parse_swizzle(c.swizzle) : ChannelMap{};
    if (*c.invert) add_inverted_channels(m, c.invert);
    write_image(dir + "/moved.png", map_channels(src.view(), m).view());
    const std::string a = dir + "/a" + c.ext, b = dir + "/b" + c.ext;
    run_ok(std::string(c.command) + " " + c.options + " -f", dir + "/src.png", a);
    run_ok(std::string(c.command) + " -f", dir + "/moved.png", b);
    EXPECT_EQ(slurp(a), slurp(b)) << c.command << " " << c.options;
  }
  // decompress: the decoded texture's channels moved as it is written.
  run_ok("compress {in} -o {out} --format bc7 --quality fast -f", dir + "/src.png", dir + "/t.dds");
  run_ok("decompress {in} -o {out} -f", dir + "/t.dds", dir + "/plain.png");
  run_ok("decompress {in} -o {out} --swizzle bgr --flip-green -f", dir + "/t.dds", dir + "/moved_dec.png");
  ChannelMap m = parse_swizzle("bgr");
  add_inverted_channels(m, "g");
  const Image want = map_channels(read_image(dir + "/plain.png").view(), m);
  const Image got = read_image(dir + "/moved_dec.png");
  ASSERT_EQ(got.channels(), 3);
  EXPECT_TRUE(std::equal(want.data(), want.data() + want.byte_size(), got.data()));
  // What cannot be done is refused, naming the option or the file.
  RunResult r =
      run_texproc("compress " + q(dir + "/src.png") + " -o " + q(dir + "/x.dds") + " --format bc1 --swizzle rgbq");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("'q' is not one of r, g, b, a, 0, 1"), std::string::npos) << r.err;
  write_image(dir + "/grey.png", random_image(8, 8, 1, PixelType::u8, 2).view());
  r = run_texproc("mip " + q(dir + "/grey.png") + " -o " + q(dir + "/g.tif") + " --invert a");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("grey.png"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cannot invert a"), std::string::npos) << r.err;
}
