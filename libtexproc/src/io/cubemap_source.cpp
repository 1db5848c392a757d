// read_cubemap and read_cubemap_faces (image_io.h): a cube map's source
// files to linear RGBA floats, each decoded image dropped as soon as it is
// in floats, so that memory stays near the cube.
#include <string>
#include <utility>
#include <vector>

#include "texproc/cubemap.h"
#include "texproc/error.h"
#include "texproc/image_io.h"

namespace texproc {
namespace {

ColorSpace source_space(const CubemapReadOptions& o, PixelType type) {
  if (o.color_space) return *o.color_space;
  return type == PixelType::f32 ? ColorSpace::linear() : ColorSpace::srgb();
}

void read_finite(const std::string& path, Image& image, CubemapSource& s) {
  if (const std::size_t n = replace_non_finite(image)) {
    s.warnings.push_back(path + ": " + std::to_string(n) + " non-finite value(s) (NaN or infinity) read as 0");
  }
}

// Faces, crosses and cube textures take the flip and the size here (a
// panorama takes them while it is sampled).
void finish(const CubemapReadOptions& o, CubemapSource& s) {
  if (o.flip != CubeFlip::none) s.cube = flip_cubemap(s.cube, o.flip);
  if (o.size > 0 && o.size != s.cube.size()) s.cube = resize_cubemap(s.cube, o.size);
}

}  // namespace

CubemapSource read_cubemap_faces(const std::array<std::string, 6>& faces, const CubemapReadOptions& o) {
  CubemapSource s;
  std::array<Image, 6> linear;
  for (int f = 0; f < 6; ++f) {
    Image img = read_image(faces[f], nullptr, o.read);
    read_finite(faces[f], img, s);
    if (img.width() != img.height()) {
      throw Error(ErrorCode::bad_arguments, faces[f] + ": a face is square; this one is " +
                                                std::to_string(img.width()) + "x" + std::to_string(img.height()));
    }
    if (f > 0 && img.width() != linear[0].width()) {
      throw Error(ErrorCode::bad_arguments,
                  faces[f] + ": " + std::to_string(img.width()) + "x" + std::to_string(img.height()) + ", but " +
                      faces[0] + " (+X) is " + std::to_string(linear[0].width()) + "x" +
                      std::to_string(linear[0].height()) + ": the six faces must be one size");
    }
    if (f == 0) {
      s.hdr = img.type() == PixelType::f32;
      s.color_space = source_space(o, img.type());
    }
    s.alpha = s.alpha || img.channels() == 2 || img.channels() == 4;
    linear[f] = to_linear_rgba(img.view(), s.color_space);
    s.files.push_back(faces[f]);
  }
  std::array<ConstImageView, 6> views;
  for (int f = 0; f < 6; ++f) views[f] = linear[f].view();
  s.cube = cubemap_from_faces(views);
  s.layout = "faces";
  finish(o, s);
  return s;
}

CubemapSource read_cubemap(const std::string& path, const CubemapReadOptions& o) {
  CubemapSource s;
  ImageFileInfo info;
  ImageArray in = read_image_array(path, &info, o.read);
  for (Image& im : in.images) read_finite(path, im, s);
  s.files.push_back(path);
  s.hdr = in.images[0].type() == PixelType::f32;
  s.color_space = source_space(o, in.images[0].type());
  s.alpha = in.images[0].channels() == 2 || in.images[0].channels() == 4;
  if (in.faces == 6 && in.images.size() == 6) {
    std::vector<Image> faces;
    for (Image& im : in.images) {
      faces.push_back(to_linear_rgba(im.view(), s.color_space));
      im = Image();  // each face read is dropped once it is in floats
    }
    s.cube = cubemap_from_images(faces);
    s.layout = "cube " + std::to_string(s.cube.size());
    finish(o, s);
    return s;
  }
  if (in.images.size() != 1) {
    throw Error(ErrorCode::unsupported, path + ": an array texture is not a cube map (6 faces, one layer)");
  }
  const int width = in.images[0].width();
  const int height = in.images[0].height();
  const CubeLayout layout = o.layout ? *o.layout : detect_cube_layout(width, height);
  if (layout == CubeLayout::equirect && width != 2 * height) {
    throw Error(ErrorCode::bad_arguments,
                path + ": " + std::to_string(width) + "x" + std::to_string(height) + " is not a 2:1 panorama");
  }
  Image rgba = to_linear_rgba(in.images[0].view(), s.color_space);
  in.images.clear();  // the floats are all that is read from here on
  release_cached_pixel_memory();
  if (layout == CubeLayout::equirect) {
    s.cube = cubemap_from_equirect(rgba.view(), o.size > 0 ? o.size : default_cube_size(width), o.flip);
  } else {
    s.cube = cubemap_from_layout(rgba.view(), layout);
  }
  rgba = Image();
  release_cached_pixel_memory();
  s.layout = std::string(to_string(layout)) + " " + std::to_string(width) + "x" + std::to_string(height);
  if (layout != CubeLayout::equirect) finish(o, s);
  return s;
}

}  // namespace texproc
