// Scoring 16 values against an 8-entry palette (BC4's, EAC's): each value's nearest entry (the
// first of equals) and its squared distance, SIMD and scalar twins with
// identical results (the per-value errors are summed by the caller, in
// order).
#pragma once

#include <cstdint>

namespace texproc {

// targets: 16 values already clamped to the code range; pal: the 8 decoded
// values by code.
void value_palette_nearest(const double targets[16], const double pal[8], std::uint8_t codes[16], double errors[16]);

namespace ref {
void value_palette_nearest(const double targets[16], const double pal[8], std::uint8_t codes[16], double errors[16]);
}  // namespace ref

}  // namespace texproc
