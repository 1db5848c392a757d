// libFuzzer harness: a texture container decoded to images, every level,
// layer and face to every pixel type (decode_texture_image), in memory and
// then through the file paths the commands take (probe_image, read_image,
// read_image_array on a file). Supercompressed
// levels are held to a small inflation budget, as the CLI holds them to its
// own: a file that declares more must be refused, not allocated.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "fuzz_files.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"

using namespace texproc;

namespace {
using Decode = Texture (*)(const std::uint8_t*, std::size_t, const std::string&, const ReadLimits&);

// Every image of `t` at every pixel type; each must have the level's size.
// Large textures (the seeds) get their first and last level only, so that
// the fuzzer spends its time on many small inputs.
void decode_all(const Texture& t) {
  const bool large = std::uint64_t(t.width) * t.height * t.layers * t.faces > 65536;
  for (std::uint32_t l = 0; l < t.levels; ++l)
    for (std::uint32_t a = 0; a < t.layers; ++a)
      for (std::uint32_t f = 0; f < t.faces; ++f)
        for (PixelType type : {PixelType::u8, PixelType::u16, PixelType::f32}) {
          if (large && ((l != 0 && l + 1 != t.levels) || a != 0 || f != 0 || type == PixelType::u16)) continue;
          const Image img = decode_texture_image(t, l, a, f, type);
          if (std::uint32_t(img.width()) != t.level_width(l) || std::uint32_t(img.height()) != t.level_height(l)) {
            __builtin_trap();
          }
        }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const ReadOptions reads = fuzz::limited_reads();
  ReadLimits limits;
  limits.max_texture_dimension = 1024;
  limits.max_layers = 16;
  limits.max_inflated_bytes = std::uint64_t(16) << 20;
  const Decode decoders[] = {decode_dds, decode_ktx2, decode_ktx1, decode_pkm, decode_astc};
  for (Decode decode : decoders) {
    try {
      const Texture t = decode(data, size, "fuzz", limits);
      if (std::uint64_t(t.width) * t.height * t.layers * t.faces > (std::uint64_t(1) << 22)) continue;
      decode_all(t);
    } catch (const Error&) {
    }
    try {
      ReadLimits headers = limits;
      headers.headers_only = true;
      const Texture h = decode(data, size, "fuzz", headers);
      if (h.images.size() != std::size_t(h.levels) * h.layers * h.faces) __builtin_trap();
    } catch (const Error&) {
    }
  }
  for (const char* ext : {".ktx2"}) {  // containers are told apart by signature, whatever the name
    const std::string path = fuzz::put_file("tex", ext, data, size);
    if (path.empty()) return 0;
    try {
      const ImageFileInfo info = probe_image(path, reads);
      const ImageArray all = read_image_array(path, nullptr, reads);
      if (all.images.empty() || all.images[0].width() != info.width || all.images[0].height() != info.height) {
        __builtin_trap();
      }
    } catch (const Error&) {
    }
    std::remove(path.c_str());
  }
  return 0;
}
