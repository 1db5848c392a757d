// What a build system needs from texproc: recipes whose jobs form a graph,
// recursive globs with excludes, defaults with per-file overrides, shards
// for job arrays, the actions of a recipe as JSON, the tool's identity
// (--version --json, --runtime-files), and summaries without timings.
#include <gtest/gtest.h>
#include <json/reader.h>
#include <json/value.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "support/images.h"
#include "support/json.h"
#include "support/run.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Heightmaps in nested folders (and one in a hidden folder, one to exclude).
std::string make_tree(const std::string& name) {
  const std::string dir = temp_dir(name);
  for (const char* d : {"/src/a/b", "/src/.hidden"}) fs::create_directories(dir + d);
  write_image(dir + "/src/h1.png", random_image(16, 16, 1, PixelType::u8, 1).view());
  write_image(dir + "/src/a/h2.png", random_image(12, 20, 1, PixelType::u8, 2).view());
  write_image(dir + "/src/a/b/h3.png", random_image(8, 8, 1, PixelType::u8, 3).view());
  write_image(dir + "/src/a/b/skip.png", random_image(8, 8, 1, PixelType::u8, 4).view());
  write_image(dir + "/src/.hidden/h4.png", random_image(8, 8, 1, PixelType::u8, 5).view());
  return dir;
}

// A compress job (first in the file) reading what a normalmap job writes;
// defaults for compress, and an override for one file.
const char* kGraph = R"(version = 1
[defaults.compress]
quality = "fast"
format = "bc5"

[[jobs]]
name = "pack"
command = "compress"
inputs = "inter/**/*_n.png"
output = "out/{stem}.dds"
options = { normal-map = true }
[[jobs.overrides]]
inputs = "inter/h1_n.png"
options = { format = "bc7" }

[[jobs]]
name = "normals"
command = "normalmap"
inputs = "src/**/*.png"
exclude = "src/**/skip.png"
output = "inter/{stem}_n.png"
options = { kernel = "scharr3" }
)";

std::vector<std::string> sorted_files(const std::string& dir) {
  std::vector<std::string> out;
  if (!fs::exists(dir)) return out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

// From a clean tree the producing job runs first, whatever the recipe's
// order; `**` reaches every folder but hidden ones, `exclude` leaves files
// out; the defaults and the override give each file the options the command
// line would; and each output is the bytes of those command lines.
TEST(RecipeGraph, ProducersRunFirstWithGlobsDefaultsAndOverrides) {
  const std::string dir = make_tree("graph_clean");
  write_text(dir + "/r.toml", kGraph);
  RunResult r = run_texproc("build r.toml -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(sorted_files(dir + "/inter"), (std::vector<std::string>{"h1_n.png", "h2_n.png", "h3_n.png"}));
  EXPECT_EQ(sorted_files(dir + "/out"), (std::vector<std::string>{"h1_n.dds", "h2_n.dds", "h3_n.dds"}));
  // The same by hand.
  fs::create_directories(dir + "/hand");
  for (const char* f : {"h1", "a/h2", "a/b/h3"}) {
    const std::string stem = fs::path(f).filename().string();
    ASSERT_EQ(
        run_texproc("normalmap src/" + std::string(f) + ".png -o hand/" + stem + "_n.png --kernel scharr3 -q", dir)
            .exit_code,
        0);
    const std::string format = stem == "h1" ? "bc7" : "bc5";
    ASSERT_EQ(run_texproc("compress hand/" + stem + "_n.png -o hand/" + stem +
                              "_n.dds --normal-map --quality fast "
                              "--format " +
                              format + " -q",
                          dir)
                  .exit_code,
              0);
    EXPECT_EQ(slurp(dir + "/inter/" + stem + "_n.png"), slurp(dir + "/hand/" + stem + "_n.png")) << f;
    EXPECT_EQ(slurp(dir + "/out/" + stem + "_n.dds"), slurp(dir + "/hand/" + stem + "_n.dds")) << f;
  }
  // --dry-run from clean lists the dependent files with their reason.
  r = run_texproc("build r.toml --out-dir clean --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("clean/inter/h2_n.png (new)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("clean/out/h2_n.dds (input made by job 'normals')"), std::string::npos) << r.out;
  // A changed heightmap: its normal map and the texture made from it, nothing else.
  write_image(dir + "/src/a/h2.png", random_image(12, 20, 1, PixelType::u8, 7).view());
  r = run_texproc("build r.toml --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out,
            "inter/h2_n.png (input changed: src/a/h2.png)\n"
            "out/h2_n.dds (input inter/h2_n.png rebuilt by job 'normals')\n");
  // The override's options changed: that file only.
  std::string text = kGraph;
  text.replace(text.find("format = \"bc7\""), 14, "format = \"bc3\"");
  write_text(dir + "/r.toml", text);
  r = run_texproc("build r.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("src/h1.png ->"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("inter/h1_n.png -> out/h1_n.dds: bc3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("src/a/h2.png -> inter/h2_n.png"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("h3"), std::string::npos) << r.out;
  fs::remove_all(dir);
}

// Jobs that read each other's outputs, or their own, are refused before any
// work, naming the jobs; a pattern that matches nothing is named too.
TEST(RecipeGraph, CyclesAndEmptyPatternsAreRefused) {
  const std::string dir = make_tree("graph_cycle");
  fs::create_directories(dir + "/x");
  write_image(dir + "/x/a.png", random_image(8, 8, 1, PixelType::u8, 1).view());
  write_text(dir + "/cycle.toml", R"(version = 1
[[jobs]]
name = "there"
command = "normalmap"
inputs = "x/*.png"
output = "y/{stem}.png"
[[jobs]]
name = "back"
command = "normalmap"
inputs = "y/*.png"
output = "x/{stem}_b.png"
)");
  RunResult r = run_texproc("build cycle.toml", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("cycle.toml:2: job 'there': jobs form a cycle: job 'there' reads outputs of job 'back', which "
                       "reads outputs of job 'there'"),
            std::string::npos)
      << r.err;
  write_text(dir + "/self.toml",
             "version = 1\n[[jobs]]\nname = \"n\"\ncommand = \"normalmap\"\ninputs = \"src/*.png\"\n"
             "output = \"src/{stem}_n.png\"\n");
  r = run_texproc("build self.toml", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("self.toml:6: job 'n': reads its own outputs"), std::string::npos) << r.err;
  write_text(dir + "/none.toml",
             "version = 1\n[[jobs]]\ncommand = \"normalmap\"\ninputs = [\"src/h1.png\",\n"
             "  \"src/**/*.tga\"]\noutput = \"z/{stem}.png\"\n");
  r = run_texproc("build none.toml", dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("none.toml:5: jobs[0]: inputs: 'src/**/*.tga' matches no file"), std::string::npos) << r.err;
  for (const char* d : {"/y", "/z"}) EXPECT_FALSE(fs::exists(dir + d)) << d;
  EXPECT_EQ(sorted_files(dir + "/src").size(), 5u);
  fs::remove_all(dir);
}

// --shard I/N: the N shares of a batch or a recipe are disjoint and
// together the whole run, the same on every call.
TEST(ScaleOut, ShardsPartitionTheRun) {
  const std::string dir = make_tree("shards");
  write_text(dir + "/r.toml", kGraph);
  std::set<std::string> seen;
  std::size_t total = 0;
  for (int i = 0; i < 3; ++i) {
    RunResult r =
        run_texproc("normalmap src -r -o 'sh/{reldir}/{stem}.png' --shard " + std::to_string(i) + "/3 --json", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Json::Value v = parse_json(r.out);
    for (const Json::Value& f : v["files"]) {
      EXPECT_TRUE(seen.insert(f["input"].asString()).second) << f["input"].asString();
      ++total;
    }
  }
  EXPECT_EQ(total, 4u);  // src -r: h1, h2, h3, skip (hidden folders are skipped)
  EXPECT_EQ(sorted_files(dir + "/sh").size(), 4u);
  // A recipe's shares, job by job (producers first): each file once, the
  // shares together the whole build.
  for (const char* job : {"normals", "pack"}) {
    for (const char* share : {"1/2", "0/2"}) {
      RunResult s = run_texproc(std::string("build r.toml --job ") + job + " --shard " + share + " --json", dir);
      ASSERT_EQ(s.exit_code, 0) << s.err;
      EXPECT_EQ(parse_json(s.out)["ok"].asInt(), std::string(share) == "1/2" ? 1 : 2) << job << " " << share;
    }
  }
  EXPECT_EQ(sorted_files(dir + "/out").size(), 3u);
  RunResult r = run_texproc("build r.toml --dry-run", dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_EQ(r.out, "");
  for (const char* bad : {"3/3", "-1/2", "1/0", "x", "1/2/3"}) {
    r = run_texproc(std::string("normalmap src -r -o sh2/ --shard ") + bad, dir);
    EXPECT_EQ(r.exit_code, 1) << bad;
    EXPECT_NE(r.err.find("--shard"), std::string::npos) << r.err;
  }
  fs::remove_all(dir);
}

// --emit-actions: one action a file, producers first; running each argv in
// the recipe's folder makes the same bytes as the build.
TEST(ScaleOut, EmitActionsReproducesTheBuild) {
  const std::string dir = make_tree("actions");
  write_text(dir + "/r.toml", kGraph);
  RunResult r = run_texproc("build r.toml --emit-actions", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out"));
  const Json::Value v = parse_json(r.out);
  EXPECT_EQ(v["tool"]["digest"].asString().size(), 32u);
  ASSERT_EQ(v["actions"].size(), 6u);
  EXPECT_EQ(v["actions"][0]["job"].asString(), "normals");
  EXPECT_EQ(v["actions"][5]["job"].asString(), "pack");
  for (const Json::Value& a : v["actions"]) {
    std::string cmd = TEXPROC_CLI_PATH;
    for (Json::ArrayIndex i = 1; i < a["argv"].size(); ++i) cmd += " '" + a["argv"][i].asString() + "'";
    EXPECT_EQ(std::system(("cd '" + dir + "' && " + cmd + " -q").c_str()), 0) << cmd;
    for (const Json::Value& o : a["outputs"]) EXPECT_TRUE(fs::exists(dir + "/" + o.asString())) << o.asString();
  }
  ASSERT_EQ(run_texproc("build r.toml --out-dir built -q", dir).exit_code, 0);
  for (const char* f : {"inter/h1_n.png", "inter/h3_n.png", "out/h1_n.dds", "out/h2_n.dds"}) {
    EXPECT_EQ(slurp(dir + "/" + f), slurp(dir + "/built/" + f)) << f;
  }
  // The actions name their paths relative to the recipe: the same JSON from
  // another working folder.
  r = run_texproc("build " + dir + "/r.toml --emit-actions --job pack");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json::Value pack = parse_json(r.out);
  ASSERT_EQ(pack["actions"].size(), 3u);
  // (Now that its input exists, the last action's outputs are known.)
  EXPECT_EQ(pack["actions"][2]["argv"], v["actions"][5]["argv"]);
  EXPECT_EQ(pack["actions"][2]["outputs"], v["actions"][5]["outputs"]);
  fs::remove_all(dir);
}

// The tool's identity for cache keys, and what an action ships beside it.
TEST(ScaleOut, VersionJsonAndRuntimeFiles) {
  RunResult r = run_texproc("--version --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json::Value v = parse_json(r.out);
  EXPECT_EQ(v["digest"].asString().size(), 32u);
  EXPECT_FALSE(v["version"].asString().empty());
  EXPECT_TRUE(v["libraries"].isObject());
  EXPECT_EQ(parse_json(run_texproc("--version --json").out), v);  // stable
  r = run_texproc("--runtime-files");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t files = 0;
  for (std::size_t p = 0, nl; (nl = r.out.find('\n', p)) != std::string::npos; p = nl + 1) {
    EXPECT_TRUE(fs::is_regular_file(r.out.substr(p, nl - p))) << r.out.substr(p, nl - p);
    ++files;
  }
  EXPECT_GE(files, 2u);  // the binary and at least one module
  EXPECT_EQ(run_texproc("--version mip").exit_code, 1);
  EXPECT_EQ(run_texproc("--json").exit_code, 1);
}

// A --json summary is the same bytes on every run unless --timings asks
// for times; --ocio-config is an input of every output.
TEST(ScaleOut, SummariesAreReproducibleAndTheOcioConfigIsAnInput) {
  const std::string dir = make_tree("summary");
  RunResult a = run_texproc("normalmap src/h1.png -o o.png --json", dir);
  RunResult b = run_texproc("normalmap src/h1.png -o o.png --json --force", dir);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out.find("seconds"), std::string::npos) << a.out;
  EXPECT_EQ(a.out, b.out);
  RunResult t = run_texproc("normalmap src/h1.png -o o.png --json --force --timings", dir);
  EXPECT_NE(t.out.find("\"seconds\""), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("\"phases\""), std::string::npos) << t.out;
  write_text(dir + "/cfg.ocio", kTestOcioConfig);

  RunResult m = run_texproc(
      "mip src/h1.png -o g.tif --colorspace curve22 --ocio-config cfg.ocio --json "
      "--depfile g.d",
      dir);
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_NE(m.out.find("cfg.ocio"), std::string::npos) << m.out;
  EXPECT_NE(slurp(dir + "/g.d").find("cfg.ocio"), std::string::npos);
  // Without it (and without $OCIO) the name is unknown.
  m = run_texproc("mip src/h1.png -o g2.tif --colorspace curve22", dir);
  EXPECT_NE(m.exit_code, 0);
  m = run_texproc("mip src/h1.png -o g3.tif --ocio-config missing.ocio", dir);
  EXPECT_EQ(m.exit_code, 1);
  EXPECT_NE(m.err.find("missing.ocio: no such file"), std::string::npos) << m.err;
  fs::remove_all(dir);
}

// Shares that run at once into one output folder (a job array on a shared
// disk) keep every record: afterwards nothing is out of date, and every
// output is known as the recipe's.
TEST(ScaleOut, ConcurrentSharesKeepEveryRecord) {
  const std::string dir = temp_dir("shards_concurrent");
  fs::create_directories(dir + "/src");
  for (int i = 0; i < 12; ++i) {
    write_image(dir + "/src/h" + std::to_string(i) + ".png", random_image(8, 8, 1, PixelType::u8, 20 + i).view());
  }
  write_text(dir + "/r.toml",
             "version = 1\n[[jobs]]\ncommand = \"normalmap\"\ninputs = \"src/*.png\"\n"
             "output = \"out/{stem}_n.png\"\n");
  std::string cmd = "cd '" + dir + "' && (";
  for (int i = 0; i < 4; ++i) {
    cmd += std::string(TEXPROC_CLI_PATH) + " build r.toml -q --threads 1 --shard " + std::to_string(i) + "/4 & ";
  }
  cmd += "wait)";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(sorted_files(dir + "/out").size(), 12u);
  RunResult r = run_texproc("build r.toml --dry-run", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  std::size_t lines = 0;
  const std::string owned = slurp(dir + "/.r.toml.outputs");
  for (char c : owned) lines += c == '\n';
  EXPECT_EQ(lines, 12u) << owned;
  fs::remove_all(dir);
}
