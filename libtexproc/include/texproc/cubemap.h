// texproc/cubemap.h: cube maps (environment maps) from panoramas, faces and
// cross layouts; seamless mip chains; image-based lighting.
//
// Faces follow Vulkan, OpenGL and Direct3D (docs/cubemap.md has the
// picture): order +X, -X, +Y, -Y, +Z, -Z; on each face u runs along the
// rows (left to right) and v down the columns (top to bottom), both in
// [-1, 1] across the face, and texel (i, j) of an N x N face is centred on
// u = 2 (i + 0.5) / N - 1, v = 2 (j + 0.5) / N - 1. A face point (u, v)
// looks along the (unnormalized) direction
//   +X ( 1, -v, -u)   -X (-1, -v,  u)   +Y ( u,  1,  v)
//   -Y ( u, -1, -v)   +Z ( u, -v,  1)   -Z (-u, -v, -1)
// and a direction picks the face of its largest-magnitude component.
//
// An equirectangular (latitude-longitude) panorama of W x H texels maps
// column x to longitude phi = 2 pi x / W - pi and row y to latitude
// lambda = pi / 2 - pi y / H (row 0 is straight up, +Y), direction
// (sin phi cos lambda, sin lambda, -cos phi cos lambda): the panorama's
// centre looks along -Z, three quarters across along +X.
//
// Every function here works on linear RGBA f32 faces (colour premultiplied
// by alpha, as the mip filters do); to_linear_rgba and from_linear_rgba
// convert at the boundary. Output bytes are identical for any thread count
// and SIMD target.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "texproc/color.h"
#include "texproc/image.h"

namespace texproc {

// How a single image holds a sphere of directions.
enum class CubeLayout {
  equirect,          // 2:1 latitude-longitude panorama
  cross_horizontal,  // 4:3:   . +Y  .  .  /  -X +Z +X -Z  /  . -Y  .  .
  cross_vertical,    // 3:4:   . +Y .  /  -X +Z +X  /  . -Y .  /  . -Z . (-Z turned 180 degrees)
  strip_horizontal,  // 6:1:   +X -X +Y -Y +Z -Z
  strip_vertical,    // 1:6:   the same, top to bottom
};
const char* to_string(CubeLayout l);
// "equirect", "cross", "hcross", "vcross", "strip", "hstrip", "vstrip".
// Throws Error{bad_arguments} listing the valid names.
CubeLayout parse_cube_layout(std::string_view name);
// The layout a width x height image has by its aspect ratio (2:1, 4:3, 3:4,
// 6:1, 1:6, each exact in whole texels). Throws Error{bad_arguments} naming
// the size and the aspect ratios that are accepted.
CubeLayout detect_cube_layout(int width, int height);

// A world axis to mirror when sampling a source (panorama, faces, cube):
// for engines that look cube maps up in a left-handed world, mirror z.
enum class CubeFlip { none, x, y, z };
CubeFlip parse_cube_flip(std::string_view name);  // "none", "x", "y", "z"

// ---- Geometry --------------------------------------------------------------
// The unnormalized direction of face point (u, v), as in the table above.
void cube_direction(int face, double u, double v, double dir[3]);
// The face a direction falls on and its (u, v) there, in [-1, 1].
int cube_face_uv(const double dir[3], double& u, double& v);
// The solid angle of texel (i, j) of an n x n face (exact: the four corners'
// atan2(u v, sqrt(u^2 + v^2 + 1)) terms). The 6 n^2 texels sum to 4 pi.
// i and j may lie one texel outside the face (the extended face plane).
double cube_texel_solid_angle(int n, int i, int j);
// Panorama coordinates (texel units, centres at k + 0.5) of a direction,
// and back.
void direction_to_equirect(const double dir[3], int width, int height, double& x, double& y);
void equirect_direction(double x, double y, int width, int height, double dir[3]);

// ---- Cube maps -------------------------------------------------------------
struct CubeLevel {
  int size = 0;                // faces are size x size
  std::array<Image, 6> faces;  // RGBA f32, linear, premultiplied alpha
};
struct Cubemap {
  std::vector<CubeLevel> levels;  // level 0 first; levels[k].size = max(1, size >> k)
  int size() const { return levels.empty() ? 0 : levels[0].size; }
};

// Decodes any image to linear RGBA f32 (missing alpha is 1, gray is
// copied to RGB) with colour premultiplied by alpha; `color_space` is the
// source space (ColorSpace::srgb() for 8/16-bit colour, linear for float).
Image to_linear_rgba(const ConstImageView& image, const ColorSpace& color_space);
// The inverse: `channels` 3 or 4 of `type`, encoded to `color_space`.
Image from_linear_rgba(const ConstImageView& rgba, const ColorSpace& color_space, int channels, PixelType type);

// The face size a panorama of this width gives by default: width / 4
// rounded to the nearest power of two (at least 1).
int default_cube_size(int panorama_width);

// Level 0 of a cube map from a panorama (linear RGBA f32). Each face texel
// averages bilinear taps spread over its own footprint on the sphere, read
// from a box-filtered pyramid of the panorama at the level where the taps
// are one panorama texel apart or less, so a panorama much larger than the
// faces does not alias; near the poles, where a texel's footprint spans
// many columns, the taps follow the footprint exactly. Throws
// Error{bad_arguments} for a size < 1 or an image that is not RGBA f32.
Cubemap cubemap_from_equirect(const ConstImageView& panorama, int size, CubeFlip flip = CubeFlip::none);
// Level 0 from six square faces of one size (RGBA f32), in face order.
// Throws Error{bad_arguments} naming the face whose size differs.
Cubemap cubemap_from_faces(const std::array<ConstImageView, 6>& faces);
// Level 0 from a cross or strip image (RGBA f32). Throws Error{bad_arguments}
// if the size does not fit the layout.
Cubemap cubemap_from_layout(const ConstImageView& image, CubeLayout layout);
// Level 0 from a cube texture's six faces (read_image_array's images, RGBA f32).
Cubemap cubemap_from_images(const std::vector<Image>& faces);
// Mirrors a world axis of a cube map (faces swapped and flipped).
Cubemap flip_cubemap(const Cubemap& cube, CubeFlip flip);
// A cube map resampled to another face size over the sphere (filtered as
// cubemap_from_equirect filters; levels built on demand). Level 0 only.
Cubemap resize_cubemap(const Cubemap& cube, int size);

// Replaces cube.levels[1...] with a seamless chain down to 1x1 (or
// `max_levels` levels): each level from the one above by a 4x4 tent
// ([1 3 3 1] / 8 each way) whose taps weigh each texel by its solid angle
// and cross the face edges onto the neighbouring faces, so no level shows a
// seam.
void generate_cube_mips(Cubemap& cube, int max_levels = 0);

// Sampling: the colour in direction `dir` at fractional level `lod`
// (trilinear; bilinear taps cross face edges).
class CubeSampler {
 public:
  explicit CubeSampler(const Cubemap& cube);  // the levels cube has (no mips are made)
  ~CubeSampler();
  CubeSampler(CubeSampler&&) noexcept;
  CubeSampler& operator=(CubeSampler&&) noexcept;
  void sample(const double dir[3], float lod, float rgba[4]) const;
  int levels() const;
  int size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A cube map level as a panorama width x width / 2 (each texel filtered over
// its footprint: trilinear at the level whose texels match it).
Image cubemap_to_equirect(const Cubemap& cube, int width, int level = 0);
// A level as a cross or strip image (cells outside the faces are 0).
Image cubemap_to_layout(const Cubemap& cube, CubeLayout layout, int level = 0);

// ---- Seams -----------------------------------------------------------------
// Mean absolute RGB step (the mean over R, G, B of |a - b|) between the two
// texels that meet across each of the 12 face edges (every texel pair along
// every edge); between horizontally or vertically neighbouring texels
// anywhere inside the faces; and between each edge texel and its inward
// neighbour, the same content and spacing as the step across the edge (a
// seam makes edge_step larger than near_edge_step; content alone, a horizon
// along a face edge, can make it larger than interior_step).
struct SeamStats {
  double edge_step = 0;
  double interior_step = 0;
  double near_edge_step = 0;
};
SeamStats measure_seams(const CubeLevel& level);

// ---- Image-based lighting ----------------------------------------------------
// Roughness of level `level` of a specular chain of `levels`:
// level / (levels - 1) (perceptual roughness; GGX alpha = roughness^2).
float specular_roughness(int level, int levels);

struct SpecularOptions {
  int size = 0;    // face size of level 0 (0: the source's, at most 256)
  int levels = 0;  // 0: down to min_size
  // The smallest face: a 1x1 or 2x2 face cannot show a wide lobe without
  // its faces showing (bilinear taps over six texels), so roughness 1 sits
  // on 8x8 faces by default.
  int min_size = 8;
  int samples = 512;  // importance samples per texel where the lobe is sampled
  // Levels whose exact convolution (every texel of a source level fine
  // enough for the lobe) costs at most this many texel pairs are convolved
  // exactly; the others use filtered importance sampling. 0: sample all.
  double exact_budget = 1.0e9;
};
// The GGX-prefiltered radiance of the split-sum approximation (N = V = R):
// level k is convolved with GGX D(h) (n.l) at roughness specular_roughness(k)
// (level 0 is the mirror: the source resized). `source` needs level 0 only;
// its seamless mips are made here unless it holds them all already (as
// generate_cube_mips made them), as for irradiance, SH and the preview.
Cubemap prefilter_specular(const Cubemap& source, const SpecularOptions& options = {});

// Diffuse irradiance E(n) / pi = (1 / pi) integral L(l) max(n.l, 0) dl,
// convolved exactly from a source level of at most 32x32 faces (the cosine
// lobe needs no more), at face size `size`.
Cubemap irradiance_cubemap(const Cubemap& source, int size = 32);

// The 9 real spherical-harmonic coefficients (bands 0-2) of the radiance,
// in the basis of Ramamoorthi and Hanrahan 2001 on texproc's axes, order
// Y00 = 0.282095, Y1-1 = 0.488603 y, Y10 = 0.488603 z, Y11 = 0.488603 x,
// Y2-2 = 1.092548 xy, Y2-1 = 1.092548 yz, Y20 = 0.315392 (3 z^2 - 1),
// Y21 = 1.092548 xz, Y22 = 0.546274 (x^2 - y^2); integrated over every
// texel of the first level with at most 128x128 faces, solid-angle weighted
// (a level of the seamless chain: the band-2 functions vary too slowly for
// finer texels to change them by more than 0.1%).
struct SphericalHarmonics9 {
  std::array<std::array<double, 3>, 9> radiance{};  // L_lm, RGB
  // Irradiance / pi at direction n, from the coefficients (Ramamoorthi and
  // Hanrahan 2001: A0 = pi, A1 = 2 pi / 3, A2 = pi / 4).
  void irradiance(const double n[3], double rgb[3]) const;
};
SphericalHarmonics9 project_sh9(const Cubemap& cube);
// The basis functions at a unit direction.
void sh9_basis(const double n[3], double y[9]);

// ---- Preview -----------------------------------------------------------------
// One sRGB RGBA8 image: the cross of every level of `chain` side by side,
// and below them spheres lit by `specular` (or, without one, a chain
// prefiltered here): a mirror and roughness 0.25, 0.5, 1. HDR values are
// tone-mapped x / (1 + x) after `exposure` (a multiplier).
Image render_cube_preview(const Cubemap& chain, const Cubemap* specular, float exposure = 1.0f);

}  // namespace texproc
