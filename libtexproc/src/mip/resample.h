// Polyphase resampling weights and the two separable passes that use them.
#pragma once

#include <vector>

#include "texproc/filters.h"

namespace texproc {

// Weights that take one axis from `src_size` texels to `dst_size` texels.
// Destination texel i is centred on source coordinate (i + 0.5) * s - 0.5,
// s = src_size / dst_size, so levels of odd size are neither shifted nor do
// they drop a row. Every destination texel has the same number of taps
// (zero-padded), starting at source index first[i], which may lie outside
// [0, src_size): the caller maps it with wrap_index or pads the row.
struct AxisWeights {
  int src_size = 0;
  int dst_size = 0;
  int taps = 0;
  std::vector<int> first;      // dst_size entries
  std::vector<float> weights;  // dst_size * taps, each row sums to 1
  int pad_before = 0;          // texels read before index 0
  int pad_after = 0;           // texels read at or past src_size
};

// When src_size == dst_size the weights are the identity (one tap of 1).
// The box filter weighs each source texel by its exact overlap with the
// destination texel's footprint; other filters are sampled at texel centres,
// their width scaled by s, and normalized. Enlarging (s < 1) keeps the
// filter one source texel wide.
AxisWeights compute_axis_weights(int src_size, int dst_size, const Filter& filter);

// out[x] = sum_k weights[k] * rows[k][x] for x in [0, n), summed in order of k
// (the SIMD twin sums in the same order without FMA: identical bytes).
void vertical_pass(const float* const* rows, const float* weights, int taps, int n, float* out);

// For each destination texel i and channel c:
// out[i*channels+c] = sum_k weights[i*taps+k] * src[(first[i]+k)*channels+c].
// `src` points at texel 0 of a row padded by the weights' pad_before/after.
void horizontal_pass(const float* src, int channels, const int* first, const float* weights, int taps, int out_width,
                     float* out);

namespace ref {
void vertical_pass(const float* const* rows, const float* weights, int taps, int n, float* out);
void horizontal_pass(const float* src, int channels, const int* first, const float* weights, int taps, int out_width,
                     float* out);
}  // namespace ref

}  // namespace texproc
