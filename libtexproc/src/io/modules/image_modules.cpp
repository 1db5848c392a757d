#include "io/modules/image_modules.h"

#include <algorithm>
#include <atomic>
#include <mutex>

#include "core/module.h"
#include "io/codecs/codecs.h"
#include "io/modules/image_module.h"
#include "texproc/error.h"

namespace texproc::modules {
namespace {

struct Slot {
  Slot(ModuleSpec s, const char* w) : spec(s), what(w) {}
  ModuleSpec spec;
  const char* what;  // for messages
  std::once_flag once;
  const TpImageModule* module = nullptr;
  std::string error;
  std::atomic<bool> loaded{false};
};

Slot& slot(Module m) {
  const auto call = [](void* entry) -> const void* { return reinterpret_cast<TpImageModuleEntry>(entry)(); };
  static Slot oiio(ModuleSpec{"texproc_oiio.so", "TEXPROC_OIIO_MODULE", "texproc_oiio_module", call},
                   "this format is read and written through OpenImageIO, and texproc's OpenImageIO module");
  static Slot exr(ModuleSpec{"texproc_exr.so", "TEXPROC_EXR_MODULE", "texproc_exr_module", call},
                  "OpenEXR files are read and written through texproc's OpenEXR module, which");
  return m == Module::oiio ? oiio : exr;
}

const TpImageModule& module_for(Module m, const std::string& path) {
  Slot& s = slot(m);
  std::call_once(s.once, [&s] {
    const auto* t = static_cast<const TpImageModule*>(load_module(s.spec, s.error));
    if (t && t->abi != TP_IMAGE_MODULE_ABI) {
      s.error = std::string(s.spec.file) + " is of another version (ABI " + std::to_string(t->abi) + ")";
      t = nullptr;
    }
    s.module = t;
    s.loaded = t != nullptr;
  });
  if (!s.module) throw Error(ErrorCode::unsupported, path + ": " + s.what + " could not be loaded (" + s.error + ")");
  return *s.module;
}

void check(int code, const char* err) {
  if (code != 0) throw Error(ErrorCode(code), err);
}

int to_tp(PixelType t) { return t == PixelType::u8 ? TP_U8 : t == PixelType::u16 ? TP_U16 : TP_F32; }
PixelType from_tp(int t) { return t == TP_U8 ? PixelType::u8 : t == TP_U16 ? PixelType::u16 : PixelType::f32; }

}  // namespace

bool loaded(Module m) { return slot(m).loaded; }

ImageFileInfo probe(Module m, const std::string& path, const ReadLimits& limits) {
  const TpImageModule& t = module_for(m, path);
  TpImageSpec spec{};
  char err[1024] = {};
  check(t.probe(path.c_str(), &spec, err, sizeof err), err);
  ImageFileInfo info;
  info.format = spec.format;
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.channels;
  info.file_type = spec.file_type;
  info.type = from_tp(spec.type);
  info.color_space_tag = spec.color_space;
  info.color_space_tagged = spec.color_space[0] != 0;  // as OpenImageIO reports it
  info.subimages = spec.subimages;
  info.mip_levels = spec.mip_levels;
  for (int l = 0; l < std::min(spec.mip_levels, int(TP_IMAGE_MAX_LEVELS)); ++l) {
    info.level_sizes.emplace_back(spec.level_width[l], spec.level_height[l]);
  }
  info.via_module = m == Module::oiio;
  codecs::check_size(path, info.width, info.height, info.channels, limits);
  return info;
}

Image read(Module m, const std::string& path, ImageFileInfo& info, const ReadLimits& limits) {
  info = probe(m, path, limits);
  info.level_sizes.resize(1);  // read_image reports level 0 only, as the direct readers do
  info.mip_levels = 1;
  info.subimages = 1;
  const int channels = std::min(info.channels, 4);
  Image img = Image::uninitialized(info.width, info.height, channels, info.type);
  const TpImageModule& t = module_for(m, path);
  char err[1024] = {};
  const ImageView v = img.view();
  check(t.read(path.c_str(), v.channels, to_tp(v.type), v.data, v.row_stride, err, sizeof err), err);
  return img;
}

void write(Module m, const std::string& file, const std::string& path, const std::vector<ConstImageView>& levels,
           bool mip_file, const WriteOptions& options) {
  const TpImageModule& t = module_for(m, path);
  std::vector<TpImageLevel> tl;
  for (const ConstImageView& v : levels)
    tl.push_back({v.data, v.width, v.height, v.channels, to_tp(v.type), v.row_stride});
  const TpWriteOptions o{options.half ? 1 : 0, options.compression.c_str(), options.color_space.c_str(),
                         options.quality, options.red_green ? 1 : 0};
  char err[1024] = {};
  check(t.write(file.c_str(), path.c_str(), tl.data(), int(tl.size()), mip_file ? 1 : 0, &o, err, sizeof err), err);
}

MipBands::MipBands(Module m, const std::string& file, const std::string& path, int width, int height, int channels,
                   const WriteOptions& options)
    : t_(&module_for(m, path)) {
  if (!t_->mip_open) throw Error(ErrorCode::unsupported, path + ": the module writes no MIP file band by band");
  const TpWriteOptions o{options.half ? 1 : 0, options.compression.c_str(), options.color_space.c_str(),
                         options.quality, options.red_green ? 1 : 0};
  char err[1024] = {};
  check(t_->mip_open(file.c_str(), path.c_str(), width, height, channels, &o, &writer_, err, sizeof err), err);
}

MipBands::~MipBands() {
  if (writer_) t_->mip_close(writer_, 0, nullptr, 0);
}

void MipBands::band(int level, int band, const void* rows, std::size_t row_stride) {
  char err[1024] = {};
  check(t_->mip_band(writer_, level, band, rows, row_stride, err, sizeof err), err);
}

void MipBands::close() {
  char err[1024] = {};
  void* w = writer_;
  writer_ = nullptr;
  check(t_->mip_close(w, 1, err, sizeof err), err);
}

}  // namespace texproc::modules
