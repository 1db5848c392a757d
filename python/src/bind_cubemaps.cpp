// Cube maps and image-based lighting. A Cubemap is immutable: each operation
// returns a new one, so arrays viewing its faces stay valid.
#include <pybind11/stl.h>

#include <memory>

#include "arrays.h"
#include "bindings.h"
#include "texproc/color.h"
#include "texproc/cubemap.h"
#include "texproc/error.h"
#include "texproc/texture.h"

namespace texproc::py_binding {
namespace {

using CubePtr = std::shared_ptr<Cubemap>;  // never changed after it is made

CubePtr own(Cubemap&& c) { return std::make_shared<Cubemap>(std::move(c)); }

ColorSpace space_for(const std::string& color_space, PixelType type) {
  if (color_space.empty()) return type == PixelType::f32 ? ColorSpace::linear() : ColorSpace::srgb();
  return ColorSpace::from_name(color_space);
}

Image linear_rgba(const py::handle& image, const std::string& color_space, const char* arg) {
  const InputImage in(image, arg);
  const ColorSpace space = space_for(color_space, in.view().type);
  py::gil_scoped_release release;
  return to_linear_rgba(in.view(), space);
}

const Image& face_of(const Cubemap& c, int face, int level) {
  if (face < 0 || face > 5) throw Error(ErrorCode::bad_arguments, "face must be 0 to 5 (+X, -X, +Y, -Y, +Z, -Z)");
  if (level < 0 || level >= int(c.levels.size())) {
    throw Error(ErrorCode::bad_arguments, "level " + std::to_string(level) + " is outside the cube's " +
                                              std::to_string(c.levels.size()) + " levels");
  }
  return c.levels[std::size_t(level)].faces[std::size_t(face)];
}

py::array face_view(const py::object& self, int face, int level) {
  const Image& f = face_of(*self.cast<CubePtr>(), face, level);
  py::array view(py::dtype::of<float>(), {py::ssize_t(f.height()), py::ssize_t(f.width()), py::ssize_t(4)},
                 {py::ssize_t(f.row_stride()), py::ssize_t(16), py::ssize_t(4)}, f.data(), self);
  view.attr("flags").attr("writeable") = false;
  return view;
}

std::shared_ptr<Texture> to_texture(const Cubemap& c, const std::string& dtype) {
  if (dtype != "float16" && dtype != "float32" && dtype != "uint8") {
    throw Error(ErrorCode::bad_arguments, "dtype '" + dtype + "' (valid: float16, float32, uint8 (sRGB))");
  }
  const bool eight_bit = dtype == "uint8";
  py::gil_scoped_release release;
  std::vector<std::vector<Image>> chains(6);
  for (const CubeLevel& l : c.levels) {
    for (int f = 0; f < 6; ++f) {
      chains[std::size_t(f)].push_back(
          eight_bit ? from_linear_rgba(l.faces[std::size_t(f)].view(), ColorSpace::srgb(), 4, PixelType::u8)
                    : from_linear_rgba(l.faces[std::size_t(f)].view(), ColorSpace::linear(), 4, PixelType::f32));
    }
  }
  return std::make_shared<Texture>(
      texture_from_surfaces(std::move(chains), {.faces = 6}, {.srgb = eight_bit, .half = dtype == "float16"}));
}

void bind_cubemap_class(py::module_& m) {
  py::class_<Cubemap, CubePtr>(m, "Cubemap",
                               "A cube map: levels of six faces, RGBA float32, linear, alpha premultiplied "
                               "(+X, -X, +Y, -Y, +Z, -Z).")
      .def_property_readonly("size", &Cubemap::size)
      .def_property_readonly("levels", [](const Cubemap& c) { return c.levels.size(); })
      .def("face", &face_view, py::arg("face"), py::arg("level") = 0,
           "One face as a read-only float32 array (it keeps the cube alive).")
      .def_static(
          "from_equirect",
          [](const py::handle& panorama, int size, const std::string& flip, const std::string& color_space) {
            Image rgba = linear_rgba(panorama, color_space, "panorama");
            const CubeFlip f = parse_cube_flip(flip);
            py::gil_scoped_release release;
            return own(cubemap_from_equirect(rgba.view(), size > 0 ? size : default_cube_size(rgba.width()), f));
          },
          py::arg("panorama"), py::kw_only(), py::arg("size") = 0, py::arg("flip") = "none",
          py::arg("color_space") = "", "From a 2:1 latitude-longitude panorama (size 0: from its width).")
      .def_static(
          "from_faces",
          [](const py::list& faces, const std::string& color_space) {
            if (faces.size() != 6) throw Error(ErrorCode::bad_arguments, "faces: want 6 images");
            std::vector<Image> rgba;
            for (const py::handle& f : faces) rgba.push_back(linear_rgba(f, color_space, "faces"));
            py::gil_scoped_release release;
            return own(cubemap_from_images(rgba));
          },
          py::arg("faces"), py::kw_only(), py::arg("color_space") = "", "From six square faces.")
      .def_static(
          "from_layout",
          [](const py::handle& image, const std::string& layout, const std::string& color_space) {
            Image rgba = linear_rgba(image, color_space, "image");
            const CubeLayout l =
                layout == "auto" ? detect_cube_layout(rgba.width(), rgba.height()) : parse_cube_layout(layout);
            py::gil_scoped_release release;
            return own(l == CubeLayout::equirect ? cubemap_from_equirect(rgba.view(), default_cube_size(rgba.width()))
                                                 : cubemap_from_layout(rgba.view(), l));
          },
          py::arg("image"), py::arg("layout") = "auto", py::kw_only(), py::arg("color_space") = "",
          "From a cross, strip or panorama image (layout 'auto' tells by the aspect ratio).")
      .def(
          "with_mips",
          [](const Cubemap& c, int max_levels) {
            py::gil_scoped_release release;
            Cubemap copy = c;
            copy.levels.resize(1);
            generate_cube_mips(copy, max_levels);
            return own(std::move(copy));
          },
          py::arg("max_levels") = 0, "A copy with a filtered mip chain from level 0.")
      .def(
          "to_equirect",
          [](const Cubemap& c, int width, int level) {
            face_of(c, 0, level);
            Image out;
            {
              py::gil_scoped_release release;
              out = cubemap_to_equirect(c, width, level);
            }
            return to_array(std::move(out));
          },
          py::arg("width"), py::arg("level") = 0, "A width x width/2 RGBA float32 panorama of a level.")
      .def(
          "to_layout",
          [](const Cubemap& c, const std::string& layout, int level) {
            face_of(c, 0, level);
            const CubeLayout l = parse_cube_layout(layout);
            Image out;
            {
              py::gil_scoped_release release;
              out = cubemap_to_layout(c, l, level);
            }
            return to_array(std::move(out));
          },
          py::arg("layout"), py::arg("level") = 0, "A cross or strip image of a level.")
      .def("to_texture", &to_texture, py::arg("dtype") = "float16",
           "An uncompressed cube texture of every level: float16 (rgba16_float), float32, or uint8 (rgba8_srgb).");
}

}  // namespace

void bind_cubemaps(py::module_& m) {
  bind_cubemap_class(m);
  m.def(
      "prefilter_specular",
      [](const Cubemap& source, int size, int levels, int min_size, int samples, double exact_budget) {
        SpecularOptions o;
        o.size = size;
        o.levels = levels;
        o.min_size = min_size;
        o.samples = samples;
        o.exact_budget = exact_budget;
        py::gil_scoped_release release;
        return own(prefilter_specular(source, o));
      },
      py::arg("source"), py::kw_only(), py::arg("size") = 0, py::arg("levels") = 0, py::arg("min_size") = 8,
      py::arg("samples") = 512, py::arg("exact_budget") = 1.0e9,
      "The GGX specular chain of an environment: level k for roughness k / (levels - 1).");
  m.def(
      "irradiance",
      [](const Cubemap& source, int size) {
        py::gil_scoped_release release;
        return own(irradiance_cubemap(source, size));
      },
      py::arg("source"), py::kw_only(), py::arg("size") = 32, "The diffuse irradiance (divided by pi) cube.");
  m.def(
      "sh9",
      [](const Cubemap& source) {
        SphericalHarmonics9 sh;
        {
          py::gil_scoped_release release;
          sh = project_sh9(source);
        }
        py::array_t<double> out({9, 3});
        for (int i = 0; i < 9; ++i)
          for (int c = 0; c < 3; ++c) out.mutable_at(i, c) = sh.radiance[std::size_t(i)][std::size_t(c)];
        return out;
      },
      py::arg("source"), "Nine spherical-harmonic radiance coefficients (9 x 3: L00, L1-1, L10, L11, L2-2...).");
}

}  // namespace texproc::py_binding
