// The parts of texproc's Python extension, one per binding file.
#pragma once

#include <pybind11/pybind11.h>

namespace texproc::py_binding {

namespace py = pybind11;

void bind_images(py::module_& m);    // bind_images.cpp: image files, mip chains, comparisons
void bind_textures(py::module_& m);  // bind_textures.cpp: textures, containers, block compression
void bind_maps(py::module_& m);      // bind_maps.cpp: normal maps, cone maps, summed-area tables
void bind_cubemaps(py::module_& m);  // bind_cubemaps.cpp: cube maps and image-based lighting

}  // namespace texproc::py_binding

#include <optional>
#include <string>

#include "texproc/image_io.h"
#include "texproc/mip.h"

namespace texproc::py_binding {

// The mip options generate_mips and compress share, checked.
MipOptions mip_options(const std::string& filter, float sigma, const std::string& wrap,
                       std::optional<float> alpha_coverage, bool premultiplied_alpha, bool normal_map, int max_levels,
                       int min_size);

// How the package reads files: as the texproc tool does
// (ReadOptions::from_environment(), read once).
const ReadOptions& read_options();

}  // namespace texproc::py_binding
