// texproc/filters.h: reconstruction filters and edge (wrap) modes for resampling.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace texproc {

// Filters, in units of the destination texel (x = 1 is one texel of the
// smaller image). See docs/mip.md for the curves and when to use which.
enum class FilterKind {
  box,       // area average: exact coverage of each source texel; support 0.5
  triangle,  // tent 1 - |x|; support 1
  gaussian,  // exp(-x^2 / (2 sigma^2)), default sigma 0.5; support 4 sigma
  kaiser,    // sinc windowed by Kaiser (alpha 4), as NVTT; support 3
  lanczos3,  // sinc(x) sinc(x / 3); support 3
  mitchell   // Mitchell-Netravali cubic, B = C = 1/3; support 2
};

// What a filter tap past the edge of the image reads.
enum class WrapMode {
  clamp,   // the edge texel (GL CLAMP_TO_EDGE)
  repeat,  // the opposite edge: tiling textures stay seamless
  mirror   // reflected, the edge texel repeated (GL MIRRORED_REPEAT)
};

struct Filter {
  FilterKind kind = FilterKind::gaussian;
  // Gaussian only: standard deviation in destination texels (0 < sigma <= 4).
  float sigma = 0.5f;
};

// Radius beyond which the filter is zero, in destination texels.
double filter_support(const Filter& f);
// The filter's value at x (destination texels), not normalized.
double filter_eval(const Filter& f, double x);

// Parsing and naming. The parsers throw Error{bad_arguments} listing the
// valid names.
FilterKind parse_filter_kind(std::string_view name);
WrapMode parse_wrap_mode(std::string_view name);
const char* to_string(FilterKind k);
const char* to_string(WrapMode w);
std::vector<std::string> filter_kind_names();
std::vector<std::string> wrap_mode_names();

// Maps a texel index i (any integer) into [0, n) according to `wrap`.
int wrap_index(int i, int n, WrapMode wrap);

}  // namespace texproc
