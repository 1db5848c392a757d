// Normal maps, cone maps, summed-area tables and the box blur.
#include <pybind11/stl.h>

#include <memory>

#include "arrays.h"
#include "bindings.h"
#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/normalmap.h"
#include "texproc/sat.h"

namespace texproc::py_binding {
namespace {

// uint8 heights give uint8 maps, the rest uint16 (as the CLI).
PixelType map_type(const py::handle& dtype, PixelType input) {
  if (const auto t = parse_optional_dtype(dtype)) return *t;
  return input == PixelType::u8 ? PixelType::u8 : PixelType::u16;
}

py::array normal(const py::handle& heights, const std::string& kernel, const std::string& height_channel, bool invert,
                 float height_scale, float strength, const std::string& wrap, bool y_up, const std::string& channels,
                 std::optional<std::vector<float>> multiscale_weights, const py::handle& dtype) {
  const InputImage in(heights, "heights");
  NormalMapOptions o;
  o.kernel = parse_gradient_kernel(kernel);
  o.height_channel = parse_height_channel(height_channel);
  o.invert = invert;
  o.height_scale = height_scale;
  o.strength = strength;
  o.wrap = parse_wrap_mode(wrap);
  o.y_up = y_up;
  o.channels = parse_normal_channels(channels);
  if (multiscale_weights) o.multiscale_weights = *multiscale_weights;
  const PixelType type = map_type(dtype, in.view().type);
  Image out;
  {
    py::gil_scoped_release release;
    out = normal_map(in.view(), o, type);
  }
  return to_array(std::move(out));
}

ConeMapOptions cone_options(float depth, float max_ratio, const std::string& wrap, int fast_reach,
                            const std::string& mode, bool bilinear_safe) {
  ConeMapOptions o;
  o.depth = depth;
  o.max_ratio = max_ratio;
  o.wrap = parse_wrap_mode(wrap);
  if (fast_reach < 0) throw Error(ErrorCode::bad_arguments, "fast_reach must be 0 (exact) or more");
  o.fast_reach = fast_reach;
  if (mode != "conservative" && mode != "relaxed") {
    throw Error(ErrorCode::bad_arguments, "unknown mode '" + mode + "' (valid: conservative, relaxed)");
  }
  o.mode = mode == "relaxed" ? ConeMode::relaxed : ConeMode::conservative;
  o.bilinear_safe = bilinear_safe;
  return o;
}

std::vector<float> heights_of(const InputImage& in, const std::string& height_channel, bool invert) {
  return extract_height(in.view(), parse_height_channel(height_channel), invert);
}

py::array cone_map(const py::handle& heights, float depth, float max_ratio, const std::string& wrap, int fast_reach,
                   const std::string& mode, bool bilinear_safe, const std::string& height_channel, bool invert,
                   int channels, const py::handle& dtype) {
  const InputImage in(heights, "heights");
  const ConeMapOptions o = cone_options(depth, max_ratio, wrap, fast_reach, mode, bilinear_safe);
  if (channels < 2 || channels > 4) throw Error(ErrorCode::bad_arguments, "channels must be 2, 3 or 4");
  const PixelType type = map_type(dtype, in.view().type);
  const int w = in.view().width, h = in.view().height;
  Image out;
  {
    py::gil_scoped_release release;
    const std::vector<float> hs = heights_of(in, height_channel, invert);
    out = cone_map_image(hs, cone_ratios(hs, w, h, o), w, h, o, type, channels);
  }
  return to_array(std::move(out));
}

py::array ratios(const py::handle& heights, float depth, float max_ratio, const std::string& wrap, int fast_reach,
                 const std::string& mode, bool bilinear_safe, const std::string& height_channel, bool invert) {
  const InputImage in(heights, "heights");
  const ConeMapOptions o = cone_options(depth, max_ratio, wrap, fast_reach, mode, bilinear_safe);
  const int w = in.view().width, h = in.view().height;
  std::vector<float> r;
  {
    py::gil_scoped_release release;
    r = cone_ratios(heights_of(in, height_channel, invert), w, h, o);
  }
  return to_array(std::move(r), {h, w});
}

using SatPtr = std::shared_ptr<SummedAreaTable>;

SatPtr build(const py::handle& image, const std::string& precision) {
  const InputImage in(image, "image");
  const ConstImageView& v = in.view();
  const SatPrecision p =
      precision.empty() ? default_sat_precision(v.type, v.width, v.height) : parse_sat_precision(precision);
  py::gil_scoped_release release;
  return std::make_shared<SummedAreaTable>(build_sat(v, p));
}

void check_box(const SummedAreaTable& t, long long x0, long long y0, long long x1, long long y1) {
  if (!(0 <= x0 && x0 <= x1 && x1 <= t.width && 0 <= y0 && y0 <= y1 && y1 <= t.height)) {
    throw Error(ErrorCode::bad_arguments, "box [" + std::to_string(x0) + ", " + std::to_string(x1) + ") x [" +
                                              std::to_string(y0) + ", " + std::to_string(y1) + ") is not inside the " +
                                              std::to_string(t.width) + "x" + std::to_string(t.height) + " table");
  }
}

// box_sum of each row (x0, y0, x1, y1) of an N x 4 integer array.
py::array box_sums(const SummedAreaTable& t,
                   const py::array_t<long long, py::array::c_style | py::array::forcecast>& boxes) {
  if (boxes.ndim() != 2 || boxes.shape(1) != 4) throw Error(ErrorCode::bad_arguments, "boxes: want an N x 4 array");
  const py::ssize_t n = boxes.shape(0);
  auto b = boxes.unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) check_box(t, b(i, 0), b(i, 1), b(i, 2), b(i, 3));
  py::array_t<double> out({n, py::ssize_t(t.channels)});
  double* o = out.mutable_data();
  const long long* p = boxes.data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t i = 0; i < n; ++i) {
      t.box_sum(int(p[4 * i]), int(p[4 * i + 1]), int(p[4 * i + 2]), int(p[4 * i + 3]), o + i * t.channels);
    }
  }
  return out;
}

void bind_sat(py::module_& m) {
  py::class_<SummedAreaTable, SatPtr>(m, "SummedAreaTable",
                                      "Inclusive prefix sums of every channel, for box sums at constant cost.")
      .def_readonly("width", &SummedAreaTable::width)
      .def_readonly("height", &SummedAreaTable::height)
      .def_readonly("channels", &SummedAreaTable::channels)
      .def_property_readonly("precision", [](const SummedAreaTable& t) { return std::string(to_string(t.precision)); })
      .def_property_readonly("max_exact_box", &SummedAreaTable::max_exact_box,
                             "The largest box (texels) summed exactly; 0: no promise (see error_bound).")
      .def("error_bound", &SummedAreaTable::error_bound, "An upper bound on |box_sum - true sum| for any box.")
      .def(
          "box_sum",
          [](const SummedAreaTable& t, int x0, int y0, int x1, int y1) {
            check_box(t, x0, y0, x1, y1);
            std::vector<double> out(std::size_t(t.channels));
            t.box_sum(x0, y0, x1, y1, out.data());
            return out;
          },
          py::arg("x0"), py::arg("y0"), py::arg("x1"), py::arg("y1"),
          "The sum over [x0, x1) x [y0, y1) of each channel.")
      .def("box_sums", &box_sums, py::arg("boxes"), "box_sum of each row (x0, y0, x1, y1) of an N x 4 array.")
      .def(
          "save",
          [](const SummedAreaTable& t, const std::string& path) {
            py::gil_scoped_release release;
            write_sat_file(path, t);
          },
          py::arg("path"), "Writes a .sat file (docs/sat.md) atomically.");
  m.def("build_sat", &build, py::arg("image"), py::kw_only(), py::arg("precision") = "",
        "A summed-area table: precision u32, u64, f32 or f64 ('' : the smallest exact one).");
  m.def(
      "read_sat",
      [](const std::string& path) {
        py::gil_scoped_release release;
        return std::make_shared<SummedAreaTable>(read_sat_file(path));
      },
      py::arg("path"), "Reads a .sat file.");
  m.def(
      "box_blur",
      [](const py::handle& image, float radius, const py::handle& radius_map, const std::string& wrap,
         const std::string& color_space) {
        const InputImage in(image, "image");
        std::optional<InputImage> map;
        if (!radius_map.is_none()) map.emplace(radius_map, "radius_map");
        BoxBlurOptions o;
        o.radius = radius;
        if (map) o.radius_map = &map->view();
        o.wrap = parse_wrap_mode(wrap);
        o.color_space = color_space;
        Image out;
        {
          py::gil_scoped_release release;
          out = box_blur(in.view(), o);
        }
        return to_array(std::move(out));
      },
      py::arg("image"), py::kw_only(), py::arg("radius") = 4.0f, py::arg("radius_map") = py::none(),
      py::arg("wrap") = "clamp", py::arg("color_space") = "",
      "A box blur of half-width radius at constant cost per texel (radius_map: per-texel factor in [0, 1]).");
}

}  // namespace

void bind_maps(py::module_& m) {
  m.def("normal_map", &normal, py::arg("heights"), py::kw_only(), py::arg("kernel") = "sobel3",
        py::arg("height_channel") = "auto", py::arg("invert") = false, py::arg("height_scale") = 8.0f,
        py::arg("strength") = 1.0f, py::arg("wrap") = "clamp", py::arg("y_up") = true, py::arg("channels") = "xyz",
        py::arg("multiscale_weights") = py::none(), py::arg("dtype") = py::none(),
        "A tangent-space normal map of a height field (heights as data in [0, 1]). height_scale: texels a "
        "height of 1 spans. channels: 'xyz', 'xy' or 'xyzh'. dtype: uint8 for uint8 heights, else uint16. "
        "The same bytes as `texproc normalmap`.");
  m.def("cone_map", &cone_map, py::arg("heights"), py::kw_only(), py::arg("depth") = 1.0f, py::arg("max_ratio") = 1.0f,
        py::arg("wrap") = "repeat", py::arg("fast_reach") = 0, py::arg("mode") = "conservative",
        py::arg("bilinear_safe") = false, py::arg("height_channel") = "auto", py::arg("invert") = false,
        py::arg("channels") = 3, py::arg("dtype") = py::none(),
        "A cone step map: R the height, G sqrt(ratio / max_ratio). fast_reach 0 is exact; 2 is `--fast`. "
        "The same bytes as `texproc conemap`.");
  m.def("cone_ratios", &ratios, py::arg("heights"), py::kw_only(), py::arg("depth") = 1.0f, py::arg("max_ratio") = 1.0f,
        py::arg("wrap") = "repeat", py::arg("fast_reach") = 0, py::arg("mode") = "conservative",
        py::arg("bilinear_safe") = false, py::arg("height_channel") = "auto", py::arg("invert") = false,
        "Each texel's cone ratio (float32, height x width).");
  bind_sat(m);
}

}  // namespace texproc::py_binding
