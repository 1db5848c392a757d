// ETC1, ETC2 and EAC block encoders.
#pragma once

#include <cstdint>
#include <vector>

#include "texproc/block_encode.h"
#include "texproc/texture.h"

namespace texproc::etc {

enum class EtcMode {
  etc1,        // individual and differential modes
  etc2,        // + T, H and planar
  etc2_punch,  // ETC2 with punch-through alpha: no individual mode; alpha < 128 is transparent
};

// Encodes 16 RGBA8 texels (row by row) into an 8-byte ETC1/ETC2 colour block,
// choosing the mode, flip, tables and colours with the least squared RGB
// error (over the visible texels for punch-through) within the quality's
// search. Returns that error.
long encode_color_block(const std::uint8_t rgba[16][4], EtcMode mode, Quality q, std::uint8_t out[8]);

enum class EacKind { alpha8, r11, r11_signed };
// Encodes 16 targets into an 8-byte EAC block. Targets are in the format's
// units: 0..255 for alpha8, 0..2047 for r11, -1023..1023 for r11_signed
// (any real value; clamped). Returns the squared error in those units.
double encode_eac_block(const float targets[16], EacKind kind, Quality q, std::uint8_t out[8]);

// A whole image in an ETC or EAC format (compress_image's ETC half).
std::vector<std::uint8_t> compress_etc(const ConstImageView& img, TexelFormat format, Quality q,
                                       const EncodeOptions& options);

}  // namespace texproc::etc
