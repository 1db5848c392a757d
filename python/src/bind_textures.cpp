// Textures, their containers, and block compression.
#include <pybind11/stl.h>

#include <memory>

#include "arrays.h"
#include "bindings.h"
#include "texproc/block_decode.h"
#include "texproc/block_encode.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/runtime.h"
#include "texproc/texture.h"

namespace texproc::py_binding {
namespace {

using TexturePtr = std::shared_ptr<Texture>;

ContainerKind parse_container(const std::string& name) {
  if (name == "dds") return ContainerKind::dds;
  if (name == "ktx2") return ContainerKind::ktx2;
  if (name == "ktx" || name == "ktx1") return ContainerKind::ktx1;
  if (name == "pkm") return ContainerKind::pkm;
  if (name == "astc") return ContainerKind::astc;
  throw Error(ErrorCode::bad_arguments, "unknown container '" + name + "' (valid: dds, ktx2, ktx, pkm, astc)");
}

DdsHeader parse_dds_header(const std::string& name) {
  if (name == "auto") return DdsHeader::automatic;
  if (name == "dx9") return DdsHeader::dx9;
  if (name == "dx10") return DdsHeader::dx10;
  throw Error(ErrorCode::bad_arguments, "unknown dds_header '" + name + "' (valid: auto, dx9, dx10)");
}

TransparentColor parse_transparent(const std::string& name) {
  if (name == "keep") return TransparentColor::keep;
  if (name == "bleed") return TransparentColor::bleed;
  if (name == "zero") return TransparentColor::zero;
  throw Error(ErrorCode::bad_arguments, "unknown transparent_color '" + name + "' (valid: keep, bleed, zero)");
}

void check_zstd(int zstd) {
  if (zstd < 0 || zstd > 22) throw Error(ErrorCode::bad_arguments, "zstd must be 0 (none) or 1 to 22");
}

py::bytes to_bytes(const Texture& t, const std::string& container, int zstd, const std::string& dds_header) {
  check_zstd(zstd);
  const ContainerKind kind = parse_container(container);
  if (zstd != 0 && kind != ContainerKind::ktx2) throw Error(ErrorCode::bad_arguments, "zstd applies to ktx2 only");
  if (dds_header != "auto" && kind != ContainerKind::dds) {
    throw Error(ErrorCode::bad_arguments, "dds_header applies to dds only");
  }
  std::vector<std::uint8_t> bytes;
  {
    py::gil_scoped_release release;
    switch (kind) {
      case ContainerKind::dds:
        bytes = encode_dds(t, parse_dds_header(dds_header));
        break;
      case ContainerKind::ktx2:
        bytes = encode_ktx2(t, "", zstd);
        break;
      case ContainerKind::ktx1:
        bytes = encode_ktx1(t);
        break;
      case ContainerKind::pkm:
        bytes = encode_pkm(t);
        break;
      case ContainerKind::astc:
        bytes = encode_astc(t);
        break;
    }
  }
  return py::bytes(reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

TexturePtr from_bytes(const py::buffer& data, const std::string& name) {
  const py::buffer_info b = data.request();
  if (b.ndim != 1 || b.itemsize != 1 || (b.ndim == 1 && b.strides[0] != 1)) {
    throw Error(ErrorCode::bad_arguments, name + ": want contiguous bytes");
  }
  const auto* p = static_cast<const std::uint8_t*>(b.ptr);
  const std::size_t n = std::size_t(b.size);
  ContainerKind kind;
  if (!container_from_signature(p, n, kind)) {
    throw Error(ErrorCode::invalid_file, name + ": not a DDS, KTX2, KTX1, PKM or .astc file (no signature)");
  }
  py::gil_scoped_release release;
  const ReadLimits& limits = read_options().limits;
  switch (kind) {
    case ContainerKind::dds:
      return std::make_shared<Texture>(decode_dds(p, n, name, limits));
    case ContainerKind::ktx2:
      return std::make_shared<Texture>(decode_ktx2(p, n, name, limits));
    case ContainerKind::ktx1:
      return std::make_shared<Texture>(decode_ktx1(p, n, name, limits));
    case ContainerKind::pkm:
      return std::make_shared<Texture>(decode_pkm(p, n, name, limits));
    case ContainerKind::astc:
      return std::make_shared<Texture>(decode_astc(p, n, name, limits));
  }
  throw Error(ErrorCode::runtime, "unknown container");
}

void check_index(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face) {
  if (level >= t.levels || layer >= t.layers || face >= t.faces) {
    throw Error(ErrorCode::bad_arguments, "level " + std::to_string(level) + ", layer " + std::to_string(layer) +
                                              ", face " + std::to_string(face) + " is outside the texture (" +
                                              std::to_string(t.levels) + " levels, " + std::to_string(t.layers) +
                                              " layers, " + std::to_string(t.faces) + " faces)");
  }
}

// The bytes of one image of the texture, read-only, kept alive by the texture.
py::array image_bytes_view(const py::object& self, std::uint32_t level, std::uint32_t layer, std::uint32_t face) {
  const Texture& t = *self.cast<TexturePtr>();
  check_index(t, level, layer, face);
  const PixelBytes& b = t.image(level, layer, face);
  py::array view(py::dtype::of<std::uint8_t>(), {py::ssize_t(b.size())}, {py::ssize_t(1)}, b.data(), self);
  view.attr("flags").attr("writeable") = false;
  return view;
}

py::array decode(const Texture& t, std::uint32_t level, std::uint32_t layer, std::uint32_t face,
                 const py::handle& dtype) {
  check_index(t, level, layer, face);
  const PixelType type = parse_dtype(dtype);
  Image image;
  {
    py::gil_scoped_release release;
    image = decode_texture_image(t, level, layer, face, type);
  }
  return to_array(std::move(image));
}

// Owning copies of the arrays `surfaces` holds (one array, or a list).
std::vector<Image> copy_surfaces(const py::handle& surfaces) {
  std::vector<Image> out;
  auto add = [&out](const py::handle& a) {
    const InputImage in(a, "image");
    const ConstImageView& v = in.view();
    Image copy = Image::uninitialized(v.width, v.height, v.channels, v.type);
    for (int y = 0; y < v.height; ++y)
      std::memcpy(copy.row<std::uint8_t>(y), v.row<std::uint8_t>(y), copy.row_stride());
    out.push_back(std::move(copy));
  };
  if (py::isinstance<py::list>(surfaces) || py::isinstance<py::tuple>(surfaces)) {
    for (const py::handle& a : surfaces) add(a);
  } else {
    add(surfaces);
  }
  if (out.empty()) throw Error(ErrorCode::bad_arguments, "image: an empty list");
  return out;
}

Image decode_to_linear(const Image& img, const ColorSpace& from) {
  Image out = Image::uninitialized(img.width(), img.height(), img.channels(), PixelType::f32);
  for_each_row_block(img.height(), 16, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      from.decode_row(img.row<std::uint8_t>(y), img.type(), img.channels(), img.width(), out.row<float>(y));
  });
  return out;
}

SurfaceLayout layout_of(std::size_t surfaces, std::uint32_t faces, bool is_array) {
  if (faces != 1 && faces != 6) throw Error(ErrorCode::bad_arguments, "faces must be 1 or 6");
  if (surfaces % faces != 0) {
    throw Error(ErrorCode::bad_arguments, std::to_string(surfaces) + " images do not make whole cubes of 6 faces");
  }
  SurfaceLayout l;
  l.faces = faces;
  l.layers = std::uint32_t(surfaces / faces);
  l.is_array = is_array || l.layers > 1;
  return l;
}

TexturePtr compress(const py::handle& images, const std::string& format_name, const std::string& quality, bool mips,
                    std::uint32_t faces, bool is_array, const std::string& color_space, bool normal_map,
                    const std::string& transparent_color, bool bc1_black, std::optional<float> astc_effort,
                    const std::string& filter, float sigma, const std::string& wrap,
                    std::optional<float> alpha_coverage, bool premultiplied_alpha, int max_levels, int min_size) {
  const TexelFormat format = parse_texel_format(format_name);
  const FormatInfo& info = format_info(format);
  if (!info.compressed) throw Error(ErrorCode::bad_arguments, format_name + " is not a block format");
  const Quality q = parse_quality(quality);
  TextureEncodeOptions options;
  options.encode.bc1_black = bc1_black;
  if (astc_effort) {
    if (!(*astc_effort >= 0.0f && *astc_effort <= 100.0f))
      throw Error(ErrorCode::bad_arguments, "astc_effort must be 0 to 100");
    options.encode.astc_effort = *astc_effort;
  }
  options.normal_map = normal_map;
  options.transparent = parse_transparent(transparent_color);
  const MipOptions mip =
      mip_options(filter, sigma, wrap, alpha_coverage, premultiplied_alpha, normal_map, max_levels, min_size);
  std::vector<Image> surfaces = copy_surfaces(images);
  const SurfaceLayout l = layout_of(surfaces.size(), faces, is_array);
  // HDR formats hold light: integer colour is decoded (from sRGB unless
  // color_space says otherwise) before the chain and the encoder see it.
  std::optional<ColorSpace> decode_from;
  if (info.is_float && surfaces[0].type() != PixelType::f32) {
    const bool srgb = color_space.empty() ? !normal_map : color_space == "srgb";
    decode_from = color_space.empty() || color_space == "srgb" || color_space == "linear"
                      ? (srgb ? ColorSpace::srgb() : ColorSpace::linear())
                      : ColorSpace::from_name(color_space);
  }
  std::size_t non_finite = 0;
  Texture t;
  {
    py::gil_scoped_release release;
    for (Image& s : surfaces) {
      non_finite += replace_non_finite(s);
      if (decode_from) s = decode_to_linear(s, *decode_from);
    }
    if (mips) {
      MipOptions m = mip;
      m.color_space = info.srgb ? "srgb" : "linear";
      t = compress_texture_mips(surfaces, m, l, format, q, options);
    } else {
      std::vector<std::vector<Image>> chains;
      for (Image& s : surfaces) chains.emplace_back().push_back(std::move(s));
      t = compress_texture(chains, l, format, q, options);
    }
  }
  if (non_finite) {
    PyErr_WarnEx(PyExc_RuntimeWarning,
                 (std::to_string(non_finite) + " non-finite value(s) (NaN or infinity) read as 0").c_str(), 1);
  }
  return std::make_shared<Texture>(std::move(t));
}

TexturePtr from_surfaces(const py::list& chains, std::uint32_t faces, bool is_array, bool srgb, bool half) {
  std::vector<std::vector<Image>> owned;
  for (const py::handle& chain : chains) owned.push_back(copy_surfaces(chain));
  const SurfaceLayout l = layout_of(owned.size(), faces, is_array);
  py::gil_scoped_release release;
  return std::make_shared<Texture>(texture_from_surfaces(std::move(owned), l, {.srgb = srgb, .half = half}));
}

py::dict format_dict(const std::string& name) {
  const FormatInfo& f = format_info(parse_texel_format(name));
  py::dict d;
  d["name"] = f.name;
  d["block_width"] = f.block_width;
  d["block_height"] = f.block_height;
  d["block_bytes"] = f.block_bytes;
  d["channels"] = f.channels;
  d["srgb"] = f.srgb;
  d["snorm"] = f.snorm;
  d["is_float"] = f.is_float;
  d["compressed"] = f.compressed;
  d["vk_format"] = f.vk_format;
  d["dxgi_format"] = f.dxgi_format;
  return d;
}

void bind_texture_class(py::module_& m) {
  py::class_<Texture, TexturePtr>(m, "Texture",
                                  "A GPU texture: levels, cube faces and array layers of texel or block bytes.")
      .def_property_readonly("format", [](const Texture& t) { return std::string(format_info(t.format).name); })
      .def_readonly("width", &Texture::width)
      .def_readonly("height", &Texture::height)
      .def_readonly("levels", &Texture::levels)
      .def_readonly("faces", &Texture::faces)
      .def_readonly("layers", &Texture::layers)
      .def_readonly("is_array", &Texture::is_array)
      .def(
          "level_size",
          [](const Texture& t, std::uint32_t level) {
            check_index(t, level, 0, 0);
            return py::make_tuple(t.level_width(level), t.level_height(level));
          },
          py::arg("level"), "(width, height) of a level.")
      .def("image", &image_bytes_view, py::arg("level") = 0, py::arg("layer") = 0, py::arg("face") = 0,
           "The stored bytes of one image (read-only uint8 array; it keeps the texture alive).")
      .def("decode", &decode, py::arg("level") = 0, py::arg("layer") = 0, py::arg("face") = 0,
           py::arg("dtype") = "uint8",
           "One image decoded to an array (block formats decoded; SNORM stored as (v + 1) / 2 in integer dtypes).")
      .def("to_bytes", &to_bytes, py::arg("container") = "ktx2", py::kw_only(), py::arg("zstd") = 0,
           py::arg("dds_header") = "auto",
           "The texture as a file's bytes: 'dds', 'ktx2', 'ktx', 'pkm', 'astc'. zstd: KTX2 Zstandard level 1-22.")
      .def(
          "save",
          [](const Texture& t, const std::string& path, int zstd, const std::string& dds_header) {
            check_zstd(zstd);
            py::gil_scoped_release release;
            write_texture(path, t, parse_dds_header(dds_header), zstd);
          },
          py::arg("path"), py::kw_only(), py::arg("zstd") = 0, py::arg("dds_header") = "auto",
          "Writes the texture atomically; the container follows the extension.")
      .def_static("from_bytes", &from_bytes, py::arg("data"), py::arg("name") = "<bytes>",
                  "A texture from a DDS, KTX2, KTX1, PKM or .astc file's bytes (found by signature).")
      .def_static(
          "from_levels",
          [](const py::list& levels, bool srgb, bool half) {
            return from_surfaces(py::list(py::make_tuple(levels)), 1, false, srgb, half);
          },
          py::arg("levels"), py::kw_only(), py::arg("srgb") = false, py::arg("half") = false,
          "An uncompressed texture from a mip chain (r8/rg8/rgba8, r16/rg16/rgba16, rgba16_float with half, "
          "rgba32_float).")
      .def_static("from_surfaces", &from_surfaces, py::arg("chains"), py::kw_only(), py::arg("faces") = 1,
                  py::arg("is_array") = false, py::arg("srgb") = false, py::arg("half") = false,
                  "Cube maps and arrays: one mip chain per surface (index layer * faces + face).")
      .def("__repr__", [](const Texture& t) {
        return "<texproc.Texture " + std::string(format_info(t.format).name) + " " + std::to_string(t.width) + "x" +
               std::to_string(t.height) + ", " + std::to_string(t.levels) + " levels, " + std::to_string(t.faces) +
               " faces, " + std::to_string(t.layers) + " layers>";
      });
}

}  // namespace

void bind_textures(py::module_& m) {
  bind_texture_class(m);
  m.def(
      "read_texture",
      [](const std::string& path) {
        py::gil_scoped_release release;
        return std::make_shared<Texture>(read_texture(path, read_options().limits));
      },
      py::arg("path"), "Reads a DDS, KTX2, KTX1, PKM or .astc file.");
  m.def("compress", &compress, py::arg("image"), py::arg("format"), py::kw_only(), py::arg("quality") = "normal",
        py::arg("mips") = false, py::arg("faces") = 1, py::arg("is_array") = false, py::arg("color_space") = "",
        py::arg("normal_map") = false, py::arg("transparent_color") = "keep", py::arg("bc1_black") = false,
        py::arg("astc_effort") = py::none(), py::arg("filter") = "gaussian", py::arg("sigma") = 0.5f,
        py::arg("wrap") = "clamp", py::arg("alpha_coverage") = py::none(), py::arg("premultiplied_alpha") = true,
        py::arg("max_levels") = 0, py::arg("min_size") = 1,
        "Block-compresses an image (or a list of surfaces: cube faces, array layers) to a Texture. format: a "
        "full name from format_names() ('bc7_srgb', 'bc5_unorm', 'astc_6x6_srgb', ...): sRGB formats filter "
        "mips as sRGB colour, the others as data. mips: the whole chain (filter, sigma, wrap, alpha_coverage, "
        "premultiplied_alpha, max_levels, min_size as generate_mips). The same bytes as `texproc compress`.");
  m.def("format_names", &texel_format_names, "Every texel format's name.");
  m.def("format_info", &format_dict, py::arg("format"), "What a format is, as a dict.");
}

}  // namespace texproc::py_binding
