// The tables of the ETC1, ETC2 and EAC formats (Khronos Data Format
// Specification 1.3, sections "ETC1" and "ETC2"), shared by the decoders
// and the encoders.
#pragma once

#include <cstddef>
#include <bit>
#include <cstdint>
#include <cstring>

namespace texproc::etc {

// Intensity modifiers of ETC1 and ETC2's individual and differential modes,
// by table index, in pixel-index order: 0 = +a, 1 = +b, 2 = -a, 3 = -b.
inline constexpr int kModifiers[8][4] = {{2, 8, -2, -8},       {5, 17, -5, -17},    {9, 29, -9, -29},
                                         {13, 42, -13, -42},   {18, 60, -18, -60},  {24, 80, -24, -80},
                                         {33, 106, -33, -106}, {47, 183, -47, -183}};

// T and H modes: the distance, by distance index.
inline constexpr int kDistances[8] = {3, 6, 11, 16, 23, 32, 41, 64};

// EAC modifiers (R11, RG11 and ETC2's alpha), by table index and 3-bit
// pixel index.
inline constexpr int kEacModifiers[16][8] = {
    {-3, -6, -9, -15, 2, 5, 8, 14}, {-3, -7, -10, -13, 2, 6, 9, 12}, {-2, -5, -8, -13, 1, 4, 7, 12},
    {-2, -4, -6, -13, 1, 3, 5, 12}, {-3, -6, -8, -12, 2, 5, 7, 11},  {-3, -7, -9, -11, 2, 6, 8, 10},
    {-4, -7, -8, -11, 3, 6, 7, 10}, {-3, -5, -8, -11, 2, 4, 7, 10},  {-2, -6, -8, -10, 1, 5, 7, 9},
    {-2, -5, -8, -10, 1, 4, 7, 9},  {-2, -4, -8, -10, 1, 3, 7, 9},   {-2, -5, -7, -10, 1, 4, 6, 9},
    {-3, -4, -7, -10, 2, 3, 6, 9},  {-1, -2, -3, -10, 0, 1, 2, 9},   {-4, -6, -8, -9, 3, 5, 7, 8},
    {-3, -5, -7, -9, 2, 4, 6, 8}};

inline int extend4(int v) { return v << 4 | v; }
inline int extend5(int v) { return v << 3 | v >> 2; }
inline int extend6(int v) { return v << 2 | v >> 4; }
inline int extend7(int v) { return v << 1 | v >> 6; }
inline int clamp255(int v) { return v < 0 ? 0 : v > 255 ? 255 : v; }

// A block as the big-endian 64-bit number the specification's bit numbers
// refer to (bit 63 is the top bit of byte 0).
inline std::uint64_t load_be64(const std::uint8_t* b) {
  std::uint64_t v;
  std::memcpy(&v, b, 8);
  if constexpr (std::endian::native == std::endian::little) v = __builtin_bswap64(v);
  return v;
}
inline void store_be64(std::uint64_t v, std::uint8_t* b) {
  for (int i = 7; i >= 0; --i, v >>= 8) b[i] = std::uint8_t(v);
}
inline int bits(std::uint64_t v, int high, int count) { return int(v >> (high - count + 1) & ((1u << count) - 1)); }

// Decoded texels are RGBA8, row by row (texel x, y at index y * 4 + x).
using Rgba8Block = std::uint8_t[16][4];

// ETC1: individual and differential modes only (a differential block whose
// second colour leaves 0..31 is not ETC1; its components wrap to 5 bits).
void decode_etc1(const std::uint8_t* block, Rgba8Block out);
// ETC2 RGB, and ETC2 RGB with punch-through alpha (`punchthrough`: bit 33
// is the opaque flag instead of the differential flag).
void decode_etc2(const std::uint8_t* block, bool punchthrough, Rgba8Block out);
// An ETC1 / ETC2 sub-block's four colours as opaque RGBA8 words (R in the
// low byte): base colour `c` plus each of table `table`'s modifiers,
// clamped. The plain reference, and the decoder's (SSE2 where the target has
// it; the same words).
void sub_block_palette_scalar(const int c[3], int table, std::uint32_t out[4]);
void sub_block_palette(const int c[3], int table, std::uint32_t out[4]);
// `count` whole blocks side by side (`block_bytes` apart) straight into an
// image's rows at `dst` (rows `stride` bytes apart): ETC1 / ETC2 RGB as RGB
// (3 bytes a texel), ETC2 with punch-through alpha and ETC2 + EAC alpha as
// RGBA; the texels decode_etc1 / decode_etc2 / decode_eac8 give.
enum class EtcRun { etc1_rgb, etc2_rgb, etc2_rgba1, etc2_rgba8 };
void decode_etc_run(const std::uint8_t* blocks, int count, int block_bytes, EtcRun kind, std::uint8_t* dst,
                    std::size_t stride);
// EAC with 11-bit results: unsigned 0..2047, signed -1023..1023.
void decode_eac11(const std::uint8_t* block, bool snorm, int out[16]);
// EAC with 8-bit results (ETC2's alpha).
void decode_eac8(const std::uint8_t* block, std::uint8_t out[16]);
// `count` whole EAC R11 blocks (`block_bytes` apart) straight into channel
// `ch` of an 8-bit image's rows (`channels` bytes a texel): each 11-bit value
// v as Image::set stores v / 2047 (SNORM: v / 1023, biased to [0, 1]).
void decode_eac11_u8_run(const std::uint8_t* blocks, int count, int block_bytes, bool snorm, int channels, int ch,
                         std::uint8_t* dst, std::size_t stride);

}  // namespace texproc::etc
