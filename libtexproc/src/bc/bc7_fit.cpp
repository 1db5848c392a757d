// The scalar reference of BC7's endpoint fit (bc7_fit.h): what
// bc7_fit_simd-inl.h computes a lane at a time.
#include "bc/bc7_fit.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>

#include "bc/axis_residual.h"

namespace texproc::ref::bc7_fit {
using bc7::EndpointFormat;
using bc7::Pbit;

// The endpoints from the set's principal axis: the texels' extent along it.
void line_ends(const Set& s, float e[2][4]) {
  int cnt = 0, S[4] = {}, Q[16] = {};  // Q[4 * a + b], a <= b: the sums of products
  int mn[4] = {255, 255, 255, 255}, mx[4] = {};
  for (int i = 0; i < 16; ++i) {
    if (!s.has(i)) continue;
    ++cnt;
    for (int a = 0; a < s.n; ++a) {
      const int xa = s.x[i][s.c0 + a];
      S[a] += xa;
      mn[a] = std::min(mn[a], xa);
      mx[a] = std::max(mx[a], xa);
      for (int b = a; b < s.n; ++b) Q[4 * a + b] += xa * s.x[i][s.c0 + b];
    }
  }
  float mean[4];
  for (int a = 0; a < s.n; ++a) mean[a] = float(S[a]) / float(cnt);
  if (s.n == 1) {
    e[0][s.c0] = float(mn[0]);
    e[1][s.c0] = float(mx[0]);
    return;
  }
  float C[4][4] = {};
  for (int a = 0; a < s.n; ++a)
    for (int b = a; b < s.n; ++b) C[a][b] = C[b][a] = float(cnt * Q[4 * a + b] - S[a] * S[b]);
  int jmax = 0;
  for (int a = 1; a < s.n; ++a)
    if (C[a][a] > C[jmax][jmax]) jmax = a;
  if (C[jmax][jmax] == 0.0f) {  // one colour
    for (int a = 0; a < s.n; ++a) e[0][s.c0 + a] = e[1][s.c0 + a] = mean[a];
    return;
  }
  float v[4];
  for (int a = 0; a < s.n; ++a) v[a] = C[a][jmax];
  for (int it = 0; it < 3; ++it) {
    float w[4], m = 0.0f;
    for (int a = 0; a < s.n; ++a) {
      w[a] = 0.0f;
      for (int b = 0; b < s.n; ++b) w[a] += C[a][b] * v[b];
      m = std::max(m, std::fabs(w[a]));
    }
    if (m == 0.0f) break;
    const float inv = 1.0f / m;
    for (int a = 0; a < s.n; ++a) v[a] = w[a] * inv;
  }
  float tmin = INFINITY, tmax = -INFINITY, tmean = 0.0f, vv = 0.0f;
  for (int i = 0; i < 16; ++i) {
    if (!s.has(i)) continue;
    float t = 0.0f;
    for (int a = 0; a < s.n; ++a) t += v[a] * float(s.x[i][s.c0 + a]);
    tmin = std::min(tmin, t);
    tmax = std::max(tmax, t);
  }
  for (int a = 0; a < s.n; ++a) {
    tmean += v[a] * mean[a];
    vv += v[a] * v[a];
  }
  const float s0 = (tmin - tmean) / vv, s1 = (tmax - tmean) / vv;
  for (int a = 0; a < s.n; ++a) {
    e[0][s.c0 + a] = mean[a] + s0 * v[a];
    e[1][s.c0 + a] = mean[a] + s1 * v[a];
  }
}

namespace {

// Float endpoints to the format's codes: each channel rounded to 8 bits,
// then the nearest code; the p-bit that quantizes the endpoint (unique) or
// both endpoints (shared) with less error, ties to 0; 1 where forced.
// `combo` >= 0: endpoint k's p-bit is bit k of it (shared: bit 0) instead.
void quantize_ends(const Set& s, const float e[2][4], EndpointFormat f, bool force_p1, SetFit& fit, int combo = -1) {
  int v[2][4];
  for (int k = 0; k < 2; ++k)
    for (int a = 0; a < s.n; ++a) v[k][a] = int(std::nearbyint(std::min(std::max(e[k][s.c0 + a], 0.0f), 255.0f)));
  auto error = [&](int k, int p) {
    int t = 0;
    for (int a = 0; a < s.n; ++a) {
      const int d = bc7::quantize(f.bits, p, v[k][a]).value - v[k][a];
      t += d * d;
    }
    return t;
  };
  int p[2] = {-1, -1};
  if (f.pbit != Pbit::none && force_p1) {
    p[0] = p[1] = 1;
  } else if (f.pbit != Pbit::none && combo >= 0) {
    p[0] = combo & 1;
    p[1] = f.pbit == Pbit::unique ? combo >> 1 & 1 : p[0];
  } else if (f.pbit == Pbit::unique) {
    for (int k = 0; k < 2; ++k) p[k] = error(k, 1) < error(k, 0) ? 1 : 0;
  } else if (f.pbit == Pbit::shared) {
    p[0] = p[1] = error(0, 1) + error(1, 1) < error(0, 0) + error(1, 0) ? 1 : 0;
  }
  for (int k = 0; k < 2; ++k) {
    fit.pbit[k] = std::max(p[k], 0);
    for (int a = 0; a < s.n; ++a) {
      const bc7::Quantized q = bc7::quantize(f.bits, p[k], v[k][a]);
      fit.code[k][s.c0 + a] = q.code;
      fit.value[k][s.c0 + a] = q.value;
    }
  }
}

}  // namespace

// Each member's index for the fit's endpoints: its projection onto their
// line, rounded; with `exact`, the neighbouring index on either side where
// it decodes closer (the lower one tried first). The error over the set.
void assign(const Set& s, int bits, bool exact, SetFit& fit) {
  const int L = (1 << bits) - 1;
  int d[4], dd = 0, pal[16][4];
  for (int a = 0; a < s.n; ++a) {
    d[a] = fit.value[1][s.c0 + a] - fit.value[0][s.c0 + a];
    dd += d[a] * d[a];
  }
  for (int j = 0; j <= L; ++j)
    for (int a = 0; a < s.n; ++a)
      pal[j][a] = bptc::interpolate(fit.value[0][s.c0 + a], fit.value[1][s.c0 + a], bptc::weights(bits)[j]);
  const float scale = dd > 0 ? float(L) / float(dd) : 0.0f;
  auto texel_error = [&](int i, int j) {
    int t = 0;
    for (int a = 0; a < s.n; ++a) {
      const int e = pal[j][a] - s.x[i][s.c0 + a];
      t += e * e;
    }
    return t;
  };
  fit.error = 0;
  for (int i = 0; i < 16; ++i) {
    if (!s.has(i)) continue;
    int t = 0;
    for (int a = 0; a < s.n; ++a) t += (s.x[i][s.c0 + a] - fit.value[0][s.c0 + a]) * d[a];
    int j = std::clamp(int(std::nearbyint(float(t) * scale)), 0, L);
    int e = texel_error(i, j);
    if (exact) {
      const int j0 = j;
      for (const int jj : {j0 - 1, j0 + 1}) {
        if (jj < 0 || jj > L) continue;
        const int ee = texel_error(i, jj);
        if (ee < e) {
          e = ee;
          j = jj;
        }
      }
    }
    fit.index[i] = std::uint8_t(j);
    fit.error += e;
  }
}

namespace {

// The weights' sums least squares solves with (out of 64): also the
// quadratic form of the error of other ends for the same indices.
struct LsqSums {
  int AA = 0, AB = 0, BB = 0;
};

// Least-squares endpoints for the fit's indices (weights out of 64); false
// where they are not determined (every index the same).
bool lsq_ends(const Set& s, int bits, const SetFit& fit, float e[2][4], LsqSums& q) {
  int RA[4] = {}, RB[4] = {};
  for (int i = 0; i < 16; ++i) {
    if (!s.has(i)) continue;
    const int b = bptc::weights(bits)[fit.index[i]], a = 64 - b;
    q.AA += a * a;
    q.AB += a * b;
    q.BB += b * b;
    for (int c = 0; c < s.n; ++c) {
      RA[c] += a * s.x[i][s.c0 + c];
      RB[c] += b * s.x[i][s.c0 + c];
    }
  }
  const float det = float(q.AA) * float(q.BB) - float(q.AB) * float(q.AB);
  if (!(det > 0.0f)) return false;
  const float inv = 64.0f / det;
  for (int c = 0; c < s.n; ++c) {
    e[0][s.c0 + c] = (float(RA[c]) * float(q.BB) - float(RB[c]) * float(q.AB)) * inv;
    e[1][s.c0 + c] = (float(RB[c]) * float(q.AA) - float(RA[c]) * float(q.AB)) * inv;
  }
  return true;
}

// Least-squares ends quantized jointly (level.joint): for the indices that
// gave them (sums q), each p-bit choice, and in it, channel by channel, the
// pair of codes (each end's nearest code and the next one on the end's
// other side) of least error for those indices. That error, 64^2 times,
// is the quadratic's value at the least-squares ends plus (y - e)' H (y - e)
// for decoded ends y (H = [AA AB; AB BB]), so only the second term is
// compared (the decoder's rounding left out). The first of least error kept.
void quantize_joint(const Set& s, const float e[2][4], const LsqSums& q, EndpointFormat f, bool force_p1, SetFit& fit) {
  const int top = (1 << f.bits) - 1;
  const int combos = f.pbit == Pbit::none || force_p1 ? 1 : f.pbit == Pbit::unique ? 4 : 2;
  const float AA = float(q.AA), AB2 = 2.0f * float(q.AB), BB = float(q.BB);
  float best = INFINITY;
  for (int combo = 0; combo < combos; ++combo) {
    int p[2] = {-1, -1};
    if (f.pbit != Pbit::none) {
      p[0] = force_p1 ? 1 : combo & 1;
      p[1] = force_p1 ? 1 : f.pbit == Pbit::unique ? combo >> 1 & 1 : p[0];
    }
    int code[2][4] = {}, value[2][4] = {};
    float total = 0.0f;
    for (int a = 0; a < s.n; ++a) {
      int cand[2][2], val[2][2];
      for (int k = 0; k < 2; ++k) {
        const int v = int(std::nearbyint(std::min(std::max(e[k][s.c0 + a], 0.0f), 255.0f)));
        const bc7::Quantized n = bc7::quantize(f.bits, p[k], v);
        const int alt = std::clamp(n.value < v ? n.code + 1 : n.code - 1, 0, top);
        cand[k][0] = n.code;
        val[k][0] = n.value;
        cand[k][1] = alt;
        val[k][1] = bc7::expand(alt, f.bits, p[k]);
      }
      float least = INFINITY;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          const float d0 = float(val[0][i]) - e[0][s.c0 + a], d1 = float(val[1][j]) - e[1][s.c0 + a];
          const float t = AA * d0 * d0 + AB2 * d0 * d1 + BB * d1 * d1;
          if (t < least) {
            least = t;
            code[0][a] = cand[0][i];
            code[1][a] = cand[1][j];
            value[0][a] = val[0][i];
            value[1][a] = val[1][j];
          }
        }
      total += least;
    }
    if (!(total < best)) continue;
    best = total;
    for (int k = 0; k < 2; ++k) {
      fit.pbit[k] = std::max(p[k], 0);
      for (int a = 0; a < s.n; ++a) {
        fit.code[k][s.c0 + a] = code[k][a];
        fit.value[k][s.c0 + a] = value[k][a];
      }
    }
  }
}

// The ends quantized and the indices assigned: the nearest p-bits, or with
// level.pbit_search every p-bit choice after them, the first of least
// error kept.
void quantize_assign(const Set& s, const float e[2][4], EndpointFormat f, int bits, bool force_p1,
                     const Bc7Level& level, SetFit& fit) {
  quantize_ends(s, e, f, force_p1, fit);
  assign(s, bits, level.exact_indices, fit);
  if (!level.pbit_search || f.pbit == Pbit::none || force_p1) return;
  for (int combo = 0; combo < (f.pbit == Pbit::unique ? 4 : 2); ++combo) {
    SetFit next = fit;
    quantize_ends(s, e, f, false, next, combo);
    assign(s, bits, level.exact_indices, next);
    if (next.error < fit.error) fit = next;
  }
}

// Seed `seed` of a fit (level.seeds): 0, the line's ends; 1, its high end
// moved out by one index step of L (the extent spans L - 1 steps, so the
// highest texels fall on index L - 1); 2, its low end; 3, both (L - 2
// steps). (Seed 0 is the line itself, not line[0] + 1 * (line[1] - line[0]).)
void seed_ends(const Set& s, const float line[2][4], int seed, int L, float e[2][4]) {
  const int lo = seed >> 1 & 1, hi = seed & 1, inside = L - lo - hi;
  const float f0 = -float(lo) / float(inside), f1 = float(hi) / float(inside) + 1.0f;
  for (int a = s.c0; a < s.c0 + s.n; ++a) {
    const float d = line[1][a] - line[0][a];
    e[0][a] = seed == 0 ? line[0][a] : line[0][a] + f0 * d;
    e[1][a] = seed == 0 ? line[1][a] : line[0][a] + f1 * d;
  }
}

}  // namespace

// One index set fitted from one seed: its ends quantized, then up to
// level.refine least-squares rounds while the error falls.
SetFit fit_seed(const Set& s, const float line[2][4], int seed, EndpointFormat f, int bits, bool force_p1,
                const Bc7Level& level) {
  float e[2][4] = {};
  seed_ends(s, line, seed, (1 << bits) - 1, e);
  SetFit fit;
  quantize_assign(s, e, f, bits, force_p1, level, fit);
  for (int pass = 0; pass < level.refine && fit.error > 0; ++pass) {
    LsqSums q;
    if (!lsq_ends(s, bits, fit, e, q)) break;
    SetFit next;
    if (level.joint) {
      quantize_joint(s, e, q, f, force_p1, next);
      assign(s, bits, level.exact_indices, next);
    } else {
      quantize_assign(s, e, f, bits, force_p1, level, next);
    }
    if (next.error >= fit.error) break;
    fit = next;
  }
  return fit;
}

// One index set fitted from each of level.seeds seeds, the seed of least
// error kept (the first of equal ones), then its steps (level.perturb).
SetFit fit_set(const Set& s, EndpointFormat f, int bits, bool force_p1, const Bc7Level& level) {
  float line[2][4] = {};
  line_ends(s, line);
  SetFit best;
  for (int seed = 0; seed < std::max(level.seeds, 1); ++seed) {
    const SetFit fit = fit_seed(s, line, seed, f, bits, force_p1, level);
    if (seed == 0 || fit.error < best.error) best = fit;
    if (best.error == 0) break;
  }
  step_ends(s, f, bits, level, level.exact_indices, level.perturb, best);
  return best;
}

// Each code one step either way, channel by channel, kept where it helps
// (with level.pair_steps, then a channel's two codes moved together);
// up to `rounds` rounds while one does; indices assigned `exact` or not.
void step_ends(const Set& s, EndpointFormat f, int bits, const Bc7Level& level, bool exact, int rounds, SetFit& best) {
  const int top = (1 << f.bits) - 1;
  for (int round = 0; round < rounds && best.error > 0; ++round) {
    bool moved = false;
    auto keep_if_better = [&](SetFit& next) {
      assign(s, bits, exact, next);
      if (next.error < best.error) {
        best = next;
        moved = true;
      }
    };
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < s.n; ++a)
        for (const int step : {-1, 1}) {
          const int code = best.code[k][s.c0 + a] + step;
          if (code < 0 || code > top) continue;
          SetFit next = best;
          next.code[k][s.c0 + a] = code;
          next.value[k][s.c0 + a] = bc7::expand(code, f.bits, f.pbit == Pbit::none ? -1 : best.pbit[k]);
          keep_if_better(next);
        }
    if (level.pair_steps)
      for (int a = 0; a < s.n; ++a)
        for (const int step : {0, 1, 2, 3}) {  // both up, both down, apart, together
          SetFit next = best;
          bool valid = true;
          for (int k = 0; k < 2; ++k) {
            const int dk = step == 0 ? 1 : step == 1 ? -1 : (step == 2) == (k == 1) ? 1 : -1;
            const int code = best.code[k][s.c0 + a] + dk;
            valid = valid && code >= 0 && code <= top;
            next.code[k][s.c0 + a] = code;
            if (valid) next.value[k][s.c0 + a] = bc7::expand(code, f.bits, f.pbit == Pbit::none ? -1 : best.pbit[k]);
          }
          if (valid) keep_if_better(next);
        }
    if (!moved) break;
  }
}

}  // namespace texproc::ref::bc7_fit
