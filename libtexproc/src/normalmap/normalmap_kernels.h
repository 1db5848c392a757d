// The per-row kernels of the normal-map generator, SIMD and scalar twins.
#pragma once

namespace texproc {

// out[x] = sum_k w[k] * in[x + k], x in [0, n), summed in order of k.
void convolve_row(const float* in, const float* w, int taps, int n, float* out);

// From gradients (dH/dx, dH/drow) to unit normals:
// (nx, ny, nz) = normalize(sx * gx, sy * gy, 1).
void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz);

namespace ref {
void convolve_row(const float* in, const float* w, int taps, int n, float* out);
void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz);
}  // namespace ref

}  // namespace texproc
