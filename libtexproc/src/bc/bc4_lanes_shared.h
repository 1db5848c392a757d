// What both twins of the BC4 lane encoder use (bc4_lanes.cpp, the scalar
// reference, and bc4_lanes_simd.cpp): the block's values as the scoring
// wants them, the two modes' exact errors, the partition variants, the
// least-squares endpoints.
#pragma once

#include <algorithm>
#include <cmath>

namespace texproc::ref {

// A block's values as the candidates' scoring wants them: clamped (t),
// times 7 and times 5 (the two modes' palettes are multiples of 1/7 and
// 1/5), and the six-value mode's squared distance (times 25) to the
// nearer of the code range's ends, which that mode holds for free.
struct Values {
  float t[16], t7[16], t5[16], ends5[16];
};

// Squared error (code units) of the eight-value mode's endpoints r0 > r1:
// each value's palette position j from r0 by rounding (the palette is
// evenly spaced under the exact decoding), its error 7 times over, summed,
// then divided by 49. `pos`, where given, gets each j.
inline float error8(const Values& v, int r0, int r1, int* pos) {
  const float f0 = float(r0), span = float(r0 - r1), k = 7.0f / span, a = 7.0f * f0;
  float e = 0.0f;
  for (int i = 0; i < 16; ++i) {
    const float j = std::min(std::max(std::nearbyint((f0 - v.t[i]) * k), 0.0f), 7.0f);
    const float d = (v.t7[i] - a) + span * j;  // 7 * (value - palette entry j)
    e += d * d;
    if (pos) pos[i] = int(j);
  }
  return e / 49.0f;
}

// The six-value mode's (r0 <= r1), where a value also takes the nearer of
// the range's ends: 5 times over, then divided by 25. `pos` gets j, or -1
// where an end was nearer.
inline float error6(const Values& v, int r0, int r1, int* pos) {
  const float f0 = float(r0), span = float(r1 - r0), k = r1 > r0 ? 5.0f / span : 0.0f, a = 5.0f * f0;
  float e = 0.0f;
  for (int i = 0; i < 16; ++i) {
    const float j = std::min(std::max(std::nearbyint((v.t[i] - f0) * k), 0.0f), 5.0f);
    const float d = (v.t5[i] - a) - span * j;
    e += std::min(d * d, v.ends5[i]);
    if (pos) pos[i] = v.ends5[i] < d * d ? -1 : int(j);
  }
  return e / 25.0f;
}

// `high`'s partition variants: the values placed on the mode's grid
// between its starting endpoints, the grid shifted by `offset` steps of
// 0.15 and stretched by `stretch` steps of 10% about its middle, then a
// least-squares fit for those positions.
inline float variant_stretch(int stretch) { return 1.0f + 0.1f * float(stretch); }
inline float variant_shift(int offset, int stretch, int steps) {
  return 0.5f + 0.15f * float(offset) - 0.1f * float(stretch) * float(steps) * 0.5f;
}

// Least-squares endpoints for the sums of a position set (u = steps - pos
// and pos weigh the two endpoints), rounded and clamped to [lo, hi]; the
// six-value mode's (mode 1) in ascending order. False where there is no
// solution, or where the eight-value mode's (mode 0) fit left that mode.
inline bool ls_endpoints(int aa, int ab, int bb, float at, float bt, int steps, int mode, int lo, int hi, int& ia,
                         int& ib) {
  const int det = aa * bb - ab * ab;
  if (det == 0) return false;
  const float fa = float(steps) * (at * float(bb) - bt * float(ab)) / float(det);
  const float fb = float(steps) * (bt * float(aa) - at * float(ab)) / float(det);
  ia = std::clamp(int(std::floor(fa + 0.5f)), lo, hi);
  ib = std::clamp(int(std::floor(fb + 0.5f)), lo, hi);
  if (mode == 1 && ia > ib) std::swap(ia, ib);
  return mode == 1 || ia > ib;
}

}  // namespace texproc::ref
