// The principal axis of a block's colours: power iteration on their
// covariance (c[0] c[1] c[2] / c[3] c[4] / c[5], symmetric), from its row of
// greatest variance (the first of equals, rows 0, 1, 2), four steps, each
// scaled by its largest component, then normalized. The BC1 searches all
// start from it. How a step is scaled is part of the bytes: the lanes'
// kernel (bc1_lanes_simd.cpp) and its scalar reference multiply by the
// reciprocal (one division per step in SIMD), the block-by-block search
// divides; the two round differently, so each keeps its own through
// `kScaling`. (ETC2's T and H split their clusters along a double-precision
// axis of their own: etc2_modes.cpp.)
#pragma once

#include <algorithm>
#include <cmath>

namespace texproc {

enum class AxisScaling {
  divide,      // v / big, then v / |v|; a zero vector stops early and gives the diagonal (1, 1, 1) / sqrt(3)
  reciprocal,  // v * (1 / big), then v * (1 / |v|); the caller has ruled out a zero covariance
};

template <AxisScaling kScaling>
inline void principal_axis(const float cov[6], float axis[3]) {
  float v[3];
  if (cov[0] >= cov[3] && cov[0] >= cov[5]) {
    v[0] = cov[0];
    v[1] = cov[1];
    v[2] = cov[2];
  } else if (cov[3] >= cov[5]) {
    v[0] = cov[1];
    v[1] = cov[3];
    v[2] = cov[4];
  } else {
    v[0] = cov[2];
    v[1] = cov[4];
    v[2] = cov[5];
  }
  for (int it = 0; it < 4; ++it) {
    const float big = std::max(std::abs(v[0]), std::max(std::abs(v[1]), std::abs(v[2])));
    float x, y, z;
    if constexpr (kScaling == AxisScaling::divide) {
      if (big == 0.0f) break;
      x = v[0] / big;
      y = v[1] / big;
      z = v[2] / big;
    } else {
      const float inv = 1.0f / big;
      x = v[0] * inv;
      y = v[1] * inv;
      z = v[2] * inv;
    }
    v[0] = cov[0] * x + cov[1] * y + cov[2] * z;
    v[1] = cov[1] * x + cov[3] * y + cov[4] * z;
    v[2] = cov[2] * x + cov[4] * y + cov[5] * z;
  }
  if constexpr (kScaling == AxisScaling::divide) {
    const float len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (len > 0.0f) {
      for (int ch = 0; ch < 3; ++ch) axis[ch] = v[ch] / len;
    } else {
      axis[0] = axis[1] = axis[2] = 0.57735027f;
    }
  } else {
    const float inv = 1.0f / std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int ch = 0; ch < 3; ++ch) axis[ch] = v[ch] * inv;
  }
}

}  // namespace texproc
