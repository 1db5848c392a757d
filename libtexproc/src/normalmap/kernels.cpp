// The classic gradient kernels, with their normalization next to them.
#include "normalmap/kernels.h"

#include <cmath>
#include <numeric>

#include "texproc/error.h"

namespace texproc {
namespace {

struct KernelEntry {
  GradientKernel kind;
  const char* name;
  int first;
  std::vector<double> deriv, smooth;
};

// Raw integer taps. The normalization (a ramp h = x must give exactly 1) is
// computed from the taps below, never typed in: sum_i deriv[i] * offset_i
// times the smoothing sum. Sobel 3: 2 * 4 = 8; Prewitt 3: 2 * 3 = 6;
// Scharr: 2 * 16 = 32; Sobel 5: 8 * 16 = 128; Prewitt 5: 10 * 5 = 50;
// central: 2; gather2x2: 1 * 2 = 2.
const std::vector<KernelEntry>& table() {
  static const std::vector<KernelEntry> t = {
      {GradientKernel::gather2x2, "gather2x2", 0, {-1, 1}, {1, 1}},
      {GradientKernel::central, "central", -1, {-1, 0, 1}, {0, 1, 0}},
      {GradientKernel::sobel3, "sobel3", -1, {-1, 0, 1}, {1, 2, 1}},
      {GradientKernel::sobel5, "sobel5", -2, {-1, -2, 0, 2, 1}, {1, 4, 6, 4, 1}},
      {GradientKernel::prewitt3, "prewitt3", -1, {-1, 0, 1}, {1, 1, 1}},
      {GradientKernel::prewitt5, "prewitt5", -2, {-2, -1, 0, 1, 2}, {1, 1, 1, 1, 1}},
      {GradientKernel::scharr3, "scharr3", -1, {-1, 0, 1}, {3, 10, 3}},
      {GradientKernel::multiscale, "multiscale", 0, {}, {}},  // built from the weights
  };
  return t;
}

SeparableKernel normalize(int first, const std::vector<double>& deriv, const std::vector<double>& smooth) {
  double moment = 0.0;
  for (std::size_t i = 0; i < deriv.size(); ++i) moment += deriv[i] * (first + int(i));
  const double ssum = std::accumulate(smooth.begin(), smooth.end(), 0.0);
  SeparableKernel k;
  k.first = first;
  for (double d : deriv) k.deriv.push_back(float(d / moment));
  for (double s : smooth) k.smooth.push_back(float(s / ssum));
  return k;
}

}  // namespace

SeparableKernel make_kernel(GradientKernel kind, const std::vector<float>& weights) {
  if (kind != GradientKernel::multiscale) {
    for (const auto& e : table()) {
      if (e.kind == kind) return normalize(e.first, e.deriv, e.smooth);
    }
  }
  // Multiscale: sum_i w_i * (h[x + 2^i] - h[x - 2^i]) / (2 * 2^i), weights
  // normalized to 1, so each term and the sum estimate the true gradient.
  if (weights.empty() || weights.size() > 6) {
    throw Error(ErrorCode::bad_arguments,
                "NormalMapOptions::multiscale_weights needs 1 to 6 weights (scales 1, 2, 4, ... 32)");
  }
  double wsum = 0.0;
  for (float w : weights) {
    if (!(w >= 0.0f))
      throw Error(ErrorCode::bad_arguments, "NormalMapOptions::multiscale_weights must not be negative");
    wsum += w;
  }
  if (wsum <= 0.0) throw Error(ErrorCode::bad_arguments, "NormalMapOptions::multiscale_weights must not all be zero");
  const int r = 1 << (weights.size() - 1);
  std::vector<double> deriv(2 * r + 1, 0.0), smooth(2 * r + 1, 0.0);
  smooth[r] = 1.0;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    const int s = 1 << i;
    deriv[r + s] += weights[i] / wsum / (2.0 * s);
    deriv[r - s] -= weights[i] / wsum / (2.0 * s);
  }
  SeparableKernel k;
  k.first = -r;
  for (double d : deriv) k.deriv.push_back(float(d));
  for (double s : smooth) k.smooth.push_back(float(s));
  return k;
}

GradientKernel parse_gradient_kernel(std::string_view name) {
  for (const auto& e : table()) {
    if (name == e.name) return e.kind;
  }
  if (name == "sobel") return GradientKernel::sobel3;
  if (name == "prewitt") return GradientKernel::prewitt3;
  if (name == "scharr") return GradientKernel::scharr3;
  std::string valid;
  for (const auto& n : gradient_kernel_names()) valid += (valid.empty() ? "" : ", ") + n;
  throw Error(ErrorCode::bad_arguments, "unknown kernel '" + std::string(name) + "' (valid: " + valid + ")");
}

const char* to_string(GradientKernel k) {
  for (const auto& e : table()) {
    if (e.kind == k) return e.name;
  }
  return "?";
}

std::vector<std::string> gradient_kernel_names() {
  std::vector<std::string> v;
  for (const auto& e : table()) v.emplace_back(e.name);
  return v;
}

HeightChannel parse_height_channel(std::string_view n) {
  if (n == "auto") return HeightChannel::automatic;
  if (n == "r") return HeightChannel::r;
  if (n == "g") return HeightChannel::g;
  if (n == "b") return HeightChannel::b;
  if (n == "a") return HeightChannel::a;
  if (n == "luma") return HeightChannel::luma;
  throw Error(ErrorCode::bad_arguments,
              "unknown height channel '" + std::string(n) + "' (valid: auto, r, g, b, a, luma)");
}

NormalChannels parse_normal_channels(std::string_view n) {
  if (n == "xyz") return NormalChannels::xyz;
  if (n == "xy") return NormalChannels::xy;
  if (n == "xyzh") return NormalChannels::xyzh;
  throw Error(ErrorCode::bad_arguments, "unknown NormalChannels '" + std::string(n) + "' (valid: xyz, xy, xyzh)");
}

int channel_count(NormalChannels c) {
  switch (c) {
    case NormalChannels::xyz:
      return 3;
    case NormalChannels::xy:
      return 2;
    case NormalChannels::xyzh:
      return 4;
  }
  return 3;
}

}  // namespace texproc
