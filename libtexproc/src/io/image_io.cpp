// Image files: which reader or writer handles a file. Reading goes by the
// file's signature (TGA, which has none, by its extension), writing by the
// extension. Formats without a direct codec, and every format when
// ImageIoPath::oiio is set, go to the OpenImageIO module.
#include "texproc/image_io.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "io/codecs/codecs.h"
#include "io/modules/image_modules.h"
#include "io/tiff_mip_writer.h"
#include "texproc/error.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc {
namespace {

std::string lower_ext(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

enum class Kind { png, jpeg, tga, exr, tiff, container, module };

Kind sniff(const std::string& path, const codecs::FileBytes& f, ImageIoPath io_path) {
  const std::uint8_t* b = f.data();
  const std::size_t n = f.size();
  auto starts = [&](const char* sig, std::size_t len) { return n >= len && std::memcmp(b, sig, len) == 0; };
  if (starts("DDS ", 4) || starts("PKM ", 4) || starts("\xABKTX 20\xBB", 8) || starts("\xABKTX 11\xBB", 8) ||
      starts("\x13\xAB\xA1\x5C", 4)) {
    return Kind::container;
  }
  if (io_path == ImageIoPath::oiio) return Kind::module;
  if (starts("\x89PNG\r\n\x1a\n", 8)) return Kind::png;
  if (starts("\xFF\xD8\xFF", 3)) return Kind::jpeg;
  if (starts("\x76\x2F\x31\x01", 4)) return Kind::exr;
  if (starts("II*\0", 4) || starts("MM\0*", 4) || starts("II+\0", 4) || starts("MM\0+", 4)) return Kind::tiff;
  const std::string e = lower_ext(path);
  if (e == ".tga" || e == ".tpic" || e == ".icb" || e == ".vda" || e == ".vst") return Kind::tga;
  // A file whose extension names a format with a signature, without that
  // signature, is refused here, in microseconds (OpenImageIO would take a
  // second to load and then refuse it too).
  if (n == 0) throw Error(ErrorCode::invalid_file, path + ": empty file (0 bytes)");
  static const std::pair<const char*, const char*> kSigned[] = {
      {".png", "PNG"}, {".jpg", "JPEG"},  {".jpeg", "JPEG"}, {".exr", "OpenEXR"}, {".tif", "TIFF"},  {".tiff", "TIFF"},
      {".dds", "DDS"}, {".ktx2", "KTX2"}, {".ktx", "KTX"},   {".pkm", "PKM"},     {".astc", ".astc"}};
  for (const auto& [ext, name] : kSigned) {
    if (e == ext) {
      throw Error(ErrorCode::invalid_file, path + ": the extension says " + std::string(name) +
                                               ", but the file does not start with " + name + "'s signature");
    }
  }
  return Kind::module;
}

void check_exists(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(ErrorCode::io, path + ": no such file");
  if (fs::is_directory(path, ec)) throw Error(ErrorCode::io, path + ": is a directory, not an image");
}

using modules::Module;

template <typename Direct>
auto direct_or_module(const std::string& path, Direct&& direct, bool& left) -> decltype(direct()) {
  try {
    return direct();
  } catch (const codecs::LeaveToModule&) {
    left = true;
    return {};
  }
}

bool module_writes(const std::string& e, ImageIoPath io_path) {
  if (io_path == ImageIoPath::oiio) return true;
  return !(e == ".png" || e == ".tga" || e == ".jpg" || e == ".jpeg" || e == ".tif" || e == ".tiff" || e == ".exr");
}

void check_writable_extension(const std::string& path) {
  const std::string e = lower_ext(path);
  for (const char* ok : {".png", ".tga", ".jpg", ".jpeg", ".tif", ".tiff", ".exr", ".bmp", ".hdr"}) {
    if (e == ok) return;
  }
  throw Error(ErrorCode::unsupported,
              path + ": cannot write '" + e + "' files (valid: .png, .tga, .jpg, .tif, .tiff, .exr, .bmp, .hdr)");
}

}  // namespace

ReadOptions ReadOptions::from_environment() {
  ReadOptions o;
  const char* e = std::getenv("TEXPROC_IMAGE_IO");
  o.io_path = e && std::string(e) == "oiio" ? ImageIoPath::oiio : ImageIoPath::direct;
  o.limits = ReadLimits::from_environment();
  return o;
}

bool image_module_loaded() { return modules::loaded(Module::oiio); }

ImageFileInfo probe_image(const std::string& path, const ReadOptions& options) {
  check_exists(path);
  const ReadLimits& limits = options.limits;
  Kind kind;
  {
    const codecs::FileBytes f(path, /*read_ahead=*/false);  // a header is all a probe reads
    kind = sniff(path, f, options.io_path);
    bool left = false;
    ImageFileInfo info = direct_or_module(
        path,
        [&]() -> ImageFileInfo {
          switch (kind) {
            case Kind::png:
              return codecs::png_probe(path, f, limits);
            case Kind::jpeg:
              return codecs::jpeg_probe(path, f, limits);
            case Kind::tga:
              return codecs::tga_probe(path, f, limits);
            case Kind::exr:
              return modules::probe(Module::exr, path, limits);
            case Kind::tiff:
              return codecs::tiff_probe(path, limits);
            case Kind::container:
              return codecs::container_probe(path, limits);
            case Kind::module:
              throw codecs::LeaveToModule{"no direct reader"};
          }
          throw codecs::LeaveToModule{""};
        },
        left);
    if (!left) return info;
  }
  return modules::probe(Module::oiio, path, limits);
}

Image read_image(const std::string& path, ImageFileInfo* info_out, const ReadOptions& options) {
  check_exists(path);
  const ReadLimits& limits = options.limits;
  ImageFileInfo info;
  Image img;
  bool left = false;
  {
    const codecs::FileBytes f(path);
    const Kind kind = sniff(path, f, options.io_path);
    try {
      img = direct_or_module(
          path,
          [&]() -> Image {
            switch (kind) {
              case Kind::png:
                return codecs::png_read(path, f, info, limits);
              case Kind::jpeg:
                return codecs::jpeg_read(path, f, info, limits);
              case Kind::tga:
                return codecs::tga_read(path, f, info, limits);
              case Kind::exr:
                return modules::read(Module::exr, path, info, limits);
              case Kind::tiff:
                return codecs::tiff_read(path, info, limits);
              case Kind::container:
                return codecs::container_read(path, info, limits);
              case Kind::module:
                throw codecs::LeaveToModule{"no direct reader"};
            }
            throw codecs::LeaveToModule{""};
          },
          left);
    } catch (const Error&) {
      f.check_intact(path);  // a decoding error that a truncation caused says so
      throw;
    }
    f.check_intact(path);
  }
  if (left) img = modules::read(Module::oiio, path, info, limits);
  if (info_out) *info_out = info;
  return img;
}

ImageArray read_image_array(const std::string& path, ImageFileInfo* info_out, const ReadOptions& options) {
  check_exists(path);
  bool container;
  {
    const codecs::FileBytes f(path, /*read_ahead=*/false);
    container = sniff(path, f, options.io_path) == Kind::container;
  }
  ImageFileInfo info;
  ImageArray out;
  if (container) {
    out = codecs::container_read_all(path, info, options.limits);
  } else {
    out.images.push_back(read_image(path, &info, options));
  }
  if (info_out) *info_out = info;
  return out;
}

ImageChains read_image_chains(const std::string& path, ImageFileInfo* info_out, const ReadOptions& options,
                              std::uint32_t max_levels) {
  check_exists(path);
  bool container;
  {
    const codecs::FileBytes f(path, /*read_ahead=*/false);
    container = sniff(path, f, options.io_path) == Kind::container;
  }
  ImageFileInfo info;
  ImageChains out;
  if (container) {
    out = codecs::container_read_chains(path, info, options.limits, max_levels);
  } else {
    out.chains.emplace_back();
    out.chains.back().push_back(read_image(path, &info, options));
  }
  if (info_out) *info_out = info;
  return out;
}

void write_image(const std::string& path, const ConstImageView& given, const WriteOptions& options) {
  check_writable_extension(path);
  const std::string e = lower_ext(path);
  // Red-green data goes to formats without a red-green layout as RGB, blue 0.
  Image rgb;
  ConstImageView image = given;
  if (options.red_green && given.channels == 2 && (e != ".exr" || options.io_path == ImageIoPath::oiio)) {
    rgb = Image(given.width, given.height, 3, given.type);  // zero-filled: blue 0
    const std::size_t bpc = bytes_per_channel(given.type);
    for (int y = 0; y < given.height; ++y)
      for (int x = 0; x < given.width; ++x)
        std::memcpy(rgb.row<std::uint8_t>(y) + std::size_t(x) * 3 * bpc,
                    given.row<std::uint8_t>(y) + std::size_t(x) * 2 * bpc, 2 * bpc);
    image = rgb.view();
  }
  if (e == ".hdr" && image.channels != 3) {
    // Radiance HDR holds RGB: grey is spread to RGB, alpha has no place.
    if (image.channels != 1) {
      throw Error(ErrorCode::unsupported, path + ": a Radiance .hdr file holds RGB without alpha, and this image has " +
                                              std::to_string(image.channels) + " channels: write .exr to keep alpha");
    }
    rgb = Image::uninitialized(image.width, image.height, 3, image.type);
    const std::size_t bpc = bytes_per_channel(image.type);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        for (int c = 0; c < 3; ++c)
          std::memcpy(rgb.row<std::uint8_t>(y) + (std::size_t(x) * 3 + c) * bpc,
                      image.row<const std::uint8_t>(y) + std::size_t(x) * bpc, bpc);
    image = rgb.view();
  }
  AtomicFile file(path);
  const bool tiff = e == ".tif" || e == ".tiff";
  if (module_writes(e, options.io_path) || (tiff && (options.half || !tiff_levels_supported(options.compression)))) {
    modules::write(Module::oiio, file.temp_path(), path, {image}, false, options);
  } else if (e == ".png") {
    codecs::png_write(file.temp_path(), path, image, options);
  } else if (e == ".tga") {
    codecs::tga_write(file.temp_path(), path, image, options);
  } else if (e == ".jpg" || e == ".jpeg") {
    codecs::jpeg_write(file.temp_path(), path, image, options);
  } else if (e == ".exr") {
    modules::write(Module::exr, file.temp_path(), path, {image}, false, options);
  } else {
    write_tiff_levels(file.temp_path(), path, {image}, false, options.compression);
  }
  file.commit();
}

void write_image(const std::string& path, const ConstImageView& shape, const RowSource& source,
                 const WriteOptions& options) {
  check_writable_extension(path);
  const std::string e = lower_ext(path);
  if (e == ".png" && !module_writes(e, options.io_path) && !(options.red_green && shape.channels == 2)) {
    AtomicFile file(path);
    codecs::png_write(file.temp_path(), path, shape, source, options);
    file.commit();
    return;
  }
  Image whole = Image::uninitialized(shape.width, shape.height, shape.channels, shape.type);
  source(0, shape.height, whole.data(), whole.row_stride());
  write_image(path, whole.view(), options);
}

bool holds_mip_levels(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == ".tif" || e == ".tiff" || e == ".exr";
}

void write_mip_file(const std::string& path, const std::vector<Image>& levels, const WriteOptions& options) {
  if (levels.empty()) throw Error(ErrorCode::bad_arguments, path + ": no levels to write");
  if (!holds_mip_levels(path)) {
    throw Error(ErrorCode::unsupported,
                path + ": this format holds one level (valid for a MIP file: .tif, .tiff, .exr)");
  }
  const bool exr = lower_ext(path) == ".exr";
  if (exr) {
    int full = 1;
    for (int w = levels[0].width(), h = levels[0].height(); w > 1 || h > 1;
         w = std::max(1, w / 2), h = std::max(1, h / 2))
      ++full;
    if (int(levels.size()) != full) {
      throw Error(ErrorCode::unsupported,
                  path + ": an OpenEXR MIP file holds every level down to 1x1; drop --levels/--min-size or write .tif");
    }
  }
  std::vector<ConstImageView> views;
  for (const Image& l : levels) views.push_back(l.view());
  AtomicFile file(path);
  if (options.io_path == ImageIoPath::oiio || (!exr && (options.half || !tiff_levels_supported(options.compression)))) {
    modules::write(Module::oiio, file.temp_path(), path, views, true, options);
  } else if (exr) {
    modules::write(Module::exr, file.temp_path(), path, views, true, options);
  } else {
    write_tiff_levels(file.temp_path(), path, views, true, options.compression);
  }
  file.commit();
}

}  // namespace texproc
