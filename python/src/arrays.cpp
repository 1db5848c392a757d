#include "arrays.h"

#include <memory>
#include <utility>

#include "texproc/error.h"

namespace texproc::py_binding {
namespace {

std::optional<PixelType> type_of(const py::dtype& d) {
  if (d.is(py::dtype::of<std::uint8_t>())) return PixelType::u8;
  if (d.is(py::dtype::of<std::uint16_t>())) return PixelType::u16;
  if (d.is(py::dtype::of<float>())) return PixelType::f32;
  // Equal but distinct dtype objects (byte order given explicitly, ...).
  if (d.kind() == 'u' && d.itemsize() == 1) return PixelType::u8;
  if (d.kind() == 'u' && d.itemsize() == 2 && d.attr("isnative").cast<bool>()) return PixelType::u16;
  if (d.kind() == 'f' && d.itemsize() == 4 && d.attr("isnative").cast<bool>()) return PixelType::f32;
  return std::nullopt;
}

// Rows of dense pixels, rows in increasing memory: what ImageView can point at.
bool viewable(const py::array& a) {
  const py::ssize_t item = a.itemsize();
  const py::ssize_t channels = a.ndim() == 3 ? a.shape(2) : 1;
  if (a.ndim() == 3 && a.strides(2) != item) return false;
  if (a.strides(1) != channels * item) return false;
  return a.strides(0) >= a.shape(1) * channels * item;
}

}  // namespace

InputImage::InputImage(const py::handle& object, const char* arg) {
  py::array a = py::array::ensure(object);
  if (!a) throw Error(ErrorCode::bad_arguments, std::string(arg) + ": not an array");
  const auto type = type_of(a.dtype());
  if (!type) {
    throw Error(ErrorCode::bad_arguments, std::string(arg) + ": dtype " + py::str(a.dtype()).cast<std::string>() +
                                              " is not one texproc takes (uint8, uint16, float32; convert with "
                                              ".astype(numpy.float32))");
  }
  if (a.ndim() != 2 && a.ndim() != 3) {
    throw Error(ErrorCode::bad_arguments, std::string(arg) + ": " + std::to_string(a.ndim()) +
                                              " dimensions (want height x width x channels, or height x width)");
  }
  const py::ssize_t channels = a.ndim() == 3 ? a.shape(2) : 1;
  if (channels < 1 || channels > 4 || a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > (1 << 30) ||
      a.shape(1) > (1 << 30)) {
    throw Error(ErrorCode::bad_arguments, std::string(arg) + ": shape (" + std::to_string(a.shape(0)) + ", " +
                                              std::to_string(a.shape(1)) + ", " + std::to_string(channels) +
                                              ") is not an image of 1 to 4 channels");
  }
  if (!viewable(a)) a = py::array::ensure(a, py::array::c_style | py::array::forcecast);
  array_ = a;
  view_.data = array_.data();
  view_.width = int(a.shape(1));
  view_.height = int(a.shape(0));
  view_.channels = int(channels);
  view_.type = *type;
  view_.row_stride = std::size_t(a.strides(0));
}

py::array to_array(Image&& image) {
  auto* owned = new Image(std::move(image));
  py::capsule owner(owned, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t item = py::ssize_t(bytes_per_channel(owned->type()));
  const std::vector<py::ssize_t> shape = {owned->height(), owned->width(), owned->channels()};
  const std::vector<py::ssize_t> strides = {py::ssize_t(owned->row_stride()), owned->channels() * item, item};
  switch (owned->type()) {
    case PixelType::u8:
      return py::array(py::dtype::of<std::uint8_t>(), shape, strides, owned->data(), owner);
    case PixelType::u16:
      return py::array(py::dtype::of<std::uint16_t>(), shape, strides, owned->data(), owner);
    case PixelType::f32:
      return py::array(py::dtype::of<float>(), shape, strides, owned->data(), owner);
  }
  throw Error(ErrorCode::runtime, "unknown pixel type");
}

py::array to_array(std::vector<float>&& values, std::vector<py::ssize_t> shape) {
  auto* owned = new std::vector<float>(std::move(values));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  return py::array(py::dtype::of<float>(), std::move(shape), {}, owned->data(), owner);
}

PixelType parse_dtype(const py::handle& dtype) {
  if (py::isinstance<py::str>(dtype)) {
    const std::string name = dtype.cast<std::string>();
    if (name == "u8") return PixelType::u8;
    if (name == "u16") return PixelType::u16;
    if (name == "f32") return PixelType::f32;
  }
  try {
    if (const auto t = type_of(py::dtype::from_args(py::reinterpret_borrow<py::object>(dtype)))) return *t;
  } catch (const py::error_already_set&) {
  }
  throw Error(ErrorCode::bad_arguments,
              "dtype " + py::str(dtype).cast<std::string>() + " is not one texproc writes (uint8, uint16, float32)");
}

std::optional<PixelType> parse_optional_dtype(const py::handle& dtype) {
  if (dtype.is_none()) return std::nullopt;
  return parse_dtype(dtype);
}

const char* dtype_name(PixelType type) {
  switch (type) {
    case PixelType::u8:
      return "uint8";
    case PixelType::u16:
      return "uint16";
    case PixelType::f32:
      return "float32";
  }
  return "?";
}

}  // namespace texproc::py_binding
