// Messages that arrive before any work: a file whose extension promises a
// format its bytes do not have, and a depfile that could not be written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "support/images.h"
#include "support/run.h"
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
  for (const Case& c : {Case{"empty.png", "empty file (0 bytes)"}, Case{"text.png", "the extension says PNG, but the file does not start with PNG's signature"},
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
  const RunResult ok = run_texproc("mip '" + dir + "/a.png' -o '" + dir + "/a.dds' --depfile '" + dir + "/deps/a.d' -q");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir + "/deps/a.d"));
  fs::remove_all(dir);
}
