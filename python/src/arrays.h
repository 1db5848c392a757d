// NumPy arrays in and out of texproc images, and the small helpers every
// binding file shares.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "texproc/image.h"

namespace texproc::py_binding {

namespace py = pybind11;

// An input image: a NumPy array (or anything np.asarray takes) of uint8,
// uint16 or float32, H x W x C (C 1 to 4) or H x W (one channel). The view
// points into the array's memory where its rows are dense pixels (any row
// stride, C-ordered pixels); otherwise into a C-ordered copy held here.
// `arg` names the argument in error messages.
class InputImage {
 public:
  InputImage(const py::handle& object, const char* arg);
  const ConstImageView& view() const { return view_; }

 private:
  py::array array_;  // keeps the memory alive while the view is used
  ConstImageView view_;
};

// An Image handed to Python without a copy: the array owns it.
py::array to_array(Image&& image);

// A float32 array of `shape` that owns `values`.
py::array to_array(std::vector<float>&& values, std::vector<py::ssize_t> shape);

// "uint8", "uint16", "float32" (also NumPy dtypes and "u8", "u16", "f32").
PixelType parse_dtype(const py::handle& dtype);
std::optional<PixelType> parse_optional_dtype(const py::handle& dtype);
const char* dtype_name(PixelType type);

}  // namespace texproc::py_binding
