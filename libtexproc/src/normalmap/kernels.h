// Gradient kernels as data: a separable derivative and smoothing pair.
#pragma once

#include <vector>

#include "texproc/normalmap.h"

namespace texproc {

// gx = sum_j sum_i smooth[j] * deriv[i] * h[y + first + j][x + first + i] / norm,
// gy the same with the axes swapped. `norm` makes a unit ramp give gradient 1:
// norm = (sum_i deriv[i] * (first + i)) * (sum_j smooth[j]).
struct SeparableKernel {
  int first = 0;              // offset of tap 0 from the texel
  std::vector<float> deriv;   // derivative taps, already divided by norm
  std::vector<float> smooth;  // smoothing taps (same length, same offset)
};

SeparableKernel make_kernel(GradientKernel kind, const std::vector<float>& multiscale_weights);

}  // namespace texproc
