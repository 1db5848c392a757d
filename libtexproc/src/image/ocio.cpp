// OcioTransform over texproc_ocio, the OpenColorIO module: loaded the first
// time a colour space other than the built-in linear and sRGB is asked for
// (image/ocio/ocio_module.h), so no other run maps OpenColorIO, yaml-cpp and
// their dependencies.
#include "image/ocio.h"

#include <mutex>

#include "core/module.h"
#include "image/ocio/ocio_module.h"
#include "texproc/error.h"

namespace texproc {
namespace {

const TpOcioModule& ocio_module() {
  static std::once_flag once;
  static const TpOcioModule* module = nullptr;
  static std::string why;
  std::call_once(once, [] {
    using Entry = const TpOcioModule* (*)();
    const ModuleSpec spec{"texproc_ocio.so", "TEXPROC_OCIO_MODULE", "texproc_ocio_module",
                          [](void* entry) -> const void* { return reinterpret_cast<Entry>(entry)(); }};
    module = static_cast<const TpOcioModule*>(load_module(spec, why));
    if (module && module->abi != TP_OCIO_MODULE_ABI) {
      why = "texproc_ocio is of another version";
      module = nullptr;
    }
  });
  if (!module) {
    throw Error(ErrorCode::unsupported,
                "colour spaces other than linear and srgb come from OpenColorIO, and texproc's OpenColorIO module "
                "could not be loaded (" +
                    why + ")");
  }
  return *module;
}

class ModuleTransform final : public OcioTransform {
 public:
  ModuleTransform(const TpOcioModule& m, void* t, std::string path) : m_(m), t_(t), path_(std::move(path)) {}
  ~ModuleTransform() override { m_.destroy(t_); }
  void to_linear(float* pixels, int channels, int width) const override { m_.to_linear(t_, pixels, channels, width); }
  void from_linear(float* pixels, int channels, int width) const override {
    m_.from_linear(t_, pixels, channels, width);
  }
  const std::string& config_path() const override { return path_; }

 private:
  const TpOcioModule& m_;
  void* t_;
  std::string path_;
};

}  // namespace

std::shared_ptr<const OcioTransform> OcioTransform::create(const std::string& space) {
  const TpOcioModule& m = ocio_module();
  char path[4096] = {}, err[2048] = {};
  int code = 0;
  void* t = m.create(space.c_str(), path, sizeof path, &code, err, sizeof err);
  if (!t) throw Error(ErrorCode(code), err);
  return std::make_shared<ModuleTransform>(m, t, path);
}

std::vector<std::string> OcioTransform::names() {
  const TpOcioModule& m = ocio_module();
  std::string buf(4096, '\0');
  char err[2048] = {};
  int code = 0;
  long n = m.names(buf.data(), buf.size(), &code, err, sizeof err);
  if (n < 0) throw Error(ErrorCode(code), err);
  if (std::size_t(n) > buf.size()) {
    buf.assign(std::size_t(n), '\0');
    n = m.names(buf.data(), buf.size(), &code, err, sizeof err);
    if (n < 0) throw Error(ErrorCode(code), err);
  }
  std::vector<std::string> out;
  for (std::size_t i = 0; i < std::size_t(n);) {
    const std::size_t end = buf.find('\0', i);
    out.push_back(buf.substr(i, end - i));
    i = end + 1;
  }
  return out;
}

}  // namespace texproc
