#include "image/oiio/module_loader.h"

#include <dlfcn.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "image/oiio/oiio_module.h"
#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc::oiio {
namespace {

constexpr const char* kModuleName = "texproc_oiio.so";

std::atomic<bool> g_loaded{false};

struct Loaded {
  const TpOiioModule* module = nullptr;
  std::string error;  // why it could not be loaded
};

std::vector<std::string> candidates() {
  if (const char* env = std::getenv("TEXPROC_OIIO_MODULE"); env && *env) return {env};
  std::vector<std::string> out;
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&candidates), &self) && self.dli_fname) {
    std::error_code ec;
    fs::path object = fs::canonical(self.dli_fname, ec);
    if (ec) object = self.dli_fname;
    const fs::path dir = object.parent_path();
    out.push_back((dir / kModuleName).string());
    out.push_back((dir / ".." / "lib" / "texproc" / kModuleName).lexically_normal().string());
  }
#ifdef TEXPROC_OIIO_MODULE_BUILD_PATH
  out.push_back(TEXPROC_OIIO_MODULE_BUILD_PATH);
#endif
  return out;
}

const Loaded& load() {
  static std::once_flag once;
  static Loaded result;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& file : candidates()) {
      std::error_code ec;
      if (!fs::exists(file, ec)) {
        tried += (tried.empty() ? "" : ", ") + file + " (absent)";
        continue;
      }
      void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        const char* why = dlerror();
        tried += (tried.empty() ? "" : ", ") + file + " (" + (why ? why : "dlopen failed") + ")";
        continue;
      }
      auto entry = reinterpret_cast<TpOiioModuleEntry>(dlsym(handle, "texproc_oiio_module"));
      const TpOiioModule* m = entry ? entry() : nullptr;
      if (!m || m->abi != TP_OIIO_MODULE_ABI) {
        tried += (tried.empty() ? "" : ", ") + file + " (not a texproc_oiio module of this version)";
        dlclose(handle);
        continue;
      }
      result.module = m;  // never unloaded: OpenImageIO keeps threads and caches
      g_loaded = true;
      return;
    }
    result.error = "tried " + (tried.empty() ? std::string("nowhere") : tried);
  });
  return result;
}

const TpOiioModule& module_for(const std::string& path) {
  const Loaded& l = load();
  if (!l.module) {
    throw Error(ErrorCode::unsupported, path +
                                            ": this format is read and written through OpenImageIO, and texproc's "
                                            "OpenImageIO module could not be loaded (" +
                                            l.error + ")");
  }
  return *l.module;
}

void check(int code, const char* err) {
  if (code != 0) throw Error(ErrorCode(code), err);
}

int to_tp(PixelType t) { return t == PixelType::u8 ? TP_U8 : t == PixelType::u16 ? TP_U16 : TP_F32; }
PixelType from_tp(int t) { return t == TP_U8 ? PixelType::u8 : t == TP_U16 ? PixelType::u16 : PixelType::f32; }

}  // namespace

bool loaded() { return g_loaded; }

ImageFileInfo probe(const std::string& path) {
  const TpOiioModule& m = module_for(path);
  TpImageSpec spec{};
  char err[1024] = {};
  check(m.probe(path.c_str(), &spec, err, sizeof err), err);
  ImageFileInfo info;
  info.format = spec.format;
  info.width = spec.width;
  info.height = spec.height;
  info.channels = spec.channels;
  info.file_type = spec.file_type;
  info.type = from_tp(spec.type);
  info.color_space_tag = spec.color_space;
  info.subimages = spec.subimages;
  info.mip_levels = spec.mip_levels;
  for (int l = 0; l < std::min(spec.mip_levels, int(TP_OIIO_MAX_LEVELS)); ++l) {
    info.level_sizes.emplace_back(spec.level_width[l], spec.level_height[l]);
  }
  info.via_module = true;
  return info;
}

void read(const std::string& path, const ImageView& into) {
  const TpOiioModule& m = module_for(path);
  char err[1024] = {};
  check(m.read(path.c_str(), into.channels, to_tp(into.type), into.data, into.row_stride, err, sizeof err), err);
}

void write(const std::string& file, const std::string& path, const std::vector<ImageView>& levels, bool mip_file,
           const WriteOptions& options) {
  const TpOiioModule& m = module_for(path);
  std::vector<TpImageLevel> tl;
  for (const ImageView& v : levels) tl.push_back({v.data, v.width, v.height, v.channels, to_tp(v.type), v.row_stride});
  const TpWriteOptions o{options.half ? 1 : 0, options.compression.c_str(), options.color_space.c_str(),
                         options.quality};
  char err[1024] = {};
  check(m.write(file.c_str(), path.c_str(), tl.data(), int(tl.size()), mip_file ? 1 : 0, &o, err, sizeof err), err);
}

}  // namespace texproc::oiio
