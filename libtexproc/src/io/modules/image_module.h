// The boundary between libtexproc and its image modules, shared objects
// loaded with dlopen the first time a file needs them (image_modules.cpp):
//   texproc_exr   OpenEXR through its own C++ API (exr_module.cpp): OpenEXR
//                 and its three libraries cost every process 3 ms to map;
//   texproc_oiio  every other format OpenImageIO reads (oiio_module.cpp):
//                 OpenImageIO's 261 libraries cost 0.4-1.6 s.
// A process that reads only PNG, JPEG, TGA, TIFF or GPU containers maps
// neither. Plain C types only: the two sides share no C++ object, allocator
// or exception.
#pragma once

#include <stddef.h>

extern "C" {

enum { TP_IMAGE_MODULE_ABI = 3, TP_IMAGE_MAX_LEVELS = 32, TP_MIP_BAND_ROWS = 64 };

// The pixel types of texproc::PixelType, in its order.
enum { TP_U8 = 0, TP_U16 = 1, TP_F32 = 2 };

struct TpImageSpec {
  int width, height;
  int channels;          // in the file
  int type;              // TP_U8 / TP_U16 / TP_F32: what read gives
  char format[32];       // OpenImageIO's format name: "openexr", "bmp", "psd", ...
  char file_type[16];    // element type in the file: "uint8", "half", ...
  char color_space[64];  // the file's colour-space tag, "" if none
  int subimages, mip_levels;
  int level_width[TP_IMAGE_MAX_LEVELS], level_height[TP_IMAGE_MAX_LEVELS];  // the first mip_levels (at most 32)
};

struct TpImageLevel {
  const void* data;
  int width, height, channels, type;
  size_t row_stride;
};

struct TpWriteOptions {
  int half;                 // f32 stored as half floats
  const char* compression;  // OpenImageIO's compression name, "" for the default
  const char* color_space;  // "srgb", "linear" or ""
  int quality;              // JPEG quality
  int red_green;            // two channels are R and G, not Y and A
};

// Every call returns 0 or a texproc::ErrorCode value; on failure `err` holds
// the message (NUL-terminated, cut to err_size), starting with the path.
struct TpImageModule {
  int abi;  // TP_IMAGE_MODULE_ABI
  int (*probe)(const char* path, struct TpImageSpec* spec, char* err, size_t err_size);
  // Subimage 0, level 0, the first `channels` channels, as `type`, into rows
  // of `row_stride` bytes.
  int (*read)(const char* path, int channels, int type, void* data, size_t row_stride, char* err, size_t err_size);
  // Writes `file` in the format `format_path`'s extension names (messages
  // name `format_path`): one image, or with mip_file a MIP chain in one TIFF
  // or OpenEXR file.
  int (*write)(const char* file, const char* format_path, const struct TpImageLevel* levels, int level_count,
               int mip_file, const struct TpWriteOptions* options, char* err, size_t err_size);
  // A MIP file written band by band, the levels' rows given as they are
  // made (null where the module has no such writer). mip_open starts
  // `file` for a width x height chain of f32 pixels down to 1x1 and sets
  // *writer; mip_band gives one band of TP_MIP_BAND_ROWS rows of a level
  // (fewer at its bottom), `band` counted from its top, in any order, one
  // call at a time; mip_close finishes the file (commit 1) or abandons it,
  // and frees the writer either way. The file's bytes are those write
  // gives for the same chain.
  int (*mip_open)(const char* file, const char* format_path, int width, int height, int channels,
                  const struct TpWriteOptions* options, void** writer, char* err, size_t err_size);
  int (*mip_band)(void* writer, int level, int band, const void* rows, size_t row_stride, char* err, size_t err_size);
  int (*mip_close)(void* writer, int commit, char* err, size_t err_size);
};

// Each module's one exported symbol.
const struct TpImageModule* texproc_oiio_module(void);
const struct TpImageModule* texproc_exr_module(void);
typedef const struct TpImageModule* (*TpImageModuleEntry)(void);
}
