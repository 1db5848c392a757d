// The scalar reference of bc4_lanes.h (namespace ref): what bc4_lanes_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
// One block at a time, in the twin's stages (Bc4Batch): load, start, refine,
// window_at, variants, codes.
#include "bc/bc4_lanes.h"
#include "bc/bc4_lanes_shared.h"

#include <algorithm>
#include <cmath>

namespace texproc::ref {
namespace {

struct Bc4Block {
  const float lo_code, hi_code;
  const int lo_int, hi_int;
  Values val;
  const float* t = val.t;
  float mn = 0, mx = 0, mn6 = 0, mx6 = 0;
  int lo = 0, hi = 0;    // the range rounded outwards
  int lo6 = 0, hi6 = 0;  // the inner values' range (six-value mode)
  int r0 = 0, r1 = 0;    // the best pair so far and its error
  float error = 0.0f;

  explicit Bc4Block(bool snorm)
      : lo_code(snorm ? -127.0f : 0.0f),
        hi_code(snorm ? 127.0f : 255.0f),
        lo_int(snorm ? -127 : 0),
        hi_int(snorm ? 127 : 255) {}

  // Block k's values clamped to the codes, with the products the errors
  // use, and the ranges of all values and of the inner ones.
  void load(const float v[16][kBc4Batch], int k) {
    mn = hi_code;
    mx = lo_code;
    mn6 = hi_code;
    mx6 = lo_code;
    for (int i = 0; i < 16; ++i) {
      val.t[i] = std::min(std::max(v[i][k], lo_code), hi_code);
      val.t7[i] = 7.0f * t[i];
      val.t5[i] = 5.0f * t[i];
      const float dl = val.t5[i] - 5.0f * lo_code;
      const float dh = val.t5[i] - 5.0f * hi_code;
      val.ends5[i] = std::min(dl * dl, dh * dh);
      mn = std::min(mn, t[i]);
      mx = std::max(mx, t[i]);
      if (t[i] > lo_code + 0.5f && t[i] < hi_code - 0.5f) {
        mn6 = std::min(mn6, t[i]);
        mx6 = std::max(mx6, t[i]);
      }
    }
  }

  float error_of(int a, int b, int* pos = nullptr) const {
    return a > b ? error8(val, a, b, pos) : error6(val, a, b, pos);
  }

  // The range (equal ends: one value, exact in the six-value mode); the
  // palette of whole code steps over a narrow range; the six-value mode over
  // the inner values.
  void start() {
    lo = int(std::floor(mn));
    hi = int(std::ceil(mx));
    r0 = hi > lo ? hi : lo;
    r1 = lo;
    error = hi > lo ? error8(val, r0, r1, nullptr) : 0.0f;
    if (hi > lo && hi - lo < 7) {  // a narrow range: also the palette of whole code steps over it (8-bit levels: exact)
      const int b = std::min(lo, hi_int - 7);
      const float e7 = error8(val, b + 7, b, nullptr);
      if (e7 < error) {
        error = e7;
        r0 = b + 7;
        r1 = b;
      }
    }
    const bool inner = mn6 <= mx6;
    lo6 = inner ? int(std::floor(mn6)) : lo;
    hi6 = inner ? int(std::ceil(mx6)) : hi;
    if (inner && (lo6 != lo || hi6 != hi)) {
      const float error6 = error_of(lo6, hi6);
      if (error6 < error) {
        error = error6;
        r0 = lo6;
        r1 = hi6;
      }
    }
  }

  // In `mode` (0: eight values from the range, 1: six from the inner
  // range): least-squares endpoints for the codes (steps of 1/7 or 1/5 from
  // m0; the six-value mode's ends left out), then codes for the endpoints,
  // twice while that helps; (m0, m1) the result, taken where it beats the
  // best so far.
  void refine(int mode, int& m0, int& m1) {
    const int steps = mode == 0 ? 7 : 5;
    m0 = mode == 0 ? hi : lo6;
    m1 = mode == 0 ? lo : std::max(lo6, hi6);
    int pos[16];
    float me = error_of(m0, m1, pos);
    for (int iter = 0; iter < 2; ++iter) {
      int aa = 0;
      int ab = 0;
      int bb = 0;
      float at = 0.0f;
      float bt = 0.0f;
      for (int i = 0; i < 16; ++i) {
        if (pos[i] < 0) continue;
        const int u = steps - pos[i];
        aa += u * u;
        ab += u * pos[i];
        bb += pos[i] * pos[i];
        at += float(u) * t[i];
        bt += float(pos[i]) * t[i];
      }
      int ia;
      int ib;
      int cp[16];
      if (!ls_endpoints(aa, ab, bb, at, bt, steps, mode, lo_int, hi_int, ia, ib)) break;
      const float ce = error_of(ia, ib, cp);
      if (ce >= me) break;
      m0 = ia;
      m1 = ib;
      me = ce;
      std::copy(cp, cp + 16, pos);
    }
    if (me < error) {
      error = me;
      r0 = m0;
      r1 = m1;
    }
  }

  // Every pair within +-w of (c0, c1) in `mode` (w = 0: the pair itself).
  void window_at(int mode, int c0, int c1, int w) {
    for (int a = c0 - w; a <= c0 + w; ++a) {
      for (int b = c1 - w; b <= c1 + w; ++b) {
        if (w > 0 && a == c0 && b == c1) continue;  // the centre, scored already
        if ((mode == 0) != (a > b) || a < lo_int || a > hi_int || b < lo_int || b > hi_int) continue;
        const float ce = error_of(a, b);
        if (ce < error) {
          error = ce;
          r0 = a;
          r1 = b;
        }
      }
    }
  }

  // `high`: partition variants in `mode` from its starting endpoints: each
  // value's place on the mode's grid between them, shifted and stretched,
  // and each such position set's least-squares pair scored.
  void variants(int mode, const Bc4LaneSearch& level) {
    const int steps = mode == 0 ? 7 : 5;
    const float a0 = float(mode == 0 ? hi : lo6);
    const float a1 = float(mode == 0 ? lo : hi6);
    if (a0 == a1) return;
    // Each value's place on the grid in steps from a0; the six-value mode
    // leaves out the values at the range's free ends.
    float base[16];
    float sum_t = 0.0f;
    bool in[16];
    int n_in = 0;
    for (int i = 0; i < 16; ++i) {
      base[i] = (a0 - t[i]) / (a0 - a1) * float(steps);
      in[i] = mode == 0 || (t[i] > lo_code + 0.5f && t[i] < hi_code - 0.5f);
      if (in[i]) {
        sum_t += t[i];
        ++n_in;
      }
    }
    for (int o = -level.variant_offsets; o <= level.variant_offsets; ++o) {
      for (int sv = -level.variant_stretches; sv <= level.variant_stretches; ++sv) {
        const float stretch = variant_stretch(sv);
        const float shift = variant_shift(o, sv, steps);
        // The sums of the positions p, their squares and p * t (exact small
        // integers but the last) give the fit's sums, with u = steps - p.
        float sp = 0.0f;
        float spp = 0.0f;
        float spt = 0.0f;
        for (int i = 0; i < 16; ++i) {
          const float p = in[i] ? std::min(std::max(std::floor(base[i] * stretch + shift), 0.0f), float(steps)) : 0.0f;
          sp += p;
          spp += p * p;
          spt += p * t[i];
        }
        const int isp = int(sp);
        const int ispp = int(spp);
        const int aa = n_in * steps * steps - 2 * steps * isp + ispp;
        const int ab = steps * isp - ispp;
        const int bb = ispp;
        int ia;
        int ib;
        if (ls_endpoints(aa, ab, bb, float(steps) * sum_t - spt, spt, steps, mode, lo_int, hi_int, ia, ib)) {
          window_at(mode, ia, ib, 0);
        }
      }
    }
  }

  // The codes of the chosen endpoints, as their error counted them, and the
  // block's bytes.
  void codes(std::uint8_t out[8]) const {
    int pos[16];
    int code[16];
    error_of(r0, r1, pos);
    const bool eight = r0 > r1;
    for (int i = 0; i < 16; ++i) {
      const int top = eight ? 7 : 5;
      code[i] = pos[i] == 0 ? 0 : pos[i] == top ? 1 : pos[i] + 1;
      if (pos[i] < 0) {  // the six-value mode's nearer end: 0 (code 6) or 255 (code 7)
        const float dl = t[i] - lo_code;
        const float dh = t[i] - hi_code;
        code[i] = dh * dh < dl * dl ? 7 : 6;
      }
    }
    out[0] = std::uint8_t(r0 & 255);
    out[1] = std::uint8_t(r1 & 255);  // SNORM: two's complement
    std::uint64_t bits = 0;
    for (int i = 0; i < 16; ++i) bits |= std::uint64_t(code[i]) << (3 * i);
    for (int b = 0; b < 6; ++b) out[2 + b] = std::uint8_t(bits >> (8 * b));
  }
};

}  // namespace

void bc4_encode_lanes(const float v[16][kBc4Batch], int count, bool snorm, const Bc4LaneSearch& level,
                      std::uint8_t out[][8]) {
  for (int k = 0; k < count; ++k) {
    Bc4Block b(snorm);
    b.load(v, k);
    b.start();
    if (level.refine && b.error > 0.0f) {
      for (int mode = 0; mode < 2; ++mode) {  // 0: eight values, 1: six
        if (mode == 0 && b.hi <= b.lo) continue;
        int m0;
        int m1;
        b.refine(mode, m0, m1);
        // The window around the refined endpoints (+-1, `high` +-2).
        b.window_at(mode, m0, m1, level.window);
        if (level.variants) b.variants(mode, level);
      }
    }
    b.codes(out[k]);
  }
}

}  // namespace texproc::ref
