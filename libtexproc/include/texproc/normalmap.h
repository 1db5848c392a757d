// texproc/normalmap.h: tangent-space normal maps from heightmaps.
//
// Heights h are read as data in [0, 1] (integers divided by their maximum,
// floats as they are; never through a transfer function). The surface is
// z = h * height_scale * strength, in texels: height_scale says how many
// texels a height of 1.0 spans, so a ramp rising 1/height_scale per texel is
// a 45 degree slope and gives a 45 degree normal with every kernel. Every
// kernel is normalized to estimate the true gradient of a linear ramp.
#pragma once

#include <string_view>
#include <vector>

#include "texproc/filters.h"
#include "texproc/image.h"

namespace texproc {

enum class GradientKernel {
  gather2x2,  // the 2x2 footprint (x..x+1, y..y+1): cheapest; centred half a texel right and down
  central,    // (h[x+1] - h[x-1]) / 2
  sobel3,     // [-1 0 1] x [1 2 1] / 8 (default)
  sobel5,     // [-1 -2 0 2 1] x [1 4 6 4 1] / 128
  prewitt3,   // [-1 0 1] x [1 1 1] / 6
  prewitt5,   // [-2 -1 0 1 2] x [1 1 1 1 1] / 50
  scharr3,    // [-1 0 1] x [3 10 3] / 32
  multiscale  // weighted central differences over 1, 2, 4, ... texels
};

enum class HeightChannel { automatic, r, g, b, a, luma };
enum class NormalChannels {
  xyz,  // RGB = n * 0.5 + 0.5
  xy,   // RG only (BC5, EAC RG11): the shader rebuilds z = sqrt(1 - x^2 - y^2)
  xyzh  // RGBA, the height in A (parallax mapping)
};

struct NormalMapOptions {
  GradientKernel kernel = GradientKernel::sobel3;
  HeightChannel height_channel = HeightChannel::automatic;  // gray: the gray; color: luma
  bool invert = false;                                      // depth maps: h -> 1 - h
  float height_scale = 8.0f;                                // texels spanned by a height of 1.0 (> 0)
  float strength = 1.0f;                                    // multiplies the slope on top (> 0)
  WrapMode wrap = WrapMode::clamp;
  bool y_up = true;  // OpenGL (+Y up, green = up); false: DirectX (green flipped)
  NormalChannels channels = NormalChannels::xyz;
  // multiscale only: the weight of scale 2^i (differences over +-2^i texels).
  // Normalized to sum 1. Default {0.5, 0.3, 0.2}: scales 1, 2 and 4.
  std::vector<float> multiscale_weights = {0.5f, 0.3f, 0.2f};
};

// Number of output channels for `c` (2, 3 or 4).
int channel_count(NormalChannels c);

// Computes the normal map of `heights` (any channel count and type) into
// `out`, which the caller allocates with the same width and height and
// channel_count(options.channels) channels of any type. Integer outputs hold
// round((n * 0.5 + 0.5) * max); f32 holds n * 0.5 + 0.5 unquantized. The
// bytes never depend on the thread count or SIMD target. Throws
// Error{bad_arguments} for invalid options (naming the option).
void compute_normal_map(const ConstImageView& heights, const ImageView& out, const NormalMapOptions& options);

// The same into a new image of `type`.
Image normal_map(const ConstImageView& heights, const NormalMapOptions& options, PixelType type);

// The height as the kernels see it (after channel selection and --invert),
// one float per texel, row after row.
std::vector<float> extract_height(const ConstImageView& image, HeightChannel channel, bool invert);
// The same, consuming `image`: its memory goes back to the system a band of
// rows at a time as the heights are made, so that the two are never held
// whole together (an 8-bit RGBA image and its heights are the same size).
// `image` is empty afterwards.
std::vector<float> extract_height(Image&& image, HeightChannel channel, bool invert);

GradientKernel parse_gradient_kernel(std::string_view name);
HeightChannel parse_height_channel(std::string_view name);
NormalChannels parse_normal_channels(std::string_view name);
const char* to_string(GradientKernel k);
std::vector<std::string> gradient_kernel_names();

}  // namespace texproc
