// What the cube map files share: faces with a one-texel border copied from
// the neighbouring faces, so that a filter or a bilinear tap near an edge
// reads across it without a special case.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "core/pixel_memory.h"
#include "texproc/cubemap.h"

namespace texproc::cube {

// Rows of one work item: faces are processed as 6 * n rows, 16 at a time
// (fixed, so the bytes do not depend on the thread count).
constexpr int kRowBlock = 16;

// One level, each face (n + 2) x (n + 2) RGBA f32: texel (i, j) of the face,
// i, j in [-1, n], at index ((j + 1) * (n + 2) + i + 1) * 4.
struct PaddedLevel {
  int n = 0;
  // Pixel memory, not zero-filled: pad_level writes every texel.
  std::array<std::vector<float, detail::DefaultInitAllocator<float>>, 6> faces;
  const float* texel(int face, int i, int j) const {
    return faces[face].data() + (std::size_t(j + 1) * (n + 2) + (i + 1)) * 4;
  }
  float* texel(int face, int i, int j) { return faces[face].data() + (std::size_t(j + 1) * (n + 2) + (i + 1)) * 4; }
};

// Copies a level into a padded one and fills the border: each border texel
// is the bilinear sample, inside the face its direction falls on, of that
// direction (the face plane extended by one texel).
PaddedLevel pad_level(const CubeLevel& level);

// Bilinear sample of a padded level in direction dir (any length > 0).
void sample_bilinear(const PaddedLevel& level, const double dir[3], float rgba[4]);

// Direction of the centre of texel (i, j) of an n x n face, normalized.
inline void texel_direction(int face, int n, double i, double j, double dir[3]) {
  cube_direction(face, 2.0 * (i + 0.5) / n - 1.0, 2.0 * (j + 0.5) / n - 1.0, dir);
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  dir[0] /= len;
  dir[1] /= len;
  dir[2] /= len;
}

// A level's texels in structure-of-arrays form for the convolution kernels:
// unit directions, solid angles and RGB, all faces, texel order face-major.
struct TexelSet {
  std::vector<float> x, y, z, w, r, g, b;
  std::size_t size() const { return x.size(); }
};
TexelSet texel_set(const CubeLevel& level);

// The seamless chain of `cube` down to 1x1: the cube itself when it holds
// every level already (generate_cube_mips made them), else level 0 and its
// chain built into `scratch`. The chain is made once per call, not again by
// every function that needs a coarser level.
const Cubemap& full_chain(const Cubemap& cube, Cubemap& scratch);

// An empty level of size n (faces allocated, uninitialized).
CubeLevel make_level(int n);

}  // namespace texproc::cube
