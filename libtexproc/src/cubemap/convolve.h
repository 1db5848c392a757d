// The exact convolution of cube map texels with a lobe that depends only on
// the angle between the output direction n and the texel direction l,
// c = n.l: the cosine lobe max(c, 0) (diffuse irradiance) or GGX
// D(h) max(c, 0), whose n.h^2 is (1 + c) / 2 when n = v (the split-sum
// prefilter). SIMD and scalar twins give identical bytes: sixteen fixed
// partial sums whatever the vector width, IEEE operations in one order, no
// FMA.
#pragma once

#include <cstddef>

namespace texproc::cube {

// Source texels, structure of arrays, count a multiple of 16 (padding
// texels have weight 0).
struct ConvolveSource {
  const float *x, *y, *z, *w, *r, *g, *b;
  std::size_t count;
};

// For each of `count` output directions (nx, ny, nz), out[3k..3k+2] =
// sum(weight * rgb) / sum(weight), weight = lobe(c) * w. ggx_alpha < 0: the
// cosine lobe; else GGX with that alpha (roughness squared), the constant
// 1 / pi dropped (it cancels).
void convolve_lobe(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
                   float ggx_alpha, float* out);

namespace ref {
void convolve_lobe(const ConvolveSource& src, const float* nx, const float* ny, const float* nz, std::size_t count,
                   float ggx_alpha, float* out);
}  // namespace ref

// The sixteen partial sums to the result (shared by both twins).
void finish_convolution(const float acc[4][16], float* out);

}  // namespace texproc::cube
