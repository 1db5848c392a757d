// Fast row codecs for the commonest texture: 8-bit sRGB RGBA with straight
// alpha, decoded to (and encoded from) linear premultiplied float. SIMD twins
// of ref::, identical bytes. The tables are those of color.cpp.
#pragma once

#include <cstdint>

namespace texproc {

// dst[4i + c] = srgb8_to_linear(src[4i + c]) * a for c < 3, dst[4i + 3] = a,
// a = src[4i + 3] / 255.
void decode_srgb8_rgba_premultiplied(const std::uint8_t* src, int pixels, float* dst);
// The inverse: color divided by alpha (0 where alpha is 0), then
// linear_to_srgb8; alpha round(clamp(a) * 255).
void encode_srgb8_rgba_unpremultiplied(const float* src, int pixels, std::uint8_t* dst);

namespace ref {
void decode_srgb8_rgba_premultiplied(const std::uint8_t* src, int pixels, float* dst);
void encode_srgb8_rgba_unpremultiplied(const float* src, int pixels, std::uint8_t* dst);
}  // namespace ref

namespace detail {
// The 256-entry decode table.
const float* srgb8_decode_table();
// The encoder's bins packed as lo | threshold_low_bits << 8; see color.cpp.
const std::uint32_t* srgb8_encode_packed();
inline constexpr int kSrgbEncodeMantissaBits = 10;
inline constexpr int kSrgbEncodeMinExponent = -13;
}  // namespace detail

}  // namespace texproc
