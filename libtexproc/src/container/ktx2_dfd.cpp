// KTX2 Data Format Descriptors, as libktx's vk2dfd writes them (Khronos Data
// Format Specification 1.3, basic descriptor block). One basic block:
//   uint32 dfdTotalSize
//   word 0  vendorId 0 (Khronos) | descriptorType 0 (basic) << 17
//   word 1  versionNumber 2 | descriptorBlockSize (24 + 16 * samples) << 16
//   word 2  colorModel | colorPrimaries << 8 (1, BT.709) | transfer << 16 | flags << 24 (0, straight alpha)
//   word 3  texelBlockDimension0..3, each minus one (compressed: 3, 3, 0, 0)
//   words 4-5 bytesPlane0..7 (bytes per texel or block in plane 0)
//   per sample: bitOffset | (bitLength - 1) << 16 | channel << 24 (with qualifier
//   bits 0x10 linear, 0x40 signed, 0x80 float), samplePosition 0, lower, upper.
#include <cstring>

#include "container/bytes.h"
#include "texproc/container.h"

namespace texproc {
namespace {

constexpr std::uint32_t kModelRgbsda = 1, kModelBc1a = 128, kModelBc2 = 129, kModelBc3 = 130, kModelBc4 = 131,
                        kModelBc5 = 132, kModelBc6h = 133, kModelBc7 = 134, kModelEtc2 = 161, kModelAstc = 162;
constexpr std::uint32_t kPrimariesBt709 = 1, kTransferLinear = 1, kTransferSrgb = 2;
constexpr std::uint32_t kLinear = 0x10, kSigned = 0x40, kFloat = 0x80;
constexpr std::uint32_t kAlpha = 15;

struct Sample {
  std::uint32_t offset, bits, channel, lower, upper;
};

std::uint32_t float_bits(float f) {
  std::uint32_t b;
  std::memcpy(&b, &f, 4);
  return b;
}

std::vector<std::uint8_t> block(std::uint32_t model, bool srgb, std::uint32_t dims, std::uint32_t bytes,
                                const std::vector<Sample>& samples) {
  ByteWriter w;
  const std::uint32_t block_size = 24 + 16 * std::uint32_t(samples.size());
  w.u32(4 + block_size);
  w.u32(0);
  w.u32(2 | block_size << 16);
  w.u32(model | kPrimariesBt709 << 8 | (srgb ? kTransferSrgb : kTransferLinear) << 16);
  w.u32(dims);
  w.u32(bytes);
  w.u32(0);
  for (const Sample& s : samples) {
    w.u32(s.offset | (s.bits - 1) << 16 | s.channel << 24);
    w.u32(0);
    w.u32(s.lower);
    w.u32(s.upper);
  }
  return std::move(w).bytes();
}

// Uncompressed, little-endian, one sample per channel (createDFDUnpacked).
std::vector<std::uint8_t> unpacked(const FormatInfo& i, bool bgra) {
  const std::uint32_t bytes = std::uint32_t(i.type_size), bits = 8 * bytes;
  std::vector<Sample> samples;
  for (int c = 0; c < i.channels; ++c) {
    std::uint32_t channel = c == 3 ? kAlpha : std::uint32_t(c);
    if (bgra && (c == 0 || c == 2)) channel ^= 2;
    std::uint32_t lower = 0, upper = bits >= 32 ? 0xFFFFFFFFu : (1u << bits) - 1u;
    if (i.is_float) {
      channel |= kFloat | kSigned;
      lower = float_bits(-1.0f);
      upper = float_bits(1.0f);
    } else if (i.srgb && channel == kAlpha) {
      channel |= kLinear;
    }
    samples.push_back({std::uint32_t(c) * bits, bits, channel, lower, upper});
  }
  return block(kModelRgbsda, i.srgb, 0, std::uint32_t(i.block_bytes), samples);
}

// Block-compressed (createDFDCompressed): 64- or 128-bit samples.
std::vector<std::uint8_t> compressed(const FormatInfo& i, std::uint32_t model,
                                     std::vector<std::pair<std::uint32_t, std::uint32_t>> channels_offsets) {
  const std::uint32_t flags = i.snorm ? kSigned : 0;
  const std::uint32_t lower = i.snorm ? 0x80000000u : 0u, upper = i.snorm ? 0x7FFFFFFFu : 0xFFFFFFFFu;
  std::vector<Sample> samples;
  // An sRGB format's alpha is linear (KTX2 validity rules; libktx and
  // `ktx validate` agree), as for the uncompressed formats above.
  for (auto [channel, offset] : channels_offsets) {
    const std::uint32_t linear = i.srgb && channel == kAlpha ? kLinear : 0;
    samples.push_back({offset, 64, channel | flags | linear, lower, upper});
  }
  return block(model, i.srgb, 0x0303, std::uint32_t(i.block_bytes), samples);
}

// ASTC (createDFDCompressed's c_ASTC): the footprint in texelBlockDimension,
// one 128-bit sample of channel 0 (ASTC data); SFLOAT is float and signed,
// with libktx's bounds -1 and 1.
std::vector<std::uint8_t> astc(const FormatInfo& i) {
  const std::uint32_t dims = std::uint32_t(i.block_width - 1) | std::uint32_t(i.block_height - 1) << 8;
  const Sample s = i.is_float ? Sample{0, 128, kFloat | kSigned, float_bits(-1.0f), float_bits(1.0f)}
                              : Sample{0, 128, 0, 0u, 0xFFFFFFFFu};
  return block(kModelAstc, i.srgb, dims, 16, {s});
}

// BC6H and BC7 (createDFDCompressed): one 128-bit sample of channel 0;
// BC6H is float (SFLOAT also signed) with libktx's bounds 0 (-1 signed) and 1.
std::vector<std::uint8_t> bptc(const FormatInfo& i, bool signed_float) {
  const Sample s = !i.is_float    ? Sample{0, 128, 0, 0u, 0xFFFFFFFFu}
                   : signed_float ? Sample{0, 128, kFloat | kSigned, float_bits(-1.0f), float_bits(1.0f)}
                                  : Sample{0, 128, kFloat, float_bits(0.0f), float_bits(1.0f)};
  return block(i.is_float ? kModelBc6h : kModelBc7, i.srgb, 0x0303, 16, {s});
}

}  // namespace

std::vector<std::uint8_t> ktx2_dfd(TexelFormat f) {
  const FormatInfo& i = format_info(f);
  if (is_astc(f)) return astc(i);
  using F = TexelFormat;
  switch (f) {
    case F::bgra8_unorm:
    case F::bgra8_srgb:
      return unpacked(i, true);
    case F::bc1_rgb_unorm:
    case F::bc1_rgb_srgb:
      return compressed(i, kModelBc1a, {{0, 0}});
    case F::bc1_rgba_unorm:
    case F::bc1_rgba_srgb:
      return compressed(i, kModelBc1a, {{1, 0}});
    case F::bc2_unorm:
    case F::bc2_srgb:
      return compressed(i, kModelBc2, {{kAlpha, 0}, {0, 64}});
    case F::bc3_unorm:
    case F::bc3_srgb:
      return compressed(i, kModelBc3, {{kAlpha, 0}, {0, 64}});
    case F::bc4_unorm:
    case F::bc4_snorm:
      return compressed(i, kModelBc4, {{0, 0}});
    case F::bc5_unorm:
    case F::bc5_snorm:
      return compressed(i, kModelBc5, {{0, 0}, {1, 64}});
    case F::bc6h_ufloat:
      return bptc(i, false);
    case F::bc6h_sfloat:
      return bptc(i, true);
    case F::bc7_unorm:
    case F::bc7_srgb:
      return bptc(i, false);
    case F::etc1_rgb:
    case F::etc2_rgb_unorm:
    case F::etc2_rgb_srgb:
      return compressed(i, kModelEtc2, {{2, 0}});
    case F::etc2_rgba1_unorm:
    case F::etc2_rgba1_srgb:
      return compressed(i, kModelEtc2, {{2, 0}, {kAlpha, 0}});
    case F::etc2_rgba8_unorm:
    case F::etc2_rgba8_srgb:
      return compressed(i, kModelEtc2, {{kAlpha, 0}, {2, 64}});
    case F::eac_r11_unorm:
    case F::eac_r11_snorm:
      return compressed(i, kModelEtc2, {{0, 0}});
    case F::eac_rg11_unorm:
    case F::eac_rg11_snorm:
      return compressed(i, kModelEtc2, {{0, 0}, {1, 64}});
    default:
      return unpacked(i, false);
  }
}

}  // namespace texproc
