// Image file I/O: the only file that includes OpenImageIO.
#include "texproc/image_io.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>

#include "image/tiff_mip_writer.h"
#include "texproc/error.h"
#include "texproc/file_io.h"

namespace fs = std::filesystem;
using OIIO::ImageInput;
using OIIO::ImageOutput;
using OIIO::ImageSpec;
using OIIO::TypeDesc;

namespace texproc {
namespace {

std::string lower_ext(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

TypeDesc to_typedesc(PixelType t, bool half) {
  switch (t) {
    case PixelType::u8: return TypeDesc::UINT8;
    case PixelType::u16: return TypeDesc::UINT16;
    case PixelType::f32: return half ? TypeDesc::HALF : TypeDesc::FLOAT;
  }
  return TypeDesc::UNKNOWN;
}

PixelType from_typedesc(TypeDesc t) {
  if (t == TypeDesc::UINT8 || t == TypeDesc::INT8) return PixelType::u8;
  if (t == TypeDesc::UINT16 || t == TypeDesc::INT16) return PixelType::u16;
  return PixelType::f32;
}

std::unique_ptr<ImageInput> open_input(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(ErrorCode::io, path + ": no such file");
  if (fs::is_directory(path, ec)) throw Error(ErrorCode::io, path + ": is a directory, not an image");
  // Keep alpha as stored: OpenImageIO would otherwise premultiply PNG and
  // TGA color on read (texproc premultiplies itself, in linear light).
  ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = ImageInput::open(path, &config);
  if (!in) {
    std::string msg = OIIO::geterror();
    if (msg.empty()) msg = "not an image format OpenImageIO reads";
    throw Error(ErrorCode::invalid_file, path + ": cannot read image: " + msg);
  }
  return in;
}

ImageFileInfo info_from(const ImageInput& in, const std::string& path) {
  const ImageSpec& spec = in.spec();
  ImageFileInfo info;
  info.format = in.format_name();
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.nchannels;
  info.file_type = spec.format.c_str();
  info.type = from_typedesc(spec.format);
  info.color_space_tag = spec.get_string_attribute("oiio:ColorSpace");
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    throw Error(ErrorCode::invalid_file, path + ": image has no pixels");
  }
  if (spec.depth > 1) throw Error(ErrorCode::unsupported, path + ": volume images are not supported");
  return info;
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
  throw Error(ErrorCode::unsupported,
              path + ": cannot write '" + e + "' files (valid: .png, .tga, .jpg, .tif, .tiff, .exr, .bmp, .hdr)");
}

std::unique_ptr<ImageOutput> create_output(const std::string& path) {
  auto out = ImageOutput::create(oiio_format_for(path));
  if (!out) throw Error(ErrorCode::unsupported, path + ": " + OIIO::geterror());
  return out;
}

ImageSpec make_spec(const ImageView& v, const WriteOptions& o, const std::string& path) {
  ImageSpec spec(v.width, v.height, v.channels, to_typedesc(v.type, o.half));
  if (v.channels == 2 || v.channels == 4) {
    spec.alpha_channel = v.channels - 1;
    spec.attribute("oiio:UnassociatedAlpha", 1);  // our color is straight, never premultiplied
  }
  const std::string e = lower_ext(path);
  if (!o.compression.empty()) spec.attribute("compression", o.compression);
  // OpenImageIO's PNG writer takes its deflate level from its own attribute.
  if (e == ".png" && o.compression.rfind("zip:", 0) == 0) {
    spec.attribute("png:compressionLevel", std::atoi(o.compression.c_str() + 4));
  }
  if (o.color_space == "srgb") spec.attribute("oiio:ColorSpace", "sRGB");
  if (o.color_space == "linear") spec.attribute("oiio:ColorSpace", "Linear");
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

[[noreturn]] void write_failed(const std::string& path, ImageOutput& out) {
  std::string msg = out.geterror();
  if (msg.empty()) msg = OIIO::geterror();
  throw Error(ErrorCode::io, path + ": cannot write: " + msg);
}

// Writes `v` tile by tile from zero-padded tile buffers. OpenImageIO 2.4's
// TIFF writer leaves the padding of partial edge tiles uninitialized when
// given the exact image, so identical inputs would give different files.
// (OpenEXR stores edge tiles cropped, so it writes the image as it is.)
void write_padded_tiles(ImageOutput& out, const ImageView& v, int tile, const std::string& path) {
  const std::size_t px = v.pixel_bytes();
  std::vector<std::uint8_t> buf(std::size_t(tile) * tile * px);
  const TypeDesc td = to_typedesc(v.type, false);
  for (int ty = 0; ty < v.height; ty += tile) {
    for (int tx = 0; tx < v.width; tx += tile) {
      std::fill(buf.begin(), buf.end(), std::uint8_t(0));
      const int w = std::min(tile, v.width - tx), h = std::min(tile, v.height - ty);
      for (int y = 0; y < h; ++y) {
        std::memcpy(buf.data() + std::size_t(y) * tile * px, v.row<std::uint8_t>(ty + y) + std::size_t(tx) * px,
                    std::size_t(w) * px);
      }
      if (!out.write_tile(tx, ty, 0, td, buf.data())) write_failed(path, out);
    }
  }
}

}  // namespace

ImageFileInfo probe_image(const std::string& path) {
  auto in = open_input(path);
  ImageFileInfo info = info_from(*in, path);
  int sub = 0;
  while (in->seek_subimage(sub + 1, 0)) ++sub;
  info.subimages = sub + 1;
  info.level_sizes.emplace_back(info.width, info.height);
  int mips = 0;
  while (in->seek_subimage(0, mips + 1)) {
    ++mips;
    info.level_sizes.emplace_back(in->spec().width, in->spec().height);
  }
  info.mip_levels = mips + 1;
  return info;
}

Image read_image(const std::string& path, ImageFileInfo* info_out) {
  auto in = open_input(path);
  ImageFileInfo info = info_from(*in, path);
  const int channels = std::min(info.channels, 4);
  Image img = Image::uninitialized(info.width, info.height, channels, info.type);
  const TypeDesc td = to_typedesc(info.type, false);
  if (!in->read_image(0, 0, 0, channels, td, img.data())) {
    std::string msg = in->geterror();
    throw Error(ErrorCode::invalid_file, path + ": cannot decode image: " + (msg.empty() ? "corrupt data" : msg));
  }
  if (info_out) *info_out = info;
  return img;
}

void write_image(const std::string& path, const ImageView& image, const WriteOptions& options) {
  auto out = create_output(path);
  AtomicFile file(path);
  ImageSpec spec = make_spec(image, options, path);
  if (!out->open(file.temp_path(), spec)) write_failed(path, *out);
  if (!out->write_image(to_typedesc(image.type, false), image.data, OIIO::AutoStride, OIIO::stride_t(image.row_stride))) {
    write_failed(path, *out);
  }
  if (!out->close()) write_failed(path, *out);
  file.commit();
}

bool holds_mip_levels(const std::string& path) {
  const std::string e = lower_ext(path);
  return e == ".tif" || e == ".tiff" || e == ".exr";
}

void write_mip_file(const std::string& path, const std::vector<Image>& levels, const WriteOptions& options) {
  if (levels.empty()) throw Error(ErrorCode::bad_arguments, path + ": no levels to write");
  if (!holds_mip_levels(path)) {
    throw Error(ErrorCode::unsupported, path + ": this format holds one level (valid for a MIP file: .tif, .tiff, .exr)");
  }
  const bool exr = lower_ext(path) == ".exr";
  if (!exr && !options.half && tiff_mips_supported(options.compression)) {
    AtomicFile file(path);
    write_tiff_mips(file.temp_path(), path, levels, options.compression, options.color_space);
    file.commit();
    return;
  }
  if (exr) {
    int full = 1;
    for (int w = levels[0].width(), h = levels[0].height(); w > 1 || h > 1; w = std::max(1, w / 2), h = std::max(1, h / 2)) ++full;
    if (int(levels.size()) != full) {
      throw Error(ErrorCode::unsupported,
                  path + ": an OpenEXR MIP file holds every level down to 1x1; drop --levels/--min-size or write .tif");
    }
  }
  auto out = create_output(path);
  // OpenImageIO's TIFF writer stores MIP levels as reduced-resolution
  // subimages (what maketx writes); its reader, seeing textureformat, hands
  // them back as MIP levels. OpenEXR has a native MIP mode.
  const bool native_mips = out->supports("mipmap");
  AtomicFile file(path);
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const ImageView v = levels[l].view();
    ImageSpec spec = make_spec(v, options, path);
    spec.tile_width = spec.tile_height = 64;
    spec.attribute("textureformat", "Plain Texture");
    if (exr) {
      spec.attribute("openexr:levelmode", 1);     // MIPMAP_LEVELS
      spec.attribute("openexr:roundingmode", 0);  // ROUND_DOWN: floor(n / 2), as texproc's levels
    }
    const auto mode = l == 0       ? ImageOutput::Create
                      : native_mips ? ImageOutput::AppendMIPLevel
                                    : ImageOutput::AppendSubimage;
    if (!out->open(file.temp_path(), spec, mode)) write_failed(path, *out);
    if (exr) {
      if (!out->write_image(to_typedesc(v.type, false), v.data, OIIO::AutoStride, OIIO::stride_t(v.row_stride))) {
        write_failed(path, *out);
      }
    } else {
      write_padded_tiles(*out, v, spec.tile_width, path);
    }
  }
  if (!out->close()) write_failed(path, *out);
  file.commit();
}

}  // namespace texproc
