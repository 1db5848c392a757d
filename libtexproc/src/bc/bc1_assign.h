// BC1 index assignment: each texel's nearest palette colour (the first of
// equals) and its squared RGB distance, SIMD and scalar twins with identical
// (integer) results.
#pragma once

#include <cstdint>

namespace texproc {

// A block's texels as planes, prepared once per block.
struct Bc1Texels {
  std::int32_t r[16], g[16], b[16];
  std::int32_t transparent[16];  // 1: takes index 3 (three-colour mode), no error
};

// candidates: 3 or 4 palette entries; codes[i] and errors[i] per texel.
void bc1_nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16],
                 std::int32_t errors[16]);

namespace ref {
void bc1_nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16],
                 std::int32_t errors[16]);
}  // namespace ref

}  // namespace texproc
