// Image files: every corpus file loads, round trips, MIP files, errors, atomicity.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/images.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/tools.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

// Every file of the public corpus loads with the size and channel count that
// MANIFEST.tsv states (its bit_depth column: 8 -> u8, 16 -> u16, else f32).
TEST(ImageIo, WholeCorpusLoads) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  std::ifstream manifest(corpus_dir() + "/MANIFEST.tsv");
  std::string line;
  std::getline(manifest, line);  // header
  int checked = 0;
  while (std::getline(manifest, line)) {
    std::istringstream row(line);
    std::string file, category, w, h, ch, bits;
    std::getline(row, file, '\t');
    std::getline(row, category, '\t');
    std::getline(row, w, '\t');
    std::getline(row, h, '\t');
    std::getline(row, ch, '\t');
    std::getline(row, bits, '\t');
    // GPU containers go through texproc's own readers: the DX10 half-float
    // cubemap (which OpenImageIO 2.4 cannot read) loads; the UASTC+Zstandard
    // KTX2 is inflated, then refused as unsupported, naming UASTC.
    if (file.ends_with(".dds")) {
      const Texture t = read_texture(corpus_dir() + "/" + file);
      EXPECT_EQ(t.width, std::uint32_t(std::stoi(w)));
      EXPECT_EQ(t.faces, 6u);
      EXPECT_EQ(t.format, TexelFormat::rgba16_float);
      const Image face = image_from_texture(t, 0, 0, 2);
      EXPECT_TRUE(std::isfinite(face.get(5, 5, 0)));
      ++checked;
      continue;
    }
    if (category == "extra_container") {
      try {
        read_texture(corpus_dir() + "/" + file);
        ADD_FAILURE() << "a supercompressed KTX2 should be refused";
      } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::unsupported);
        EXPECT_NE(std::string(e.what()).find("vkFormat 0 (UASTC, Basis Universal)"), std::string::npos) << e.what();
      }
      continue;
    }
    SCOPED_TRACE(file);
    ImageFileInfo info;
    const Image img = read_image(corpus_dir() + "/" + file, &info);
    EXPECT_EQ(img.width(), std::stoi(w));
    EXPECT_EQ(img.height(), std::stoi(h));
    EXPECT_EQ(img.channels(), std::min(4, std::stoi(ch)));
    const PixelType want = bits == "8" ? PixelType::u8 : bits == "16" ? PixelType::u16 : PixelType::f32;
    EXPECT_EQ(img.type(), want);
    ++checked;
  }
  EXPECT_GE(checked, 40);
}

TEST(ImageIo, RoundTripsEveryWritableFormat) {
  const std::string dir = temp_dir("io");
  struct Case {
    const char* ext;
    PixelType type;
    int channels;
  };
  for (const Case& c : {Case{".png", PixelType::u8, 1}, Case{".png", PixelType::u8, 2}, Case{".png", PixelType::u16, 4},
                        Case{".tga", PixelType::u8, 4}, Case{".tif", PixelType::u16, 3},
                        Case{".exr", PixelType::f32, 4}, Case{".tif", PixelType::f32, 1}}) {
    const Image img = random_image(19, 7, c.channels, c.type, 3);
    const std::string path = dir + "/img" + std::to_string(c.channels) + to_string(c.type) + c.ext;
    write_image(path, img.view());
    ImageFileInfo info;
    const Image back = read_image(path, &info);
    ASSERT_EQ(back.type(), img.type()) << path;
    ASSERT_EQ(back.channels(), img.channels()) << path;
    EXPECT_EQ(0, std::memcmp(back.data(), img.data(), img.byte_size())) << path;
  }
  // Half: f32 written as f16 comes back within half precision.
  const Image img = random_image(8, 8, 3, PixelType::f32, 4);
  WriteOptions half;
  half.half = true;
  write_image(dir + "/half.exr", img.view(), half);
  ImageFileInfo info;
  const Image back = read_image(dir + "/half.exr", &info);
  EXPECT_EQ(info.file_type, "half");
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) EXPECT_NEAR(back.get(x, y, 1), img.get(x, y, 1), 1e-3);
  fs::remove_all(dir);
}

TEST(ImageIo, ErrorsNameTheFileAndKind) {
  const std::string dir = temp_dir("ioerr");
  try {
    read_image(dir + "/missing.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::io);
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos);
  }
  {
    std::ofstream bad(dir + "/bad.png", std::ios::binary);
    bad << "\x89PNG\r\n\x1a\n this is not a png";
  }
  try {
    read_image(dir + "/bad.png");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::invalid_file);
    EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos);
  }
  const Image img = random_image(4, 4, 3, PixelType::u8, 1);
  try {
    write_image(dir + "/out.xyz", img.view());
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::unsupported);
  }
  fs::remove_all(dir);
}

// A write that fails leaves neither the final file nor a temporary behind,
// and a file that existed before is untouched.
// The limits a read runs under come with the call; nothing else changes them.
TEST(ImageIo, ReadLimitsComeWithTheCall) {
  const std::string dir = temp_dir("limits");
  const std::string png = dir + "/a.png";
  write_image(png, Image(64, 32, 3, PixelType::u8).view());
  ReadOptions small;
  small.limits.max_image_pixels = 1000;
  for (ImageIoPath io : {ImageIoPath::direct, ImageIoPath::oiio}) {
    small.io_path = io;
    try {
      read_image(png, nullptr, small);
      ADD_FAILURE() << "a 64x32 image read under a limit of 1000 pixels";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::invalid_file);
      EXPECT_NE(std::string(e.what()).find(png), std::string::npos) << e.what();
    }
    EXPECT_THROW(probe_image(png, small), Error);
  }
  EXPECT_EQ(read_image(png).width(), 64);  // the defaults again: no state was left behind
  fs::remove_all(dir);
}

// ReadLimits{} and ReadOptions{} are the documented defaults whatever the
// environment says; from_environment() takes each variable that holds a
// positive number.
TEST(ImageIo, ReadOptionsFromEnvironment) {
  ::setenv("TEXPROC_MAX_IMAGE_PIXELS", "1234", 1);
  ::setenv("TEXPROC_MAX_JPEG_SCANS", "7", 1);
  ::setenv("TEXPROC_MAX_TEXTURE_BYTES", "4096", 1);
  ::setenv("TEXPROC_IMAGE_IO", "oiio", 1);
  const ReadLimits defaults;
  EXPECT_EQ(defaults.max_image_pixels, 16384LL * 8192);
  EXPECT_EQ(ReadOptions{}.io_path, ImageIoPath::direct);
  const ReadOptions env = ReadOptions::from_environment();
  EXPECT_EQ(env.io_path, ImageIoPath::oiio);
  EXPECT_EQ(env.limits.max_image_pixels, 1234);
  EXPECT_EQ(env.limits.max_jpeg_scans, 7);
  EXPECT_EQ(env.limits.max_inflated_bytes, 4096u);
  for (const char* bad : {"0", "-5", "12abc", ""}) {
    ::setenv("TEXPROC_MAX_IMAGE_PIXELS", bad, 1);
    EXPECT_EQ(ReadLimits::from_environment().max_image_pixels, defaults.max_image_pixels) << "'" << bad << "'";
  }
  for (const char* name :
       {"TEXPROC_MAX_IMAGE_PIXELS", "TEXPROC_MAX_JPEG_SCANS", "TEXPROC_MAX_TEXTURE_BYTES", "TEXPROC_IMAGE_IO"}) {
    ::unsetenv(name);
  }
  EXPECT_EQ(ReadOptions::from_environment().io_path, ImageIoPath::direct);
}

TEST(ImageIo, FailedWriteLeavesNothingBehind) {
  const std::string dir = temp_dir("atomic");
  {
    std::ofstream keep(dir + "/keep.png");
    keep << "old";
  }
  {
    AtomicFile f(dir + "/keep.png");
    std::ofstream(f.temp_path()) << "half-writ";
    // no commit: destroyed as if an exception had been thrown
  }
  std::size_t files = 0;
  for (auto& e : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(e.path().filename(), "keep.png");
  }
  EXPECT_EQ(files, 1u);
  std::ifstream in(dir + "/keep.png");
  std::string s;
  in >> s;
  EXPECT_EQ(s, "old");
  // An image whose writer fails (JPEG cannot hold 2 channels of u16? it
  // converts; a folder that vanished cannot be written) leaves nothing.
  const Image img = random_image(4, 4, 3, PixelType::u8, 1);
  EXPECT_THROW(write_image(dir + "/no/such/folder/x.png", img.view()), Error);
  EXPECT_FALSE(fs::exists(dir + "/no"));
  fs::remove_all(dir);
}

// A group's policy applies to the files committed in it, a file's own policy
// wins over it, and outside any group files replace what is there.
TEST(ImageIo, CommitPolicyComesFromTheGroup) {
  const std::string dir = temp_dir("group_policy");
  const std::string path = dir + "/f.bin";
  write_file_atomic(path, "one");
  {
    CommitGroup group(CommitPolicy::no_replace);
    write_file_atomic(path, "two");
    EXPECT_THROW(group.commit(), Error);
  }
  {
    CommitGroup group(CommitPolicy::no_replace);
    write_file_atomic(path, "three", CommitPolicy::replace);
    group.commit();
  }
  std::ifstream in(path);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "three");
  write_file_atomic(path, "four");  // no group: replace
  std::ifstream again(path);
  again >> s;
  EXPECT_EQ(s, "four");
  fs::remove_all(dir);
}

// CommitPolicy::keep_identical: the same bytes leave the file (and its time
// stamp) alone; other bytes, or another size, replace it; no temporaries stay.
TEST(ImageIo, KeepIdenticalCommitPolicy) {
  const std::string dir = temp_dir("keep_identical");
  const std::string path = dir + "/f.bin";
  write_file_atomic(path, "abcdef");
  const auto old_time = fs::file_time_type::clock::now() - std::chrono::seconds(100);
  fs::last_write_time(path, old_time);
  // The policy comes from the group open on this thread.
  auto write_kept = [&](const std::string& bytes) {
    CommitGroup group(CommitPolicy::keep_identical);
    write_file_atomic(path, bytes);
    group.commit();
  };
  write_kept("abcdef");
  EXPECT_EQ(fs::last_write_time(path), old_time);
  write_kept("abcdeg");  // same size, other bytes
  EXPECT_NE(fs::last_write_time(path), old_time);
  fs::last_write_time(path, old_time);
  write_kept("abcdegh");  // other size
  EXPECT_NE(fs::last_write_time(path), old_time);
  std::ifstream in(path);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "abcdegh");
  std::size_t files = 0;
  for (auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u);
  fs::remove_all(dir);
}
