// The scalar reference of etc_lanes.h (namespace ref): what etc_lanes_simd.cpp, its
// Highway twin, must equal byte for byte (tests compare them on every target).
#include "etc/etc_lanes.h"
#include "etc/etc_lanes_shared.h"

#include <algorithm>
#include <cstdlib>

#include "etc/etc_tables.h"

namespace texproc::etc {
namespace ref {
namespace {

struct HalfFit {
  int err, q[3], table, idx[8];
};

HalfFit fit(const int rgb[16][3], int h, int bits, int t0, const int* fixed_q = nullptr) {
  HalfFit best{};
  best.err = -1;
  int sum[3] = {};
  for (int i = 0; i < 8; ++i)
    for (int c = 0; c < 3; ++c) sum[c] += rgb[fast::kHalf[h][i]][c];
  int base[3];
  for (int c = 0; c < 3; ++c) {
    best.q[c] = fixed_q ? fixed_q[c] : fast::quantize_sum(sum[c], bits);
    base[c] = bits == 5 ? extend5(best.q[c]) : extend4(best.q[c]);
  }
  // Each texel's distance from the base (squared) and its R + G + B
  // offset: the modifier m costs d2 - 2 m dl + 3 m^2 (unclamped), least at
  // the modifier nearest dl / 3.
  int d2[8], dl[8];
  for (int i = 0; i < 8; ++i) {
    const int* px = rgb[fast::kHalf[h][i]];
    const int dr = px[0] - base[0], dg = px[1] - base[1], db = px[2] - base[2];
    d2[i] = dr * dr + dg * dg + db * db;
    dl[i] = dr + dg + db;
  }
  // Beside the tables around the spread's, the one whose far modifier
  // reaches the farthest texel: a half of dark texels and one bright one
  // (line art, text) needs a far modifier that the spread does not suggest.
  int reach = 0, t_far = 0;
  for (int i = 0; i < 8; ++i) reach = std::max(reach, std::abs(dl[i]));
  for (int t = 1; t < 8; ++t)
    if (std::abs(3 * kModifiers[t][1] - reach) < std::abs(3 * kModifiers[t_far][1] - reach)) t_far = t;
  for (int dt = -1; dt <= 1; ++dt) {
    const int t = dt == -1 && t_far > t0 + 1 ? t_far : std::clamp(t0 + dt, 0, 7), a = kModifiers[t][0],
              b = kModifiers[t][1];
    int err = 0, idx[8];
    for (int i = 0; i < 8; ++i) {
      const bool up = dl[i] >= 0, far = up ? 2 * dl[i] > 3 * (a + b) : 2 * dl[i] < -3 * (a + b);
      const int m = up ? (far ? b : a) : (far ? -b : -a);
      idx[i] = up ? (far ? 1 : 0) : (far ? 3 : 2);
      err += d2[i] + m * (3 * m - 2 * dl[i]);
    }
    if (best.err < 0 || err < best.err) {
      best.err = err;
      best.table = t;
      std::copy(idx, idx + 8, best.idx);
    }
  }
  return best;
}

// Exact score of base q (4 or 5 bits) with table t for half h: each texel
// at its best modifier under the decoder's clamping (the first of equals).
HalfFit eval_exact(const int rgb[16][3], int h, const int q[3], int bits, int t) {
  HalfFit f{};
  int pal[4][3];
  for (int c = 0; c < 3; ++c) {
    f.q[c] = q[c];
    const int base = bits == 5 ? extend5(q[c]) : extend4(q[c]);
    for (int k = 0; k < 4; ++k) pal[k][c] = clamp255(base + kModifiers[t][k]);
  }
  f.table = t;
  for (int i = 0; i < 8; ++i) {
    const int* px = rgb[fast::kHalf[h][i]];
    int be = 0;
    for (int k = 0; k < 4; ++k) {
      const int dr = px[0] - pal[k][0], dg = px[1] - pal[k][1], db = px[2] - pal[k][2];
      const int e = dr * dr + dg * dg + db * db;
      if (k == 0 || e < be) {
        be = e;
        f.idx[i] = k;
      }
    }
    f.err += be;
  }
  return f;
}

}  // namespace

void etc1_fast_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool differential_only,
                     std::uint8_t out[][8]) {
  for (int k = 0; k < count; ++k) {
    int rgb[16][3];
    for (int i = 0; i < 16; ++i) {
      const std::uint32_t t = texel[i][k];
      rgb[i][0] = int(t & 255);
      rgb[i][1] = int(t >> 8 & 255);
      rgb[i][2] = int(t >> 16 & 255);
    }
    int t0[4];
    for (int h = 0; h < 4; ++h) {
      int total = 0, spread = 0;
      for (int i = 0; i < 8; ++i)
        total += rgb[fast::kHalf[h][i]][0] + rgb[fast::kHalf[h][i]][1] + rgb[fast::kHalf[h][i]][2];
      for (int i = 0; i < 8; ++i) {
        const int* px = rgb[fast::kHalf[h][i]];
        spread += std::abs(8 * (px[0] + px[1] + px[2]) - total);
      }
      t0[h] = 0;
      for (int t = 1; t < 8; ++t)
        if (std::abs(fast::kMid96[t] - spread) < std::abs(fast::kMid96[t0[h]] - spread)) t0[h] = t;
    }
    HalfFit f5[4], f4[4];
    for (int h = 0; h < 4; ++h) f5[h] = fit(rgb, h, 5, t0[h]);
    fast::Params best{};
    int best_err = -1;
    for (int flip = 0; flip < 2; ++flip) {
      const int a = 2 * flip, b = a + 1;
      const bool fits = fast::delta_reaches(f5[a].q, f5[b].q);
      const HalfFit* pa = &f5[a];
      const HalfFit* pb = &f5[b];
      HalfFit pulled_a, pulled_b;  // differential only: either base pulled within the delta of the other, refitted
      if (!fits && differential_only) {
        int qa[3], qb[3];
        for (int c = 0; c < 3; ++c) {
          qa[c] = std::clamp(f5[a].q[c], f5[b].q[c] - 3, f5[b].q[c] + 4);
          qb[c] = std::clamp(f5[b].q[c], f5[a].q[c] - 4, f5[a].q[c] + 3);
        }
        pulled_a = fit(rgb, a, 5, t0[a], qa);
        pulled_b = fit(rgb, b, 5, t0[b], qb);
        if (pulled_a.err + f5[b].err < f5[a].err + pulled_b.err)
          pa = &pulled_a;
        else
          pb = &pulled_b;
      } else if (!fits) {
        f4[a] = fit(rgb, a, 4, t0[a]);
        f4[b] = fit(rgb, b, 4, t0[b]);
        pa = &f4[a];
        pb = &f4[b];
      }
      const int err = pa->err + pb->err;
      if (best_err >= 0 && err >= best_err) continue;
      best_err = err;
      best.flip = flip;
      best.differential = fits || differential_only ? 1 : 0;
      for (int s = 0; s < 2; ++s) {
        const HalfFit& f = s ? *pb : *pa;
        std::copy(f.q, f.q + 3, best.q[s]);
        best.table[s] = f.table;
        std::copy(f.idx, f.idx + 8, best.idx[s]);
      }
    }
    // The modifiers again under the decoder's clamping, which the estimate
    // above leaves out (beside a bright base a black texel wants the far
    // modifier that clamps to 0, not the near one).
    for (int s = 0; s < 2; ++s) {
      const HalfFit f = eval_exact(rgb, 2 * best.flip + s, best.q[s], best.differential ? 5 : 4, best.table[s]);
      std::copy(f.idx, f.idx + 8, best.idx[s]);
    }
    fast::pack(best, out[k]);
  }
}

namespace {

// `normal` and `high` for one block, stage by stage as the twin's
// Etc1SearchBatch (etc_search_lanes_simd.cpp): recentre, best_two,
// extremes, seed, fit_high, fit_normal, fit_fixed, search_flip.
struct Etc1Search {
  int rgb[16][3];
  fast::Params best{};
  int best_err = -1;

  Etc1Search(const std::uint32_t texel[16][kEtcBatch], int k) {
    for (int i = 0; i < 16; ++i) {
      const std::uint32_t t = texel[i][k];
      rgb[i][0] = int(t & 255);
      rgb[i][1] = int(t >> 8 & 255);
      rgb[i][2] = int(t >> 16 & 255);
    }
  }

  // Re-centres `cur` (the base that minimizes the error for its indices:
  // the mean of the texels minus their modifiers) up to `passes` times while
  // that helps.
  HalfFit recentre(int h, int bits, HalfFit cur, int passes) const {
    for (int pass = 0; pass < passes; ++pass) {
      int centre[3] = {};
      for (int i = 0; i < 8; ++i) {
        for (int c = 0; c < 3; ++c) centre[c] += rgb[fast::kHalf[h][i]][c] - kModifiers[cur.table][cur.idx[i]];
      }
      const int q1[3] = {fast::quantize_centre(centre[0], bits), fast::quantize_centre(centre[1], bits),
                         fast::quantize_centre(centre[2], bits)};
      if (std::equal(q1, q1 + 3, cur.q)) break;
      const HalfFit next = eval_exact(rgb, h, q1, bits, cur.table);
      if (next.err >= cur.err) break;
      cur = next;
    }
    return cur;
  }

  // The two tables with the least error (first of equals).
  static void best_two(const int err[8], int& t1, int& t2) {
    int e1 = -1;
    int e2 = -1;
    t1 = 0;
    t2 = 0;
    for (int t = 0; t < 8; ++t) {
      if (e1 < 0 || err[t] < e1) {
        e2 = e1;
        t2 = t1;
        e1 = err[t];
        t1 = t;
      } else if (e2 < 0 || err[t] < e2) {
        e2 = err[t];
        t2 = t;
      }
    }
  }

  // Half h's brightest and darkest texels (by R + G + B, first of equals).
  void extremes(int h, int& bright, int& dark) const {
    bright = fast::kHalf[h][0];
    dark = bright;
    for (int i = 1; i < 8; ++i) {
      const int p = fast::kHalf[h][i];
      const int sp = rgb[p][0] + rgb[p][1] + rgb[p][2];
      if (sp > rgb[bright][0] + rgb[bright][1] + rgb[bright][2]) bright = p;
      if (sp < rgb[dark][0] + rgb[dark][1] + rgb[dark][2]) dark = p;
    }
  }

  // Base = texel minus modifier m for table t, if that beats `start`: in an
  // exact fit the extreme texels carry the extreme modifiers.
  void seed(int h, int bits, HalfFit& start, int texel, int m, int t) const {
    const int top = bits == 5 ? 31 : 15;
    auto quantize8 = [&](int v) { return std::clamp(int(float(v * top) / 255.0f + 0.5f), 0, top); };
    const int q[3] = {quantize8(rgb[texel][0] - m), quantize8(rgb[texel][1] - m), quantize8(rgb[texel][2] - m)};
    const HalfFit f = eval_exact(rgb, h, q, bits, t);
    if (f.err < start.err) start = f;
  }

  // `high`: every table seeded and re-centred up to three times, then the
  // +-1 neighbourhood of the two best bases.
  HalfFit fit_high(int h, int bits, const HalfFit at_mean[8], int bright, int dark, HalfFit* per_table) const {
    const int top = bits == 5 ? 31 : 15;
    HalfFit best_fit{};
    best_fit.err = -1;
    HalfFit refined[8];
    int err[8];
    for (int t = 0; t < 8; ++t) {
      HalfFit start = at_mean[t];
      const int seeds[4][2] = {
          {bright, kModifiers[t][1]}, {dark, -kModifiers[t][1]}, {bright, kModifiers[t][0]}, {dark, -kModifiers[t][0]}};
      for (const auto& sd : seeds) seed(h, bits, start, sd[0], sd[1], t);
      refined[t] = recentre(h, bits, start, 3);
      err[t] = refined[t].err;
      if (best_fit.err < 0 || refined[t].err < best_fit.err) best_fit = refined[t];
    }
    if (per_table) std::copy(refined, refined + 8, per_table);
    int t1;
    int t2;
    best_two(err, t1, t2);
    for (int t : {t1, t2}) {
      for (int dr = -1; dr <= 1; ++dr) {
        for (int dg = -1; dg <= 1; ++dg) {
          for (int db = -1; db <= 1; ++db) {
            const int q[3] = {refined[t].q[0] + dr, refined[t].q[1] + dg, refined[t].q[2] + db};
            if (std::min({q[0], q[1], q[2]}) < 0 || std::max({q[0], q[1], q[2]}) > top) continue;
            const HalfFit f = eval_exact(rgb, h, q, bits, t);
            if (f.err < best_fit.err) best_fit = f;
          }
        }
      }
    }
    return best_fit;
  }

  // Half h at `bits`: every table at the mean; `normal`: the best two,
  // each also seeded from the extreme texels (where the far modifier clamps,
  // black texels beside one bright one, the base is the bright texel minus
  // it, far from the mean) and re-centred up to twice; `high`: fit_high.
  HalfFit fit_normal(int h, int bits, bool high, HalfFit* per_table = nullptr) const {
    int sum[3] = {};
    for (int i = 0; i < 8; ++i) {
      for (int c = 0; c < 3; ++c) sum[c] += rgb[fast::kHalf[h][i]][c];
    }
    const int q0[3] = {fast::quantize_sum(sum[0], bits), fast::quantize_sum(sum[1], bits),
                       fast::quantize_sum(sum[2], bits)};
    HalfFit at_mean[8];
    int err[8];
    for (int t = 0; t < 8; ++t) {
      at_mean[t] = eval_exact(rgb, h, q0, bits, t);
      err[t] = at_mean[t].err;
    }
    int bright;
    int dark;
    extremes(h, bright, dark);
    if (high) return fit_high(h, bits, at_mean, bright, dark, per_table);
    int t1;
    int t2;
    best_two(err, t1, t2);
    HalfFit start = at_mean[t1];
    seed(h, bits, start, bright, kModifiers[t1][1], t1);
    seed(h, bits, start, dark, -kModifiers[t1][1], t1);
    HalfFit best_fit = recentre(h, bits, start, 2);
    HalfFit start2 = at_mean[t2];
    seed(h, bits, start2, bright, kModifiers[t2][1], t2);
    seed(h, bits, start2, dark, -kModifiers[t2][1], t2);
    const HalfFit second = recentre(h, bits, start2, 2);
    if (second.err < best_fit.err) best_fit = second;
    return best_fit;
  }

  // Half h at a fixed 5-bit base: the best table.
  HalfFit fit_fixed(int h, const int q[3]) const {
    HalfFit best_fit = eval_exact(rgb, h, q, 5, 0);
    for (int t = 1; t < 8; ++t) {
      const HalfFit f = eval_exact(rgb, h, q, 5, t);
      if (f.err < best_fit.err) best_fit = f;
    }
    return best_fit;
  }

  void consider(int flip, bool differential, const HalfFit& a, const HalfFit& b) {
    if (best_err >= 0 && a.err + b.err >= best_err) return;
    best_err = a.err + b.err;
    best.flip = flip;
    best.differential = differential ? 1 : 0;
    for (int s = 0; s < 2; ++s) {
      const HalfFit& f = s ? b : a;
      std::copy(f.q, f.q + 3, best.q[s]);
      best.table[s] = f.table;
      std::copy(f.idx, f.idx + 8, best.idx[s]);
    }
  }

  // One flip's candidates: the halves' fits where the delta reaches; at
  // `high` every pair of their per-table fits; the individual mode where
  // the delta does not reach (always at `high`); else a base pulled within
  // the delta of the other and its half refitted (`high`: and the pulled
  // base's neighbours).
  void search_flip(int flip, bool high, bool differential_only, const HalfFit f5[4], const HalfFit tables[4][9]) {
    const int a = 2 * flip;
    const int b = a + 1;
    const bool fits = fast::delta_reaches(f5[a].q, f5[b].q);
    if (fits) consider(flip, true, f5[a], f5[b]);
    for (int ta = 0; high && ta < 9; ++ta) {
      for (int tb = 0; tb < 9; ++tb) {
        if (fast::delta_reaches(tables[a][ta].q, tables[b][tb].q)) consider(flip, true, tables[a][ta], tables[b][tb]);
      }
    }
    if (fits && !high) return;
    if (!differential_only) consider(flip, false, fit_normal(a, 4, high), fit_normal(b, 4, high));
    if (fits) return;
    int qa[3];
    int qb[3];
    for (int c = 0; c < 3; ++c) qa[c] = std::clamp(f5[a].q[c], f5[b].q[c] - 3, f5[b].q[c] + 4);
    const HalfFit pa = fit_fixed(a, qa);
    consider(flip, true, pa, f5[b]);
    for (int c = 0; c < 3; ++c) qb[c] = std::clamp(f5[b].q[c], f5[a].q[c] - 4, f5[a].q[c] + 3);
    const HalfFit pb = fit_fixed(b, qb);
    consider(flip, true, f5[a], pb);
    if (!high) return;
    auto in_range = [](const int q[3]) {
      return std::min({q[0], q[1], q[2]}) >= 0 && std::max({q[0], q[1], q[2]}) <= 31;
    };
    for (int n = 0; n < 27; ++n) {
      const int dd[3] = {n / 9 - 1, n / 3 % 3 - 1, n % 3 - 1};
      if (n == 13) continue;
      const int na[3] = {qa[0] + dd[0], qa[1] + dd[1], qa[2] + dd[2]};
      const int nb[3] = {qb[0] + dd[0], qb[1] + dd[1], qb[2] + dd[2]};
      if (in_range(na) && fast::delta_reaches(na, f5[b].q)) {
        consider(flip, true, eval_exact(rgb, a, na, 5, pa.table), f5[b]);
      }
      if (in_range(nb) && fast::delta_reaches(f5[a].q, nb)) {
        consider(flip, true, f5[a], eval_exact(rgb, b, nb, 5, pb.table));
      }
    }
  }
};

}  // namespace

void etc1_search_lanes(const std::uint32_t texel[16][kEtcBatch], int count, bool high, bool differential_only,
                       std::uint8_t out[][8], std::int32_t error[]) {
  for (int k = 0; k < count; ++k) {
    Etc1Search s(texel, k);
    HalfFit f5[4];
    HalfFit tables[4][9];
    for (int h = 0; h < 4; ++h) {
      f5[h] = s.fit_normal(h, 5, high, tables[h]);
      tables[h][8] = f5[h];
    }
    for (int flip = 0; flip < 2; ++flip) s.search_flip(flip, high, differential_only, f5, tables);
    fast::pack(s.best, out[k]);
    error[k] = s.best_err;
  }
}

}  // namespace ref
}  // namespace texproc::etc
