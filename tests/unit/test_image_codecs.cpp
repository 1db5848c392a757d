// The direct image codecs (PNG, JPEG, TGA, TIFF, OpenEXR, GPU containers)
// against OpenImageIO's readers through texproc's module: the same pixels,
// channel count, element type, colour-space tag and levels on every corpus
// file and on files in every layout an independent encoder (Pillow) writes;
// the module is loaded only when a file needs it; hostile files are refused.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "support/images.h"
#include "support/run.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

using namespace texproc;
using namespace texproc::test;
namespace fs = std::filesystem;

namespace {

struct Read {
  ImageFileInfo info, probed;
  Image image;
};

Read read_with(ImageIoPath path, const std::string& file) {
  ReadOptions options;
  options.io_path = path;
  Read r;
  r.probed = probe_image(file, options);
  r.image = read_image(file, &r.info, options);
  return r;
}

void expect_same(const std::string& file) {
  SCOPED_TRACE(file);
  const Read d = read_with(ImageIoPath::direct, file);
  const Read o = read_with(ImageIoPath::oiio, file);
  EXPECT_TRUE(o.info.via_module);
  for (const ImageFileInfo* pair : {&d.info, &d.probed}) {
    const ImageFileInfo& a = *pair;
    const ImageFileInfo& b = pair == &d.info ? o.info : o.probed;
    EXPECT_EQ(a.format, b.format);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.channels, b.channels);
    EXPECT_EQ(a.file_type, b.file_type);
    EXPECT_EQ(a.type, b.type);
    EXPECT_EQ(a.color_space_tag, b.color_space_tag);
  }
  EXPECT_EQ(d.probed.subimages, o.probed.subimages);
  EXPECT_EQ(d.probed.mip_levels, o.probed.mip_levels);
  EXPECT_EQ(d.probed.level_sizes, o.probed.level_sizes);
  ASSERT_EQ(d.image.channels(), o.image.channels());
  ASSERT_EQ(d.image.type(), o.image.type());
  ASSERT_EQ(d.image.byte_size(), o.image.byte_size());
  if (d.image.type() == PixelType::f32) {
    // Bit for bit, NaN payloads included.
    EXPECT_EQ(0, std::memcmp(d.image.data(), o.image.data(), d.image.byte_size()));
  } else {
    std::size_t differ = 0;
    for (std::size_t i = 0; i < d.image.byte_size(); ++i) differ += d.image.data()[i] != o.image.data()[i];
    EXPECT_EQ(differ, 0u) << "bytes differ";
  }
}

std::vector<std::string> corpus_images() {
  std::vector<std::string> out;
  std::ifstream manifest(corpus_dir() + "/MANIFEST.tsv");
  std::string line;
  std::getline(manifest, line);
  while (std::getline(manifest, line)) {
    const std::string file = line.substr(0, line.find('\t'));
    if (file.ends_with(".dds") || file.ends_with(".ktx2")) continue;  // OpenImageIO 2.4 reads neither
    out.push_back(corpus_dir() + "/" + file);
  }
  return out;
}

std::string make_variants() {
  const std::string dir = temp_dir("variants");
  const std::string cmd =
      "/usr/bin/python3 '" + std::string(TEXPROC_SOURCE_DIR) + "/tests/tools/make_image_variants.py' '" + dir + "'";
  if (std::system(cmd.c_str()) != 0) return "";
  return dir;
}

void write_bytes(const std::string& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

}  // namespace

TEST(ImageCodecs, DirectReadersMatchOpenImageIOOnTheCorpus) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  int direct = 0;
  for (const std::string& f : corpus_images()) {
    expect_same(f);
    const ImageFileInfo i = probe_image(f);
    if (!f.ends_with(".bmp")) {
      EXPECT_FALSE(i.via_module) << f;
      ++direct;
    }
  }
  EXPECT_GE(direct, 35);
}

TEST(ImageCodecs, DirectReadersMatchOpenImageIOOnEveryLayout) {
  const std::string dir = make_variants();
  if (dir.empty()) GTEST_SKIP() << "python3 with Pillow is not installed";
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    expect_same(e.path().string());
    ++n;
  }
  EXPECT_GE(n, 35);
  fs::remove_all(dir);
}

// What texproc writes, OpenImageIO reads back identically, and so do
// texproc's readers: every writable format, type and channel count.
TEST(ImageCodecs, WrittenFilesReadTheSameBothWays) {
  const std::string dir = temp_dir("written");
  int n = 0;
  for (const char* ext : {".png", ".tif", ".exr", ".tga", ".jpg"}) {
    for (PixelType t : {PixelType::u8, PixelType::u16, PixelType::f32}) {
      for (int c = 1; c <= 4; ++c) {
        const std::string e(ext);
        if ((e == ".tga" || e == ".jpg") && t != PixelType::u8) continue;
        if (e == ".jpg" && (c == 2 || c == 4)) continue;
        if (e == ".tga" && c == 2) continue;
        if (e == ".png" && t == PixelType::f32) continue;
        const std::string path = dir + "/w" + std::to_string(c) + to_string(t) + ext;
        const Image img = random_image(70, 45, c, t, 17 + c);
        WriteOptions w;
        if (e == ".png") w.color_space = c == 1 ? "linear" : "srgb";
        write_image(path, img.view(), w);
        expect_same(path);
        ImageFileInfo info;
        const Image back = read_image(path, &info);
        if (e == ".exr") {
          EXPECT_EQ(back.type(), PixelType::f32);  // OpenEXR holds floats
        }
        if (e != ".jpg" && e != ".exr") {
          ASSERT_EQ(back.byte_size(), img.byte_size())
              << path << " came back with " << back.channels() << " channels of " << to_string(back.type());
          EXPECT_EQ(0, std::memcmp(back.data(), img.data(), img.byte_size())) << path;
        }
        ++n;
      }
    }
  }
  EXPECT_GE(n, 30);
  // MIP files: OpenImageIO sees the same levels as texproc's probe.
  const Image img = random_image(40, 24, 4, PixelType::u8, 8);
  MipOptions fo;
  fo.output_type = PixelType::f32;
  write_mip_file(dir + "/m.tif", generate_mips(img.view(), MipOptions{}).levels);
  write_mip_file(dir + "/m.exr", generate_mips(img.view(), fo).levels);
  expect_same(dir + "/m.tif");
  expect_same(dir + "/m.exr");
  EXPECT_EQ(probe_image(dir + "/m.tif").mip_levels, 6);
  EXPECT_EQ(probe_image(dir + "/m.exr").mip_levels, 6);
  fs::remove_all(dir);
}

// PNG's writer deflates strips of rows on every thread: the bytes never
// depend on the thread count.
TEST(ImageCodecs, PngBytesDoNotDependOnThreads) {
  const std::string dir = temp_dir("pngthreads");
  const Image img = random_image(300, 2100, 3, PixelType::u8, 5);  // several strips
  {
    ThreadLimit one(1);
    write_image(dir + "/a.png", img.view());
  }
  write_image(dir + "/b.png", img.view());
  EXPECT_EQ(slurp(dir + "/a.png"), slurp(dir + "/b.png"));
  const Image back = read_image(dir + "/b.png");
  EXPECT_EQ(0, std::memcmp(back.data(), img.data(), img.byte_size()));
  fs::remove_all(dir);
}

// Reading PNG, JPEG, TGA, TIFF, OpenEXR and GPU containers never loads
// OpenImageIO; a BMP does. (CTest runs each test in a process of its own.)
TEST(ImageCodecs, ModuleLoadsOnlyForFormatsThatNeedIt) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  if (image_module_loaded()) GTEST_SKIP() << "an earlier test in this process loaded the module (run it alone)";
  const std::string dir = temp_dir("noload");
  for (const char* f :
       {"/photo/skimage_astronaut_512.png", "/photo/skimage_rocket_640x427.jpg", "/alpha/openarena_frame1_l_ui.tga",
        "/hdr/blender_matcap_metal_carpaint.exr", "/hdr/qt3d_default_specular_cube_rgba16f.dds"}) {
    const Image img = read_image(corpus_dir() + f);
    write_image(dir + "/x.tif", img.view());
    read_image(dir + "/x.tif");
    probe_image(corpus_dir() + f);
  }
  EXPECT_FALSE(image_module_loaded()) << "OpenImageIO loaded for a directly read format";
  read_image(corpus_dir() + "/albedo_srgb/scorched3d_f18_512.bmp");
  EXPECT_TRUE(image_module_loaded());
  fs::remove_all(dir);
}

TEST(ImageCodecs, CliStartsWithoutOpenImageIO) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const std::string dir = temp_dir("clinoload");
  // The dynamic loader lists every object it maps, dlopen'ed ones too.
  const RunResult png = run_texproc("compress '" + corpus_dir() + "/photo/skimage_astronaut_512.png' -o '" + dir +
                                    "/a.dds' --format bc1 -q --force");
  ASSERT_EQ(png.exit_code, 0) << png.err;
  const std::string cmd = "LD_DEBUG=files " + std::string(TEXPROC_CLI_PATH) + " compress '" + corpus_dir() +
                          "/photo/skimage_astronaut_512.png' -o '" + dir + "/b.dds' --format bc1 -q --force 2>" + dir +
                          "/ld.txt";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string ld = slurp(dir + "/ld.txt");
  EXPECT_NE(ld.find("libspng"), std::string::npos) << "LD_DEBUG gave no list";
  EXPECT_EQ(ld.find("OpenImageIO"), std::string::npos);
  EXPECT_EQ(ld.find("texproc_oiio"), std::string::npos);
  // Nor OpenEXR or OpenColorIO: their modules load when a file or a colour space needs them.
  EXPECT_EQ(ld.find("OpenEXR"), std::string::npos);
  EXPECT_EQ(ld.find("OpenColorIO"), std::string::npos);
  auto loads = [&](const std::string& args, const std::string& object) {
    const std::string c =
        "LD_DEBUG=files " + std::string(TEXPROC_CLI_PATH) + " " + args + " >/dev/null 2>" + dir + "/ld3.txt";
    EXPECT_EQ(std::system(c.c_str()), 0) << args;
    return slurp(dir + "/ld3.txt").find(object) != std::string::npos;
  };
  EXPECT_TRUE(loads("info '" + corpus_dir() + "/hdr/blender_world_city.exr'", "texproc_exr"));
  EXPECT_FALSE(loads("info '" + corpus_dir() + "/hdr/blender_world_city.exr'", "texproc_oiio"));
  EXPECT_TRUE(loads("mip '" + corpus_dir() + "/photo/skimage_astronaut_512.png' -o '" + dir +
                        "/c.dds' --colorspace ACEScg -q --force",
                    "OpenColorIO"));
  EXPECT_FALSE(loads("mip '" + corpus_dir() + "/photo/skimage_astronaut_512.png' -o '" + dir + "/d.dds' -q --force",
                     "OpenColorIO"));
  const std::string bmp = "LD_DEBUG=files " + std::string(TEXPROC_CLI_PATH) + " info '" + corpus_dir() +
                          "/albedo_srgb/scorched3d_f18_512.bmp' >/dev/null 2>" + dir + "/ld2.txt";
  ASSERT_EQ(std::system(bmp.c_str()), 0);
  EXPECT_NE(slurp(dir + "/ld2.txt").find("texproc_oiio"), std::string::npos);
  fs::remove_all(dir);
}

TEST(ImageCodecs, MissingModuleNamesTheFileAndSparesOtherFormats) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const std::string dir = temp_dir("nomodule");
  const std::string env = "TEXPROC_OIIO_MODULE=" + dir + "/absent.so ";
  const std::string bmp = corpus_dir() + "/albedo_srgb/scorched3d_f18_512.bmp";
  const std::string cmd =
      env + TEXPROC_CLI_PATH + " mip '" + bmp + "' -o '" + dir + "/x.dds' >" + dir + "/o.txt 2>" + dir + "/e.txt";
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 5);
  const std::string err = slurp(dir + "/e.txt");
  EXPECT_NE(err.find("scorched3d_f18_512.bmp"), std::string::npos) << err;
  EXPECT_NE(err.find("OpenImageIO module"), std::string::npos) << err;
  EXPECT_NE(err.find("absent.so"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir + "/x.dds"));
  const std::string png =
      env + TEXPROC_CLI_PATH + " mip '" + corpus_dir() + "/photo/skimage_astronaut_512.png' -o '" + dir + "/y.dds' -q";
  EXPECT_EQ(std::system(png.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir + "/y.dds"));
  fs::remove_all(dir);
}

// Malformed files of each directly read format: exit 3, a message naming
// the file, no output.
TEST(ImageCodecs, MalformedFilesExitThreeWithNoOutput) {
  const std::string dir = temp_dir("malformed");
  const Image img = random_image(33, 17, 3, PixelType::u8, 2);
  for (const char* ext : {".png", ".jpg", ".tga", ".tif", ".exr"}) write_image(dir + "/good" + ext, img.view());
  std::vector<std::pair<std::string, std::string>> bad;  // name, bytes
  for (const char* ext : {".png", ".jpg", ".tga", ".tif", ".exr"}) {
    const std::string good = slurp(dir + "/good" + ext);
    for (std::size_t cut : {std::size_t(5), std::size_t(20), good.size() / 2, good.size() - 9}) {
      bad.push_back({"cut" + std::to_string(cut) + ext, good.substr(0, cut)});
    }
    if (std::string(ext) == ".tga") continue;  // TGA has no checksum: flipped pixels are valid pixels
    std::string flipped = good;
    for (std::size_t i = 40; i < flipped.size(); i += 7) flipped[i] = char(flipped[i] ^ 0x5A);
    bad.push_back({std::string("flipped") + ext, flipped});
  }
  // A PNG whose IHDR declares 100000 x 100000 (with a correct CRC): refused
  // from the header, before any pixel memory.
  {
    std::string png = slurp(dir + "/good.png");
    const std::uint32_t big = 100000;
    for (int i = 0; i < 4; ++i) png[16 + i] = png[20 + i] = char(big >> (24 - 8 * i));
    const std::uint32_t crc = [&] {
      std::uint32_t c = 0xFFFFFFFFu;
      for (int i = 12; i < 29; ++i) {
        c ^= std::uint8_t(png[std::size_t(i)]);
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
      }
      return ~c;
    }();
    for (int i = 0; i < 4; ++i) png[29 + i] = char(crc >> (24 - 8 * i));
    bad.push_back({"huge.png", png});
  }
  // A TGA declaring 65535 x 65535 in an 18-byte file.
  bad.push_back({"huge.tga", std::string("\0\0\2\0\0\0\0\0\0\0\0\0\xff\xff\xff\xff\x18\x20", 18)});
  for (const auto& [name, bytes] : bad) {
    SCOPED_TRACE(name);
    write_bytes(dir + "/" + name, bytes);
    const RunResult r = run_texproc("mip '" + dir + "/" + name + "' -o '" + dir + "/out_" + name + ".dds'");
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir + "/out_" + name + ".dds"));
  }
  const RunResult huge = run_texproc("info '" + dir + "/huge.png'");
  EXPECT_NE(huge.err.find("past the limit"), std::string::npos) << huge.err;
  fs::remove_all(dir);
}

// GPU containers are inputs: uncompressed ones give the image they hold,
// compressed ones the same as decoding them first.
TEST(ImageCodecs, ContainersAreInputs) {
  const std::string dir = temp_dir("containers_in");
  const Image img = random_image(64, 48, 4, PixelType::u8, 12);
  write_image(dir + "/src.png", img.view());
  auto ok = [](const RunResult& r) { EXPECT_EQ(r.exit_code, 0) << r.err; };
  // The PNG as an uncompressed one-level DDS, KTX2 and KTX1.
  for (const char* c : {"dds", "ktx2", "ktx"}) {
    ok(run_texproc("mip '" + dir + "/src.png' -o '" + dir + "/src." + c + "' --levels 1 -q"));
    const Image back = read_image(dir + "/src." + std::string(c));
    ASSERT_EQ(back.byte_size(), img.byte_size());
    EXPECT_EQ(0, std::memcmp(back.data(), img.data(), img.byte_size())) << c;
    // compress, mip and normalmap take it as they take the PNG.
    ok(run_texproc("compress '" + dir + "/src." + c + "' -o '" + dir + "/from_" + c + ".ktx2' --format bc3 --mips -q"));
    ok(run_texproc("mip '" + dir + "/src." + c + "' -o '" + dir + "/mip_" + c + ".dds' -q"));
  }
  ok(run_texproc("compress '" + dir + "/src.png' -o '" + dir + "/from_png.ktx2' --format bc3 --mips -q"));
  ok(run_texproc("mip '" + dir + "/src.png' -o '" + dir + "/mip_png.dds' -q"));
  for (const char* c : {"dds", "ktx2", "ktx"}) {
    EXPECT_EQ(slurp(dir + "/from_png.ktx2"), slurp(dir + "/from_" + std::string(c) + ".ktx2")) << c;
    EXPECT_EQ(slurp(dir + "/mip_png.dds"), slurp(dir + "/mip_" + std::string(c) + ".dds")) << c;
  }
  // A BC1 DDS recompressed equals its decoded PNG recompressed.
  ok(run_texproc("compress '" + dir + "/src.png' -o '" + dir + "/bc1.dds' --format bc1 -q"));
  ok(run_texproc("decompress '" + dir + "/bc1.dds' -o '" + dir + "/bc1.png' -q"));
  ok(run_texproc("compress '" + dir + "/bc1.dds' -o '" + dir + "/re_dds.ktx2' --format bc3 -q"));
  ok(run_texproc("compress '" + dir + "/bc1.png' -o '" + dir + "/re_png.ktx2' --format bc3 -q"));
  EXPECT_EQ(slurp(dir + "/re_dds.ktx2"), slurp(dir + "/re_png.ktx2"));
  const ImageFileInfo info = probe_image(dir + "/bc1.dds");
  EXPECT_EQ(info.format, "dds");
  EXPECT_EQ(info.file_type.rfind("bc1_", 0), 0u) << info.file_type;
  fs::remove_all(dir);
}

// A cubemap input keeps its six faces through mip and compress: each face
// of the output is that face processed alone; an image output is refused.
TEST(ImageCodecs, CubemapInputsKeepTheirFaces) {
  if (!have_corpus()) GTEST_SKIP() << "no corpus at " << corpus_dir();
  const std::string dir = temp_dir("cube_in");
  const std::string cube = corpus_dir() + "/hdr/qt3d_default_specular_cube_rgba16f.dds";
  ImageArray in = read_image_array(cube);
  ASSERT_EQ(in.images.size(), 6u);
  ASSERT_EQ(in.faces, 6u);
  RunResult r = run_texproc("mip '" + cube + "' -o '" + dir + "/m.ktx2' -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture m = read_texture(dir + "/m.ktx2");
  EXPECT_EQ(m.faces, 6u);
  EXPECT_EQ(m.format, TexelFormat::rgba16_float);  // a half-float texture stays half
  for (std::uint32_t f = 0; f < 6; ++f) {
    MipOptions o;
    o.output_type = PixelType::f32;
    const Texture alone = texture_from_levels(generate_mips(in.images[f].view(), o).levels, {.half = true});
    ASSERT_EQ(alone.levels, m.levels);
    for (std::uint32_t l = 0; l < m.levels; ++l)
      EXPECT_TRUE(m.image(l, 0, f) == alone.image(l)) << "face " << f << " level " << l;
  }
  // compress: the faces' level 0 as compress_image encodes each alone.
  r = run_texproc("compress '" + cube + "' -o '" + dir + "/c.dds' --format bc4 --linear -q");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Texture c = read_texture(dir + "/c.dds");
  EXPECT_EQ(c.faces, 6u);
  for (std::uint32_t f = 0; f < 6; ++f) {
    const std::vector<std::uint8_t> alone =
        compress_image(in.images[f].view(), TexelFormat::bc4_unorm, Quality::normal);
    EXPECT_TRUE(c.image(0, 0, f) == alone) << "face " << f;
  }
  r = run_texproc("mip '" + cube + "' -o '" + dir + "/m.png' -q");
  EXPECT_EQ(r.exit_code, 5);
  EXPECT_NE(r.err.find("cubemap"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/m_mip0.png"));
  fs::remove_all(dir);
}

// An OpenEXR header whose attribute declares more bytes than the file holds
// is refused before OpenEXR allocates them (a 1.6 KB file from fuzz_images
// declared 1.9 GB and made OpenEXR take it): exit 3, the attribute named.
TEST(ImageCodecs, ExrAttributeLargerThanTheFileIsRefused) {
  const std::string dir = temp_dir("exr_hostile");
  write_image(dir + "/ok.exr", random_image(8, 6, 3, PixelType::f32, 4).view());
  std::string bytes = slurp(dir + "/ok.exr");
  // The first attribute: name, type name, then its int32 size.
  const std::size_t name_end = bytes.find('\0', 8), type_end = bytes.find('\0', name_end + 1);
  ASSERT_NE(type_end, std::string::npos);
  const std::int32_t huge = 0x70000000;
  std::memcpy(&bytes[type_end + 1], &huge, 4);
  std::ofstream(dir + "/bad.exr", std::ios::binary) << bytes;
  try {
    read_image(dir + "/bad.exr");
    ADD_FAILURE() << "a hostile OpenEXR header was read";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::invalid_file);
    EXPECT_NE(std::string(e.what()).find("declares 1879048192 bytes"), std::string::npos) << e.what();
  }
  EXPECT_EQ(read_image(dir + "/ok.exr").width(), 8);
  fs::remove_all(dir);
}
