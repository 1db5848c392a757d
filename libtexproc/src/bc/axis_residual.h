// The squared residual of a set of RGB points off their principal axis,
// from their 3x3 scatter (or covariance) matrix: its trace less its largest
// eigenvalue, that estimated by one power step from the column of the
// largest diagonal and the Rayleigh quotient u'Cu / u'u (which does not
// depend on u's scale, so u is not normalized). The partition estimates of
// BC7's and BC6H's scalar references; their SIMD twins repeat these steps
// in the same order. The caller keeps C's entries small enough that u'Cu
// stays finite (both bound it below 1.2e35).
#pragma once

namespace texproc::bc {

inline float axis_residual(float c00, float c01, float c02, float c11, float c12, float c22) {
  const float trace = c00 + c11 + c22;
  float v0 = c00, v1 = c01, v2 = c02;  // the column of the largest diagonal
  if (c11 > c00 && c11 >= c22) {
    v0 = c01;
    v1 = c11;
    v2 = c12;
  }
  if (c22 > c00 && c22 > c11) {
    v0 = c02;
    v1 = c12;
    v2 = c22;
  }
  const float u0 = c00 * v0 + c01 * v1 + c02 * v2, u1 = c01 * v0 + c11 * v1 + c12 * v2,
              u2 = c02 * v0 + c12 * v1 + c22 * v2;
  const float w0 = c00 * u0 + c01 * u1 + c02 * u2, w1 = c01 * u0 + c11 * u1 + c12 * u2,
              w2 = c02 * u0 + c12 * u1 + c22 * u2;
  const float uu = u0 * u0 + u1 * u1 + u2 * u2, ucu = u0 * w0 + u1 * w1 + u2 * w2;
  const float lambda = uu > 0.0f ? ucu / uu : 0.0f;
  return trace - lambda;
}

}  // namespace texproc::bc
