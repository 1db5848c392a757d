// A colour channel in [0, 255] quantized to an endpoint's levels (BC1's 5
// and 6 bits), as every BC1 search rounds it: int(v * (max / 255) + 0.5),
// clamped to [0, max]. The lanes' kernel (bc1_lanes_simd.cpp) evaluates the
// same expression. (The block-by-block search once wrote v * max / 255: for
// max 31 and 63 both give the same level for every one of the 1,132,396,545
// floats in [0, 255], checked exhaustively, so one quantizer serves both.)
#pragma once

#include <algorithm>

namespace texproc {

inline int quantize_channel(float v, int max) { return std::clamp(int(v * (float(max) / 255.0f) + 0.5f), 0, max); }

}  // namespace texproc
