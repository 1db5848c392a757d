// Faults: a full disk, a read-only folder, a process killed mid-batch, an
// output that is another input, two processes writing one output, a long
// output name. Every failure exits 2 (or 1 for a refused plan) naming the
// file, leaves no file under the final name and no temporary behind.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <filesystem>
#include <fstream>
#include <thread>

#include "support/disks.h"
#include "support/images.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

TEST(Faults, FullDiskLeavesNoFileUnderTheFinalName) {
  SmallDisk disk(64);
  if (disk.dir.empty()) GTEST_SKIP() << "cannot mount a tmpfs here (not root?)";
  const std::string src = temp_dir("fullsrc");
  write_image(src + "/h.png", random_image(256, 256, 1, PixelType::u8, 4).view());
  write_image(src + "/a.png", random_image(128, 128, 4, PixelType::u8, 5).view());
  write_image(src + "/b.png", random_image(256, 256, 4, PixelType::u8, 7).view());
  {
    std::ofstream filler(disk.dir + "/filler", std::ios::binary);
    filler << std::string(32 * 1024, 'x');
  }
  struct Case {
    std::string args, output;
  };
  const std::vector<Case> cases = {
      {"normalmap '" + src + "/h.png' -o '" + disk.dir + "/n16.png' --type u16", "n16.png"},
      {"normalmap '" + src + "/h.png' -o '" + disk.dir + "/n.tga'", "n.tga"},
      {"mip '" + src + "/a.png' -o '" + disk.dir + "/a.exr' --type f32", "a.exr"},
      {"mip '" + src + "/a.png' -o '" + disk.dir + "/a.tif' --type f32", "a.tif"},
      {"mip '" + src + "/a.png' -o '" + disk.dir + "/a.dds' --type f32", "a.dds"},
      {"compress '" + src + "/b.png' -o '" + disk.dir + "/b.ktx2' --format bc3 --mips", "b.ktx2"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    // `timeout` turns a hang (OpenEXR's tiled writer after a failed write, before) into a failure.
    const std::string cmd =
        "timeout 60 " + std::string(TEXPROC_CLI_PATH) + " " + c.args + " -q >/dev/null 2>'" + src + "/err.txt'";
    const int status = std::system(cmd.c_str());
    const std::string err = slurp(src + "/err.txt");
    EXPECT_EQ(WEXITSTATUS(status), 2) << err;
    EXPECT_NE(err.find(c.output), std::string::npos) << err;
    EXPECT_NE(err.find("No space left"), std::string::npos) << err;
    EXPECT_EQ(entries(disk.dir), std::vector<std::string>{"filler"}) << "something was left on the disk";
  }
  // A batch: the file that fits is written, the one that does not is not.
  write_image(src + "/tiny.png", random_image(8, 8, 3, PixelType::u8, 6).view());
  const RunResult r =
      run_texproc("mip '" + src + "/tiny.png' '" + src + "/a.png' -o '" + disk.dir + "/{stem}.dds' --type f32 -q");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(fs::exists(disk.dir + "/tiny.dds"));
  EXPECT_FALSE(fs::exists(disk.dir + "/a.dds"));
  EXPECT_EQ(entries(disk.dir), (std::vector<std::string>{"filler", "tiny.dds"}));
  fs::remove_all(src);
}

TEST(Faults, ReadOnlyFolderExitsTwo) {
  SmallDisk disk(64, true);
  if (disk.dir.empty()) GTEST_SKIP() << "cannot mount a tmpfs here (not root?)";
  const std::string src = temp_dir("rosrc");
  write_image(src + "/a.png", random_image(32, 32, 3, PixelType::u8, 5).view());
  for (const char* out : {"a.png", "a.dds", "a.exr", "a.tif"}) {
    const RunResult r = run_texproc("mip '" + src + "/a.png' -o '" + disk.dir + "/" + out + "' -q");
    EXPECT_EQ(r.exit_code, 2) << out << ": " << r.err;
    EXPECT_NE(r.err.find("Read-only"), std::string::npos) << r.err;
  }
  EXPECT_TRUE(entries(disk.dir).empty());
  fs::remove_all(src);
}

// SIGKILL at any moment of a batch: every file under a final name is
// complete, and nothing else is in the folder (the temporaries are unnamed
// files that vanish with the process).
TEST(Faults, KilledBatchLeavesNoTemporaries) {
  const std::string dir = temp_dir("killbatch");
  fs::create_directories(dir + "/in");
  for (int i = 0; i < 6; ++i) {
    write_image(dir + "/in/img" + std::to_string(i) + ".png", random_image(700, 700, 4, PixelType::u8, 20 + i).view());
  }
  const std::string args = "mip '" + dir + "/in' -o '" + dir + "/out/' --type f32 -q -f -j 2";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(run_texproc(args + " --write-if-changed").exit_code, 0);
  const auto full = std::chrono::steady_clock::now() - t0;
  std::map<std::string, std::string> reference;
  for (const auto& f : entries(dir + "/out")) reference[f] = slurp(dir + "/out/" + f);
  ASSERT_EQ(reference.size(), 6u);
  for (int trial = 0; trial < 6; ++trial) {
    fs::remove_all(dir + "/out");
    const pid_t pid = fork();
    if (pid == 0) {
      ::execl("/bin/sh", "sh", "-c", (std::string(TEXPROC_CLI_PATH) + " " + args + " >/dev/null 2>&1").c_str(),
              static_cast<char*>(nullptr));
      _exit(127);
    }
    std::this_thread::sleep_for(full * (trial + 1) / 8);
    // The shell and texproc under it.
    if (std::system("pkill -KILL -f 'texproc mip .*killbatch' >/dev/null 2>&1") < 0) ADD_FAILURE();
    ::kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    if (!fs::exists(dir + "/out")) continue;
    for (const auto& f : entries(dir + "/out")) {
      ASSERT_TRUE(reference.count(f)) << "a stray file after a kill: " << f;
      EXPECT_TRUE(slurp(dir + "/out/" + f) == reference[f]) << f << " is incomplete";
    }
  }
  fs::remove_all(dir);
}

TEST(Faults, OutputThatIsAnotherInputIsRefused) {
  const std::string dir = temp_dir("outisin");
  write_image(dir + "/a.png", random_image(16, 16, 1, PixelType::u8, 1).view());
  write_image(dir + "/a_n.png", random_image(16, 16, 1, PixelType::u8, 2).view());
  const std::string before = slurp(dir + "/a_n.png");
  // a.png's output is a_n.png, the second input: refused before any work, even with -f.
  RunResult r =
      run_texproc("normalmap '" + dir + "/a.png' '" + dir + "/a_n.png' -o '" + dir + "/{stem}_n.png' -f -j 2");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("a_n.png"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("never overwrite inputs"), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir + "/a_n.png"), before);
  EXPECT_FALSE(fs::exists(dir + "/a_n_n.png"));
  // Through a symlink to the input, and through a hard link.
  fs::create_symlink(dir + "/a.png", dir + "/link.png");
  r = run_texproc("normalmap '" + dir + "/a.png' -o '" + dir + "/link.png' -f");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  fs::create_hard_link(dir + "/a.png", dir + "/hard.png");
  r = run_texproc("normalmap '" + dir + "/a.png' -o '" + dir + "/hard.png' -f");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  // Two inputs that would write one output (through "..").
  fs::create_directories(dir + "/sub");
  r = run_texproc("normalmap '" + dir + "/a.png' '" + dir + "/a_n.png' -o '" + dir + "/sub/../x.png' -f");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  fs::remove_all(dir);
}

// Two processes writing one output that does not exist yet, without
// --force: never both succeed (the rename refuses a file that appeared
// since the check).
TEST(Faults, TwoProcessesNeverBothReplaceOneOutput) {
  const std::string dir = temp_dir("race");
  write_image(dir + "/a.png", random_image(512, 512, 4, PixelType::u8, 3).view());
  int both = 0, one = 0;
  for (int trial = 0; trial < 6; ++trial) {
    fs::remove(dir + "/out.dds");
    const std::string cmd =
        std::string(TEXPROC_CLI_PATH) + " mip '" + dir + "/a.png' -o '" + dir + "/out.dds' -q 2>/dev/null";
    const std::string both_cmd =
        "(" + cmd + "; echo $? > '" + dir + "/rc1') & (" + cmd + "; echo $? > '" + dir + "/rc2') & wait";
    ASSERT_EQ(std::system(both_cmd.c_str()), 0);
    const int rc1 = std::stoi(slurp(dir + "/rc1")), rc2 = std::stoi(slurp(dir + "/rc2"));
    both += rc1 == 0 && rc2 == 0;
    one += (rc1 == 0) != (rc2 == 0);
    EXPECT_TRUE(fs::exists(dir + "/out.dds"));
  }
  EXPECT_EQ(both, 0) << "both processes reported writing the one output";
  EXPECT_EQ(one, 6);
  for (const auto& f : entries(dir)) EXPECT_TRUE(f == "a.png" || f == "out.dds" || f == "rc1" || f == "rc2") << f;
  fs::remove_all(dir);
}

TEST(Faults, LongOutputNamesWork) {
  const std::string dir = temp_dir("longname");
  write_image(dir + "/a.png", random_image(16, 16, 3, PixelType::u8, 3).view());
  const std::string name = std::string(240, 'n') + ".dds";  // 244 bytes
  RunResult r = run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/" + name + "' -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/" + name));
  // Replacing it goes through a named temporary, cut to fit.
  r = run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/" + name + "' -q -f");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(entries(dir).size(), 2u);
  fs::remove_all(dir);
}

// KTX-Software's `ktx validate` (built outside the tree; its path in
// $TEXPROC_KTX_TOOL, or `ktx` on PATH) accepts every KTX2 texproc writes:
// each block format in sRGB and linear, with and without mips, the
// uncompressed types, cube maps (uncompressed, BC6H, BC7).
TEST(Faults, KtxValidateAcceptsEveryKtx2) {
  const char* env = std::getenv("TEXPROC_KTX_TOOL");
  std::string ktx = env && *env ? env : "";
  if (ktx.empty() && std::system("command -v ktx >/dev/null 2>&1") == 0) ktx = "ktx";
  if (ktx.empty()) GTEST_SKIP() << "no `ktx` tool (set TEXPROC_KTX_TOOL to KTX-Software's ktx)";
  const std::string dir = temp_dir("ktxvalidate");
  write_image(dir + "/src.png", random_image(37, 21, 4, PixelType::u8, 2).view());
  std::vector<std::string> files;
  for (const char* fmt : {"bc1",      "bc1a",      "bc2",  "bc3",      "bc4",      "bc4s",       "bc5",
                          "bc5s",     "etc1",      "etc2", "etc2a1",   "etc2a",    "eac-r11",    "eac-r11s",
                          "eac-rg11", "eac-rg11s", "bc7",  "astc-4x4", "astc-6x5", "astc-12x12", "astc-8x8-hdr"}) {
    for (const char* cs : {"", " --linear"}) {
      for (const char* mips : {"", " --mips"}) {
        const std::string out = dir + "/" + fmt + (cs[0] ? "_lin" : "") + (mips[0] ? "_mips" : "") + ".ktx2";
        if (run_texproc("compress '" + dir + "/src.png' -o '" + out + "' --format " + fmt + cs + mips + " -q")
                .exit_code == 0) {
          files.push_back(out);
        }
      }
    }
  }
  for (const char* fmt : {"bc1", "bc3", "etc2a", "bc5"}) {  // Zstandard-supercompressed
    const std::string out = dir + "/z_" + fmt + ".ktx2";
    ASSERT_EQ(run_texproc("compress '" + dir + "/src.png' -o '" + out + "' --format " + fmt + " --mips --zstd 9 -q")
                  .exit_code,
              0);
    files.push_back(out);
  }
  for (const char* type : {"u8", "u16", "f16", "f32"}) {
    const std::string out = dir + "/m_" + type + ".ktx2";
    ASSERT_EQ(run_texproc("mip '" + dir + "/src.png' -o '" + out + "' --type " + type + " -q").exit_code, 0);
    files.push_back(out);
  }
  // Cube maps from `cubemap`: sRGB bytes and half floats with seamless mips,
  // float, and an IBL specular chain.
  Image pano(64, 32, 3, PixelType::f32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64 * 3; ++x) pano.row<float>(y)[x] = float((x * 7 + y * 3) % 23) / 11.0f;
  write_image(dir + "/pano.exr", pano.view());
  write_image(dir + "/pano.png", random_image(64, 32, 3, PixelType::u8, 5).view());
  for (const char* args :
       {"pano.png' -o '{}/cube_srgb.ktx2' --mips", "pano.exr' -o '{}/cube_half.ktx2' --mips",
        "pano.exr' -o '{}/cube_f32.ktx2' --format rgba32f", "pano.exr' -o '{}/cube_ibl.ktx2' --ibl specular"}) {
    std::string a = args;
    a.replace(a.find("{}"), 2, dir);
    ASSERT_EQ(run_texproc("cubemap '" + dir + "/" + a + " -q").exit_code, 0) << a;
    files.push_back(dir + "/" + a.substr(a.find("cube_"), a.find(".ktx2") - a.find("cube_") + 5));
  }
  // BC6H (UF16, SF16) from floats with float mips, and both encoders' cube
  // maps.
  for (const char* args :
       {"pano.exr' -o '{}/hdr_bc6h.ktx2' --format bc6h --mips", "pano.exr' -o '{}/hdr_bc6hs.ktx2' --format bc6hs",
        "cube_half.ktx2' -o '{}/cube_bc6h.ktx2' --format bc6h", "cube_srgb.ktx2' -o '{}/cube_bc7.ktx2' --format bc7"}) {
    std::string a = args;
    a.replace(a.find("{}"), 2, dir);
    ASSERT_EQ(run_texproc("compress '" + dir + "/" + a + " -q").exit_code, 0) << a;
    const std::size_t at = a.find("-o '") + 4;
    files.push_back(a.substr(at, a.find('\'', at) - at));
  }
  // BC6H and BC7 random blocks (every mode, reserved ones included), three
  // levels, written by the container layer.
  for (TexelFormat bf :
       {TexelFormat::bc6h_ufloat, TexelFormat::bc6h_sfloat, TexelFormat::bc7_unorm, TexelFormat::bc7_srgb}) {
    Texture t;
    t.format = bf;
    t.width = 12;
    t.height = 8;
    t.levels = 3;
    t.layers = t.faces = 1;
    std::uint32_t seed = 17;
    for (std::uint32_t l = 0; l < 3; ++l) {
      std::vector<std::uint8_t> level(image_bytes(bf, t.level_width(l), t.level_height(l)));
      for (auto& v : level) v = std::uint8_t((seed = seed * 1103515245u + 12345u) >> 16);
      t.images.push_back(level);
    }
    const std::string out = dir + "/" + format_info(bf).name + ".ktx2";
    write_texture(out, t);
    files.push_back(out);
  }
  EXPECT_GE(files.size(), 90u);
  for (const std::string& f : files) {
    const std::string cmd = ktx + " validate --warnings-as-errors '" + f + "' >'" + dir + "/v.txt' 2>&1";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << f << ":\n" << slurp(dir + "/v.txt");
  }
  fs::remove_all(dir);
}

// What the files say matches what the values are: a 16-bit sRGB chain goes
// into a container linear (no GPU format is 16-bit sRGB), an sRGB texture
// decompressed to OpenEXR is decoded to linear; --all-levels works for one
// level and writes a whole chain into one .exr.
TEST(Faults, ColourMetadataMatchesTheValues) {
  const std::string dir = temp_dir("colourmeta");
  const Image src = random_image(8, 8, 4, PixelType::u16, 3);
  write_image(dir + "/in16.png", src.view());
  ASSERT_EQ(run_texproc("mip '" + dir + "/in16.png' -o '" + dir + "/m.ktx2' -q").exit_code, 0);
  const Texture m = read_texture(dir + "/m.ktx2");
  EXPECT_EQ(m.format, TexelFormat::rgba16_unorm);
  const Image l0 = image_from_texture(m, 0);
  for (int x = 0; x < 8; ++x) {
    const float want = srgb16_to_linear(src.row<std::uint16_t>(3)[4 * x]);
    EXPECT_NEAR(l0.get(x, 3, 0), want, 1.0 / 65535) << x;
    EXPECT_EQ(l0.row<std::uint16_t>(3)[4 * x + 3], src.row<std::uint16_t>(3)[4 * x + 3]);  // alpha as it was
  }
  write_image(dir + "/in8.png", random_image(16, 16, 3, PixelType::u8, 4).view());
  ASSERT_EQ(run_texproc("compress '" + dir + "/in8.png' -o '" + dir + "/c.dds' --format bc1 --mips -q").exit_code, 0);
  ASSERT_EQ(run_texproc("decompress '" + dir + "/c.dds' -o '" + dir + "/c.exr' -q").exit_code, 0);
  ASSERT_EQ(run_texproc("decompress '" + dir + "/c.dds' -o '" + dir + "/c.png' -q").exit_code, 0);
  ImageFileInfo info;
  const Image e = read_image(dir + "/c.exr", &info);
  const Image p = read_image(dir + "/c.png");
  EXPECT_EQ(info.color_space_tag, "Linear");
  for (int x = 0; x < 16; ++x)
    EXPECT_NEAR(e.get(x, 5, 1), srgb8_to_linear(p.row<std::uint8_t>(5)[4 * x + 1]), 2e-3) << x;
  // --all-levels: one level is one file; a chain into .exr is one MIP file.
  ASSERT_EQ(run_texproc("compress '" + dir + "/in8.png' -o '" + dir + "/one.dds' --format bc1 -q").exit_code, 0);
  RunResult r = run_texproc("decompress '" + dir + "/one.dds' -o '" + dir + "/one.png' --all-levels -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/one.png"));
  r = run_texproc("decompress '" + dir + "/c.dds' -o '" + dir + "/chain.exr' --all-levels -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(probe_image(dir + "/chain.exr").mip_levels, 5);
  fs::remove_all(dir);
}

// The format names users type (texconv's, nvcompress's, any case) are
// accepted; options that would be silently ignored are refused with the way out.
TEST(Faults, FormatAliasesAndIgnoredOptions) {
  const std::string dir = temp_dir("aliases");
  write_image(dir + "/a.png", random_image(16, 16, 4, PixelType::u8, 2).view());
  for (const auto& [alias, name] : std::vector<std::pair<std::string, TexelFormat>>{{"DXT1", TexelFormat::bc1_rgb_srgb},
                                                                                    {"dxt5", TexelFormat::bc3_srgb},
                                                                                    {"ATI2", TexelFormat::bc5_unorm},
                                                                                    {"BC4", TexelFormat::bc4_unorm},
                                                                                    {"dxt3", TexelFormat::bc2_srgb}}) {
    const RunResult r =
        run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/" + alias + ".ktx2' --format " + alias + " -q");
    ASSERT_EQ(r.exit_code, 0) << alias << ": " << r.err;
    EXPECT_EQ(read_texture(dir + "/" + alias + ".ktx2").format, name) << alias;
  }
  RunResult r = run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/x.dds' --format bc1 --levels 3 -q");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("add --mips"), std::string::npos) << r.err;
  r = run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/x.dds' --format bc5 --srgb -q");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("no sRGB variant"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/x.dds"));
  r = run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/x.ktx2' --format bc1 --dds-header dx9 -q");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("applies to .dds outputs only"), std::string::npos) << r.err;
  r = run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/x.dds' --format bc1 --zstd 5 -q");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("applies to .ktx2 outputs only"), std::string::npos) << r.err;
  // Dead ends name the way out.
  r = run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/x.pkm' --format etc2 -q");
  EXPECT_NE(r.err.find("--linear"), std::string::npos) << r.err;
  r = run_texproc("compress '" + dir + "/a.png' -o '" + dir + "/x.dds' --format bc1 --dds-header dx9 -q");
  EXPECT_NE(r.err.find("--linear"), std::string::npos) << r.err;
  // A legacy header for float RGBA: D3DFMT 116 as the FourCC.
  r = run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/f.dds' --type f32 --dds-header dx9 -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string f = slurp(dir + "/f.dds");
  std::uint32_t cc;
  std::memcpy(&cc, f.data() + 84, 4);
  EXPECT_EQ(cc, 116u);
  EXPECT_EQ(read_texture(dir + "/f.dds").format, TexelFormat::rgba32_float);
  fs::remove_all(dir);
}

// NaN and infinity in float inputs: a warning naming the file and the count,
// and they do not spread (12 bad texels used to become 57 of 256 at level 1).
TEST(Faults, NonFiniteInputsWarnAndDoNotSpread) {
  const std::string dir = temp_dir("nonfinite");
  Image img = random_image(16, 16, 1, PixelType::f32, 8);
  for (int i = 0; i < 12; ++i) {
    img.row<float>(i)[i] = i % 3 == 0   ? std::numeric_limits<float>::quiet_NaN()
                           : i % 3 == 1 ? std::numeric_limits<float>::infinity()
                                        : -std::numeric_limits<float>::infinity();
  }
  write_image(dir + "/h.exr", img.view());
  RunResult r = run_texproc("mip '" + dir + "/h.exr' -o '" + dir + "/m.ktx2' --type f32");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("h.exr: 12 non-finite"), std::string::npos) << r.err;
  const Texture t = read_texture(dir + "/m.ktx2");
  for (std::uint32_t l = 0; l < t.levels; ++l) {
    const Image level = image_from_texture(t, l);
    const float* p = reinterpret_cast<const float*>(level.data());
    for (std::size_t i = 0; i < level.byte_size() / 4; ++i) ASSERT_TRUE(std::isfinite(p[i])) << "level " << l;
  }
  r = run_texproc("normalmap '" + dir + "/h.exr' -o '" + dir + "/n.exr' --type f32");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("non-finite"), std::string::npos) << r.err;
  const Image n = read_image(dir + "/n.exr");
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) {
      const float* v = n.row<float>(y) + 3 * x;
      ASSERT_TRUE(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]));
      EXPECT_GT(std::abs(v[0]) + std::abs(v[1]) + std::abs(v[2]), 0.5f) << x << "," << y;
    }
  // -q: no warning.
  r = run_texproc("mip '" + dir + "/h.exr' -o '" + dir + "/m2.ktx2' --type f32 -q");
  EXPECT_EQ(r.err, "");
  fs::remove_all(dir);
}

// The same bytes for every command at --threads 1, 2 and 7, --jobs 1 and 3,
// and with the scalar kernels (TEXPROC_FORCE_SCALAR=1).
TEST(Faults, EveryCommandIsDeterministic) {
  const std::string dir = temp_dir("determinism");
  fs::create_directories(dir + "/in");
  for (int i = 0; i < 3; ++i) {
    write_image(dir + "/in/c" + std::to_string(i) + ".png",
                random_image(150 + 20 * i, 97, 4, PixelType::u8, 30 + i).view());
  }
  struct Case {
    std::string command, options, ext;
  };
  const std::vector<Case> cases = {
      {"compress", "--format bc1 --mips", ".dds"},
      {"compress", "--format bc3 --quality high", ".ktx2"},
      {"compress", "--format etc2a --mips", ".ktx2"},
      {"compress", "--format bc5 --normal-map", ".dds"},
      {"mip", "--filter lanczos3", ".ktx2"},
      {"mip", "--type f32", ".exr"},
      {"normalmap", "--kernel sobel5 --mips", ".ktx2"},
      {"conemap", "--mode relaxed", ".png"},
      {"sat", "", ".sat"},
      {"sat blur", "--radius 3", ".png"},
      {"compress", "--format astc-6x6 --mips --quality fast", ".ktx2"},
  };
  const std::vector<std::pair<std::string, std::string>> configs = {
      {"", "--threads 1 --jobs 1"},
      {"", "--threads 2 --jobs 3"},
      {"", "--threads 7 --jobs 1"},
      {"TEXPROC_FORCE_SCALAR=1 ", "--threads 2 --jobs 3"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.command + " " + c.options);
    std::map<std::string, std::string> reference;
    for (std::size_t k = 0; k < configs.size(); ++k) {
      const std::string out = dir + "/out" + std::to_string(k);
      fs::remove_all(out);
      const std::string cmd = configs[k].first + TEXPROC_CLI_PATH + " " + c.command + " '" + dir + "/in' -o '" + out +
                              "/{stem}" + c.ext + "' -q " + c.options + " " + configs[k].second + " 2>'" + dir +
                              "/err'";
      ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + "/err");
      for (const auto& f : entries(out)) {
        const std::string bytes = slurp(out + "/" + f);
        if (k == 0) {
          reference[f] = bytes;
        } else {
          EXPECT_TRUE(reference.count(f) && reference[f] == bytes)
              << f << " differs under " << configs[k].first << configs[k].second;
        }
      }
      if (k == 0) {
        EXPECT_EQ(reference.size(), 3u);
      }
    }
  }
  fs::remove_all(dir);
}
