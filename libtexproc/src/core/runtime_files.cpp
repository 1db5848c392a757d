// runtime_files(): what a process built on libtexproc needs beside the
// system's libraries, for build systems that copy a tool to other machines
// (remote execution) or key a cache on it.
#include <dlfcn.h>
#include <hwy/highway.h>
#include <jpeglib.h>
#include <spng.h>
#include <tbb/version.h>
#include <tiffio.h>
#include <zlib.h>
#include <zstd.h>

#include <cstdio>
#include <filesystem>

#include "core/module.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc {

std::vector<std::string> runtime_files() {
  std::vector<std::string> out;
  Dl_info self{};
  if (dladdr(reinterpret_cast<void*>(&runtime_files), &self) && self.dli_fname) {
    std::error_code ec;
    const fs::path object = fs::canonical(self.dli_fname, ec);
    out.push_back(ec ? std::string(self.dli_fname) : object.string());
  }
  // Every runtime module a command may load (OpenEXR, OpenImageIO,
  // OpenColorIO), where it would be loaded from.
  for (const auto& [file, env] :
       {std::pair{"texproc_exr.so", "TEXPROC_EXR_MODULE"}, std::pair{"texproc_oiio.so", "TEXPROC_OIIO_MODULE"},
        std::pair{"texproc_ocio.so", "TEXPROC_OCIO_MODULE"}}) {
    const std::string found = find_module(ModuleSpec{file, env, "", nullptr});
    if (!found.empty()) out.push_back(found);
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> linked_libraries() {
  std::string tiff = TIFFGetVersion();  // "LIBTIFF, Version 4.5.0\nCopyright..."
  tiff = tiff.substr(0, tiff.find('\n'));
  if (const auto v = tiff.find("Version "); v != std::string::npos) tiff = tiff.substr(v + 8);
  char jpeg[32], hwy[32];
#ifdef LIBJPEG_TURBO_VERSION_NUMBER
  std::snprintf(jpeg, sizeof jpeg, "%d.%d.%d", LIBJPEG_TURBO_VERSION_NUMBER / 1000000,
                LIBJPEG_TURBO_VERSION_NUMBER / 1000 % 1000, LIBJPEG_TURBO_VERSION_NUMBER % 1000);
#else
  std::snprintf(jpeg, sizeof jpeg, "jpeglib %d", JPEG_LIB_VERSION);
#endif
  std::snprintf(hwy, sizeof hwy, "%d.%d", HWY_MAJOR, HWY_MINOR);
  return {{"libtiff", tiff},
          {"libjpeg-turbo", jpeg},
          {"libspng", spng_version_string()},
          {"zlib", zlibVersion()},
          {"libzstd", ZSTD_versionString()},
          {"oneTBB", TBB_runtime_version()},
          {"Highway", hwy},
          {"astc-encoder", TEXPROC_ASTCENC_VERSION " (" TEXPROC_ASTCENC_SONAME ")"},
          {"OpenEXR", TEXPROC_OPENEXR_VERSION " (module)"},
          {"OpenImageIO", TEXPROC_OIIO_VERSION " (module)"},
          {"OpenColorIO", TEXPROC_OCIO_VERSION " (module)"}};
}

}  // namespace texproc
