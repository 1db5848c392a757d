#include "core/module.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace fs = std::filesystem;

namespace texproc {
namespace {

#ifndef TEXPROC_MODULE_RELATIVE_DIR
#define TEXPROC_MODULE_RELATIVE_DIR "../lib/texproc"
#endif
#ifndef TEXPROC_MODULE_INSTALL_DIR
#define TEXPROC_MODULE_INSTALL_DIR ""
#endif

std::vector<std::string> candidates(const ModuleSpec& spec) {
  if (const char* env = std::getenv(spec.env); env && *env) return {env};
  if (const char* dir = std::getenv("TEXPROC_MODULE_DIR"); dir && *dir) return {(fs::path(dir) / spec.file).string()};
  std::vector<std::string> out;
  auto add = [&out](const fs::path& p) {
    const std::string s = p.lexically_normal().string();
    if (std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
  };
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&candidates), &self) && self.dli_fname) {
    std::error_code ec;
    fs::path object = fs::canonical(self.dli_fname, ec);
    if (ec) object = self.dli_fname;
    const fs::path dir = object.parent_path();
    add(dir / spec.file);
    add(dir / TEXPROC_MODULE_RELATIVE_DIR / spec.file);
  }
  if (*TEXPROC_MODULE_INSTALL_DIR) add(fs::path(TEXPROC_MODULE_INSTALL_DIR) / spec.file);
  return out;
}

}  // namespace

std::string find_module(const ModuleSpec& spec) {
  for (const std::string& file : candidates(spec)) {
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) continue;
    const fs::path real = fs::canonical(file, ec);
    return ec ? file : real.string();
  }
  return "";
}

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
    if (const void* table = entry ? spec.call_entry(entry) : nullptr)
      return table;  // kept loaded: the libraries keep threads and caches
    note(file, std::string("no ") + spec.entry);
    dlclose(handle);
  }
  why = "tried " + (tried.empty() ? std::string("nowhere") : tried);
  return nullptr;
}

}  // namespace texproc
