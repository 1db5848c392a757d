// The per-row kernels of the normal-map generator, SIMD and scalar twins.
#pragma once

#include <cstdint>

namespace texproc {

// Both passes of a separable pair at once, each summed in order of k as
// vertical_pass and ref::convolve_row do (same bytes, one read of the inputs):
// a[x] = sum_k wa[k] * rows[k][x], b[x] = sum_k wb[k] * rows[k][x].
void vertical_pass2(const float* const* rows, const float* wa, const float* wb, int taps, int n, float* a, float* b);
// a[x] = sum_k wa[k] * ina[x + k], b[x] = sum_k wb[k] * inb[x + k].
void convolve_rows2(const float* ina, const float* wa, const float* inb, const float* wb, int taps, int n, float* a,
                    float* b);

// From gradients (dH/dx, dH/drow) to unit normals:
// (nx, ny, nz) = normalize(sx * gx, sy * gy, 1).
void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz);

// normals_from_gradients followed by ref::encode_normals_u8, in one pass.
void gradients_to_u8(const float* gx, const float* gy, const float* h, int n, float sx, float sy, int channels,
                     std::uint8_t* out);

namespace ref {
void vertical_pass2(const float* const* rows, const float* wa, const float* wb, int taps, int n, float* a, float* b);
void convolve_rows2(const float* ina, const float* wa, const float* inb, const float* wb, int taps, int n, float* a,
                    float* b);
void gradients_to_u8(const float* gx, const float* gy, const float* h, int n, float sx, float sy, int channels,
                     std::uint8_t* out);
// Interleaves unit normals (and, with 4 channels, heights h in [0, 1]) into
// 8-bit texels: round((v * 0.5 + 0.5) * 255), clamped; channels 2, 3 or 4.
void encode_normals_u8(const float* nx, const float* ny, const float* nz, const float* h, int n, int channels,
                       std::uint8_t* out);
// out[x] = sum_k w[k] * in[x + k], x in [0, n), summed in order of k.
void convolve_row(const float* in, const float* w, int taps, int n, float* out);
void normals_from_gradients(const float* gx, const float* gy, int n, float sx, float sy, float* nx, float* ny,
                            float* nz);
}  // namespace ref

}  // namespace texproc
