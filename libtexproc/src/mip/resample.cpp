// Polyphase weights and the scalar reference passes.
#include "mip/resample.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "texproc/runtime.h"

namespace texproc {

AxisWeights compute_axis_weights(int src_size, int dst_size, const Filter& filter) {
  assert(src_size > 0 && dst_size > 0);
  AxisWeights aw;
  aw.src_size = src_size;
  aw.dst_size = dst_size;
  aw.first.resize(dst_size);
  if (src_size == dst_size) {
    aw.taps = 1;
    aw.weights.assign(dst_size, 1.0f);
    for (int i = 0; i < dst_size; ++i) aw.first[i] = i;
    return aw;
  }
  const double s = double(src_size) / dst_size;
  // Shrinking widens the filter by the scale; enlarging keeps it one source
  // texel wide (a narrower one would fall between the texels).
  const double scale = std::max(s, 1.0);
  const double radius = filter_support(filter) * scale;

  // Collect each destination texel's weights in double, trimmed of zeros.
  std::vector<std::vector<double>> rows(dst_size);
  std::vector<int> firsts(dst_size);
  int taps = 1;
  for (int i = 0; i < dst_size; ++i) {
    const double c = (i + 0.5) * s - 0.5;
    int j0, j1;
    if (filter.kind == FilterKind::box) {
      // Footprint [c - s/2, c + s/2] in texel-centre coordinates; texel j
      // covers [j - 0.5, j + 0.5].
      j0 = int(std::floor(c - scale / 2 + 0.5));
      j1 = int(std::ceil(c + scale / 2 - 0.5));
    } else {
      j0 = int(std::ceil(c - radius));
      j1 = int(std::floor(c + radius));
    }
    std::vector<double> w;
    double sum = 0.0;
    for (int j = j0; j <= j1; ++j) {
      double v;
      if (filter.kind == FilterKind::box) {
        const double lo = std::max(j - 0.5, c - scale / 2), hi = std::min(j + 0.5, c + scale / 2);
        v = std::max(0.0, hi - lo);
      } else {
        v = filter_eval(filter, (j - c) / scale);
      }
      w.push_back(v);
      sum += v;
    }
    // Trim zero weights at both ends (tails of truncated or cubic kernels).
    int lead = 0;
    while (lead + 1 < int(w.size()) && w[lead] == 0.0) ++lead;
    int trail = int(w.size());
    while (trail - 1 > lead && w[trail - 1] == 0.0) --trail;
    w = std::vector<double>(w.begin() + lead, w.begin() + trail);
    if (sum == 0.0) {  // cannot happen for the supported filters; keep the centre
      w.assign(1, 1.0);
      sum = 1.0;
      lead = int(std::lround(c)) - j0;
    }
    for (double& v : w) v /= sum;
    firsts[i] = j0 + lead;
    rows[i] = std::move(w);
    taps = std::max(taps, int(rows[i].size()));
  }
  aw.taps = taps;
  aw.weights.assign(std::size_t(dst_size) * taps, 0.0f);
  for (int i = 0; i < dst_size; ++i) {
    aw.first[i] = firsts[i];
    for (std::size_t k = 0; k < rows[i].size(); ++k) aw.weights[std::size_t(i) * taps + k] = float(rows[i][k]);
    aw.pad_before = std::max(aw.pad_before, -firsts[i]);
    aw.pad_after = std::max(aw.pad_after, firsts[i] + taps - src_size);
  }
  return aw;
}

namespace ref {

void vertical_pass(const float* const* rows, const float* weights, int taps, int n, float* out) {
  for (int x = 0; x < n; ++x) {
    float acc = 0.0f;
    for (int k = 0; k < taps; ++k) acc = acc + weights[k] * rows[k][x];
    out[x] = acc;
  }
}

void horizontal_pass(const float* src, int channels, const int* first, const float* weights, int taps, int out_width,
                     float* out) {
  for (int i = 0; i < out_width; ++i) {
    const float* s = src + std::ptrdiff_t(first[i]) * channels;
    const float* w = weights + std::size_t(i) * taps;
    for (int c = 0; c < channels; ++c) {
      float acc = 0.0f;
      for (int k = 0; k < taps; ++k) acc = acc + w[k] * s[k * channels + c];
      out[i * channels + c] = acc;
    }
  }
}

}  // namespace ref
}  // namespace texproc
