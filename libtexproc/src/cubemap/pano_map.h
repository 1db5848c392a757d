// Where each texel of a face row falls on a panorama, and the sides of its
// footprint there: the per-texel trigonometry of cubemap_from_equirect, in
// float, SIMD and scalar twins giving identical bytes (the same IEEE
// operations in one order, no FMA, one atan2 polynomial).
#pragma once

namespace texproc::cube {

struct FaceRowMap {
  float *px, *py;  // panorama coordinates of the texel centre, level-0 texels
  float *ax, *ay;  // the footprint's side along u (one texel), in panorama texels
  float *bx, *by;  // ... along v
  float *cosl;     // cos(latitude) of the centre: rho / |d|
};

// Row j of an n x n face. axes[0..2] = the face centre's direction, [3..5]
// d/du, [6..8] d/dv (cube_direction's table, flips applied): each entry
// -1, 0 or 1.
void map_face_row(const float axes[9], int n, int j, int width, int height, const FaceRowMap &out);

// atan2 in float: Cephes' atanf polynomial after reducing to [0, tan(pi/8)]
// (error below 2e-7 rad), written once for both twins.
float atan2_poly(float y, float x);

namespace ref {
void map_face_row(const float axes[9], int n, int j, int width, int height, const FaceRowMap &out);
}  // namespace ref

}  // namespace texproc::cube
