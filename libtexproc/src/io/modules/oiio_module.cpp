// texproc_oiio: every image format OpenImageIO reads and texproc has no
// direct reader for (PSD, BMP, Radiance HDR, WebP, JPEG 2000, ...), behind
// the C boundary of oiio_module.h. Built as a separate shared object and
// loaded on first use; nothing in libtexproc links OpenImageIO.
#include "io/modules/image_module.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace {

// texproc::ErrorCode values (error.h), which this module does not include.
enum : int { kOk = 0, kIo = 2, kInvalidFile = 3, kUnsupported = 5, kBadArguments = 1 };

struct Failure {
  int code;
  std::string message;
};

int report(const Failure& f, char* err, size_t err_size) {
  if (err && err_size) {
    const size_t n = std::min(err_size - 1, f.message.size());
    std::memcpy(err, f.message.data(), n);
    err[n] = '\0';
  }
  return f.code;
}

void copy_string(char* dst, size_t size, const std::string& s) {
  const size_t n = std::min(size - 1, s.size());
  std::memcpy(dst, s.data(), n);
  dst[n] = '\0';
}

std::string lower_ext(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

TypeDesc to_typedesc(int t, bool half) {
  switch (t) {
    case TP_U8:
      return TypeDesc::UINT8;
    case TP_U16:
      return TypeDesc::UINT16;
    default:
      return half ? TypeDesc::HALF : TypeDesc::FLOAT;
  }
}

int from_typedesc(TypeDesc t) {
  if (t == TypeDesc::UINT8 || t == TypeDesc::INT8) return TP_U8;
  if (t == TypeDesc::UINT16 || t == TypeDesc::INT16) return TP_U16;
  return TP_F32;
}

std::unique_ptr<ImageInput> open_input(const std::string& path) {
  // Keep alpha as stored: OpenImageIO would otherwise premultiply PNG and
  // TGA colour on read (texproc premultiplies itself, in linear light).
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = ImageInput::open(path, &config);
  if (!in) {
    std::string msg = OIIO::geterror();
    if (msg.empty()) msg = "not an image format OpenImageIO reads";
    throw Failure{kInvalidFile, path + ": cannot read image: " + msg};
  }
  const ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw Failure{kInvalidFile, path + ": image has no pixels"};
  if (spec.depth > 1) throw Failure{kUnsupported, path + ": volume images are not supported"};
  return in;
}

std::string oiio_format_for(const std::string& path) {
  const std::string e = lower_ext(path);
  if (e == ".png") return "png";
  if (e == ".tga") return "targa";
  if (e == ".jpg" || e == ".jpeg") return "jpeg";
  if (e == ".tif" || e == ".tiff") return "tiff";
  if (e == ".exr") return "openexr";
  if (e == ".bmp") return "bmp";
  if (e == ".hdr") return "hdr";
  throw Failure{kUnsupported,
                path + ": cannot write '" + e + "' files (valid: .png, .tga, .jpg, .tif, .tiff, .exr, .bmp, .hdr)"};
}

ImageSpec make_spec(const TpImageLevel& v, const TpWriteOptions& o, const std::string& path) {
  ImageSpec spec(v.width, v.height, v.channels, to_typedesc(v.type, o.half));
  if (v.channels == 2 || v.channels == 4) {
    spec.alpha_channel = v.channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // our colour is straight, never premultiplied
  }
  const std::string e = lower_ext(path);
  const std::string compression = o.compression ? o.compression : "";
  if (!compression.empty()) spec.attribute("compression", compression);
  // OpenImageIO's PNG writer takes its deflate level from its own attribute.
  if (e == ".png" && compression.rfind("zip:", 0) == 0) {
    spec.attribute("png:compressionLevel", std::atoi(compression.c_str() + 4));
  }
  const std::string cs = o.color_space ? o.color_space : "";
  if (cs == "srgb") spec.attribute("oiio:ColorSpace", "sRGB");
  if (cs == "linear") spec.attribute("oiio:ColorSpace", "Linear");
  spec.attribute("Software", "texproc");
  if (e == ".jpg" || e == ".jpeg") spec.attribute("Compression", "jpeg:" + std::to_string(o.quality));
  // No timestamps: outputs are a pure function of inputs and options.
  spec.attribute("DateTime", "");
  // OpenImageIO 2.4 writes an Exif directory into appended TIFF subimages
  // with four uninitialized bytes in it: leave Exif out so that the same
  // input always gives the same bytes.
  spec.attribute("tiff:write_exif", 0);
  return spec;
}

// Writes `bytes` to `file`, every failure (a short write, a full disk, a
// failed close) an error naming `path` and the OS error.
void write_checked(const std::string& file, const std::string& path, const std::vector<unsigned char>& bytes) {
  auto fail = [&](int err) { throw Failure{kIo, path + ": cannot write: " + std::strerror(err)}; };
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail(errno);
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : EIO;
      ::close(fd);
      fail(err);
    }
    done += std::size_t(n);
  }
  if (::close(fd) != 0) fail(errno);
}

[[noreturn]] void write_failed(const std::string& path, ImageOutput& out) {
  std::string msg = out.geterror();
  if (msg.empty()) msg = OIIO::geterror();
  throw Failure{kIo, path + ": cannot write: " + msg};
}

// Writes `v` tile by tile from zero-padded tile buffers. OpenImageIO 2.4's
// TIFF writer leaves the padding of partial edge tiles uninitialized when
// given the exact image, so identical inputs would give different files.
void write_padded_tiles(ImageOutput& out, const TpImageLevel& v, int tile, const std::string& path) {
  const size_t px = size_t(v.channels) * (v.type == TP_U8 ? 1 : v.type == TP_U16 ? 2 : 4);
  std::vector<std::uint8_t> buf(size_t(tile) * tile * px);
  const TypeDesc td = to_typedesc(v.type, false);
  const auto* base = static_cast<const std::uint8_t*>(v.data);
  for (int ty = 0; ty < v.height; ty += tile) {
    for (int tx = 0; tx < v.width; tx += tile) {
      std::fill(buf.begin(), buf.end(), std::uint8_t(0));
      const int w = std::min(tile, v.width - tx), h = std::min(tile, v.height - ty);
      for (int y = 0; y < h; ++y) {
        std::memcpy(buf.data() + size_t(y) * tile * px, base + size_t(ty + y) * v.row_stride + size_t(tx) * px,
                    size_t(w) * px);
      }
      if (!out.write_tile(tx, ty, 0, td, buf.data())) write_failed(path, out);
    }
  }
}

void probe(const std::string& path, TpImageSpec& out) {
  auto in = open_input(path);
  const ImageSpec& spec = in->spec();
  out = TpImageSpec{};
  out.width = spec.width;
  out.height = spec.height;
  out.channels = spec.nchannels;
  out.type = from_typedesc(spec.format);
  copy_string(out.format, sizeof out.format, in->format_name());
  copy_string(out.file_type, sizeof out.file_type, spec.format.c_str());
  copy_string(out.color_space, sizeof out.color_space, spec.get_string_attribute("oiio:ColorSpace"));
  int sub = 0;
  while (in->seek_subimage(sub + 1, 0)) ++sub;
  out.subimages = sub + 1;
  out.level_width[0] = spec.width;
  out.level_height[0] = spec.height;
  int mips = 0;
  while (in->seek_subimage(0, mips + 1)) {
    ++mips;
    if (mips < TP_IMAGE_MAX_LEVELS) {
      out.level_width[mips] = in->spec().width;
      out.level_height[mips] = in->spec().height;
    }
  }
  out.mip_levels = mips + 1;
}

void read(const std::string& path, int channels, int type, void* data, size_t row_stride) {
  auto in = open_input(path);
  if (!in->read_image(0, 0, 0, channels, to_typedesc(type, false), data, OIIO::AutoStride,
                      OIIO::stride_t(row_stride))) {
    const std::string msg = in->geterror();
    throw Failure{kInvalidFile, path + ": cannot decode image: " + (msg.empty() ? "corrupt data" : msg)};
  }
}

void write_levels(ImageOutput* out, const std::string& file, const std::string& path, const TpImageLevel* levels,
                  int count, bool mip_file, const TpWriteOptions& o);

void write(const std::string& file, const std::string& path, const TpImageLevel* levels, int count, bool mip_file,
           const TpWriteOptions& o) {
  auto out = ImageOutput::create(oiio_format_for(path));
  if (!out) throw Failure{kUnsupported, path + ": " + OIIO::geterror()};
  if (!out->supports("ioproxy")) {
    throw Failure{kUnsupported, path + ": OpenImageIO cannot write this format to memory"};
  }
  // The writers write to memory and texproc writes the file: OpenImageIO's
  // writers do not all check their writes (its BMP writer ignores a full
  // disk) and OpenEXR's threads hang on a write that fails.
  OIIO::Filesystem::IOVecOutput memory;
  out->set_ioproxy(&memory);
  try {
    write_levels(out.get(), file, path, levels, count, mip_file, o);
  } catch (...) {
    out.reset();  // the writer goes before the buffer it writes to
    throw;
  }
  out.reset();
  write_checked(file, path, memory.buffer());
}

void write_levels(ImageOutput* out, const std::string& file, const std::string& path, const TpImageLevel* levels,
                  int count, bool mip_file, const TpWriteOptions& o) {
  if (!mip_file) {
    const ImageSpec spec = make_spec(levels[0], o, path);
    if (!out->open(file, spec)) write_failed(path, *out);
    if (!out->write_image(to_typedesc(levels[0].type, false), levels[0].data, OIIO::AutoStride,
                          OIIO::stride_t(levels[0].row_stride))) {
      write_failed(path, *out);
    }
    if (!out->close()) write_failed(path, *out);
    return;
  }
  const bool exr = lower_ext(path) == ".exr";
  // OpenImageIO's TIFF writer stores MIP levels as reduced-resolution
  // subimages (what maketx writes); its reader, seeing textureformat, hands
  // them back as MIP levels. OpenEXR has a native MIP mode.
  const bool native_mips = out->supports("mipmap");
  for (int l = 0; l < count; ++l) {
    const TpImageLevel& v = levels[l];
    ImageSpec spec = make_spec(v, o, path);
    spec.tile_width = spec.tile_height = 64;
    spec.attribute("textureformat", "Plain Texture");
    if (exr) {
      spec.attribute("openexr:levelmode", 1);     // MIPMAP_LEVELS
      spec.attribute("openexr:roundingmode", 0);  // ROUND_DOWN: floor(n / 2), as texproc's levels
    }
    const auto mode = l == 0        ? ImageOutput::Create
                      : native_mips ? ImageOutput::AppendMIPLevel
                                    : ImageOutput::AppendSubimage;
    if (!out->open(file, spec, mode)) write_failed(path, *out);
    if (exr) {
      if (!out->write_image(to_typedesc(v.type, false), v.data, OIIO::AutoStride, OIIO::stride_t(v.row_stride))) {
        write_failed(path, *out);
      }
    } else {
      write_padded_tiles(*out, v, spec.tile_width, path);
    }
  }
  if (!out->close()) write_failed(path, *out);
}

template <typename Fn>
int guarded(char* err, size_t err_size, Fn&& fn) {
  try {
    fn();
    return kOk;
  } catch (const Failure& f) {
    return report(f, err, err_size);
  } catch (const std::exception& e) {
    return report(Failure{kIo, e.what()}, err, err_size);
  }
}

int probe_c(const char* path, TpImageSpec* spec, char* err, size_t err_size) {
  return guarded(err, err_size, [&] { probe(path, *spec); });
}
int read_c(const char* path, int channels, int type, void* data, size_t row_stride, char* err, size_t err_size) {
  return guarded(err, err_size, [&] { read(path, channels, type, data, row_stride); });
}
int write_c(const char* file, const char* path, const TpImageLevel* levels, int count, int mip_file,
            const TpWriteOptions* o, char* err, size_t err_size) {
  return guarded(err, err_size, [&] { write(file, path, levels, count, mip_file != 0, *o); });
}

const TpImageModule kModule = {TP_IMAGE_MODULE_ABI, probe_c, read_c, write_c, nullptr, nullptr, nullptr};

}  // namespace

extern "C" __attribute__((visibility("default"))) const TpImageModule* texproc_oiio_module(void) { return &kModule; }
