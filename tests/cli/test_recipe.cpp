// `texproc build`: recipes in TOML and JSON, run as the command lines they
// stand for, with mistakes named by line and key before any work.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "support/images.h"
#include "support/json.h"
#include "support/run.h"
#include "texproc/image_io.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::string make_project(const std::string& name) {
  const std::string dir = temp_dir(name);
  fs::create_directories(dir + "/src/albedo");
  fs::create_directories(dir + "/src/height");
  write_image(dir + "/src/albedo/rock.png", random_image(20, 12, 3, PixelType::u8, 1).view());
  write_image(dir + "/src/albedo/moss.png", random_image(16, 16, 3, PixelType::u8, 2).view());
  write_image(dir + "/src/height/rock_h.png", random_image(16, 16, 1, PixelType::u8, 3).view());
  return dir;
}

const char* kToml = R"(version = 1
[[jobs]]
name = "albedo"
command = "compress"
inputs = ["src/albedo/*.png"]
output = "out/{stem}.dds"
options = { format = "bc1", quality = "high", mips = true }

[[jobs]]
name = "normals"
command = "normalmap"
inputs = "src/height"
output = "out/{stem}_n.png"
[jobs.options]
kernel = "scharr3"
height-scale = 4
)";

const char* kJson = R"({
  "version": 1,
  "jobs": [
    {"name": "albedo", "command": "compress", "inputs": ["src/albedo/*.png"], "output": "out/{stem}.dds",
     "options": {"format": "bc1", "quality": "high", "mips": true}},
    {"name": "normals", "command": "normalmap", "inputs": "src/height", "output": "out/{stem}_n.png",
     "options": {"kernel": "scharr3", "height-scale": 4}}
  ]
}
)";

}  // namespace

// A recipe does what its command lines do, byte for byte; TOML and JSON
// alike; paths are the recipe's, wherever texproc runs from.
TEST(Recipe, RunsItsJobsAsTheCommandLineWould) {
  const std::string dir = make_project("recipe_run");
  write_text(dir + "/r.toml", kToml);
  write_text(dir + "/r.json", kJson);
  RunResult r = run_texproc("build " + dir + "/r.toml --depfile " + dir + "/r.d -q");  // from elsewhere
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"/out/rock.dds", "/out/moss.dds", "/out/rock_h_n.png"}) {
    EXPECT_TRUE(fs::exists(dir + f)) << f;
  }
  r = run_texproc("compress src/albedo/rock.png -o cl/rock.dds --format bc1 --quality high --mips -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/out/rock.dds"), slurp(dir + "/cl/rock.dds"));
  r = run_texproc("normalmap src/height/rock_h.png -o cl/rock_h_n.png --kernel scharr3 --height-scale 4 -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/out/rock_h_n.png"), slurp(dir + "/cl/rock_h_n.png"));
  // The depfile lists the recipe as an input of every output.
  const std::string d = slurp(dir + "/r.d");
  EXPECT_NE(d.find(dir + "/r.toml"), std::string::npos) << d;
  EXPECT_NE(d.find(dir + "/src/albedo/moss.png"), std::string::npos) << d;
  // The JSON recipe, into another folder with --out-dir: the same bytes.
  r = run_texproc("build r.json --out-dir alt -q", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"/out/rock.dds", "/out/moss.dds", "/out/rock_h_n.png"}) {
    EXPECT_EQ(slurp(dir + f), slurp(dir + "/alt" + f)) << f;
  }
  // --job picks jobs; --dry-run lists and writes nothing.
  r = run_texproc("build r.toml --out-dir dry --job normals --dry-run", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "dry/out/rock_h_n.png (new)\n");
  EXPECT_FALSE(fs::exists(dir + "/dry"));
  // A second run is incremental: nothing to redo, exit 0 (Recipe.SecondRunIsIncremental); --skip-existing passes.
  r = run_texproc("build r.toml -q", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  r = run_texproc("build r.toml -q --skip-existing", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  fs::remove_all(dir);
}

// Every mistake names the file, the line and the key, and stops the build
// before it writes anything.
TEST(Recipe, MistakesAreNamedByLineAndKey) {
  const std::string dir = make_project("recipe_errors");
  struct Case {
    const char* file;
    std::string text;
    const char* expected;
  };
  const std::string toml = kToml;
  auto replace = [](std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return s.replace(at, from.size(), to);
  };
  const Case cases[] = {
      {"a.toml", replace(toml, "quality = \"high\"", "qualty = \"high\""),
       "a.toml:7: job 'albedo': options.qualty: unknown option for compress"},
      {"b.toml", replace(toml, "height-scale = 4", "height-scale = \"steep\""),
       "b.toml:16: job 'normals': options.height-scale: "},
      {"c.toml", replace(toml, "command = \"normalmap\"", "command = \"normalmapp\""),
       "c.toml:11: job 'normals': command: unknown command 'normalmapp' (valid: mip, compress"},
      {"d.toml", replace(toml, "version = 1", "version = 1\nbogus = ["), "d.toml:3: invalid TOML: "},
      {"e.toml", replace(toml, "mips = true", "mips = true, threads = 2"),
       "e.toml:7: job 'albedo': options.threads: belongs to the whole run"},
      {"f.toml", replace(toml, "mips = true", "mips = \"yes\""), "f.toml:7: job 'albedo': options.mips: is a switch"},
      {"g.toml", replace(toml, "src/albedo/*.png", "src/albedo/*.tga"),
       "g.toml:5: job 'albedo': inputs: 'src/albedo/*.tga' matches no file"},
      {"h.toml", replace(toml, "version = 1", "version = 2"), "h.toml:1: version: this texproc reads version 1"},
      {"i.toml", replace(toml, "name = \"normals\"", "name = \"normals\"\noutptu = \"x\""),
       "i.toml:11: jobs[1].outptu: unknown key (valid: name, command, inputs, exclude, output, recursive, options, "
       "overrides)"},
      {"j.toml", replace(toml, "output = \"out/{stem}_n.png\"\n", ""), "j.toml:9: jobs[1].output: missing"},
      {"k.toml", replace(toml, "format = \"bc1\"", "format = \"bc9\""),
       "k.toml:7: job 'albedo': options.format: unknown --format 'bc9'"},
      {"a.json", replace(kJson, "\"height-scale\": 4", "\"height-scal\": 4"),
       "a.json:7: job 'normals': options.height-scal: unknown option for normalmap"},
      {"b.json", replace(kJson, "\"version\": 1,", "\"version\": 1,,"), "b.json:2: invalid JSON: "},
      {"c.json", replace(kJson, "\"inputs\": \"src/height\"", "\"inputs\": 7"),
       "c.json:6: jobs[1].inputs: expected a string or a non-empty array of strings"},
      {"r.yaml", "jobs: []", "r.yaml: a recipe is a .toml or .json file"},
  };
  for (const Case& c : cases) {
    write_text(dir + "/" + c.file, c.text);
    RunResult r = run_texproc(std::string("build ") + c.file, dir);
    EXPECT_EQ(r.exit_code, 1) << c.file << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos)
        << c.file << "\nexpected: " << c.expected << "\ngot: " << r.err;
    EXPECT_FALSE(fs::exists(dir + "/out/rock_h_n.png")) << c.file;
  }
  RunResult r = run_texproc("build missing.toml", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.toml: cannot open recipe"), std::string::npos) << r.err;
  fs::remove_all(dir);
}

// The bundled samples/recipe.toml cooks every sample.
TEST(Recipe, SampleRecipeCooksTheSamples) {
  const std::string dir = temp_dir("recipe_samples");
  RunResult r =
      run_texproc("build " + std::string(TEXPROC_SAMPLES_DIR) + "/recipe.toml --out-dir " + dir + " -j 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f :
       {"textures/albedo_desert_512.dds", "textures/cutout_fence_512x256.dds", "textures/normal_stein_256.ktx2",
        "textures/height_mount_250_n.dds", "textures/height_stein_256_n.dds", "textures/height_stein_256_cones.png",
        "previews/height_stein_256_cones_preview.png"}) {
    EXPECT_TRUE(fs::exists(dir + "/" + f)) << f;
  }
  const Json::Value summary = parse_json(r.out);
  EXPECT_TRUE(std::any_of(summary["files"].begin(), summary["files"].end(), [](const Json::Value& f) {
    return f["job"].asString() == "heights-to-normals";
  })) << r.out;
  fs::remove_all(dir);
}

// A build is incremental, file by file: a second run skips every file; a
// touched input whose bytes did not change rebuilds nothing; changed bytes
// rebuild that file only; editing one job's options reruns only that job's
// files; a comment or another job's line reruns nothing; --force reruns all.
TEST(Recipe, SecondRunIsIncremental) {
  const std::string dir = make_project("recipe_incremental");
  write_text(dir + "/r.toml", kToml);
  // The files run (status ok) by a build, by output name.
  auto rebuilt = [&](const std::string& extra) {
    const RunResult r = run_texproc("build '" + dir + "/r.toml' --json" + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<std::string> ok;
    const Json::Value summary = parse_json(r.out);
    for (const Json::Value& f : summary["files"]) {
      if (f["status"].asString() == "ok") ok.push_back(fs::path(f["outputs"][0].asString()).filename().string());
    }
    std::sort(ok.begin(), ok.end());
    return ok;
  };
  using Names = std::vector<std::string>;
  const Names all = {"moss.dds", "rock.dds", "rock_h_n.png"};
  EXPECT_EQ(rebuilt(""), all);
  EXPECT_TRUE(fs::exists(dir + "/.r.toml.state"));
  EXPECT_EQ(rebuilt(""), Names{});
  // Touched, same bytes: nothing (and the new time stamp is remembered).
  const auto later = fs::file_time_type::clock::now() + std::chrono::seconds(5);
  fs::last_write_time(dir + "/src/albedo/rock.png", later);
  EXPECT_EQ(rebuilt(""), Names{});
  EXPECT_EQ(rebuilt(""), Names{});
  // New bytes: that file only.
  write_image(dir + "/src/albedo/rock.png", random_image(20, 12, 3, PixelType::u8, 9).view());
  EXPECT_EQ(rebuilt(""), Names{"rock.dds"});
  // A comment and a reordered table: nothing.
  std::string text = kToml;
  write_text(dir + "/r.toml", "# the project's textures\n" + text);
  EXPECT_EQ(rebuilt(""), Names{});
  // One option of one job: that job's files only.
  text.replace(text.find("height-scale = 4"), 16, "height-scale = 5");
  write_text(dir + "/r.toml", text);
  EXPECT_EQ(rebuilt(""), Names{"rock_h_n.png"});
  // An output deleted or changed by hand is made again.
  fs::remove(dir + "/out/moss.dds");
  EXPECT_EQ(rebuilt(""), Names{"moss.dds"});
  write_text(dir + "/out/rock.dds", "scribbled over");
  EXPECT_EQ(rebuilt(""), Names{"rock.dds"});
  EXPECT_EQ(rebuilt(" --force"), all);
  // --dry-run says why, and lists nothing that is up to date.
  text.replace(text.find("quality = \"high\""), 16, "quality = \"fast\"");
  write_text(dir + "/r.toml", text);
  const RunResult dry = run_texproc("build '" + dir + "/r.toml' --dry-run");
  EXPECT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_NE(dry.out.find("out/moss.dds (job settings changed)"), std::string::npos) << dry.out;
  EXPECT_NE(dry.out.find("out/rock.dds (job settings changed)"), std::string::npos) << dry.out;
  EXPECT_EQ(dry.out.find("rock_h_n.png"), std::string::npos) << dry.out;
  fs::remove_all(dir);
}
