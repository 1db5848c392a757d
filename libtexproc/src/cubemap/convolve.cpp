// Scalar reference of the lobe convolution (convolve.h).
#include "cubemap/convolve.h"

#include <algorithm>

namespace texproc::cube {

void finish_convolution(const float acc[4][16], float* out) {
  float s[4] = {0, 0, 0, 0};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 16; ++k) s[c] += acc[c][k];
  const float inv = s[3] > 0.0f ? 1.0f / s[3] : 0.0f;
  for (int c = 0; c < 3; ++c) out[c] = s[c] * inv;
}

namespace ref {

void convolve_lobe(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
                   float ggx_alpha, float* out) {
  const bool ggx = ggx_alpha >= 0.0f;
  const float a2 = ggx_alpha * ggx_alpha, h = (a2 - 1.0f) * 0.5f;
  for (std::size_t o = 0; o < count; ++o) {
    float acc[4][16] = {};
    for (std::size_t base = 0; base < src.count; base += 16) {
      for (int k = 0; k < 16; ++k) {
        const std::size_t t = base + k;
        const float c = (nx[o] * src.x[t] + ny[o] * src.y[t]) + nz[o] * src.z[t];
        float w = std::max(c, 0.0f) * src.w[t];
        if (ggx) {
          const float q = (1.0f + c) * h + 1.0f;
          w = w / (q * q);
        }
        acc[0][k] += w * src.r[t];
        acc[1][k] += w * src.g[t];
        acc[2][k] += w * src.b[t];
        acc[3][k] += w;
      }
    }
    finish_convolution(acc, out + 3 * o);
  }
}

}  // namespace ref
}  // namespace texproc::cube
