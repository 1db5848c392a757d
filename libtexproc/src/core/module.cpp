#include "core/module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;

namespace texproc {
namespace {

std::vector<std::string> candidates(const ModuleSpec& spec) {
  if (const char* env = std::getenv(spec.env); env && *env) return {env};
  std::vector<std::string> out;
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&candidates), &self) && self.dli_fname) {
    std::error_code ec;
    fs::path object = fs::canonical(self.dli_fname, ec);
    if (ec) object = self.dli_fname;
    const fs::path dir = object.parent_path();
    out.push_back((dir / spec.file).string());
    out.push_back((dir / ".." / "lib" / "texproc" / spec.file).lexically_normal().string());
  }
  if (spec.build_path && *spec.build_path) out.push_back(spec.build_path);
  return out;
}

}  // namespace

const void* load_module(const ModuleSpec& spec, std::string& why) {
  std::string tried;
  auto note = [&](const std::string& file, const std::string& what) {
    tried += (tried.empty() ? "" : ", ") + file + " (" + what + ")";
  };
  for (const std::string& file : candidates(spec)) {
    std::error_code ec;
    if (!fs::exists(file, ec)) {
      note(file, "absent");
      continue;
    }
    void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      note(file, e ? e : "dlopen failed");
      continue;
    }
    void* entry = dlsym(handle, spec.entry);
    if (const void* table = entry ? spec.call_entry(entry) : nullptr) return table;  // kept loaded: the libraries keep threads and caches
    note(file, std::string("no ") + spec.entry);
    dlclose(handle);
  }
  why = "tried " + (tried.empty() ? std::string("nowhere") : tried);
  return nullptr;
}

}  // namespace texproc
