// Hostile conditions: a busy machine at exit, recipes that would overwrite
// sources, writers on a full disk, non-finite samples, files that declare
// enormous work, inputs truncated while read, signals mid-batch, and options
// out of range. Each failure exits with its documented code, names the file,
// and leaves nothing under a final name.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <vector>

#include <jpeglib.h>
#include <sys/resource.h>

#include "io/codecs/codecs.h"
#include "support/disks.h"
#include "support/images.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/metrics.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

int run_status(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

// Keeps every core busy while it lives, as `make -j` does.
class BusyCores {
 public:
  BusyCores() {
    const unsigned n = std::max(2u, std::thread::hardware_concurrency());
    for (unsigned i = 0; i < n; ++i) {
      threads_.emplace_back([this] {
        volatile unsigned long x = 0;
        while (!stop_) x = x + 1;
      });
    }
  }
  ~BusyCores() {
    stop_ = true;
    for (auto& t : threads_) t.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::vector<std::thread> threads_;
};

// Starts `texproc ARGS` (shell words, redirections included) in a child
// process with `env` added ("NAME=value"), without waiting for it.
pid_t spawn_texproc(const std::string& args, const std::vector<std::string>& env = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    for (const auto& e : env) ::putenv(const_cast<char*>(e.c_str()));
    const std::string cmd = "exec " + std::string(TEXPROC_CLI_PATH) + " " + args;
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// The exit code and the peak resident memory (KiB) of `texproc ARGS`.
struct Measured {
  int exit_code = -1;
  long max_rss_kib = 0;
  std::string err;
};
Measured run_measured(const std::string& args, const std::vector<std::string>& env = {}) {
  const std::string err_file = temp_dir("measured") + "/err";
  const pid_t pid = spawn_texproc(args + " >/dev/null 2>" + err_file, env);
  int status = 0;
  rusage usage{};
  ::wait4(pid, &status, 0, &usage);
  Measured m;
  m.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  m.max_rss_kib = usage.ru_maxrss;
  m.err = slurp(err_file);
  return m;
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f << bytes;
}

// A little-endian TIFF of a 16x16 RGBA image stored as one deflate tile of
// tile_w x tile_h (the tile's bytes are a few of zlib's, not the tile).
std::string tiff_with_tile(std::uint32_t tile_w, std::uint32_t tile_h) {
  std::string b = std::string("II*\0", 4);
  auto u16 = [&](std::uint16_t v) { b.append(reinterpret_cast<const char*>(&v), 2); };
  auto u32 = [&](std::uint32_t v) { b.append(reinterpret_cast<const char*>(&v), 4); };
  u32(8);
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count, value;
  };
  const std::uint32_t entries_at = 8, n = 11;
  const std::uint32_t bits_at = entries_at + 2 + n * 12 + 4;
  const std::uint32_t data_at = bits_at + 8;
  const std::string zlib_of_nothing("\x78\x9c\x03\x00\x00\x00\x00\x01", 8);
  const Entry e[n] = {{256, 3, 1, 16},
                      {257, 3, 1, 16},
                      {258, 3, 4, bits_at},
                      {259, 3, 1, 8},
                      {262, 3, 1, 2},
                      {277, 3, 1, 4},
                      {284, 3, 1, 1},
                      {322, 4, 1, tile_w},
                      {323, 4, 1, tile_h},
                      {324, 4, 1, data_at},
                      {325, 4, 1, std::uint32_t(zlib_of_nothing.size())}};
  u16(n);
  for (const Entry& x : e) {
    u16(x.tag);
    u16(x.type);
    u32(x.count);
    u32(x.value);
  }
  u32(0);
  for (int i = 0; i < 4; ++i) u16(8);
  return b + zlib_of_nothing;
}

// A 64x64 grey JPEG; progressive with `refinements` successive-approximation
// scans on each AC coefficient (63 * (refinements + 1) + 1 scans), or
// baseline when refinements < 0.
std::string jpeg_with_scans(int refinements) {
  const int w = 64, h = 64;
  std::vector<unsigned char> pixels(std::size_t(w) * h);
  for (int i = 0; i < w * h; ++i) pixels[std::size_t(i)] = static_cast<unsigned char>((i * 37) ^ (i >> 6));
  jpeg_compress_struct c;
  jpeg_error_mgr err;
  c.err = jpeg_std_error(&err);
  jpeg_create_compress(&c);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&c, &out, &size);
  c.image_width = w;
  c.image_height = h;
  c.input_components = 1;
  c.in_color_space = JCS_GRAYSCALE;
  jpeg_set_defaults(&c);
  std::vector<jpeg_scan_info> scans;
  if (refinements >= 0) {
    scans.push_back({1, {0, 0, 0, 0}, 0, 0, 0, 0});  // DC
    for (int k = 1; k < 64; ++k) {
      scans.push_back({1, {0, 0, 0, 0}, k, k, 0, refinements});
      for (int al = refinements; al > 0; --al) scans.push_back({1, {0, 0, 0, 0}, k, k, al, al - 1});
    }
    c.scan_info = scans.data();
    c.num_scans = int(scans.size());
  }
  jpeg_start_compress(&c, TRUE);
  while (c.next_scanline < c.image_height) {
    JSAMPROW row = pixels.data() + std::size_t(c.next_scanline) * w;
    jpeg_write_scanlines(&c, &row, 1);
  }
  jpeg_finish_compress(&c);
  jpeg_destroy_compress(&c);
  std::string bytes(reinterpret_cast<char*>(out), size);
  std::free(out);
  return bytes;
}

// A PID no process has now.
pid_t unused_pid() {
  for (pid_t p = 4000000; p > 1000; p -= 7919) {
    if (::kill(p, 0) != 0 && errno == ESRCH) return p;
  }
  return 0;
}

}  // namespace

// Pixel memory freed by a destructor that runs after the library's statics
// are destroyed (here a program's own static; in the CLI, oneTBB workers'
// thread_local scratch at exit) must not reach a destroyed cache.
TEST(Hostile, PixelMemoryFreedAfterStaticsExitsCleanly) {
  EXPECT_EQ(run_status(std::string(TEXPROC_EXIT_ORDER_PATH) + " 2>/dev/null"), 0);
}

// The scenario that crashed: a large mip chain (its per-thread scratch made
// of large blocks) on a machine whose every core is busy, many times.
TEST(Hostile, LargeMipUnderContentionExitsCleanly) {
  const std::string dir = temp_dir("contention");
  write_image(dir + "/big.tga", random_image(8192, 8192, 4, PixelType::u8, 3).view());
  BusyCores busy;
  for (int i = 0; i < 4; ++i) {
    SCOPED_TRACE(i);
    const RunResult r = run_texproc("mip '" + dir + "/big.tga' -o '" + dir + "/big.dds' --force");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
  }
  fs::remove_all(dir);
}

// A job of a recipe that would write another job's source is refused before
// any job runs; an existing file the recipe did not make is not replaced by
// an incremental build, while the recipe's own outputs are.
TEST(Hostile, BuildNeverOverwritesAnotherJobsSource) {
  const std::string dir = temp_dir("buildsource");
  write_image(dir + "/a.png", random_image(32, 32, 3, PixelType::u8, 1).view());
  write_image(dir + "/b.png", random_image(32, 32, 1, PixelType::u8, 2).view());
  const std::string albedo = slurp(dir + "/a.png");
  write_bytes(dir + "/r.toml",
              "version = 1\n[[jobs]]\nname = \"one\"\ncommand = \"mip\"\ninputs = [\"a.png\"]\noutput = \"out/a.dds\"\n"
              "[[jobs]]\nname = \"two\"\ncommand = \"normalmap\"\ninputs = [\"b.png\"]\noutput = \"a.png\"\n");
  RunResult r = run_texproc("build '" + dir + "/r.toml'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("output " + dir + "/a.png is an input of"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("job 'one'"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir + "/a.png"), albedo);
  EXPECT_FALSE(fs::exists(dir + "/out/a.dds")) << "no job may run";

  // An existing file that this recipe did not write: not replaced without --force.
  write_bytes(dir + "/r.toml",
              "version = 1\n[[jobs]]\nname = \"one\"\ncommand = \"mip\"\ninputs = [\"a.png\"]\noutput = \"out/a.dds\"\n"
              "[[jobs]]\nname = \"two\"\ncommand = \"normalmap\"\ninputs = [\"b.png\"]\noutput = \"n.png\"\n");
  write_bytes(dir + "/n.png", "the user's own file");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  write_image(dir + "/b.png", random_image(32, 32, 1, PixelType::u8, 4).view());  // n.png is now out of date
  r = run_texproc("build '" + dir + "/r.toml'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("n.png: output exists and was not written by this recipe; --force replaces it"),
            std::string::npos)
      << r.err;
  EXPECT_EQ(slurp(dir + "/n.png"), "the user's own file");
  EXPECT_TRUE(fs::exists(dir + "/out/a.dds")) << "the other job runs";

  // What the recipe made it may rebuild: after --force wrote n.png, a newer
  // input rebuilds it without --force.
  ASSERT_EQ(run_texproc("build '" + dir + "/r.toml' --force").exit_code, 0);
  const std::string first = slurp(dir + "/n.png");
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  write_image(dir + "/b.png", random_image(32, 32, 1, PixelType::u8, 3).view());
  r = run_texproc("build '" + dir + "/r.toml'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(dir + "/n.png"), first);
  fs::remove_all(dir);
}

// Writers through OpenImageIO (.bmp, and every format with
// TEXPROC_IMAGE_IO=oiio) on a full disk: exit 2 with the OS error, and no
// file under any final name.
TEST(Hostile, ImageModuleWritersOnAFullDiskLeaveNothing) {
  SmallDisk disk(64, false, "fullmodule");
  if (disk.dir.empty()) GTEST_SKIP() << "cannot mount a tmpfs here (not root?)";
  const std::string src = temp_dir("fullmodule_src");
  write_image(src + "/a.png", random_image(256, 256, 4, PixelType::u8, 9).view());
  disk.fill_to(40 * 1024);
  auto check = [&](const std::string& out, const std::string& options) {
    SCOPED_TRACE(out);
    const RunResult r = run_texproc("mip '" + src + "/a.png' -o '" + disk.dir + "/" + out + "' " + options);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("No space left on device"), std::string::npos) << r.err;
    EXPECT_EQ(entries(disk.dir), std::vector<std::string>{"filler"});
  };
  check("a.bmp", "");  // one file per level: none may stay
  ::setenv("TEXPROC_IMAGE_IO", "oiio", 1);
  check("b.png", "");
  check("c.tga", "");
  check("d.tif", "--type u16");
  check("e.exr", "--type f32");
  ::unsetenv("TEXPROC_IMAGE_IO");
  fs::remove_all(src);
}

// NaN and infinities are differences: counted, exit 7 whatever the limits,
// and every figure printed as a number or a word.
TEST(Hostile, CompareCountsNonFiniteSamplesAsDifferences) {
  const std::string dir = temp_dir("comparenan");
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  Image good(16, 16, 3, PixelType::f32), all_nan(16, 16, 3, PixelType::f32), one_nan(16, 16, 3, PixelType::f32),
      all_inf(16, 16, 3, PixelType::f32);
  for (int y = 0; y < 16; ++y)
    for (int i = 0; i < 48; ++i) {
      good.row<float>(y)[i] = one_nan.row<float>(y)[i] = 0.5f;
      all_nan.row<float>(y)[i] = nan;
      all_inf.row<float>(y)[i] = inf;
    }
  one_nan.row<float>(7)[4] = nan;
  write_image(dir + "/good.exr", good.view());
  write_image(dir + "/nan.exr", all_nan.view());
  write_image(dir + "/one.exr", one_nan.view());
  write_image(dir + "/inf.exr", all_inf.view());
  struct Case {
    std::string other, limits, count;
  };
  for (const Case& c : {Case{"nan.exr", "", "256 of them"}, Case{"nan.exr", "--max-error 0.001 --min-psnr 40", "256"},
                        Case{"one.exr", "", "1 of them"}, Case{"one.exr", "--min-psnr 40", "1 texels hold"},
                        Case{"inf.exr", "", "256 of them"}, Case{"inf.exr", "--max-error 1", "256"}}) {
    SCOPED_TRACE(c.other + " " + c.limits);
    const RunResult r = run_texproc("compare '" + dir + "/good.exr' '" + dir + "/" + c.other + "' " + c.limits);
    EXPECT_EQ(r.exit_code, 7) << r.out << r.err;
    EXPECT_NE((r.out + r.err).find(c.count), std::string::npos) << r.out << r.err;
    EXPECT_EQ(r.out.find("PSNR inf"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("9223372036854775808"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("max error inf"), std::string::npos) << r.out;
  }
  const RunResult same = run_texproc("compare '" + dir + "/good.exr' '" + dir + "/good.exr'");
  EXPECT_EQ(same.exit_code, 0) << same.err;
  // The library's figures: the distance is undefined, the largest error infinite.
  const ImageDifference d = compare_images(good.view(), one_nan.view());
  EXPECT_EQ(d.nonfinite_texels, 1u);
  EXPECT_EQ(d.differing_texels, 1u);
  EXPECT_TRUE(std::isnan(d.psnr()));
  EXPECT_TRUE(std::isinf(d.max_abs));
  fs::remove_all(dir);
}

// Small files that declare enormous work are refused before any pixel
// memory is allocated: exit 3 naming the limit, in little memory.
TEST(Hostile, DeclaredWorkIsBoundedBeforeAllocation) {
  const std::string dir = temp_dir("bombs");
  // One 32768x32768 RGBA tile over a 16x16 image: 4 GiB if decoded.
  write_bytes(dir + "/tile.tif", tiff_with_tile(32768, 32768));
  for (const std::string cmd : {"info", "mip"}) {
    SCOPED_TRACE(cmd);
    const Measured m = run_measured(cmd + " '" + dir + "/tile.tif'" + (cmd == "mip" ? " -o '" + dir + "/t.png'" : ""));
    EXPECT_EQ(m.exit_code, 3) << m.err;
    EXPECT_NE(m.err.find("tile.tif: TIFF tile 32768x32768 is larger than its image (16x16) needs"), std::string::npos)
        << m.err;
    EXPECT_LT(m.max_rss_kib, 100 * 1024);
  }
  // A tile the image needs (16 rounded) still reads.
  write_image(dir + "/ok.tif", random_image(40, 24, 4, PixelType::u8, 5).view());
  EXPECT_EQ(run_texproc("info '" + dir + "/ok.tif'").exit_code, 0);

  // A progressive JPEG of 694 scans: its header is described, its pixels refused.
  write_bytes(dir + "/scans.jpg", jpeg_with_scans(10));
  EXPECT_EQ(run_texproc("info '" + dir + "/scans.jpg'").exit_code, 0);
  Measured m = run_measured("mip '" + dir + "/scans.jpg' -o '" + dir + "/s.png'");
  EXPECT_EQ(m.exit_code, 3) << m.err;
  EXPECT_NE(m.err.find("scans.jpg: JPEG with more than 100 scans"), std::string::npos) << m.err;
  EXPECT_NE(m.err.find("TEXPROC_MAX_JPEG_SCANS"), std::string::npos) << m.err;
  EXPECT_FALSE(fs::exists(dir + "/s_mip0.png"));
  m = run_measured("mip '" + dir + "/scans.jpg' -o '" + dir + "/s.png'", {"TEXPROC_MAX_JPEG_SCANS=1000"});
  EXPECT_EQ(m.exit_code, 0) << m.err;
  // Ordinary progressive and baseline files decode.
  write_bytes(dir + "/few.jpg", jpeg_with_scans(0));
  write_bytes(dir + "/base.jpg", jpeg_with_scans(-1));
  EXPECT_EQ(run_texproc("mip '" + dir + "/few.jpg' -o '" + dir + "/few.png'").exit_code, 0);
  EXPECT_EQ(run_texproc("mip '" + dir + "/base.jpg' -o '" + dir + "/base.png'").exit_code, 0);

  // An OpenEXR header whose channel list runs past its declared size
  // (fuzz_images found it: 893 bytes made OpenEXR allocate 1.7 GB).
  const std::string exr = std::string(TEXPROC_SOURCE_DIR) + "/tests/data/fuzz/exr_channel_list_overrun.exr";
  m = run_measured("info '" + exr + "'");
  EXPECT_EQ(m.exit_code, 3) << m.err;
  EXPECT_NE(m.err.find("its channel list does not end where its size says"), std::string::npos) << m.err;
  EXPECT_LT(m.max_rss_kib, 100 * 1024);
  // A 64x262466 tile over a 64x64 image (fuzz_images: 14 s under ASan).
  m = run_measured("info '" + std::string(TEXPROC_SOURCE_DIR) + "/tests/data/fuzz/exr_tall_tile.exr'");
  EXPECT_EQ(m.exit_code, 3) << m.err;
  EXPECT_NE(m.err.find("tile 64x262466 is larger than its 64x64 image needs"), std::string::npos) << m.err;
  EXPECT_LT(m.max_rss_kib, 100 * 1024);
  // A 26 KB TIFF of 250x250 pixels with 18817 samples each (fuzz_images: over 20 s under ASan,
  // 158 MB in a release build, before it failed on its third chunk).
  m = run_measured("mip '" + std::string(TEXPROC_SOURCE_DIR) + "/tests/data/fuzz/tiff_18817_samples.tif' -o '" + dir +
                   "/samples.png'");
  EXPECT_EQ(m.exit_code, 3) << m.err;
  EXPECT_NE(m.err.find("(18817 a pixel) in"), std::string::npos) << m.err;
  EXPECT_NE(m.err.find("more than any compression it may use can hold"), std::string::npos) << m.err;
  EXPECT_LT(m.max_rss_kib, 100 * 1024);

  // Devices are refused, not read until memory runs out.
  m = run_measured("info /dev/zero");
  EXPECT_EQ(m.exit_code, 3) << m.err;
  EXPECT_NE(m.err.find("/dev/zero: cannot read a character device"), std::string::npos) << m.err;
  EXPECT_LT(m.max_rss_kib, 100 * 1024);
  m = run_measured("compare /dev/zero /dev/zero");
  EXPECT_EQ(m.exit_code, 3) << m.err;

  // Supercompressed levels: inflated only within the budget, and `info`
  // reads the level index without inflating any.
  Texture t;
  t.format = TexelFormat::rgba32_float;
  t.width = t.height = 64;
  t.images.emplace_back(std::size_t(64) * 64 * 16, std::uint8_t(0));
  {
    const std::vector<std::uint8_t> bytes = encode_ktx2(t, "test", 19);
    write_bytes(dir + "/z.ktx2", std::string(bytes.begin(), bytes.end()));
  }
  m = run_measured("decompress '" + dir + "/z.ktx2' -o '" + dir + "/z.exr'", {"TEXPROC_MAX_TEXTURE_BYTES=4096"});
  EXPECT_EQ(m.exit_code, 3) << m.err;
  EXPECT_NE(m.err.find("inflate to 65536 bytes, over the limit of 4096 (TEXPROC_MAX_TEXTURE_BYTES raises it)"),
            std::string::npos)
      << m.err;
  m = run_measured("info '" + dir + "/z.ktx2'", {"TEXPROC_MAX_TEXTURE_BYTES=4096"});
  EXPECT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(run_texproc("decompress '" + dir + "/z.ktx2' -o '" + dir + "/z.exr'").exit_code, 0);
  fs::remove_all(dir);
}

// A mapped input truncated while it is read reads as zeros past its new end
// and is reported, never a SIGBUS.
TEST(Hostile, InputTruncatedWhileMappedIsAnError) {
  const std::string dir = temp_dir("truncmap");
  const std::string path = dir + "/x.bin";
  write_bytes(path, std::string(1 << 20, '\x7f'));
  codecs::FileBytes f(path);
  ASSERT_EQ(f.size(), std::size_t(1) << 20);
  EXPECT_FALSE(f.truncated());
  ASSERT_EQ(::truncate(path.c_str(), 4096), 0);
  unsigned sum = 0;
  for (std::size_t i = 0; i < f.size(); i += 4096) sum += f.data()[i];
  EXPECT_EQ(sum, 0x7fu) << "the first page is still the file; pages past the end read as zeros";
  EXPECT_TRUE(f.truncated());
  try {
    f.check_intact(path);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::invalid_file);
    EXPECT_NE(std::string(e.what()).find("x.bin: the file was truncated while it was read"), std::string::npos);
  }
  // A map that no one truncates says nothing.
  write_bytes(dir + "/y.bin", "intact");
  codecs::FileBytes g(dir + "/y.bin");
  EXPECT_FALSE(g.truncated());
  fs::remove_all(dir);
}

// The CLI under a truncation at a random moment: it finishes, or exits 3
// naming the file; it is never killed by a signal.
TEST(Hostile, CommandsSurviveInputsTruncatedWhileRead) {
  const std::string dir = temp_dir("trunccli");
  for (const std::string ext : {".tga", ".png"}) {
    const std::string in = dir + "/x" + ext;
    write_image(dir + "/full" + ext, random_image(4096, 2048, 4, PixelType::u8, 8).view());
    const std::string full = slurp(dir + "/full" + ext);
    for (int delay_ms : {0, 5, 20, 60}) {
      SCOPED_TRACE(ext + " after " + std::to_string(delay_ms) + " ms");
      write_bytes(in, full);
      const pid_t pid = spawn_texproc("sat '" + in + "' -o '" + dir + "/x.sat' -f -q 2>" + dir + "/err");
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      ASSERT_EQ(::truncate(in.c_str(), 1000), 0);
      int status = 0;
      ::waitpid(pid, &status, 0);
      ASSERT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
      const int rc = WEXITSTATUS(status);
      EXPECT_TRUE(rc == 0 || rc == 3) << rc << " " << slurp(dir + "/err");
      if (rc == 3) {
        EXPECT_NE(slurp(dir + "/err").find("x" + ext + ":"), std::string::npos) << slurp(dir + "/err");
      }
    }
  }
  fs::remove_all(dir);
}

// SIGINT and SIGTERM during a batch that replaces outputs: the process exits
// promptly with 128 + the signal and leaves no temporary; a temporary that a
// killed process left is removed by the next run that writes its folder.
TEST(Hostile, SignalsLeaveNoTemporaries) {
  const std::string dir = temp_dir("signals");
  fs::create_directories(dir + "/in");
  for (int i = 0; i < 24; ++i) {
    write_image(dir + "/in/img" + std::to_string(i) + ".png", random_image(512, 512, 4, PixelType::u8, 40 + i).view());
  }
  const std::string args = "mip '" + dir + "/in' -o '" + dir + "/out/' --type f32 -q -f -j 2";
  ASSERT_EQ(run_texproc(args).exit_code, 0);
  for (int sig : {SIGINT, SIGTERM, SIGINT, SIGTERM}) {
    const pid_t pid = spawn_texproc(args);
    std::this_thread::sleep_for(std::chrono::milliseconds(150));
    ::kill(pid, sig);
    const auto t0 = std::chrono::steady_clock::now();
    int status = 0;
    ::waitpid(pid, &status, 0);
    const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(WIFEXITED(status)) << "signal " << sig << " killed it instead of a clean exit";
    EXPECT_EQ(WEXITSTATUS(status), 128 + sig);
    EXPECT_LT(waited, 1.0) << "exits promptly";
    for (const auto& f : entries(dir + "/out")) EXPECT_EQ(f.rfind(".~", 0), std::string::npos) << f;
  }
  // Stale temporaries: a dead process's are removed, a live one's are kept.
  const pid_t dead = unused_pid();
  ASSERT_GT(dead, 0);
  const std::string stale = dir + "/out/.~img0.dds.tmp" + std::to_string(dead) + "-7.dds";
  const std::string live = dir + "/out/.~img1.dds.tmp" + std::to_string(::getpid()) + "-7.dds";
  write_bytes(stale, "left by a killed run");
  write_bytes(live, "being written");
  write_bytes(dir + "/out/.~notes.txt", "not a temporary");
  ASSERT_EQ(run_texproc("mip '" + dir + "/in/img0.png' -o '" + dir + "/out/x.dds' -q").exit_code, 0);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(dir + "/out/.~notes.txt"));
  fs::remove_all(dir);
}

// A file's outputs are put in place together or not at all.
TEST(Hostile, AFilesOutputsAreCommittedTogether) {
  SmallDisk disk(96, false, "together");
  if (disk.dir.empty()) GTEST_SKIP() << "cannot mount a tmpfs here (not root?)";
  const std::string src = temp_dir("together_src");
  write_image(src + "/h.png", random_image(64, 64, 1, PixelType::u8, 11).view());
  disk.fill_to(80 * 1024);
  // The cone map fits; its preview does not.
  RunResult r = run_texproc("conemap '" + src + "/h.png' -o '" + disk.dir + "/c.png' --preview '" + disk.dir +
                            "/pv.png' --preview-size 256");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(entries(disk.dir), std::vector<std::string>{"filler"});
  // Per-level files (level 0 about 16 KiB, the chain 22 KiB): all or none.
  write_image(src + "/a.png", random_image(64, 64, 4, PixelType::u8, 12).view());
  disk.fill_to(76 * 1024);
  r = run_texproc("mip '" + src + "/a.png' -o '" + disk.dir + "/a.png'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("_mip"), std::string::npos) << "a level after the first fails: " << r.err;
  EXPECT_EQ(r.err.find("a_mip0.png"), std::string::npos) << "a level after the first fails: " << r.err;
  EXPECT_EQ(entries(disk.dir), std::vector<std::string>{"filler"});
  fs::remove(disk.dir + "/filler");
  r = run_texproc("mip '" + src + "/a.png' -o '" + disk.dir + "/a.png'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(disk.dir).size(), 7u);
  fs::remove_all(src);
}

// texproc writes only what it reads back.
TEST(Hostile, TexturesPastTheReadLimitsAreRefusedBeforeWriting) {
  const std::string dir = temp_dir("widewrite");
  write_image(dir + "/wide.png", random_image(65536, 1, 4, PixelType::u8, 13).view());
  for (const std::string& args : {"mip '" + dir + "/wide.png' -o '" + dir + "/w.dds'",
                                  "compress '" + dir + "/wide.png' -o '" + dir + "/w.ktx2' --format bc1 -q"}) {
    SCOPED_TRACE(args);
    const RunResult r = run_texproc(args);
    EXPECT_EQ(r.exit_code, 5) << r.err;
    EXPECT_NE(r.err.find("65536x1 is over 16384 texels a side"), std::string::npos) << r.err;
  }
  EXPECT_FALSE(fs::exists(dir + "/w.dds"));
  EXPECT_FALSE(fs::exists(dir + "/w.ktx2"));
  fs::remove_all(dir);
}

// Make reads depfiles line by line: a name with a line break is refused
// before any work.
TEST(Hostile, DepfileRefusesNamesWithLineBreaks) {
  const std::string dir = temp_dir("depnewline");
  write_image(dir + "/a\nb.png", random_image(8, 8, 3, PixelType::u8, 14).view());
  const RunResult r = run_texproc("mip '" + dir + "/a\nb.png' -o '" + dir + "/out.dds' --depfile '" + dir + "/d.d'");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("a file name with a line break cannot be written to --depfile"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.dds"));
  EXPECT_FALSE(fs::exists(dir + "/d.d"));
  EXPECT_EQ(run_texproc("mip '" + dir + "/a\nb.png' -o '" + dir + "/out.dds'").exit_code, 0) << "fine without one";
  fs::remove_all(dir);
}

// Every numeric option is range-checked: exit 1 naming the option and its range.
TEST(Hostile, NumericOptionsAreRangeChecked) {
  const std::string dir = temp_dir("ranges");
  write_image(dir + "/a.png", random_image(16, 16, 4, PixelType::u8, 15).view());
  const std::string a = "'" + dir + "/a.png'", o = " -o '" + dir + "/o.dds'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"cubemap " + a + o + " --equirect-width 2147483647", "--equirect-width: 2147483647 is outside the valid range"},
      {"cubemap " + a + o + " --equirect-width -4", "--equirect-width: -4 is outside"},
      {"cubemap " + a + o + " --samples 0", "--samples: 0 is outside"},
      {"compress " + a + o + " --format astc-4x4 --astc-effort -5",
       "--astc-effort: -5 is outside the valid range [0, 100]"},
      {"compress " + a + o + " --format bc1 --mips --alpha-coverage nan", "--alpha-coverage: nan is outside"},
      {"mip " + a + o + " --alpha-coverage 1.5", "--alpha-coverage: 1.5 is outside the valid range (0, 1]"},
      {"mip " + a + o + " --sigma inf", "--sigma: inf is outside"},
      {"mip " + a + o + " --zstd 23", "--zstd: 23 is outside the valid range [1, 22]"},
      {"normalmap " + a + o + " --height-scale -1", "--height-scale: -1 is outside"},
      {"normalmap " + a + o + " --strength nan", "--strength: nan is outside"},
      {"compare " + a + " " + a + " --min-psnr nan", "--min-psnr: nan is outside"},
      {"compare " + a + " " + a + " --max-error -1", "--max-error: -1 is outside"},
      {"sat blur " + a + " -o '" + dir + "/b.png' --radius nan", "--radius: nan is outside"},
      {"decompress " + a + " -o '" + dir + "/d.png' --face 6", "--face: 6 is outside the valid range [0, 5]"},
      {"conemap " + a + " -o '" + dir + "/c.png' --view-angle 90", "--view-angle: 90 is outside"},
      {"normalmap " + a + o + " --kernel multiscale --multiscale-weights 0.5,nan",
       "--multiscale-weights: nan is outside"},
      {"mip " + a + o + " -j abc", "'abc' is not a number (valid: [0, 4096])"},
      {"mip " + a + o + " --threads 100000", "--threads: 100000 is outside the valid range [0, 4096]"},
  };
  for (const auto& [args, message] : cases) {
    SCOPED_TRACE(args);
    const RunResult r = run_texproc(args);
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
  }
  EXPECT_EQ(entries(dir), std::vector<std::string>{"a.png"});
  fs::remove_all(dir);
}

// Exit codes say what went wrong: unsupported (5), I/O with the OS error (2).
TEST(Hostile, ExitCodesAndMessagesNameTheCause) {
  const std::string dir = temp_dir("exitcodes");
  write_image(dir + "/rgba.png", random_image(8, 8, 4, PixelType::u8, 16).view());
  write_image(dir + "/grey.png", random_image(8, 8, 1, PixelType::u8, 17).view());
  RunResult r = run_texproc("mip '" + dir + "/rgba.png' -o '" + dir + "/x.hdr' --levels 1");
  EXPECT_EQ(r.exit_code, 5) << r.err;
  EXPECT_NE(r.err.find("a Radiance .hdr file holds RGB without alpha"), std::string::npos) << r.err;
  r = run_texproc("mip '" + dir + "/grey.png' -o '" + dir + "/g.hdr' --levels 1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_image(dir + "/g_mip0.hdr").channels(), 3);
  SmallDisk disk(64, false, "exitcodes_disk");
  if (!disk.dir.empty()) {
    write_image(dir + "/big.png", random_image(256, 256, 4, PixelType::u8, 18).view());
    r = run_texproc("sat '" + dir + "/big.png' -o '" + disk.dir + "/t.sat'");
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("t.sat: cannot write: No space left on device"), std::string::npos) << r.err;
    EXPECT_TRUE(entries(disk.dir).empty());
  }
  fs::remove_all(dir);
}
