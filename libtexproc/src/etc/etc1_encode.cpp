// ETC1's individual and differential modes: the four half blocks (left,
// right, top, bottom) are fitted once at 4 bits (individual mode) and at 5
// bits (differential mode): for each of the 8 intensity tables the base
// colour starts at the half's mean, each texel takes its best modifier, the
// base is re-centred on the texels minus their modifiers (least squares),
// and at `high` a +-1 neighbourhood of the quantized base is searched. Flips
// and modes then combine the halves; a differential pair whose bases are
// too far apart is brought within the 3-bit delta and the moved half is
// refitted. Every candidate is scored with the decoder's own arithmetic.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "etc/etc_search.h"

namespace texproc::etc {

const std::array<HalfLayout, 4>& halves() {
  static const std::array<HalfLayout, 4> h = [] {
    std::array<HalfLayout, 4> r{};
    for (int k = 0; k < 4; ++k) {
      int n = 0;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
          const bool in = k == 0 ? x < 2 : k == 1 ? x >= 2 : k == 2 ? y < 2 : y >= 2;
          if (in) {
            r[k].x[n] = x;
            r[k].y[n] = y;
            ++n;
          }
        }
    }
    return r;
  }();
  return h;
}

namespace {

// Sorts up to eight table numbers by a key, stably (insertion sort).
template <typename Key>
void sort_tables(int* order, int count, Key key) {
  for (int a = 1; a < count; ++a)
    for (int b = a; b > 0 && key(order[b]) < key(order[b - 1]); --b) std::swap(order[b], order[b - 1]);
}

void try_base(const Texels& tx, int h, const int q[3], int bits, int t, bool non_opaque, HalfFit& best) {
  const int col[3] = {expand(q[0], bits), expand(q[1], bits), expand(q[2], bits)};
  std::uint8_t idx[8];
  const long e = tx.half[h].eval(tx.half[h], col, t, non_opaque, idx);
  if (e < best.err) {
    best.err = e;
    std::memcpy(best.q, q, sizeof best.q);
    best.table = t;
    std::memcpy(best.idx, idx, 8);
  }
}

}  // namespace

// The best base and table for half h at `bits` (4 or 5).
HalfFit fit_half(const Texels& tx, int h, int bits, const Etc1BlockSearch& search, bool non_opaque) {
  const HalfLayout& L = halves()[std::size_t(h)];
  double mean[3] = {0, 0, 0};
  int visible = 0;
  for (int i = 0; i < 8; ++i) {
    const int p = L.y[i] * 4 + L.x[i];
    if (non_opaque && tx.transparent[p]) continue;
    for (int c = 0; c < 3; ++c) mean[c] += tx.rgb[p][c];
    ++visible;
  }
  HalfFit best;
  if (visible == 0) {  // every texel transparent: any colour
    best.err = 0;
    std::fill(best.idx, best.idx + 8, std::uint8_t(2));
    return best;
  }
  for (double& m : mean) m /= visible;
  // The brightest and darkest visible texels (by R + G + B): in an exact
  // fit they carry the largest and smallest modifiers, so base = texel -
  // modifier seeds the search where the mean alone would lock the indices
  // one step off.
  int bright = -1, dark = -1;
  for (int i = 0; i < 8 && search.seeds > 0; ++i) {  // only seeds use them
    const int p = L.y[i] * 4 + L.x[i];
    if (non_opaque && tx.transparent[p]) continue;
    const int sum = tx.rgb[p][0] + tx.rgb[p][1] + tx.rgb[p][2];
    if (bright < 0 || sum > tx.rgb[bright][0] + tx.rgb[bright][1] + tx.rgb[bright][2]) bright = p;
    if (dark < 0 || sum < tx.rgb[dark][0] + tx.rgb[dark][1] + tx.rgb[dark][2]) dark = p;
  }
  const int q0[3] = {quantize(mean[0], bits), quantize(mean[1], bits), quantize(mean[2], bits)};
  // Tables worth refining: every table is scored at the mean first (at
  // `fast`, only the three whose modifiers are nearest the texels' spread
  // around the mean); `normal` refines the best three, `high` all.
  HalfFit at_mean[8];
  int order[8], tables = 0;
  if (!search.all_tables) {
    double spread = 0;
    const double mean_sum = mean[0] + mean[1] + mean[2];
    for (int i = 0; i < 8; ++i) {
      const int p = L.y[i] * 4 + L.x[i];
      if (non_opaque && tx.transparent[p]) continue;
      spread += std::fabs(tx.rgb[p][0] + tx.rgb[p][1] + tx.rgb[p][2] - mean_sum) / 3.0;
    }
    spread /= visible;
    int t0 = 0;
    for (int t = 1; t < 8; ++t) {
      const double mid = (kModifiers[t][0] + kModifiers[t][1]) / 2.0,
                   best_mid = (kModifiers[t0][0] + kModifiers[t0][1]) / 2.0;
      if (std::fabs(mid - spread) < std::fabs(best_mid - spread)) t0 = t;
    }
    for (int t = std::max(0, t0 - 1); t <= std::min(7, t0 + 1); ++t) order[tables++] = t;
  } else {
    for (int t = 0; t < 8; ++t) order[tables++] = t;
  }
  for (int k = 0; k < tables; ++k) try_base(tx, h, q0, bits, order[k], non_opaque, at_mean[order[k]]);
  sort_tables(order, tables, [&](int t) { return at_mean[t].err; });
  const int refine = std::min(tables, search.refined_tables);
  HalfFit refined[8];
  for (int k = 0; k < tables; ++k) {
    const int t = order[k];
    HalfFit fit = at_mean[t];
    if (k < refine) {
      // Seeds: the extremes minus the extreme modifiers (+-b; at high also +-a).
      const int big = kModifiers[t][1], small = kModifiers[t][0];
      const int offsets[4][2] = {{bright, big}, {dark, -big}, {bright, small}, {dark, -small}};
      const int seeds = search.seeds;
      for (int sd = 0; sd < seeds; ++sd) {
        if (non_opaque && sd >= 2) break;  // +-a are 0 with punch-through
        const int* p = tx.rgb[offsets[sd][0]];
        const int qs[3] = {quantize(p[0] - offsets[sd][1], bits), quantize(p[1] - offsets[sd][1], bits),
                           quantize(p[2] - offsets[sd][1], bits)};
        try_base(tx, h, qs, bits, t, non_opaque, fit);
      }
      // Re-centre: the base that minimizes the error for these indices is
      // the mean of the texels minus their modifiers.
      for (int pass = 0; pass < 3; ++pass) {
        double centre[3] = {0, 0, 0};
        int n = 0;
        for (int i = 0; i < 8; ++i) {
          const int p = L.y[i] * 4 + L.x[i];
          if (non_opaque && tx.transparent[p]) continue;
          const int m = non_opaque && (fit.idx[i] == 0) ? 0 : kModifiers[t][fit.idx[i]];
          for (int c = 0; c < 3; ++c) centre[c] += tx.rgb[p][c] - m;
          ++n;
        }
        const int q1[3] = {quantize(centre[0] / n, bits), quantize(centre[1] / n, bits), quantize(centre[2] / n, bits)};
        if (std::equal(q1, q1 + 3, fit.q)) break;
        const long before = fit.err;
        try_base(tx, h, q1, bits, t, non_opaque, fit);
        if (fit.err >= before) break;
      }
    }
    refined[t] = fit;
    if (fit.err < best.err) best = fit;
  }
  if (search.neighbour_tables > 0) {
    // The neighbourhood of the quantized base, for the best tables after
    // refinement (`high`: two, +-1; `max`: every table, +-2).
    sort_tables(order, tables, [&](int t) { return refined[t].err; });
    const int r = search.neighbour_radius, top = (1 << bits) - 1;
    const int searched = std::min(tables, search.neighbour_tables);
    for (int k = 0; k < searched; ++k) {
      const int t = order[k];
      HalfFit fit = refined[t];
      const int c0[3] = {fit.q[0], fit.q[1], fit.q[2]};
      for (int dr = -r; dr <= r; ++dr)
        for (int dg = -r; dg <= r; ++dg)
          for (int db = -r; db <= r; ++db) {
            const int c[3] = {c0[0] + dr, c0[1] + dg, c0[2] + db};
            if (std::min({c[0], c[1], c[2]}) < 0 || std::max({c[0], c[1], c[2]}) > top) continue;
            try_base(tx, h, c, bits, t, non_opaque, fit);
          }
      if (fit.err < best.err) best = fit;
    }
  }
  return best;
}

HalfFit fit_fixed(const Texels& tx, int h, const int q[3], bool non_opaque) {
  HalfFit best;
  for (int t = 0; t < 8; ++t) try_base(tx, h, q, 5, t, non_opaque, best);
  return best;
}

std::uint64_t pack_halves(const HalfFit& a, const HalfFit& b, bool flip, bool differential, int bit33) {
  std::uint64_t v = 0;
  for (int c = 0; c < 3; ++c) {
    if (differential) {
      put(v, 63 - 8 * c, 5, a.q[c]);
      put(v, 58 - 8 * c, 3, (b.q[c] - a.q[c]) & 7);
    } else {
      put(v, 63 - 8 * c, 4, a.q[c]);
      put(v, 59 - 8 * c, 4, b.q[c]);
    }
  }
  put(v, 39, 3, a.table);
  put(v, 36, 3, b.table);
  put(v, 33, 1, bit33);
  put(v, 32, 1, flip ? 1 : 0);
  const HalfLayout& la = halves()[flip ? 2 : 0];
  const HalfLayout& lb = halves()[flip ? 3 : 1];
  for (int i = 0; i < 8; ++i) {
    put_index(v, la.x[i], la.y[i], a.idx[i]);
    put_index(v, lb.x[i], lb.y[i], b.idx[i]);
  }
  return v;
}

// Keeps a pair of halves if it beats the best so far (packed only then).
void keep_pair(Candidate& best, const HalfFit& a, const HalfFit& b, bool flip, bool differential, int bit33) {
  const long err = a.err + b.err;
  if (err < best.err) keep(best, err, pack_halves(a, b, flip, differential, bit33));
}

// Individual and differential modes, both flips.
void search_etc1_modes(const Texels& tx, const Etc1BlockSearch& search, bool allow_individual, bool non_opaque,
                       int bit33_diff, Candidate& best) {
  HalfFit h4[4], h5[4];
  for (int h = 0; h < 4; ++h) h5[h] = fit_half(tx, h, 5, search, non_opaque);
  for (int flip = 0; flip < 2; ++flip) {
    const int a = flip ? 2 : 0, b = flip ? 3 : 1;
    // Individual mode (4-bit bases) can only win when the halves are too far
    // apart for the differential delta, or at `high` and above, where it is
    // always tried.
    if (allow_individual && (search.individual_always || !delta_fits(h5[a].q, h5[b].q))) {
      for (int hh : {a, b})
        if (h4[hh].err == kNone) h4[hh] = fit_half(tx, hh, 4, search, non_opaque);
      keep_pair(best, h4[a], h4[b], flip, false, 0);
    }
    if (delta_fits(h5[a].q, h5[b].q)) {
      keep_pair(best, h5[a], h5[b], flip, true, bit33_diff);
      continue;
    }
    // Too far apart for the 3-bit delta: pull one base towards the other and
    // refit the moved half's table and indices.
    for (int moved = 0; moved < 2; ++moved) {
      const HalfFit& fixed = moved ? h5[a] : h5[b];
      const int mh = moved ? b : a;
      int qm[3];
      for (int c = 0; c < 3; ++c) {
        const int other = (moved ? h5[b] : h5[a]).q[c];
        qm[c] = moved ? std::clamp(other, fixed.q[c] - 4, fixed.q[c] + 3)
                      : std::clamp(other, fixed.q[c] - 3, fixed.q[c] + 4);
      }
      const HalfFit refit = fit_fixed(tx, mh, qm, non_opaque);
      const HalfFit& first = moved ? fixed : refit;
      const HalfFit& second = moved ? refit : fixed;
      keep_pair(best, first, second, flip, true, bit33_diff);
    }
  }
}

}  // namespace texproc::etc
