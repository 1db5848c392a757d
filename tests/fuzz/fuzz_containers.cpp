// libFuzzer harness: the DDS, KTX2, KTX1, PKM and .astc readers. Whatever they
// accept must write back and read again to the same texture (the writers are
// texproc's, so the bytes may differ from another writer's, not the texels).
#include <cstdint>
#include <cstdlib>

#include "texproc/container.h"
#include "texproc/error.h"

using namespace texproc;

namespace {
using Decode = Texture (*)(const std::uint8_t*, std::size_t, const std::string&, const ReadLimits&);
using Encode = std::vector<std::uint8_t> (*)(const Texture&);
std::vector<std::uint8_t> dds(const Texture& t) { return encode_dds(t); }
std::vector<std::uint8_t> ktx2(const Texture& t) { return encode_ktx2(t, "fuzz"); }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  ReadLimits limits;
  limits.max_texture_dimension = 4096;
  limits.max_layers = 64;
  limits.max_inflated_bytes = std::uint64_t(64) << 20;
  const std::pair<Decode, Encode> kinds[] = {{decode_dds, dds},
                                             {decode_ktx2, ktx2},
                                             {decode_ktx1, encode_ktx1},
                                             {decode_pkm, encode_pkm},
                                             {decode_astc, encode_astc}};
  for (const auto& [decode, encode] : kinds) {
    Texture t;
    try {
      t = decode(data, size, "fuzz", limits);
    } catch (const Error&) {
      continue;  // refused: fine
    }
    std::vector<std::uint8_t> again;
    try {
      again = encode(t);
    } catch (const Error&) {
      continue;  // a texture this container reads but cannot write (e.g. DDS legacy quirks)
    }
    const Texture back = decode(again.data(), again.size(), "fuzz-again", limits);
    if (back.format != t.format || back.width != t.width || back.height != t.height || back.levels != t.levels ||
        back.faces != t.faces || back.layers != t.layers || back.images.size() != t.images.size()) {
      std::abort();
    }
    for (std::size_t i = 0; i < t.images.size(); ++i)
      if (!(back.images[i] == t.images[i])) std::abort();
  }
  return 0;
}
