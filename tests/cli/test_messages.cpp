// Messages that arrive before any work: a file whose extension promises a
// format its bytes do not have, and a depfile that could not be written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "support/images.h"
#include "support/json.h"
#include "support/run.h"
#include "texproc/container.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

// An empty or mislabelled file is refused by texproc itself (exit 3, naming
// the file and what is wrong), not handed to OpenImageIO.
TEST(Messages, MislabelledFilesAreRefusedByTheirSignature) {
  const std::string dir = temp_dir("mislabelled");
  std::ofstream(dir + "/empty.png").close();
  std::ofstream(dir + "/text.png") << "not an image at all";
  std::ofstream(dir + "/text.exr") << "not an image at all";
  struct Case {
    const char* file;
    const char* says;
  };
  for (const Case& c : {Case{"empty.png", "empty file (0 bytes)"},
                        Case{"text.png", "the extension says PNG, but the file does not start with PNG's signature"},
                        Case{"text.exr", "the extension says OpenEXR"}}) {
    for (const char* cmd : {"mip", "info"}) {
      const std::string out = std::string(cmd) == "mip" ? " -o '" + dir + "/o.dds'" : "";
      const RunResult r = run_texproc(std::string(cmd) + " '" + dir + "/" + c.file + "'" + out);
      EXPECT_EQ(r.exit_code, 3) << cmd << " " << c.file << ": " << r.err;
      EXPECT_NE(r.err.find(std::string(c.file) + ": " + c.says), std::string::npos) << r.err;
      EXPECT_EQ(r.err.find("OpenImageIO"), std::string::npos) << r.err;
    }
  }
  EXPECT_FALSE(fs::exists(dir + "/o.dds"));
  // A PNG named .jpg is still read by its signature.
  write_image(dir + "/real.png", random_image(8, 8, 3, PixelType::u8, 1).view());
  fs::copy_file(dir + "/real.png", dir + "/named.jpg");
  EXPECT_EQ(run_texproc("info '" + dir + "/named.jpg'").exit_code, 0);
  fs::remove_all(dir);
}

// A depfile whose folder cannot be made fails the run before any output is
// written (exit 2), so Make never sees outputs without their dependencies.
TEST(Messages, DepfileFolderIsCheckedBeforeAnyWork) {
  const std::string dir = temp_dir("depfile_folder");
  write_image(dir + "/a.png", random_image(16, 16, 3, PixelType::u8, 2).view());
  std::ofstream(dir + "/plain") << "a file, not a folder";
  const RunResult r =
      run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/a.dds' --depfile '" + dir + "/plain/deps/a.d'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--depfile cannot be written in"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/a.dds"));
  // A folder that does not exist yet is made, as an output's is.
  const RunResult ok =
      run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/a.dds' --depfile '" + dir + "/deps/a.d' -q");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir + "/deps/a.d"));
  fs::remove_all(dir);
}

// info: a KTX2 file's supercompression and stored level sizes (text and
// JSON, the sizes those of the level index), and failed files in the JSON.
TEST(Messages, InfoShowsSupercompressionAndFailures) {
  const std::string dir = temp_dir("info_zstd");
  write_image(dir + "/a.png", random_image(32, 32, 3, PixelType::u8, 3).view());
  ASSERT_EQ(run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/z.ktx2' --zstd 19 -q").exit_code, 0);
  ASSERT_EQ(run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/p.ktx2' -q").exit_code, 0);
  const Ktx2Storage st = ktx2_storage(dir + "/z.ktx2");
  EXPECT_EQ(st.scheme, 2u);
  ASSERT_EQ(st.stored_bytes.size(), 6u);
  EXPECT_EQ(st.inflated_bytes[0], 32u * 32u * 4u);
  RunResult r = run_texproc("info '" + dir + "/z.ktx2'");
  EXPECT_NE(r.out.find("Zstandard-supercompressed to "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("level 0: 32x32, 4096 bytes, stored in " + std::to_string(st.stored_bytes[0])),
            std::string::npos)
      << r.out;
  r = run_texproc("info '" + dir + "/p.ktx2'");
  EXPECT_EQ(r.out.find("supercompressed"), std::string::npos) << r.out;
  std::ofstream(dir + "/bad.png") << "no";
  r = run_texproc("info --json '" + dir + "/z.ktx2' '" + dir + "/bad.png' '" + dir + "/p.ktx2'");
  EXPECT_EQ(r.exit_code, 3);
  const Json::Value files = parse_json(r.out);
  ASSERT_EQ(files.size(), 3u) << r.out;
  EXPECT_EQ(files[0]["supercompression"].asString(), "Zstandard") << r.out;
  EXPECT_EQ(files[1]["error"].asString().rfind(dir + "/bad.png: the extension says PNG", 0), 0u) << r.out;
  EXPECT_EQ(files[1]["exit_code"].asInt(), 3) << r.out;
  EXPECT_EQ(files[2]["supercompression"].asString(), "none") << r.out;
  fs::remove_all(dir);
}

// --write-if-changed says which outputs it kept and which it wrote, in the
// line and in --json.
TEST(Messages, WriteIfChangedReportsKeptAndReplaced) {
  const std::string dir = temp_dir("kept");
  write_image(dir + "/a.png", random_image(16, 16, 3, PixelType::u8, 4).view());
  const std::string cmd = "mip '" + dir + "/a.png' -o '" + dir + "/a.dds' --write-if-changed";
  RunResult r = run_texproc(cmd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(written)"), std::string::npos) << r.out;
  r = run_texproc(cmd);
  EXPECT_NE(r.out.find("(unchanged: kept)"), std::string::npos) << r.out;
  r = run_texproc(cmd + " --json");
  Json::Value file = parse_json(r.out)["files"][0];
  ASSERT_EQ(file["kept"].size(), 1u) << r.out;
  EXPECT_EQ(file["kept"][0].asString(), dir + "/a.dds");
  EXPECT_EQ(file["replaced"].size(), 0u) << r.out;
  r = run_texproc(cmd + " --wrap repeat --json");
  file = parse_json(r.out)["files"][0];
  EXPECT_EQ(file["kept"].size(), 0u) << r.out;
  EXPECT_EQ(file["replaced"].size(), 1u) << r.out;
  fs::remove_all(dir);
}

// info says "tagged" only for a file that carries a colour tag: a PNG with
// an sRGB chunk is tagged, one without (Pillow writes none) is read as sRGB
// by default and says so.
TEST(Messages, InfoSaysTaggedOnlyForTaggedFiles) {
  if (std::system("/usr/bin/python3 -c 'import PIL' >/dev/null 2>&1") != 0) GTEST_SKIP() << "python3-pil not installed";
  const std::string dir = temp_dir("info_tag");
  const std::string make =
      "/usr/bin/python3 -c \"from PIL import Image; Image.new('RGB', (4, 4)).save('" + dir + "/plain.png')\"";
  ASSERT_EQ(std::system(make.c_str()), 0);
  RunResult r = run_texproc("info '" + dir + "/plain.png'");
  EXPECT_NE(r.out.find("no colour tag (read as sRGB)"), std::string::npos) << r.out;
  r = run_texproc("info --json '" + dir + "/plain.png'");
  EXPECT_NE(r.out.find("\"color_space_tagged\": false"), std::string::npos) << r.out;
  r = run_texproc("info '" + std::string(TEXPROC_SAMPLES_DIR) + "/albedo_desert_512.png'");  // has an sRGB chunk
  EXPECT_NE(r.out.find("tagged sRGB"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("no colour tag"), std::string::npos) << r.out;
  fs::remove_all(dir);
}
