// texproc/image_io.h: reading and writing image files (through OpenImageIO).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "texproc/image.h"

namespace texproc {

struct ImageFileInfo {
  std::string format;       // OpenImageIO's format name: "png", "tiff", "openexr", ...
  int width = 0, height = 0;
  int channels = 0;         // channels in the file (texproc reads at most 4)
  std::string file_type;    // element type in the file: "uint8", "uint16", "half", "float", ...
  PixelType type = PixelType::u8;  // the type read_image returns
  std::string color_space_tag;     // what the file says ("sRGB", "Linear"...), a hint only
  int subimages = 1;
  int mip_levels = 1;
  std::vector<std::pair<int, int>> level_sizes;  // probe_image: width, height of each MIP level
};

// Reads subimage 0, level 0 of any format OpenImageIO reads, with at most
// 4 channels: 8-bit files give u8, 16-bit u16, everything else f32.
// Throws Error{io} if the file cannot be opened, Error{invalid_file} if it
// cannot be decoded. Messages start with the path.
Image read_image(const std::string& path, ImageFileInfo* info = nullptr);

// Header facts without reading pixels. Throws as read_image.
ImageFileInfo probe_image(const std::string& path);

struct WriteOptions {
  bool half = false;        // store f32 pixels as 16-bit half floats (EXR, TIFF)
  std::string compression;  // OpenImageIO compression name; empty: the format's default
  std::string color_space;  // tag to record: "srgb" or "linear"; empty: none
  int quality = 95;         // JPEG quality
};

// Writes one image atomically. The format follows the extension. Throws
// Error{unsupported} for an unknown extension, Error{io} on write failure.
void write_image(const std::string& path, const ImageView& image, const WriteOptions& options = {});

// True if the extension names a format that holds a MIP chain in one file
// (.tif/.tiff, .exr).
bool holds_mip_levels(const std::string& path);

// Writes a MIP chain into one tiled TIFF (textureformat "Plain Texture", as
// maketx writes) or a tiled OpenEXR file in MIPMAP_LEVELS mode (round down).
// OpenImageIO reads them back as MIP levels. EXR needs the whole chain.
void write_mip_file(const std::string& path, const std::vector<Image>& levels, const WriteOptions& options = {});

}  // namespace texproc
