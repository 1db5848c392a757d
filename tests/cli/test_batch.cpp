// Many files in one call: inputs (files, folders, -r, --file-list), output
// naming (-o FILE, DIR/, templates), parallel files (--jobs) with identical
// bytes, failures that do not stop the others, --fail-fast,
// --skip-existing, --json and --report, progress.
#include <gtest/gtest.h>
#include <json/reader.h>
#include <json/value.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "support/images.h"
#include "support/json.h"
#include "support/run.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

// A folder of small textures: a/b.png, a/c.png, a/sub/d.png, a/sub/deeper/e.tga.
std::string make_tree(const std::string& name) {
  const std::string dir = temp_dir(name);
  fs::create_directories(dir + "/a/sub/deeper");
  write_image(dir + "/a/b.png", random_image(24, 16, 3, PixelType::u8, 1).view());
  write_image(dir + "/a/c.png", random_image(13, 9, 4, PixelType::u8, 2).view());
  write_image(dir + "/a/sub/d.png", random_image(32, 32, 1, PixelType::u8, 3).view());
  write_image(dir + "/a/sub/deeper/e.tga", random_image(8, 20, 3, PixelType::u8, 4).view());
  std::ofstream(dir + "/a/notes.txt") << "not an image\n";
  return dir;
}

}  // namespace

TEST(Batch, FolderInputsMirrorTheTreeUnderAnOutputFolder) {
  const std::string dir = make_tree("batch_tree");
  RunResult r = run_texproc("compress a -o out/ --format bc1 -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/out/b.dds"));
  EXPECT_TRUE(fs::exists(dir + "/out/c.dds"));
  EXPECT_FALSE(fs::exists(dir + "/out/sub"));  // without -r only the folder's own files
  r = run_texproc("compress a -r -o out2 --format bc1 --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "out2/b.dds\nout2/c.dds\nout2/sub/d.dds\nout2/sub/deeper/e.dds\n");
  // A folder without images is an error, not a silent no-op.
  fs::create_directories(dir + "/empty");
  r = run_texproc("compress empty -o out3/ --format bc1", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("empty: folder holds no input files"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Batch, TemplatesNameEachOutput) {
  const std::string dir = make_tree("batch_template");
  RunResult r = run_texproc("normalmap a -r -o 'n/{reldir}/{stem}_{ext}.png' --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "n/b_png.png\nn/c_png.png\nn/sub/d_png.png\nn/sub/deeper/e_tga.png\n");
  r = run_texproc("mip a/b.png a/sub/d.png -o 'm/{dir}/{name}.ktx2' --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "m/a/b.png.ktx2\nm/a/sub/d.png.ktx2\n");
  r = run_texproc("mip a/b.png -o '{{x}}/{stem}.dds' --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "{x}/b.dds\n");
  // Mistakes are caught before any work, with the fix in the message.
  r = run_texproc("mip a/b.png -o 'm/{base}.dds'", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("unknown placeholder {base} (valid: {stem}, {name}, {ext}, {dir}, {reldir})"), std::string::npos)
      << r.err;
  r = run_texproc("mip a/b.png a/c.png -o m.dds", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("-o m.dds names one file, but there are 2 inputs"), std::string::npos) << r.err;
  r = run_texproc("mip a/b.png a/c.png -o 'm/x.dds{ext}'", dir);  // both give m/x.dspng
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("both a/b.png and a/c.png would write this output"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/m"));
  fs::remove_all(dir);
}

TEST(Batch, FileListAddsInputsAndIsADependency) {
  const std::string dir = make_tree("batch_list");
  std::ofstream(dir + "/list.txt") << "# textures\n\n  a/b.png  \na/sub/d.png\n";
  RunResult r = run_texproc("sat --file-list list.txt -o 't/{stem}.sat' --depfile t.d -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/t/b.sat"));
  EXPECT_TRUE(fs::exists(dir + "/t/d.sat"));
  EXPECT_EQ(slurp(dir + "/t.d"), "t/b.sat t/d.sat: \\\n  list.txt \\\n  a/b.png \\\n  a/sub/d.png\n");
  r = run_texproc("sat --file-list nope.txt -o t/", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nope.txt: cannot open file list"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// The same batch on one file at a time and on two at once, one thread or
// two: identical bytes.
TEST(Batch, OutputsAreIdenticalForAnyJobsAndThreads) {
  const std::string dir = make_tree("batch_determinism");
  struct Case {
    const char* command;
    const char* options;
  };
  for (const Case& c : {Case{"compress", "--format bc3 --mips --quality high"}, Case{"mip", "--filter lanczos3"},
                        Case{"normalmap", "--kernel sobel5 --mips"}, Case{"conemap", ""}}) {
    RunResult r = run_texproc(std::string(c.command) + " a -r -o one/ -q --jobs 1 --threads 1 " + c.options, dir);
    ASSERT_EQ(r.exit_code, 0) << c.command << r.err;
    r = run_texproc(std::string(c.command) + " a -r -o two/ -q --jobs 2 --threads 2 " + c.options, dir);
    ASSERT_EQ(r.exit_code, 0) << c.command << r.err;
    int files = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir + "/one")) {
      if (!e.is_regular_file()) continue;
      const std::string rel = fs::relative(e.path(), dir + "/one").string();
      ASSERT_TRUE(fs::exists(dir + "/two/" + rel)) << c.command << " " << rel;
      EXPECT_EQ(slurp(e.path().string()), slurp(dir + "/two/" + rel)) << c.command << " " << rel;
      ++files;
    }
    EXPECT_GE(files, 4) << c.command;
    fs::remove_all(dir + "/one");
    fs::remove_all(dir + "/two");
  }
  fs::remove_all(dir);
}

// A missing file, an unreadable file and a good one: the good output is
// written, both failures are reported, the exit code says so.
TEST(Batch, FailuresDoNotStopTheOthers) {
  const std::string dir = make_tree("batch_errors");
  std::ofstream(dir + "/broken.png") << "this is not a PNG";
  RunResult r = run_texproc("compress missing.png broken.png a/b.png -o out/ --format bc1 --json", dir);
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(fs::exists(dir + "/out/b.dds"));
  EXPECT_FALSE(fs::exists(dir + "/out/broken.dds"));
  EXPECT_NE(r.err.find("missing.png: no such file"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("broken.png: the extension says PNG"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2 of 3 files failed"), std::string::npos) << r.err;
  const Json::Value j = parse_json(r.out);
  EXPECT_EQ(j["ok"].asInt(), 1);
  EXPECT_EQ(j["failed"].asInt(), 2);
  EXPECT_EQ(j["exit_code"].asInt(), r.exit_code);
  ASSERT_EQ(j["files"].size(), 3u);
  EXPECT_EQ(j["files"][0]["status"].asString(), "failed");
  EXPECT_EQ(j["files"][0]["exit_code"].asInt(), 2);
  EXPECT_EQ(j["files"][1]["status"].asString(), "failed");
  EXPECT_EQ(j["files"][1]["exit_code"].asInt(), 3);
  EXPECT_EQ(j["files"][2]["status"].asString(), "ok");
  EXPECT_EQ(j["files"][2]["outputs"][0].asString(), "out/b.dds");
  // --fail-fast: nothing more is started after the first failure.
  r = run_texproc("compress broken.png a/b.png a/c.png -o ff/ --format bc1 --json --fail-fast -j 1", dir);
  EXPECT_EQ(r.exit_code, 3);
  const Json::Value f = parse_json(r.out);
  EXPECT_EQ(f["files"][0]["status"].asString(), "failed");
  EXPECT_EQ(f["not_run"].asInt(), 2);
  EXPECT_FALSE(fs::exists(dir + "/ff/c.dds"));
  fs::remove_all(dir);
}

TEST(Batch, ExistingOutputsAreRefusedSkippedOrReplaced) {
  const std::string dir = make_tree("batch_existing");
  RunResult r = run_texproc("mip a/b.png -o out/ -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("mip a/b.png a/c.png -o out/ -q", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("out/b.dds: output exists (use --force"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(dir + "/out/c.dds"));  // the other file still ran
  fs::remove(dir + "/out/c.dds");
  r = run_texproc("mip a/b.png a/c.png -o out/ --skip-existing --json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json::Value j = parse_json(r.out);
  EXPECT_EQ(j["files"][0]["status"].asString(), "skipped");
  EXPECT_EQ(j["files"][1]["status"].asString(), "ok");
  EXPECT_EQ(j["skipped"].asInt(), 1);
  r = run_texproc("mip a/b.png a/c.png -o out/ --force -q", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  fs::remove_all(dir);
}

TEST(Batch, JsonSummaryWithReport) {
  const std::string dir = make_tree("batch_json");
  RunResult r = run_texproc("compress a/b.png a/c.png -o 'o/{stem}.ktx2' --format bc3 --json --report", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json::Value j = parse_json(r.out);
  EXPECT_EQ(j["command"].asString(), "compress");
  ASSERT_EQ(j["files"].size(), 2u);
  const Json::Value& c = j["files"][1];
  EXPECT_EQ(c["input"].asString(), "a/c.png");
  ASSERT_EQ(c["inputs"].size(), 1u);  // no config or map named by the options
  EXPECT_EQ(c["inputs"][0].asString(), "a/c.png");
  EXPECT_EQ(c["format"].asString(), "bc3_srgb");
  EXPECT_EQ(c["width"].asInt(), 13);
  EXPECT_EQ(c["height"].asInt(), 9);
  EXPECT_EQ(c["output_bytes"].asUInt64(), fs::file_size(dir + "/o/c.ktx2"));
  EXPECT_EQ(c["input_bytes"].asUInt64(), fs::file_size(dir + "/a/c.png"));
  // Random texels are the worst case for BC3; the figure is a real
  // measurement: between 10 and 40 dB, RGB below all channels (alpha is
  // coded separately and better).
  const double psnr = c["report"]["psnr"].asDouble(), rgb = c["report"]["psnr_rgb"].asDouble();
  EXPECT_GT(psnr, 10.0);
  EXPECT_LT(psnr, 40.0);
  EXPECT_LT(rgb, psnr);
  EXPECT_EQ(c["report"]["psnr_channels"].size(), 4u);
  // An error of the whole run still gives a JSON document.
  r = run_texproc("compress a/b.png -o o2/ --format bc9 --json", dir);
  EXPECT_EQ(r.exit_code, 1);
  const Json::Value e = parse_json(r.out);
  EXPECT_EQ(e["exit_code"].asInt(), 1);
  EXPECT_NE(e["error"].asString().find("unknown --format 'bc9'"), std::string::npos);
  fs::remove_all(dir);
}

TEST(Batch, ProgressOnlyWhereAsked) {
  const std::string dir = make_tree("batch_progress");
  // stderr is a file here, not a terminal: no progress unless --progress.
  RunResult r = run_texproc("mip a -o p1/", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  r = run_texproc("mip a -o p2/ --progress", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("texproc mip [2/2] 100%"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("files/s"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Compare, ExitCodesAndFigures) {
  const std::string dir = temp_dir("compare");
  write_image(dir + "/a.png", random_image(16, 16, 3, PixelType::u8, 1).view());
  RunResult r = run_texproc("compress a.png -o a.dds --format bc1 -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("compare a.png a.png", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("PSNR inf dB"), std::string::npos) << r.out;
  // Without limits any difference is exit 7; with limits, the limits decide.
  r = run_texproc("compare a.png a.dds", dir);
  EXPECT_EQ(r.exit_code, 7) << r.err;
  EXPECT_NE(r.err.find("a.png and a.dds differ: texels differ"), std::string::npos) << r.err;
  r = run_texproc("compare a.png a.dds --json --ssim", dir);
  const Json::Value j = parse_json(r.out);
  const double psnr = j["psnr"].asDouble();
  EXPECT_GT(psnr, 10.0);
  EXPECT_LT(psnr, 45.0);
  EXPECT_EQ(j["channel"].size(), 3u);
  EXPECT_GT(j["ssim"].asDouble(), 0.0);
  EXPECT_LT(j["ssim"].asDouble(), 1.0);
  r = run_texproc("compare a.png a.dds --min-psnr " + std::to_string(psnr - 0.01) + " -q", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("compare a.png a.dds --min-psnr " + std::to_string(psnr + 0.01) + " -q", dir);
  EXPECT_EQ(r.exit_code, 7) << r.err;
  // The figure agrees with compress --report's.
  r = run_texproc("compress a.png -o b.dds --format bc1 --json --report", dir);
  EXPECT_NEAR(parse_json(r.out)["files"][0]["report"]["psnr"].asDouble(), psnr, 1e-3);
  write_image(dir + "/small.png", random_image(8, 8, 3, PixelType::u8, 1).view());
  r = run_texproc("compare a.png small.png", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("images of different sizes"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

TEST(Batch, InfoDescribesFolders) {
  const std::string dir = make_tree("batch_info");
  RunResult r = run_texproc("info a -r --json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json::Value j = parse_json(r.out);
  ASSERT_EQ(j.size(), 4u);  // notes.txt is not an image
  EXPECT_EQ(j[0]["file"].asString(), "a/b.png");
  EXPECT_EQ(j[3]["file"].asString(), "a/sub/deeper/e.tga");
  EXPECT_EQ(j[3]["height"].asInt(), 20);
  fs::remove_all(dir);
}
