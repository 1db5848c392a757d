// The scalar reference of bc1_lanes.h (namespace ref): what bc1_lanes_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "bc/bc1_lanes.h"
#include "block/principal_axis.h"
#include "block/quantize.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace texproc::ref {
namespace {

int quantize(float v, int max) { return quantize_channel(v, max); }  // block/quantize.h

// The palette of quantized endpoints qa, qb (four colours, or three: the
// average and no black); each texel's nearest entry (first of equals); the
// total squared error.
std::int32_t nearest(const int rgb[16][3], const bool clear[16], const int qa[3], const int qb[3], bool four,
                     int codes[16]) {
  int pal[4][3];
  for (int ch = 0; ch < 3; ++ch) {
    const int ea = ch == 1 ? (qa[ch] << 2 | qa[ch] >> 4) : (qa[ch] << 3 | qa[ch] >> 2);
    const int eb = ch == 1 ? (qb[ch] << 2 | qb[ch] >> 4) : (qb[ch] << 3 | qb[ch] >> 2);
    pal[0][ch] = ea;
    pal[1][ch] = eb;
    pal[2][ch] = four ? (2 * ea + eb + 1) / 3 : (ea + eb + 1) / 2;
    pal[3][ch] = (ea + 2 * eb + 1) / 3;
  }
  std::int32_t total = 0;
  for (int i = 0; i < 16; ++i) {
    if (clear[i]) {  // punch-through: transparent (index 3 of the three-colour mode), no error
      codes[i] = 3;
      continue;
    }
    std::int32_t be = 0;
    for (int k = 0; k < (four ? 4 : 3); ++k) {
      const std::int32_t dr = rgb[i][0] - pal[k][0], dg = rgb[i][1] - pal[k][1], db = rgb[i][2] - pal[k][2];
      const std::int32_t e = dr * dr + dg * dg + db * db;
      if (k == 0 || e < be) {
        be = e;
        codes[i] = k;
      }
    }
    total += be;
  }
  return total;
}

void endpoints(const float a[3], const float b[3], int qa[3], int qb[3]) {
  for (int ch = 0; ch < 3; ++ch) {
    const int max = ch == 1 ? 63 : 31;
    qa[ch] = quantize(a[ch], max);
    qb[ch] = quantize(b[ch], max);
  }
}

struct State {
  int qa[3], qb[3], codes[16];
  std::int32_t error;
};

// Least-squares endpoints for s's codes (weights by code in thirds, four
// colours: 0, 3, 1, 2; in halves, three: 0, 2, 1), quantized and scored;
// kept if better.
void refit(const int rgb[16][3], const bool clear[16], bool four, State& s) {
  const int den = four ? 3 : 2;
  std::int32_t aa = 0, ab = 0, bb = 0, at[3] = {}, bt[3] = {};
  for (int i = 0; i < 16; ++i) {
    if (clear[i] || (!four && s.codes[i] == 3)) continue;
    const int c = s.codes[i], w = c == 1 ? den : c == 0 ? 0 : c - 1, u = den - w;
    aa += u * u;
    ab += u * w;
    bb += w * w;
    for (int ch = 0; ch < 3; ++ch) {
      at[ch] += u * rgb[i][ch];
      bt[ch] += w * rgb[i][ch];
    }
  }
  const std::int32_t det = aa * bb - ab * ab;
  if (det == 0) return;
  float ra[3], rb[3];
  const float inv = 1.0f / float(det);
  for (int ch = 0; ch < 3; ++ch) {
    ra[ch] = std::clamp(float(den * (at[ch] * bb - bt[ch] * ab)) * inv, 0.0f, 255.0f);
    rb[ch] = std::clamp(float(den * (bt[ch] * aa - at[ch] * ab)) * inv, 0.0f, 255.0f);
  }
  State n;
  endpoints(ra, rb, n.qa, n.qb);
  n.error = nearest(rgb, clear, n.qa, n.qb, four, n.codes);
  if (n.error < s.error) s = n;
}

// Least-squares endpoints for the four-colour positions of each texel
// (weights w in thirds on the second endpoint); false if singular. `red`:
// the fit's reduction of the squared error (sum of squares minus the
// residual, unquantized).
bool fit_positions(const int rgb[16][3], const bool clear[16], const int w[16], float ra[3], float rb[3], float& red) {
  std::int32_t aa = 0, ab = 0, bb = 0, at[3] = {}, bt[3] = {};
  for (int i = 0; i < 16; ++i) {
    if (clear[i]) continue;
    const int u = 3 - w[i];
    aa += u * u;
    ab += u * w[i];
    bb += w[i] * w[i];
    for (int ch = 0; ch < 3; ++ch) {
      at[ch] += u * rgb[i][ch];
      bt[ch] += w[i] * rgb[i][ch];
    }
  }
  const std::int32_t det = aa * bb - ab * ab;
  if (det == 0) return false;
  const float inv = 1.0f / float(det);
  red = 0.0f;
  for (int ch = 0; ch < 3; ++ch) {
    const float x = float(at[ch]), y = float(bt[ch]);
    red += (x * x * float(bb) - 2.0f * x * y * float(ab) + y * y * float(aa)) * inv;
    ra[ch] = std::clamp(float(3 * (at[ch] * bb - bt[ch] * ab)) * inv, 0.0f, 255.0f);
    rb[ch] = std::clamp(float(3 * (bt[ch] * aa - at[ch] * ab)) * inv, 0.0f, 255.0f);
  }
  return true;
}

// Each quantized endpoint channel nudged by one step while that lowers the
// error (at most four passes over the twelve moves).
void nudge(const int rgb[16][3], const bool clear[16], bool four, State& s) {
  for (int pass = 0; pass < 4; ++pass) {
    bool improved = false;
    for (int m = 0; m < 12; ++m) {
      State n = s;
      // Through a pointer: GCC 12.2 miscompiles the index of `(c ? n.qa :
      // n.qb)[m % 6 / 2]` under -fsanitize=integer-divide-by-zero (and
      // shift, signed-integer-overflow): the asan preset's bytes differed.
      int* q = m < 6 ? n.qa : n.qb;
      int& v = q[m % 6 / 2];
      v += m % 2 ? 1 : -1;
      if (v < 0 || v > (m % 6 / 2 == 1 ? 63 : 31)) continue;
      n.error = nearest(rgb, clear, n.qa, n.qb, four, n.codes);
      if (n.error < s.error) {
        s = n;
        improved = true;
      }
    }
    if (!improved) break;
  }
}

// `high` for blocks with transparent texels (their only mode is the
// three-colour one): partition variants on halves of the extent (45, each a
// least-squares fit, scored and refitted), then one-step nudges of the
// quantized endpoints while they help (at most four passes).
void three_colour_search(const int rgb[16][3], const bool clear[16], float hi, float lo, const float proj[16],
                         State& t) {
  for (int o = -4; o <= 4; ++o)
    for (int sv = -2; sv <= 2; ++sv) {
      const float scale = hi > lo ? 2.0f * (1.0f + kVariantStep * float(sv)) / (hi - lo) : 0.0f;
      const float shift = 0.5f + kVariantStep * float(o) - kVariantStep * float(sv);
      std::int32_t aa = 0, ab = 0, bb = 0, at[3] = {}, bt[3] = {};
      for (int i = 0; i < 16; ++i) {
        if (clear[i]) continue;
        const int w = std::clamp(int(std::floor((hi - proj[i]) * scale + shift)), 0, 2), u = 2 - w;
        aa += u * u;
        ab += u * w;
        bb += w * w;
        for (int ch = 0; ch < 3; ++ch) {
          at[ch] += u * rgb[i][ch];
          bt[ch] += w * rgb[i][ch];
        }
      }
      const std::int32_t det = aa * bb - ab * ab;
      if (det == 0) continue;
      const float inv = 1.0f / float(det);
      float ra[3], rb[3];
      for (int ch = 0; ch < 3; ++ch) {
        ra[ch] = std::clamp(float(2 * (at[ch] * bb - bt[ch] * ab)) * inv, 0.0f, 255.0f);
        rb[ch] = std::clamp(float(2 * (bt[ch] * aa - at[ch] * ab)) * inv, 0.0f, 255.0f);
      }
      State n;
      endpoints(ra, rb, n.qa, n.qb);
      n.error = nearest(rgb, clear, n.qa, n.qb, false, n.codes);
      refit(rgb, clear, false, n);
      if (n.error < t.error) t = n;
    }
  nudge(rgb, clear, false, t);
}

// A block's texels (transparent ones as black, out of every sum) and where
// they lie along its principal axis.
struct Block {
  int rgb[16][3];
  bool clear[16];          // punch-through: transparent (index 3 of the three-colour mode)
  bool transparent;        // any texel clear: only the three-colour mode can have them
  float proj[16], lo, hi;  // each texel's projection; the opaque texels' extent
  float a[3], b[3];        // the extent's ends as colours
};

// False where the opaque texels are one colour, or there are none (the
// caller's): the covariance's diagonal is 0.
bool load(const std::uint32_t texel[16][kBc1Batch], int k, bool punch, Block& blk) {
  int n_opaque = 0;
  std::int32_t s[3] = {}, q[6] = {};
  for (int i = 0; i < 16; ++i) {
    const std::uint32_t t = texel[i][k];
    blk.clear[i] = punch && (t >> 24) < 128;
    // Transparent texels count as black in the sums (that is, not at all).
    const bool clear = blk.clear[i];
    const int r = clear ? 0 : int(t & 255), g = clear ? 0 : int(t >> 8 & 255), b = clear ? 0 : int(t >> 16 & 255);
    n_opaque += clear ? 0 : 1;
    blk.rgb[i][0] = r;
    blk.rgb[i][1] = g;
    blk.rgb[i][2] = b;
    s[0] += r;
    s[1] += g;
    s[2] += b;
    q[0] += r * r;
    q[1] += r * g;
    q[2] += r * b;
    q[3] += g * g;
    q[4] += g * b;
    q[5] += b * b;
  }
  // Covariance of the opaque texels times n^2 (exact).
  const int no = n_opaque;
  const std::int32_t c[6] = {no * q[0] - s[0] * s[0], no * q[1] - s[0] * s[1], no * q[2] - s[0] * s[2],
                             no * q[3] - s[1] * s[1], no * q[4] - s[1] * s[2], no * q[5] - s[2] * s[2]};
  blk.transparent = no < 16;
  if (c[0] == 0 && c[3] == 0 && c[5] == 0) return false;
  // The principal axis, each step scaled by the reciprocal of its largest
  // component (the SIMD twin's order: block/principal_axis.h).
  const float cov[6] = {float(c[0]), float(c[1]), float(c[2]), float(c[3]), float(c[4]), float(c[5])};
  float axis[3];
  principal_axis<AxisScaling::reciprocal>(cov, axis);
  float lo = 1e30f, hi = -1e30f;
  for (int i = 0; i < 16; ++i) {
    const float p = float(blk.rgb[i][0]) * axis[0] + float(blk.rgb[i][1]) * axis[1] + float(blk.rgb[i][2]) * axis[2];
    if (!blk.clear[i]) {
      lo = std::min(lo, p);
      hi = std::max(hi, p);
    }
    blk.proj[i] = p;
  }
  blk.lo = lo;
  blk.hi = hi;
  const float mean[3] = {float(s[0]) / float(no), float(s[1]) / float(no), float(s[2]) / float(no)};
  const float mean_p = mean[0] * axis[0] + mean[1] * axis[1] + mean[2] * axis[2];
  for (int ch = 0; ch < 3; ++ch) {
    blk.a[ch] = std::clamp(mean[ch] + (hi - mean_p) * axis[ch], 0.0f, 255.0f);
    blk.b[ch] = std::clamp(mean[ch] + (lo - mean_p) * axis[ch], 0.0f, 255.0f);
  }
  return true;
}

// `fast` (thirds_fit): each texel at the nearest third of the extent along
// the axis; one least-squares fit for those positions; then the nearest
// colours. st: the extent's ends on entry.
void thirds_fit(const Block& blk, State& st) {
  const float lo = blk.lo, hi = blk.hi;
  const float scale = hi > lo ? 3.0f / (hi - lo) : 0.0f;
  std::int32_t aa = 0, ab = 0, bb = 0, at[3] = {}, bt[3] = {};
  for (int i = 0; i < 16; ++i) {
    if (blk.clear[i]) continue;
    const int w = std::min(int((hi - blk.proj[i]) * scale + 0.5f), 3), u = 3 - w;
    aa += u * u;
    ab += u * w;
    bb += w * w;
    for (int ch = 0; ch < 3; ++ch) {
      at[ch] += u * blk.rgb[i][ch];
      bt[ch] += w * blk.rgb[i][ch];
    }
  }
  const std::int32_t det = aa * bb - ab * ab;
  if (det != 0) {
    float ra[3], rb[3];
    const float inv_det = 1.0f / float(det);
    for (int ch = 0; ch < 3; ++ch) {
      ra[ch] = std::clamp(float(3 * (at[ch] * bb - bt[ch] * ab)) * inv_det, 0.0f, 255.0f);
      rb[ch] = std::clamp(float(3 * (bt[ch] * aa - at[ch] * ab)) * inv_det, 0.0f, 255.0f);
    }
    endpoints(ra, rb, st.qa, st.qb);
  }
  st.error = nearest(blk.rgb, blk.clear, st.qa, st.qb, true, st.codes);
}

// Partition variants along the axis (a cluster fit's neighbourhood), four
// colours: `normal` ranks them by their unquantized error and scores the
// best two exactly; `high` (score_every_variant) scores every one, each
// refitted once. st is replaced where a variant wins.
void variants(const Block& blk, const Bc1LaneSearch& level, State& st) {
  const float lo = blk.lo, hi = blk.hi;
  const int offsets = level.variant_offsets, stretches = level.variant_stretches;
  float e1 = 0.0f, e2 = 0.0f;
  int have = 0, q1[2][3] = {}, q2[2][3] = {};
  for (int o = -offsets; o <= offsets; ++o)
    for (int sv = -stretches; sv <= stretches; ++sv) {
      const float scale = hi > lo ? 3.0f * (1.0f + kVariantStep * float(sv)) / (hi - lo) : 0.0f;
      const float shift = variant_shift(o, sv);
      int w[16];
      for (int i = 0; i < 16; ++i) w[i] = std::clamp(int(std::floor((hi - blk.proj[i]) * scale + shift)), 0, 3);
      float ra[3], rb[3], red;
      if (!fit_positions(blk.rgb, blk.clear, w, ra, rb, red)) continue;
      State n;
      endpoints(ra, rb, n.qa, n.qb);
      if (level.score_every_variant) {
        n.error = nearest(blk.rgb, blk.clear, n.qa, n.qb, true, n.codes);
        refit(blk.rgb, blk.clear, true, n);
        if (n.error < st.error) st = n;
        continue;
      }
      const float e = -red;  // less is better: the sum of squares is the same for every variant
      if (have == 0 || e < e1) {
        if (have > 0) {
          e2 = e1;
          std::copy(&q1[0][0], &q1[0][0] + 6, &q2[0][0]);
        }
        e1 = e;
        std::copy(n.qa, n.qa + 3, q1[0]);
        std::copy(n.qb, n.qb + 3, q1[1]);
        have = std::min(have + 1, 2);
      } else if (have == 1 || e < e2) {
        e2 = e;
        std::copy(n.qa, n.qa + 3, q2[0]);
        std::copy(n.qb, n.qb + 3, q2[1]);
        have = 2;
      }
    }
  for (int m = 0; m < have; ++m) {
    State n;
    std::copy((m ? q2 : q1)[0], (m ? q2 : q1)[0] + 3, n.qa);
    std::copy((m ? q2 : q1)[1], (m ? q2 : q1)[1] + 3, n.qb);
    n.error = nearest(blk.rgb, blk.clear, n.qa, n.qb, true, n.codes);
    if (n.error < st.error) st = n;
  }
}

// The block's bytes: four colours with c0 > c1 (swapping the ends flips the
// codes' low bit; equal ends: every code 0), three with c0 <= c1 (swapping
// exchanges codes 0 and 1).
void pack(const State& st, bool four, std::uint8_t out[8]) {
  std::uint32_t c0 = std::uint32_t(st.qa[0] << 11 | st.qa[1] << 5 | st.qa[2]);
  std::uint32_t c1 = std::uint32_t(st.qb[0] << 11 | st.qb[1] << 5 | st.qb[2]);
  const bool swap = four ? c0 < c1 : c0 > c1;
  std::uint32_t bits = 0;
  for (int i = 0; i < 16; ++i) {
    int code = st.codes[i];
    if (four && c0 == c1) code = 0;
    if (swap && (four || code < 2)) code ^= 1;
    bits |= std::uint32_t(code) << (2 * i);
  }
  if (swap) std::swap(c0, c1);
  const std::uint32_t head = c0 | c1 << 16;
  std::memcpy(out, &head, 4);  // little-endian hosts (as the rest of texproc)
  std::memcpy(out + 4, &bits, 4);
}

}  // namespace

void bc1_encode_lanes(const std::uint32_t texel[16][kBc1Batch], int count, const Bc1LaneSearch& level, bool three,
                      bool punch, std::uint8_t out[][8], bool handled[]) {
  for (int k = 0; k < count; ++k) {
    Block blk;
    handled[k] = load(texel, k, punch, blk);
    if (!handled[k]) continue;
    State st{};
    endpoints(blk.a, blk.b, st.qa, st.qb);
    const State start = st;
    bool four = true;
    if (level.thirds_fit) {
      thirds_fit(blk, st);
      if (blk.transparent) {  // the three-colour mode from the extent's ends, refitted once
        State t = start;
        t.error = nearest(blk.rgb, blk.clear, t.qa, t.qb, false, t.codes);
        refit(blk.rgb, blk.clear, false, t);
        st = t;
        four = false;
      }
    } else {
      st.error = nearest(blk.rgb, blk.clear, st.qa, st.qb, true, st.codes);
      refit(blk.rgb, blk.clear, true, st);
      refit(blk.rgb, blk.clear, true, st);
      variants(blk, level, st);
      nudge(blk.rgb, blk.clear, true, st);
      if (three || blk.transparent) {  // the three-colour mode from the extent's ends, refitted once
        State t = start;
        t.error = nearest(blk.rgb, blk.clear, t.qa, t.qb, false, t.codes);
        refit(blk.rgb, blk.clear, false, t);
        if (blk.transparent) refit(blk.rgb, blk.clear, false, t);  // the block's only mode: refitted twice
        if (blk.transparent && level.punch_variants)
          three_colour_search(blk.rgb, blk.clear, blk.hi, blk.lo, blk.proj, t);
        if (blk.transparent || t.error < st.error) {
          st = t;
          four = false;
        }
      }
    }
    pack(st, four, out[k]);
  }
}

}  // namespace texproc::ref
