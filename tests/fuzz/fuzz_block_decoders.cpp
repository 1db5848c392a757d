// libFuzzer harness: every block decoder (BC1-BC5, ETC1, ETC2, EAC; ASTC
// through astc-encoder's decoder) on
// arbitrary blocks, at a size taken from the input (edge blocks included).
#include <cstdint>
#include <cstring>
#include <vector>

#include "texproc/block_decode.h"
#include "texproc/error.h"
#include "texproc/texture.h"

using namespace texproc;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  static const std::vector<std::string> names = texel_format_names();
  const FormatInfo& info = format_info(parse_texel_format(names[data[0] % names.size()]));
  if (!info.compressed) return 0;
  const int w = 1 + data[1] % 37, h = 1 + data[2] % 29;
  const std::size_t need = image_bytes(info.format, std::uint32_t(w), std::uint32_t(h));
  std::vector<std::uint8_t> blocks(need);
  for (std::size_t i = 0; i < need; ++i) blocks[i] = size > 3 ? data[3 + i % (size - 3)] : 0;
  for (PixelType t : {PixelType::u8, PixelType::u16, PixelType::f32}) {
    try {
      const Image img = decompress_image(blocks, w, h, info.format, t);
      if (img.width() != w || img.height() != h) __builtin_trap();
    } catch (const Error&) {
    }
  }
  return 0;
}
