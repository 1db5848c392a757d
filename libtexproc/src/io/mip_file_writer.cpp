// MipFileWriter: a MIP file fed row by row. Each level is cut into bands of
// the file's tile height; a band's rows are staged until its last row is
// done, then written through the OpenEXR module and freed.
#include <algorithm>
#include <atomic>
#include <mutex>

#include "io/modules/image_module.h"
#include "io/modules/image_modules.h"
#include "texproc/error.h"
#include "texproc/tools.h"
#include "texproc/image_io.h"

namespace texproc {

namespace {
constexpr int kBand = TP_MIP_BAND_ROWS;

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return e;
}
}  // namespace

struct MipFileWriter::Impl {
  struct Level {
    int width = 0, height = 0, bands = 0;
    std::vector<std::unique_ptr<float[]>> staged;   // per band, while its rows arrive
    std::unique_ptr<std::atomic<int>[]> rows_done;  // per band
  };
  AtomicFile file;
  int channels = 0;
  std::vector<Level> levels;
  std::mutex staging, writing;
  modules::MipBands bands;

  Impl(const std::string& path, int width, int height, int channels_, const WriteOptions& o)
      : file(path),
        channels(channels_),
        bands(modules::Module::exr, file.temp_path(), path, width, height, channels_, o) {
    for (int w = width, h = height;; w = std::max(1, w / 2), h = std::max(1, h / 2)) {
      Level l;
      l.width = w;
      l.height = h;
      l.bands = (h + kBand - 1) / kBand;
      l.staged.resize(l.bands);
      l.rows_done = std::make_unique<std::atomic<int>[]>(l.bands);
      for (int b = 0; b < l.bands; ++b) l.rows_done[b] = 0;
      levels.push_back(std::move(l));
      if (w == 1 && h == 1) break;
    }
  }
  std::size_t row_floats(const Level& l) const { return std::size_t(l.width) * channels; }
};

bool MipFileWriter::supports(const std::string& path, const WriteOptions& options) {
  return lower_extension(path) == ".exr" && options.io_path != ImageIoPath::oiio;
}

MipFileWriter::MipFileWriter(const std::string& path, int width, int height, int channels, const WriteOptions& o) {
  if (!supports(path, o)) {
    throw Error(ErrorCode::unsupported, path + ": written row by row only as OpenEXR through texproc's module");
  }
  if (width < 1 || height < 1 || channels < 1 || channels > 4) {
    throw Error(ErrorCode::bad_arguments, path + ": a MIP file of " + std::to_string(width) + "x" +
                                              std::to_string(height) + ", " + std::to_string(channels) + " channels");
  }
  impl_ = std::make_unique<Impl>(path, width, height, channels, o);
}

MipFileWriter::~MipFileWriter() = default;

float* MipFileWriter::row(int level, int y) {
  Impl::Level& l = impl_->levels.at(std::size_t(level));
  const int b = y / kBand;
  std::lock_guard<std::mutex> lock(impl_->staging);
  std::unique_ptr<float[]>& band = l.staged.at(std::size_t(b));
  if (!band)
    band = std::make_unique_for_overwrite<float[]>(impl_->row_floats(l) * std::min(kBand, l.height - b * kBand));
  return band.get() + impl_->row_floats(l) * std::size_t(y - b * kBand);
}

void MipFileWriter::row_done(int level, int y) {
  Impl::Level& l = impl_->levels.at(std::size_t(level));
  const int b = y / kBand;
  if (l.rows_done[b].fetch_add(1) + 1 != std::min(kBand, l.height - b * kBand)) return;
  std::unique_ptr<float[]> band;
  {
    std::lock_guard<std::mutex> lock(impl_->staging);
    band = std::move(l.staged[std::size_t(b)]);
  }
  std::lock_guard<std::mutex> lock(impl_->writing);
  impl_->bands.band(level, b, band.get(), impl_->row_floats(l) * sizeof(float));
}

void MipFileWriter::commit() {
  impl_->bands.close();
  impl_->file.commit();
}

}  // namespace texproc
