// Names users type: every format name `info` prints, DXGI's and Vulkan's
// names, and enumerated option values in any case.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/images.h"
#include "support/json.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

// The library's parser: texproc's names, DXGI's and Vulkan's, any case.
TEST(Names, FormatNamesOfEveryTool) {
  for (const std::string& n : texel_format_names()) EXPECT_EQ(format_info(parse_texel_format(n)).name, n);
  struct Case {
    const char* name;
    TexelFormat want;
  };
  for (const Case& c :
       {Case{"BC7_UNORM_SRGB", TexelFormat::bc7_srgb}, Case{"DXGI_FORMAT_BC7_UNORM", TexelFormat::bc7_unorm},
        Case{"bc1_unorm", TexelFormat::bc1_rgb_unorm}, Case{"BC5_SNORM", TexelFormat::bc5_snorm},
        Case{"BC6H_UF16", TexelFormat::bc6h_ufloat}, Case{"VK_FORMAT_BC1_RGBA_SRGB_BLOCK", TexelFormat::bc1_rgba_srgb},
        Case{"ETC2_R8G8B8_UNORM_BLOCK", TexelFormat::etc2_rgb_unorm},
        Case{"vk_format_eac_r11g11_snorm_block", TexelFormat::eac_rg11_snorm},
        Case{"VK_FORMAT_ASTC_6x6_SRGB_BLOCK", TexelFormat::astc_6x6_srgb},
        Case{"ASTC_8X8_SFLOAT_BLOCK", TexelFormat::astc_8x8_sfloat},
        Case{"R8G8B8A8_UNORM_SRGB", TexelFormat::rgba8_srgb}, Case{"EAC_RG11_UNORM", TexelFormat::eac_rg11_unorm}}) {
    EXPECT_EQ(parse_texel_format(c.name), c.want) << c.name;
  }
  EXPECT_THROW(parse_texel_format("BC8_UNORM"), Error);
}

// compress: a full name fixes the stored format (sRGB or UNORM whatever the
// input), the short names keep choosing sRGB for colour; a contradiction is
// refused; enumerated values in any case.
TEST(Names, CompressTakesFullNamesAndAnyCase) {
  const std::string dir = temp_dir("names");
  write_image(dir + "/c.png", random_image(16, 16, 4, PixelType::u8, 7).view());
  const std::string in = "'" + dir + "/c.png'";
  struct Case {
    const char* format;
    TexelFormat want;
    const char* ext;
  };
  for (const Case& c : {Case{"bc7", TexelFormat::bc7_srgb, ".dds"}, Case{"bc7_unorm", TexelFormat::bc7_unorm, ".dds"},
                        Case{"BC7_UNORM_SRGB", TexelFormat::bc7_srgb, ".dds"},
                        Case{"BC1_UNORM", TexelFormat::bc1_rgb_unorm, ".ktx2"},  // (DDS reads DXT1 as RGBA)

                        Case{"eac_rg11_unorm", TexelFormat::eac_rg11_unorm, ".ktx2"},
                        Case{"VK_FORMAT_ETC2_R8G8B8A8_SRGB_BLOCK", TexelFormat::etc2_rgba8_srgb, ".ktx2"},
                        Case{"ASTC_4x4_UNORM_BLOCK", TexelFormat::astc_4x4_unorm, ".ktx2"},
                        Case{"BC7", TexelFormat::bc7_srgb, ".dds"}}) {
    const std::string out = dir + "/o" + c.ext;
    const RunResult r =
        run_texproc("compress " + in + " -o '" + out + "' --format " + c.format + " --quality Fast -f -q");
    ASSERT_EQ(r.exit_code, 0) << c.format << ": " << r.err;
    EXPECT_EQ(read_texture(out).format, c.want) << c.format;
  }
  // Folder outputs pick KTX2 for a format DDS cannot hold, whatever its name.
  RunResult r = run_texproc("compress " + in + " -o '" + dir + "/out/' --format VK_FORMAT_EAC_R11_UNORM_BLOCK -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/out/c.ktx2"));
  r = run_texproc("compress " + in + " -o '" + dir + "/x.dds' --format bc7_unorm --srgb");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("--srgb contradicts --format bc7_unorm"), std::string::npos) << r.err;
  r = run_texproc("compress " + in + " -o '" + dir + "/x.dds' --format BC7_UNORM_SRGB --linear");
  EXPECT_EQ(r.exit_code, 1);
  // Enumerated values in any case; a wrong one still names the valid ones.
  r = run_texproc("mip " + in + " -o '" + dir + "/m.dds' --wrap Repeat --filter LANCZOS3 -q");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("compress " + in + " -o '" + dir + "/x.dds' --format bc1 --quality Best");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("fast, normal, high, max"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// A mistyped option is named, with the closest valid one, before the errors
// it causes (a required option it was meant to be); with --json a parse
// failure still prints the JSON document.
TEST(Names, UnknownOptionsAreNamedWithTheClosest) {
  const std::string dir = temp_dir("names_unknown");
  write_image(dir + "/c.png", random_image(8, 8, 3, PixelType::u8, 8).view());
  const std::string in = "'" + dir + "/c.png'";
  RunResult r = run_texproc("compress " + in + " -o '" + dir + "/x.dds' --fromat bc1");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown option --fromat (did you mean --format?)"), std::string::npos) << r.err;
  r = run_texproc("mip " + in + " -o '" + dir + "/x.dds' --json --fliter=box");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown option --fliter (did you mean --filter?)"), std::string::npos) << r.err;
  const Json::Value summary = parse_json(r.out);
  EXPECT_EQ(summary["error"].asString(), "unknown option --fliter (did you mean --filter?)") << r.out;
  EXPECT_EQ(summary["exit_code"].asInt(), 1) << r.out;
  r = run_texproc("sat blur " + in + " -o '" + dir + "/b.png' --radius 2 --wrpa repeat");  // a command's command
  EXPECT_NE(r.err.find("unknown option --wrpa (did you mean --wrap?)"), std::string::npos) << r.err;
  r = run_texproc("mip " + in + " -o '" + dir + "/x.dds' --zzzzzz");
  EXPECT_NE(r.err.find("unknown option --zzzzzz\n"), std::string::npos) << r.err;  // nothing close: no guess
  // Top-level options may follow the command.
  r = run_texproc("mip " + in + " -o '" + dir + "/x.exr' --module-dir '" + dir + "'");
  EXPECT_EQ(r.exit_code, 5) << r.err;  // no modules in that folder: named
  EXPECT_NE(r.err.find(dir + "/texproc_exr.so (absent)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/x.exr"));
  fs::remove_all(dir);
}

// --format dxt5 (a DX9-era name) on sRGB colour writes the DX10 header that
// sRGB needs: said, with the way to a legacy header.
TEST(Names, DxtNamesOnSrgbColourSayTheHeaderNeedsDx10) {
  const std::string dir = temp_dir("names_dxt");
  write_image(dir + "/c.png", random_image(8, 8, 3, PixelType::u8, 9).view());
  const std::string base = "compress '" + dir + "/c.png' -o '" + dir + "/d.dds' --format dxt5 -f";
  RunResult r = run_texproc(base);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("needs a DX10 header that DX9-era readers (NVTT 2) cannot read; --linear writes a legacy "
                       "DXT5 header"),
            std::string::npos)
      << r.err;
  r = run_texproc(base + " --linear");
  EXPECT_EQ(r.err.find("DX10"), std::string::npos) << r.err;
  EXPECT_EQ(read_texture(dir + "/d.dds").format, TexelFormat::bc3_unorm);
  r = run_texproc("compress '" + dir + "/c.png' -o '" + dir + "/d.dds' --format bc3 -f");  // texproc's name
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("DX10"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// --no-mips exists and the last of --mips / --no-mips wins; without either,
// level 0 only.
TEST(Names, NoMipsIsTheStatedDefault) {
  const std::string dir = temp_dir("names_mips");
  write_image(dir + "/c.png", random_image(16, 16, 3, PixelType::u8, 10).view());
  const std::string base = "compress '" + dir + "/c.png' -o '" + dir + "/m.ktx2' --format bc1 -f -q";
  struct Case {
    const char* flags;
    std::uint32_t levels;
  };
  for (const Case& c : {Case{"", 1}, Case{" --mips", 5}, Case{" --no-mips", 1}, Case{" --mips --no-mips", 1},
                        Case{" --no-mips --mips", 5}}) {
    const RunResult r = run_texproc(base + c.flags);
    ASSERT_EQ(r.exit_code, 0) << c.flags << ": " << r.err;
    EXPECT_EQ(read_texture(dir + "/m.ktx2").levels, c.levels) << c.flags;
  }
  fs::remove_all(dir);
}
