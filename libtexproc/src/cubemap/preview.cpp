// A picture of a cube map for people: every level's cross and lit spheres.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "cubemap/cube_internal.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

Image render_cube_preview(const Cubemap& chain_in, const Cubemap* specular_in, float exposure) {
  if (chain_in.levels.empty()) throw Error(ErrorCode::bad_arguments, "render_cube_preview: the cube map is empty");
  // The crosses start at the first level of at most 256 texels a face.
  Cubemap resized, scratch;
  if (chain_in.size() > 256) resized = resize_cubemap(chain_in, 256);
  const Cubemap& chain = cube::full_chain(chain_in.size() > 256 ? resized : chain_in, scratch);
  Cubemap own;
  if (!specular_in) {
    SpecularOptions so;
    so.size = std::min(chain.size(), 64);
    so.samples = 64;
    own = prefilter_specular(chain, so);
  }
  const Cubemap& specular = specular_in ? *specular_in : own;
  const CubeSampler sampler(specular);
  const int n = chain.size(), sphere = 2 * n;
  const int width = 8 * n + 16, height = 3 * n + sphere;
  Image crosses(width, height, 4, PixelType::f32);
  int x0 = 0;
  for (std::size_t k = 0; k < chain.levels.size(); ++k) {
    const Image c = cubemap_to_layout(chain, CubeLayout::cross_horizontal, int(k));
    if (x0 + c.width() > width) break;
    for (int y = 0; y < c.height(); ++y) std::memcpy(crosses.row<float>(y) + 4 * x0, c.row<float>(y), c.row_stride());
    x0 += c.width() + 1;
  }
  // Spheres seen from +Z (orthographic): a mirror, then rougher.
  const float roughness[4] = {0.0f, 0.25f, 0.5f, 1.0f};
  const float top_lod = float(sampler.levels() - 1);
  for_each_row_block(sphere, cube::kRowBlock, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      float* row = crosses.row<float>(3 * n + y);
      for (int s = 0; s < 4; ++s)
        for (int x = 0; x < sphere; ++x) {
          const double nx = (x + 0.5) / sphere * 2.0 - 1.0, ny = 1.0 - (y + 0.5) / sphere * 2.0;
          const double r2 = nx * nx + ny * ny;
          float* t = row + 4 * (s * sphere + x);
          if (r2 >= 1.0) {
            t[0] = t[1] = t[2] = 0.02f, t[3] = 1.0f;
            continue;
          }
          const double nz = std::sqrt(1.0 - r2);
          const double R[3] = {2.0 * nz * nx, 2.0 * nz * ny, 2.0 * nz * nz - 1.0};
          sampler.sample(R, roughness[s] * top_lod, t);
          t[3] = 1.0f;
        }
    }
  });
  // Tone map only what is HDR.
  float peak = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width * 4; ++x)
      if (x % 4 != 3) peak = std::max(peak, crosses.row<float>(y)[x] * exposure);
  const bool hdr = peak > 1.0f;
  for (int y = 0; y < height; ++y) {
    float* row = crosses.row<float>(y);
    for (int x = 0; x < width; ++x) {
      for (int c = 0; c < 3; ++c) {
        const float v = std::max(0.0f, row[4 * x + c] * exposure);
        row[4 * x + c] = hdr ? v / (1.0f + v) : v;
      }
      row[4 * x + 3] = 1.0f;
    }
  }
  return from_linear_rgba(crosses.view(), ColorSpace::srgb(), 4, PixelType::u8);
}

}  // namespace texproc
