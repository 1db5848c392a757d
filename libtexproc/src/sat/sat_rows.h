// One summed-area-table row of RGBA input from the row above, SIMD and
// scalar twins (integer sums: identical results by construction; tested).
#pragma once

#include <cstdint>

namespace texproc {

// cur[i] = prev[i] + (prefix over x of in, per channel), 4 channels, u32
// arithmetic modulo 2^32.
void sat_row_rgba8_u32(const std::uint8_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur);
void sat_row_rgba16_u32(const std::uint16_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur);

namespace ref {
void sat_row_rgba8_u32(const std::uint8_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur);
void sat_row_rgba16_u32(const std::uint16_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur);
}  // namespace ref

}  // namespace texproc
