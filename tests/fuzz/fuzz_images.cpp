// libFuzzer harness: the direct image readers (PNG, JPEG, TGA, TIFF), OpenEXR
// through texproc_exr (the module built with the same sanitizers; fuzz.sh
// names it in TEXPROC_EXR_MODULE) and the .sat reader, through the files they
// read: the input goes to a file in /dev/shm named for each format (TGA and
// .sat are chosen by extension, the others by signature).
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_files.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/sat.h"

using namespace texproc;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const ReadOptions reads = fuzz::limited_reads();
  for (const char* ext : {".png", ".tga", ".sat"}) {  // PNG/JPEG/TIFF/EXR by signature, whatever the name
    const std::string path = fuzz::put_file("img", ext, data, size);
    if (path.empty()) return 0;
    try {
      if (std::string(ext) == ".sat") {
        read_sat_file(path);
      } else {
        const ImageFileInfo info = probe_image(path, reads);
        const Image img = read_image(path, nullptr, reads);
        if (img.width() != info.width || img.height() != info.height) __builtin_trap();
      }
    } catch (const Error&) {
    }
    std::remove(path.c_str());
  }
  return 0;
}
