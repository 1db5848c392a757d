// Image files, mip chains and comparisons.
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/metrics.h"
#include "texproc/mip.h"

namespace texproc::py_binding {

MipOptions mip_options(const std::string& filter, float sigma, const std::string& wrap,
                       std::optional<float> alpha_coverage, bool premultiplied_alpha, bool normal_map, int max_levels,
                       int min_size) {
  MipOptions o;
  o.filter.kind = parse_filter_kind(filter);
  if (!(sigma > 0.0f && sigma <= 4.0f)) {
    throw Error(ErrorCode::bad_arguments, "sigma " + std::to_string(sigma) + " is outside (0, 4]");
  }
  o.filter.sigma = sigma;
  o.wrap = parse_wrap_mode(wrap);
  if (alpha_coverage) {
    if (!(*alpha_coverage > 0.0f && *alpha_coverage <= 1.0f)) {
      throw Error(ErrorCode::bad_arguments, "alpha_coverage " + std::to_string(*alpha_coverage) + " is outside (0, 1]");
    }
    o.alpha_coverage_ref = *alpha_coverage;
  }
  o.premultiplied_alpha = premultiplied_alpha;
  o.normal_map = normal_map;
  if (max_levels < 0) throw Error(ErrorCode::bad_arguments, "max_levels must be 0 (all) or more");
  o.max_levels = max_levels;
  o.min_size = min_size;
  return o;
}

const ReadOptions& read_options() {
  static const ReadOptions options = ReadOptions::from_environment();
  return options;
}

namespace {

py::dict file_info_dict(const ImageFileInfo& i) {
  py::dict d;
  d["format"] = i.format;
  d["width"] = i.width;
  d["height"] = i.height;
  d["channels"] = i.channels;
  d["file_type"] = i.file_type;
  d["dtype"] = dtype_name(i.type);
  d["color_space"] = i.color_space_tag;
  d["color_space_tagged"] = i.color_space_tagged;
  d["subimages"] = i.subimages;
  d["mip_levels"] = i.mip_levels;
  d["level_sizes"] = i.level_sizes;
  return d;
}

py::array read(const std::string& path) {
  Image image;
  {
    py::gil_scoped_release release;
    image = read_image(path, nullptr, read_options());
  }
  return to_array(std::move(image));
}

void write(const std::string& path, const py::handle& array, bool half, const std::string& compression,
           const std::string& color_space, int quality, bool red_green) {
  const InputImage in(array, "image");
  WriteOptions o;
  o.io_path = read_options().io_path;
  o.half = half;
  o.compression = compression;
  o.color_space = color_space;
  if (quality < 1 || quality > 100) throw Error(ErrorCode::bad_arguments, "quality must be 1 to 100");
  o.quality = quality;
  o.red_green = red_green;
  py::gil_scoped_release release;
  write_image(path, in.view(), o);
}

py::list mips(const py::handle& array, const std::string& filter, float sigma, const std::string& wrap,
              const std::string& color_space, const std::string& output_color_space, const py::handle& dtype,
              bool premultiplied_alpha, std::optional<float> alpha_coverage, bool normal_map, int max_levels,
              int min_size) {
  const InputImage in(array, "image");
  MipOptions o =
      mip_options(filter, sigma, wrap, alpha_coverage, premultiplied_alpha, normal_map, max_levels, min_size);
  o.color_space = color_space;
  o.output_color_space = output_color_space;
  o.output_type = parse_optional_dtype(dtype);
  MipChain chain;
  {
    py::gil_scoped_release release;
    chain = generate_mips(in.view(), o);
  }
  py::list levels;
  for (Image& level : chain.levels) levels.append(to_array(std::move(level)));
  return levels;
}

ImageDifference compare(const py::handle& a, const py::handle& b) {
  const InputImage ia(a, "a"), ib(b, "b");
  py::gil_scoped_release release;
  return compare_images(ia.view(), ib.view());
}

std::vector<double> ssim(const py::handle& a, const py::handle& b) {
  const InputImage ia(a, "a"), ib(b, "b");
  py::gil_scoped_release release;
  return ssim_per_channel(ia.view(), ib.view());
}

void bind_difference(py::module_& m) {
  py::class_<ImageDifference>(m, "Difference",
                              "How far two images are apart, on a [0, 1] scale (8-bit codes / 255, 16-bit / 65535, "
                              "floats as they are).")
      .def_readonly("width", &ImageDifference::width)
      .def_readonly("height", &ImageDifference::height)
      .def_readonly("channels", &ImageDifference::channels)
      .def_readonly("mse", &ImageDifference::mse, "Mean squared difference over every channel.")
      .def_readonly("mse_rgb", &ImageDifference::mse_rgb, "Over the first min(3, channels) channels.")
      .def_readonly("max_abs", &ImageDifference::max_abs, "Largest absolute difference.")
      .def_readonly("differing_texels", &ImageDifference::differing_texels,
                    "Texels where any channel differs by more than 1e-6.")
      .def_readonly("nonfinite_texels", &ImageDifference::nonfinite_texels,
                    "Texels holding NaN or an infinity in either image (each one makes mse NaN).")
      .def_readonly("hdr", &ImageDifference::hdr)
      .def_property_readonly("psnr", &ImageDifference::psnr, "10 log10(1 / mse); inf for identical images.")
      .def_property_readonly("psnr_rgb", &ImageDifference::psnr_rgb)
      .def_property_readonly("log_rmse_rgb", &ImageDifference::log_rmse_rgb,
                             "HDR: RMS difference of sign(v) log2(1 + |v|) over RGB.")
      .def("psnr_channel", &ImageDifference::psnr_channel, py::arg("channel"))
      .def_property_readonly("channel_mse",
                             [](const ImageDifference& d) {
                               std::vector<double> v;
                               for (const auto& c : d.channel) v.push_back(c.mse);
                               return v;
                             })
      .def_property_readonly("channel_max_abs",
                             [](const ImageDifference& d) {
                               std::vector<double> v;
                               for (const auto& c : d.channel) v.push_back(c.max_abs);
                               return v;
                             })
      .def("__repr__", [](const ImageDifference& d) {
        return "<texproc.Difference " + std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
               std::to_string(d.channels) + " psnr=" + std::to_string(d.psnr()) +
               " differing_texels=" + std::to_string(d.differing_texels) + ">";
      });
}

}  // namespace

void bind_images(py::module_& m) {
  m.def("read_image", &read, py::arg("path"),
        "Reads an image file (PNG, JPEG, TGA, TIFF, OpenEXR, DDS/KTX2/KTX1/PKM/.astc level 0 decoded, and what "
        "OpenImageIO reads) as an array: height x width x channels of uint8, uint16 or float32.");
  m.def(
      "probe_image", [](const std::string& path) { return file_info_dict(probe_image(path, read_options())); },
      py::arg("path"), "Header facts of an image file without reading its pixels, as a dict.");
  m.def("write_image", &write, py::arg("path"), py::arg("image"), py::kw_only(), py::arg("half") = false,
        py::arg("compression") = "", py::arg("color_space") = "", py::arg("quality") = 95, py::arg("red_green") = false,
        "Writes an image atomically; the format follows the extension. half: float32 stored as 16-bit halves "
        "(EXR, TIFF). compression: PNG zip:N, TIFF none/zip/lzw/packbits, EXR none/rle/zips/zip/piz/... "
        "color_space: 'srgb' or 'linear' to tag. quality: JPEG. red_green: two channels are RG, not grey+alpha.");
  m.def("generate_mips", &mips, py::arg("image"), py::kw_only(), py::arg("filter") = "gaussian",
        py::arg("sigma") = 0.5f, py::arg("wrap") = "clamp", py::arg("color_space") = "",
        py::arg("output_color_space") = "", py::arg("dtype") = py::none(), py::arg("premultiplied_alpha") = true,
        py::arg("alpha_coverage") = py::none(), py::arg("normal_map") = false, py::arg("max_levels") = 0,
        py::arg("min_size") = 1,
        "A gamma-correct mip chain, level 0 first, each level filtered from the previous one in linear, "
        "premultiplied float. color_space: the source's ('' : sRGB for uint8/uint16, linear for float32; any "
        "OpenColorIO name). alpha_coverage: keep the fraction of texels with alpha >= it. normal_map: filter "
        "the vectors and renormalise. The same bytes as `texproc mip`.");
  bind_difference(m);
  m.def("compare", &compare, py::arg("a"), py::arg("b"),
        "Compares two images of the same size and channel count (types may differ).");
  m.def("ssim", &ssim, py::arg("a"), py::arg("b"), "Mean structural similarity per channel.");
}

}  // namespace texproc::py_binding
