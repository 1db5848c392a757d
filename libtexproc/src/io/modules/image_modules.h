// Loads the image modules (image_module.h) on first use and wraps their C
// calls in texproc's types and errors. Where it looks: core/module.h, with
// $TEXPROC_OIIO_MODULE / $TEXPROC_EXR_MODULE naming the file to use instead.
#pragma once

#include <string>
#include <vector>

#include "texproc/image.h"
#include "texproc/image_io.h"

struct TpImageModule;

namespace texproc::modules {

enum class Module { oiio, exr };

bool loaded(Module m);
// Each throws Error: the module's own code and message, or Error{unsupported}
// naming `path` and every place looked in when the module cannot be loaded.
// probe checks the size against `limits`.
ImageFileInfo probe(Module m, const std::string& path, const ReadLimits& limits);
// probe, then the pixels: at most 4 channels of the type probe gave.
Image read(Module m, const std::string& path, ImageFileInfo& info, const ReadLimits& limits);
void write(Module m, const std::string& file, const std::string& path, const std::vector<ConstImageView>& levels,
           bool mip_file, const WriteOptions& options);

// A module's band-by-band MIP file (image_module.h: mip_open, mip_band,
// mip_close). Destroyed without close(), the file is abandoned.
class MipBands {
 public:
  MipBands(Module m, const std::string& file, const std::string& path, int width, int height, int channels,
           const WriteOptions& options);
  ~MipBands();
  MipBands(const MipBands&) = delete;
  MipBands& operator=(const MipBands&) = delete;
  void band(int level, int band, const void* rows, std::size_t row_stride);  // one call at a time
  void close();

 private:
  const TpImageModule* t_ = nullptr;
  void* writer_ = nullptr;
};

}  // namespace texproc::modules
