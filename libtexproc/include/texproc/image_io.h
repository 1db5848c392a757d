// texproc/image_io.h: reading and writing image files.
//
// PNG (libspng), JPEG (libjpeg-turbo), TGA, TIFF (libtiff), OpenEXR and the
// GPU containers (DDS, KTX2, KTX1, PKM) are read and written directly.
// Every other format OpenImageIO reads (PSD, BMP, Radiance HDR, WebP, JPEG
// 2000, ...) goes through texproc_oiio, a module loaded with dlopen the first
// time a file needs it: a process that never reads such a file never loads
// OpenImageIO. See docs/formats.md.
#pragma once

#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "texproc/color.h"
#include "texproc/cubemap.h"
#include "texproc/image.h"
#include "texproc/read_limits.h"
#include "texproc/texture.h"

namespace texproc {

struct ImageFileInfo {
  std::string format;  // OpenImageIO's format name: "png", "tiff", "openexr", ...; "dds", "ktx2", "ktx1", "pkm"
  int width = 0, height = 0;
  int channels = 0;                // channels in the file (texproc reads at most 4)
  std::string file_type;           // element type in the file: "uint8", "uint16", "half", "float", ...
  PixelType type = PixelType::u8;  // the type read_image returns
  std::string color_space_tag;     // what the file says ("sRGB", "Linear"...), a hint only
  // Whether the file carries that tag (a PNG sRGB, gAMA or iCCP chunk, a
  // texture format's sRGB or UNORM); false: the tag is the format's default
  // (a PNG or JPEG without one reads as sRGB).
  bool color_space_tagged = false;
  int subimages = 1;
  int mip_levels = 1;
  std::vector<std::pair<int, int>> level_sizes;  // probe_image: width, height of each MIP level
  bool via_module = false;                       // read through the OpenImageIO module
};

// Where image files go. direct (the default): texproc's own readers and
// writers for the formats above, the module for the rest. oiio: the module
// for every format OpenImageIO handles (GPU containers still go through
// texproc's readers), for comparisons and as a fallback.
enum class ImageIoPath { direct, oiio };

// How read_image, read_image_array and probe_image read a file.
struct ReadOptions {
  ImageIoPath io_path = ImageIoPath::direct;
  ReadLimits limits;  // sizes refused before anything is allocated
  // The defaults, with io_path from TEXPROC_IMAGE_IO (oiio or direct) and
  // ReadLimits::from_environment(): what the texproc tool reads with.
  static ReadOptions from_environment();
};

// True once this process has loaded the OpenImageIO module.
bool image_module_loaded();

// Reads subimage 0, level 0 (of a GPU container: level 0, layer 0, face 0,
// decoded when block-compressed), with at most 4 channels: 8-bit files give
// u8, 16-bit u16, everything else f32. Throws Error{io} if the file cannot
// be opened, Error{invalid_file} if it cannot be decoded or declares a size
// past options.limits, Error{unsupported} if it needs the OpenImageIO
// module and that cannot be loaded. Messages start with the path.
Image read_image(const std::string& path, ImageFileInfo* info = nullptr, const ReadOptions& options = {});

// Every face and layer of a GPU container (level 0 of each, decoded as
// read_image decodes it), or the one image of any other file. images holds
// layers * faces images, index layer * faces + face (+X, -X, +Y, -Y, +Z, -Z).
struct ImageArray {
  std::vector<Image> images;
  std::uint32_t faces = 1, layers = 1;
  bool is_array = false;  // an array texture, even with one layer
  SurfaceLayout layout() const { return {faces, layers, is_array}; }
};
ImageArray read_image_array(const std::string& path, ImageFileInfo* info = nullptr, const ReadOptions& options = {});

// Every level of every surface: a texture container's chains as stored
// (chains[layer * faces + face][level], decoded as read_image_array
// decodes level 0), the first `max_levels` of each where that is not 0;
// any other image file is one chain of one level (its level 0).
struct ImageChains {
  std::vector<std::vector<Image>> chains;
  std::uint32_t faces = 1, layers = 1;
  bool is_array = false;
  SurfaceLayout layout() const { return {faces, layers, is_array}; }
};
ImageChains read_image_chains(const std::string& path, ImageFileInfo* info = nullptr, const ReadOptions& options = {},
                              std::uint32_t max_levels = 0);

// Header facts without reading pixels. Throws as read_image.
ImageFileInfo probe_image(const std::string& path, const ReadOptions& options = {});

struct WriteOptions {
  bool half = false;        // store f32 pixels as 16-bit half floats (EXR, TIFF)
  std::string compression;  // PNG zip:N (1-9); TIFF none, zip[:N], lzw, packbits; EXR none, rle, zips, zip, piz,
                            // pxr24, b44, b44a, dwaa, dwab; empty: the format's default
  std::string color_space;  // tag to record: "srgb" or "linear"; empty: none
  int quality = 95;         // JPEG quality
  // Two channels are red and green (BC5, EAC RG11, RG8 data), not grey and
  // alpha: OpenEXR names them R and G; PNG, TGA, JPEG, TIFF and the others,
  // which have no red-green layout (a grey+alpha file would be shown as
  // transparency), get RGB with blue 0.
  bool red_green = false;
  // ImageIoPath::oiio: the OpenImageIO module writes every format it can.
  ImageIoPath io_path = ImageIoPath::direct;
};

// Writes one image atomically. The format follows the extension. Throws
// Error{unsupported} for an unknown extension, Error{io} on write failure.
void write_image(const std::string& path, const ConstImageView& image, const WriteOptions& options = {});

// write_image of an image that is not held: `shape` gives its width, height,
// channels and type (its data is not read) and `source` its rows. PNG asks
// for them strip by strip, so the image is never whole in memory; other
// formats make it whole first.
void write_image(const std::string& path, const ConstImageView& shape, const RowSource& source,
                 const WriteOptions& options = {});

// True if the extension names a format that holds a MIP chain in one file
// (.tif/.tiff, .exr).
bool holds_mip_levels(const std::string& path);

// Writes a MIP chain into one tiled TIFF (textureformat "Plain Texture", as
// maketx writes) or a tiled OpenEXR file in MIPMAP_LEVELS mode (round down).
// OpenImageIO reads them back as MIP levels. EXR needs the whole chain.
void write_mip_file(const std::string& path, const std::vector<Image>& levels, const WriteOptions& options = {});

// A MIP file written as its levels' rows are made, holding neither the chain
// nor a level: an OpenEXR file, tiled, every level down to 1x1 of f32
// pixels, with the bytes write_mip_file writes for the same levels. Each
// row is asked for (row) and then given (row_done) once, in any order, from
// several threads at once; a band of 64 rows goes to the file as soon as
// its last row is done. commit() names the file; a writer destroyed before
// that (an error, an exception) leaves nothing under the path.
class MipFileWriter {
 public:
  // True where a path can be written this way (.exr, through texproc's
  // OpenEXR module; not with ImageIoPath::oiio).
  static bool supports(const std::string& path, const WriteOptions& options = {});

  // Throws Error{unsupported} where !supports(path).
  MipFileWriter(const std::string& path, int width, int height, int channels, const WriteOptions& options = {});
  ~MipFileWriter();
  MipFileWriter(const MipFileWriter&) = delete;
  MipFileWriter& operator=(const MipFileWriter&) = delete;

  // Where row y of `level` goes: width(level) * channels floats.
  float* row(int level, int y);
  // Row y of `level` is written; a band's last row writes the band. Throws
  // Error{io} when the file cannot be written.
  void row_done(int level, int y);
  // Checks every row was given, closes and names the file.
  void commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// ---- Cube maps from files ----------------------------------------------------

// How read_cubemap takes its source.
struct CubemapReadOptions {
  // The source's layout; std::nullopt: from its shape (detect_cube_layout).
  std::optional<CubeLayout> layout;
  // The face size; 0: the source's (a panorama's: default_cube_size).
  int size = 0;
  CubeFlip flip = CubeFlip::none;
  // The source's colour space; std::nullopt: linear for float files, sRGB
  // for 8- and 16-bit ones.
  std::optional<ColorSpace> color_space;
  ReadOptions read;
};

// A cube map read from files, as linear RGBA floats, and what it was read from.
struct CubemapSource {
  Cubemap cube;
  // The source: "equirect 4096x2048", "hcross 1024x768" (a layout
  // and the image's size), "cube 512" (a cube texture), "faces".
  std::string layout;
  bool hdr = false;    // float input (kept as it is, no clipping)
  bool alpha = false;  // the input had an alpha channel
  ColorSpace color_space = ColorSpace::srgb();
  std::vector<std::string> files;     // every file read
  std::vector<std::string> warnings;  // "FILE: N non-finite value(s) (NaN or infinity) read as 0"
};

// One file: a 2:1 panorama, a cross or a strip of faces, or a cube texture
// (DDS, KTX2, KTX1 with six faces). NaN and infinity read as 0 (a warning).
// Throws Error{bad_arguments} for a shape that is no layout (or a panorama
// that is not 2:1), Error{unsupported} for an array texture, and what
// read_image_array throws.
CubemapSource read_cubemap(const std::string& path, const CubemapReadOptions& options = {});
// Six square images of one size, +X, -X, +Y, -Y, +Z, -Z. Throws
// Error{bad_arguments} naming the face that is not square or not the size of
// the first.
CubemapSource read_cubemap_faces(const std::array<std::string, 6>& faces, const CubemapReadOptions& options = {});

}  // namespace texproc
