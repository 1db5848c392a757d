// ETC1, ETC2 and EAC block encoding. Every candidate is scored with the
// decoder's own arithmetic (clamping included), so the error the search
// minimizes is the error a GPU shows.
//
// ETC1 modes: the four half blocks (left, right, top, bottom) are fitted
// once at 4 bits (individual mode) and at 5 bits (differential mode): for
// each of the 8 intensity tables the base colour starts at the half's mean,
// each texel takes its best modifier, the base is re-centred on the texels
// minus their modifiers (least squares), and at `high` a +-1 neighbourhood
// of the quantized base is searched. Flips and modes then combine the
// halves; a differential pair whose bases are too far apart is brought
// within the 3-bit delta and the moved half is refitted.
// ETC2 adds planar (a least-squares plane per channel, quantized, with a
// +-1 search per value: channels are independent) and the T and H modes (two
// clusters split along the principal axis, their centres quantized to 4
// bits, every distance tried).
#include "etc/etc_encode.h"
#include "etc/etc_eval.h"
#include "etc/eac_lanes.h"
#include "etc/etc_lanes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "bc/bc1_assign.h"
#include "bc/bc4_eval.h"
#include "bc/block_gather.h"
#include "etc/etc_tables.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc::etc {

static_assert(kEtcBatch == kBlockBatch, "the lanes take the texels gather_rows_rgba8 reads");
namespace {

constexpr long kNone = std::numeric_limits<long>::max() / 4;

// The texels of each half block, as (x, y): 0 left, 1 right, 2 top, 3 bottom.
struct HalfLayout {
  int x[8], y[8];
};
const std::array<HalfLayout, 4>& halves() {
  static const std::array<HalfLayout, 4> h = [] {
    std::array<HalfLayout, 4> r{};
    for (int k = 0; k < 4; ++k) {
      int n = 0;
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
          const bool in = k == 0 ? x < 2 : k == 1 ? x >= 2 : k == 2 ? y < 2 : y >= 2;
          if (in) r[k].x[n] = x, r[k].y[n] = y, ++n;
        }
    }
    return r;
  }();
  return h;
}

struct Texels {
  int rgb[16][3];
  bool transparent[16];  // punch-through: alpha < 128
  bool any_transparent = false;
  HalfTexels half[4];    // the texels of each half block, as planes (for eval_half)
  Bc1Texels planes;      // all 16 as planes (for bc1_nearest: T and H of opaque blocks)
};

struct HalfFit {
  long err = kNone;
  int q[3] = {0, 0, 0};  // base colour at 4 or 5 bits
  int table = 0;
  std::uint8_t idx[8] = {};
};

int expand(int q, int bits) { return bits == 4 ? extend4(q) : extend5(q); }
int quantize(double v, int bits) {
  // Rounded to nearest (halves up) and clamped, without a libm call.
  const int top = (1 << bits) - 1;
  const double x = v * top / 255.0;
  if (!(x > 0.0)) return 0;
  return std::min(int(x + 0.5), top);
}

// Sorts up to eight table numbers by a key, stably (insertion sort).
template <typename Key>
void sort_tables(int* order, int count, Key key) {
  for (int a = 1; a < count; ++a)
    for (int b = a; b > 0 && key(order[b]) < key(order[b - 1]); --b) std::swap(order[b], order[b - 1]);
}

void try_base(const Texels& tx, int h, const int q[3], int bits, int t, bool non_opaque, HalfFit& best) {
  const int col[3] = {expand(q[0], bits), expand(q[1], bits), expand(q[2], bits)};
  std::uint8_t idx[8];
  const long e = eval_half(tx.half[h], col, t, non_opaque, idx);
  if (e < best.err) {
    best.err = e;
    std::memcpy(best.q, q, sizeof best.q);
    best.table = t;
    std::memcpy(best.idx, idx, 8);
  }
}

// The best base and table for half h at `bits` (4 or 5).
HalfFit fit_half(const Texels& tx, int h, int bits, Quality q, bool non_opaque) {
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
  for (int i = 0; i < 8 && q != Quality::fast; ++i) {  // seeds are not used at `fast`
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
  if (q == Quality::fast) {
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
      const double mid = (kModifiers[t][0] + kModifiers[t][1]) / 2.0, best_mid = (kModifiers[t0][0] + kModifiers[t0][1]) / 2.0;
      if (std::fabs(mid - spread) < std::fabs(best_mid - spread)) t0 = t;
    }
    for (int t = std::max(0, t0 - 1); t <= std::min(7, t0 + 1); ++t) order[tables++] = t;
  } else {
    for (int t = 0; t < 8; ++t) order[tables++] = t;
  }
  for (int k = 0; k < tables; ++k) try_base(tx, h, q0, bits, order[k], non_opaque, at_mean[order[k]]);
  sort_tables(order, tables, [&](int t) { return at_mean[t].err; });
  const int refine = q == Quality::fast ? 0 : q == Quality::normal ? std::min(tables, 3) : tables;
  HalfFit refined[8];
  for (int k = 0; k < tables; ++k) {
    const int t = order[k];
    HalfFit fit = at_mean[t];
    if (k < refine) {
      // Seeds: the extremes minus the extreme modifiers (+-b; at high also +-a).
      const int big = kModifiers[t][1], small = kModifiers[t][0];
      const int offsets[4][2] = {{bright, big}, {dark, -big}, {bright, small}, {dark, -small}};
      const int seeds = q == Quality::normal ? 2 : 4;
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
  if (q == Quality::high || q == Quality::max) {
    // The neighbourhood of the quantized base, for the best two tables
    // after refinement (`max`: every table, +-2).
    sort_tables(order, tables, [&](int t) { return refined[t].err; });
    const int r = q == Quality::max ? 2 : 1, top = (1 << bits) - 1;
    const int searched = q == Quality::max ? tables : std::min(tables, 2);
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

// Half h refitted with its base fixed at q (5 bits): the best table.
HalfFit fit_fixed(const Texels& tx, int h, const int q[3], bool non_opaque) {
  HalfFit best;
  for (int t = 0; t < 8; ++t) try_base(tx, h, q, 5, t, non_opaque, best);
  return best;
}

void put(std::uint64_t& v, int high, int count, int value) {
  const int low = high - count + 1;
  const std::uint64_t mask = ((std::uint64_t(1) << count) - 1) << low;
  v = (v & ~mask) | ((std::uint64_t(unsigned(value)) << low) & mask);
}

void put_index(std::uint64_t& v, int x, int y, int idx) {
  const int k = x * 4 + y;
  put(v, k + 16, 1, idx >> 1);
  put(v, k, 1, idx & 1);
}

struct Candidate {
  long err = kNone;
  std::uint64_t bits = 0;
};

void keep(Candidate& best, long err, std::uint64_t bits) {
  if (err < best.err) best.err = err, best.bits = bits;
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

bool delta_fits(const int a[3], const int b[3]) {
  for (int c = 0; c < 3; ++c)
    if (b[c] - a[c] < -4 || b[c] - a[c] > 3) return false;
  return true;
}

// Individual and differential modes, both flips.
void search_etc1_modes(const Texels& tx, Quality q, bool allow_individual, bool non_opaque, int bit33_diff,
                       Candidate& best) {
  HalfFit h4[4], h5[4];
  for (int h = 0; h < 4; ++h) h5[h] = fit_half(tx, h, 5, q, non_opaque);
  for (int flip = 0; flip < 2; ++flip) {
    const int a = flip ? 2 : 0, b = flip ? 3 : 1;
    // Individual mode (4-bit bases) can only win when the halves are too far
    // apart for the differential delta, or at `high` and above, where it is
    // always tried.
    if (allow_individual && (q == Quality::high || q == Quality::max || !delta_fits(h5[a].q, h5[b].q))) {
      for (int hh : {a, b})
        if (h4[hh].err == kNone) h4[hh] = fit_half(tx, hh, 4, q, non_opaque);
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
        qm[c] = moved ? std::clamp(other, fixed.q[c] - 4, fixed.q[c] + 3) : std::clamp(other, fixed.q[c] - 3, fixed.q[c] + 4);
      }
      const HalfFit refit = fit_fixed(tx, mh, qm, non_opaque);
      const HalfFit& first = moved ? fixed : refit;
      const HalfFit& second = moved ? refit : fixed;
      keep_pair(best, first, second, flip, true, bit33_diff);
    }
  }
}

std::uint64_t pack_planar(const int o[3], const int hq[3], const int vq[3]);

// Planar: per channel a least-squares plane, quantized (6/7/6 bits), with a
// +-1 search of each of O, H, V (channels are scored independently).
void search_planar(const Texels& tx, Quality q, Candidate& best) {
  int o[3], hq[3], vq[3];
  long total = 0;
  for (int c = 0; c < 3; ++c) {
    const std::int32_t* px = c == 0 ? tx.planes.r : c == 1 ? tx.planes.g : tx.planes.b;
    const int bits = c == 1 ? 7 : 6;
    // The plane through the texels' mean with slopes a (x) and b (y):
    // sums of integers, exact (sx, sy: twice the x and y moments about 1.5).
    int sum = 0, sx = 0, sy = 0;
    for (int i = 0; i < 16; ++i) sum += px[i], sx += (2 * (i & 3) - 3) * px[i], sy += (2 * (i >> 2) - 3) * px[i];
    const double a = sx / 40.0, b = sy / 40.0, O = sum / 16.0 - 1.5 * a - 1.5 * b;
    const int top = (1 << bits) - 1;
    auto qz = [&](double v) { return std::clamp(int(std::lround(v * top / 255.0)), 0, top); };
    auto ex = [&](int v) { return bits == 7 ? extend7(v) : extend6(v); };
    const int c0[3] = {qz(O), qz(O + 4 * a), qz(O + 4 * b)};
    int be = std::numeric_limits<int>::max();
    int bo = c0[0], bh = c0[1], bv = c0[2];
    const int r = q == Quality::high || q == Quality::max ? 1 : 0;
    for (int d0 = -r; d0 <= r; ++d0)
      for (int d1 = -r; d1 <= r; ++d1)
        for (int d2 = -r; d2 <= r; ++d2) {
          const int vo = c0[0] + d0, vh = c0[1] + d1, vv = c0[2] + d2;
          if (std::min({vo, vh, vv}) < 0 || std::max({vo, vh, vv}) > top) continue;
          const int eo = ex(vo), eh = ex(vh), ev = ex(vv);
          int e = 0;
          for (int i = 0; i < 16; ++i) {
            const int d = clamp255(((i & 3) * (eh - eo) + (i >> 2) * (ev - eo) + 4 * eo + 2) >> 2) - px[i];
            e += d * d;
          }
          if (e < be) be = e, bo = vo, bh = vh, bv = vv;
        }
    o[c] = bo, hq[c] = bh, vq[c] = bv;
    total += be;
    if (total >= best.err) return;  // errors only add up: planar cannot win
  }
  keep(best, total, pack_planar(o, hq, vq));
}

// A planar block's bits for O, H and V (6/7/6 bits a channel).
std::uint64_t pack_planar(const int o[3], const int hq[3], const int vq[3]) {
  std::uint64_t v = 0;
  put(v, 62, 6, o[0]);
  put(v, 56, 1, o[1] >> 6), put(v, 54, 6, o[1] & 63);
  put(v, 48, 1, o[2] >> 5), put(v, 44, 2, o[2] >> 3 & 3), put(v, 41, 2, o[2] >> 1 & 3), put(v, 39, 1, o[2] & 1);
  put(v, 38, 5, hq[0] >> 1), put(v, 32, 1, hq[0] & 1), put(v, 31, 7, hq[1]);
  put(v, 24, 1, hq[2] >> 5), put(v, 23, 5, hq[2] & 31);
  put(v, 18, 6, vq[0]), put(v, 12, 7, vq[1]), put(v, 5, 6, vq[2]);
  put(v, 33, 1, 1);
  // The mode is read from overflows: red and green must stay in range, blue
  // must leave it. Each has a free bit (63, 55; 47-45 and 42) that decides.
  auto in_range = [&](int high5, int high3) {
    const int base = int(v >> (high5 - 4) & 31), d3 = int(v >> (high3 - 2) & 7);
    const int s = base + (d3 >= 4 ? d3 - 8 : d3);
    return s >= 0 && s <= 31;
  };
  if (!in_range(63, 58)) put(v, 63, 1, 1);
  if (!in_range(55, 50)) put(v, 55, 1, 1);
  if ((o[2] >> 3 & 3) + (o[2] >> 1 & 3) > 3) {
    put(v, 47, 3, 7), put(v, 42, 1, 0);
  } else {
    put(v, 47, 3, 0), put(v, 42, 1, 1);
  }
  return v;
}

// T and H modes: two clusters along the principal axis.
void search_t_h(const Texels& tx, bool non_opaque, Quality q_level, Candidate& best) {
  int n = 0;
  double mean[3] = {0, 0, 0};
  for (int i = 0; i < 16; ++i) {
    if (non_opaque && tx.transparent[i]) continue;
    for (int c = 0; c < 3; ++c) mean[c] += tx.rgb[i][c];
    ++n;
  }
  if (n < 2) return;
  for (double& m : mean) m /= n;
  double cov[3][3] = {};
  for (int i = 0; i < 16; ++i) {
    if (non_opaque && tx.transparent[i]) continue;
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = tx.rgb[i][c] - mean[c];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov[a][b] += d[a] * d[b];
  }
  double axis[3] = {1, 1, 1};
  for (int it = 0; it < 8; ++it) {
    double nx[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) nx[a] += cov[a][b] * axis[b];
    const double len = std::sqrt(nx[0] * nx[0] + nx[1] * nx[1] + nx[2] * nx[2]);
    if (len < 1e-9) break;
    for (int a = 0; a < 3; ++a) axis[a] = nx[a] / len;
  }
  // Two clusters by the sign of the projection, refined by two k-means steps.
  bool side[16] = {};
  double centre[2][3] = {};
  for (int i = 0; i < 16; ++i) {
    double p = 0;
    for (int c = 0; c < 3; ++c) p += (tx.rgb[i][c] - mean[c]) * axis[c];
    side[i] = p > 0;
  }
  for (int it = 0; it < 3; ++it) {
    int count[2] = {0, 0};
    std::memset(centre, 0, sizeof centre);
    for (int i = 0; i < 16; ++i) {
      if (non_opaque && tx.transparent[i]) continue;
      for (int c = 0; c < 3; ++c) centre[side[i]][c] += tx.rgb[i][c];
      ++count[side[i]];
    }
    if (count[0] == 0 || count[1] == 0) return;
    for (int s = 0; s < 2; ++s)
      for (int c = 0; c < 3; ++c) centre[s][c] /= count[s];
    for (int i = 0; i < 16; ++i) {
      double d[2] = {0, 0};
      for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c) d[s] += (tx.rgb[i][c] - centre[s][c]) * (tx.rgb[i][c] - centre[s][c]);
      side[i] = d[1] < d[0];
    }
  }
  int q[2][3];
  for (int s = 0; s < 2; ++s)
    for (int c = 0; c < 3; ++c) q[s][c] = quantize(centre[s][c], 4);
  // Distances worth trying: at `normal`, the three nearest to the clusters'
  // spread about their centres (the mean absolute deviation along the
  // channels); `high` tries all eight.
  int d_lo = 0, d_hi = 7;
  if (q_level != Quality::high && q_level != Quality::max) {
    double spread = 0;
    int cnt = 0;
    for (int i = 0; i < 16; ++i) {
      if (non_opaque && tx.transparent[i]) continue;
      for (int c = 0; c < 3; ++c) spread += std::fabs(tx.rgb[i][c] - centre[side[i]][c]) / 3.0;
      ++cnt;
    }
    spread /= cnt;
    int nearest = 0;
    for (int di = 1; di < 8; ++di)
      if (std::fabs(kDistances[di] - spread) < std::fabs(kDistances[nearest] - spread)) nearest = di;
    d_lo = std::max(0, nearest - 1), d_hi = std::min(7, nearest + 1);
  }

  // Scores four paint colours; `usable[k]`: index k may be used.
  auto score = [&](const int paint[4][3], std::uint8_t idx[16]) {
    if (!non_opaque) {  // each texel's nearest paint colour, first of equals (SIMD twins)
      int pal[4][3];
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) pal[k][c] = clamp255(paint[k][c]);
      return long(bc1_nearest(tx.planes, pal, 4, idx));
    }
    long err = 0;
    for (int i = 0; i < 16; ++i) {
      if (non_opaque && tx.transparent[i]) {
        idx[i] = 2;
        continue;
      }
      long be = kNone;
      int bk = 0;
      for (int k = 0; k < 4; ++k) {
        if (non_opaque && k == 2) continue;
        long e = 0;
        for (int c = 0; c < 3; ++c) {
          const long d = clamp255(paint[k][c]) - tx.rgb[i][c];
          e += d * d;
        }
        if (e < be) be = e, bk = k;
      }
      idx[i] = std::uint8_t(bk);
      err += be;
    }
    return err;
  };
  auto put_indices = [&](std::uint64_t& v, const std::uint8_t idx[16]) {
    for (int i = 0; i < 16; ++i) put_index(v, i % 4, i / 4, idx[i]);
  };
  const int opaque_bit = non_opaque ? 0 : 1;  // bit 33: the differential flag, or punch-through's opaque flag
  // Scores T and H for one pair of 4-bit cluster colours.
  long th_min = kNone;  // the least T or H error seen
  const long before = best.err;  // the best of the other modes
  auto try_colours = [&](const int (&qc)[2][3]) {
    // T: one cluster is the single colour C1, the other C2 +- d.
    for (int single = 0; single < 2; ++single) {
      const int* c1 = qc[single];
      const int* c2 = qc[1 - single];
      for (int di = d_lo; di <= d_hi; ++di) {
        const int d = kDistances[di];
        int paint[4][3];
        for (int c = 0; c < 3; ++c) {
          paint[0][c] = extend4(c1[c]);
          paint[1][c] = extend4(c2[c]) + d;
          paint[2][c] = extend4(c2[c]);
          paint[3][c] = extend4(c2[c]) - d;
        }
        std::uint8_t idx[16];
        const long e = score(paint, idx);
        th_min = std::min(th_min, e);
        if (e >= best.err) continue;
        std::uint64_t v = 0;
        put(v, 60, 2, c1[0] >> 2), put(v, 57, 2, c1[0] & 3), put(v, 55, 4, c1[1]), put(v, 51, 4, c1[2]);
        put(v, 47, 4, c2[0]), put(v, 43, 4, c2[1]), put(v, 39, 4, c2[2]);
        put(v, 35, 2, di >> 1), put(v, 32, 1, di & 1), put(v, 33, 1, opaque_bit);
        if ((c1[0] >> 2) + (c1[0] & 3) > 3) {
          put(v, 63, 3, 7), put(v, 58, 1, 0);
        } else {
          put(v, 63, 3, 0), put(v, 58, 1, 1);
        }
        put_indices(v, idx);
        keep(best, e, v);
      }
    }
    // H: C1 +- d and C2 +- d; the distance index's low bit is the order of
    // the two colours, so a colour pair in the wrong order is swapped.
    for (int di = d_lo; di <= d_hi; ++di) {
      const int* c1 = qc[0];
      const int* c2 = qc[1];
      const int k1 = c1[0] << 8 | c1[1] << 4 | c1[2], k2 = c2[0] << 8 | c2[1] << 4 | c2[2];
      if ((k1 >= k2) != bool(di & 1)) std::swap(c1, c2);
      const int a1 = c1[0] << 8 | c1[1] << 4 | c1[2], a2 = c2[0] << 8 | c2[1] << 4 | c2[2];
      if ((a1 >= a2) != bool(di & 1)) continue;  // equal colours: only odd indices
      const int d = kDistances[di];
      int paint[4][3];
      for (int c = 0; c < 3; ++c) {
        paint[0][c] = extend4(c1[c]) + d;
        paint[1][c] = extend4(c1[c]) - d;
        paint[2][c] = extend4(c2[c]) + d;
        paint[3][c] = extend4(c2[c]) - d;
      }
      std::uint8_t idx[16];
      const long e = score(paint, idx);
      th_min = std::min(th_min, e);
      if (e >= best.err) continue;
      std::uint64_t v = 0;
      put(v, 62, 4, c1[0]), put(v, 58, 3, c1[1] >> 1), put(v, 52, 1, c1[1] & 1);
      put(v, 51, 1, c1[2] >> 3), put(v, 49, 2, c1[2] >> 1 & 3), put(v, 47, 1, c1[2] & 1);
      put(v, 46, 4, c2[0]), put(v, 42, 3, c2[1] >> 1), put(v, 39, 1, c2[1] & 1), put(v, 38, 4, c2[2]);
      put(v, 34, 1, di >> 2), put(v, 32, 1, di >> 1 & 1), put(v, 33, 1, opaque_bit);
      // Red in range (bit 63), green out of range (bits 55-53 and 50).
      {
        const int s = c1[0] + ((c1[1] >> 1) >= 4 ? (c1[1] >> 1) - 8 : (c1[1] >> 1));
        put(v, 63, 1, s < 0 ? 1 : 0);
      }
      const int g = (c1[1] & 1) * 2 + (c1[2] >> 3), bb = c1[2] >> 1 & 3;
      if (g + bb > 3) {
        put(v, 55, 3, 7), put(v, 50, 1, 0);
      } else {
        put(v, 55, 3, 0), put(v, 50, 1, 1);
      }
      put_indices(v, idx);
      keep(best, e, v);
    }
  };
  try_colours(q);
  // Where T or H came close to the other modes (within a quarter), at
  // `high`: the quantization's other neighbours too.
  if ((q_level == Quality::high || q_level == Quality::max) && th_min < before + before / 4) {
    // Each centre rounded down or up instead of to nearest (the clamps keep
    // 0..15): the quantization's other neighbours.
    for (int va = 0; va < 3; ++va)
      for (int vb = 0; vb < 3; ++vb) {
        if (va == 0 && vb == 0) continue;
        int alt[2][3];
        for (int c = 0; c < 3; ++c) {
          const double ca = centre[0][c] * 15.0 / 255.0, cb = centre[1][c] * 15.0 / 255.0;
          alt[0][c] = std::clamp(va == 0 ? q[0][c] : va == 1 ? int(std::floor(ca)) : int(std::ceil(ca)), 0, 15);
          alt[1][c] = std::clamp(vb == 0 ? q[1][c] : vb == 1 ? int(std::floor(cb)) : int(std::ceil(cb)), 0, 15);
        }
        try_colours(alt);
      }
  }
}

}  // namespace

namespace {

Texels make_texels(const std::uint8_t rgba[16][4], ColorMode mode) {
  Texels tx;
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 3; ++c) tx.rgb[i][c] = rgba[i][c];
    tx.transparent[i] = mode == ColorMode::etc2_punch && rgba[i][3] < 128;
    tx.any_transparent |= tx.transparent[i];
    tx.planes.r[i] = rgba[i][0], tx.planes.g[i] = rgba[i][1], tx.planes.b[i] = rgba[i][2];
    tx.planes.transparent[i] = 0;
  }
  for (int h = 0; h < 4; ++h) {
    const HalfLayout& L = halves()[std::size_t(h)];
    for (int i = 0; i < 8; ++i) {
      const int p = L.y[i] * 4 + L.x[i];
      tx.half[h].r[i] = tx.rgb[p][0], tx.half[h].g[i] = tx.rgb[p][1], tx.half[h].b[i] = tx.rgb[p][2];
      tx.half[h].sum[i] = tx.rgb[p][0] + tx.rgb[p][1] + tx.rgb[p][2];
      tx.half[h].transparent[i] = tx.transparent[p] ? 1 : 0;
    }
  }
  return tx;
}

// A colour block as `mode`'s decoder reads it (ETC1, ETC2, punch-through).
void decode_colour(const std::uint8_t block[8], ColorMode mode, Rgba8Block out) {
  if (mode == ColorMode::etc1) {
    decode_etc1(block, out);
  } else {
    decode_etc2(block, mode == ColorMode::etc2_punch, out);
  }
}

// Squared RGB error of a block (ETC1, or ETC2 in `mode`).
long block_error(const std::uint8_t rgba[16][4], const std::uint8_t block[8], ColorMode mode = ColorMode::etc1) {
  Rgba8Block decoded;
  decode_colour(block, mode, decoded);
  long err = 0;
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) err += long(rgba[i][c] - decoded[i][c]) * (rgba[i][c] - decoded[i][c]);
  return err;
}

// Opaque colour goes sixteen blocks at a time (etc_lanes.h) at every quality
// but `max`: every block of ETC1 and ETC2 RGB, and punch-through's opaque
// blocks (differential mode only: its bit 33 is the opaque flag).
bool etc_blocks_in_lanes(Quality q) { return q != Quality::max; }

// Punch-through's blocks with a texel of alpha below 128 (transparent).
bool any_transparent(const std::uint8_t rgba[16][4]) {
  for (int i = 0; i < 16; ++i)
    if (rgba[i][3] < 128) return true;
  return false;
}

// ETC2 at `normal` and `high`: the planar mode, and the T and H modes (at
// `normal` only where the lanes' ETC1 block, its error `err`, leaves more
// than 120 per texel, squared RGB), tried against it; the block is replaced
// if one wins. The texels come as the lanes took them (row by row,
// R | G << 8 | B << 16).
long finish_etc2_block(const std::uint32_t texel[16][kEtcBatch], int k, long err, Quality q, std::uint8_t block[8]) {
  Texels tx;
  for (int i = 0; i < 16; ++i) {
    const std::uint32_t t = texel[i][k];
    tx.rgb[i][0] = tx.planes.r[i] = int(t & 255), tx.rgb[i][1] = tx.planes.g[i] = int(t >> 8 & 255);
    tx.rgb[i][2] = tx.planes.b[i] = int(t >> 16 & 255);
    tx.transparent[i] = false, tx.planes.transparent[i] = 0;
  }
  Candidate best;
  best.err = err;
  best.bits = load_be64(block);
  search_planar(tx, q, best);
  if (q != Quality::normal || best.err > 16 * 120) search_t_h(tx, false, q, best);
  store_be64(best.bits, block);
  return best.err;
}

// One colour: the least error of each channel value under a base of `bits`
// (4 or 5) plus each of the 32 modifiers (the tables' entries, clamped as
// the decoder does), and the base that reaches it (the first of equals);
// and in a planar channel of 6 or 7 bits: O, H and V within 2 of the
// nearest level (a slightly tilted plane rounds to values on both sides of
// the colour, less error in all than one flat level).
struct FlatTables {
  int err[2][32][256], base[2][32][256];  // [bits 4, 5][table * 4 + index][value]
  int planar_err[2][256], planar_ohv[2][256][3];  // [6 bits, 7 bits][value]
};
const FlatTables& flat_tables() {
  static const FlatTables* t = [] {
    auto* f = new FlatTables;
    for (int b = 0; b < 2; ++b)
      for (int m = 0; m < 32; ++m)
        for (int v = 0; v < 256; ++v) {
          int best = std::numeric_limits<int>::max(), base = 0;
          for (int q = 0; q < (b ? 32 : 16); ++q) {
            const int d = v - clamp255(expand(q, b ? 5 : 4) + kModifiers[m / 4][m % 4]);
            if (d * d < best) best = d * d, base = q;
          }
          f->err[b][m][v] = best, f->base[b][m][v] = base;
        }
    for (int b = 0; b < 2; ++b)
      for (int v = 0; v < 256; ++v) {
        const int top = b ? 127 : 63;
        auto ex = [&](int q) { return b ? extend7(q) : extend6(q); };
        int q0 = 0;
        for (int q = 1; q <= top; ++q)
          if (std::abs(v - ex(q)) < std::abs(v - ex(q0))) q0 = q;
        int best = std::numeric_limits<int>::max();
        for (int o = std::max(0, q0 - 2); o <= std::min(top, q0 + 2); ++o)
          for (int h = std::max(0, q0 - 2); h <= std::min(top, q0 + 2); ++h)
            for (int w = std::max(0, q0 - 2); w <= std::min(top, q0 + 2); ++w) {
              int e = 0;
              for (int i = 0; i < 16; ++i) {  // as the decoder's plane
                const int d = clamp255(((i & 3) * (ex(h) - ex(o)) + (i >> 2) * (ex(w) - ex(o)) + 4 * ex(o) + 2) >> 2) - v;
                e += d * d;
              }
              if (e < best) best = e, f->planar_ohv[b][v][0] = o, f->planar_ohv[b][v][1] = h, f->planar_ohv[b][v][2] = w;
            }
        f->planar_err[b][v] = best;
      }
    return f;
  }();
  return *t;
}

// An opaque block of one colour (all 16 texels `rgb`): the least error the
// format allows it. Both halves share a base, a table and one modifier for
// every texel (the differential mode at 5 bits; the individual mode at 4,
// not with punch-through, whose bit 33 is the opaque flag), or, in ETC2, a
// flat plane. `block` is replaced where that beats its error.
void best_flat_block(const int rgb[3], ColorMode mode, std::uint8_t block[8]) {
  const FlatTables& f = flat_tables();
  Candidate best;
  for (int b = 1; b >= 0; --b) {
    if (b == 0 && mode == ColorMode::etc2_punch) continue;
    for (int m = 0; m < 32; ++m) {
      const long err = 16L * (f.err[b][m][rgb[0]] + f.err[b][m][rgb[1]] + f.err[b][m][rgb[2]]);
      if (err >= best.err) continue;
      HalfFit h;
      for (int c = 0; c < 3; ++c) h.q[c] = f.base[b][m][rgb[c]];
      h.table = m / 4;
      std::fill(h.idx, h.idx + 8, std::uint8_t(m % 4));
      keep(best, err, pack_halves(h, h, false, b == 1, b == 1 ? 1 : 0));
    }
  }
  if (mode != ColorMode::etc1) {
    int o[3], h[3], w[3];
    long err = 0;
    for (int c = 0; c < 3; ++c) {
      const int b = c == 1 ? 1 : 0;
      const int* ohv = f.planar_ohv[b][rgb[c]];
      o[c] = ohv[0], h[c] = ohv[1], w[c] = ohv[2], err += f.planar_err[b][rgb[c]];
    }
    keep(best, err, pack_planar(o, h, w));
  }
  Rgba8Block decoded;
  decode_colour(block, mode, decoded);
  long current = 0;
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) current += long(rgb[c] - decoded[i][c]) * (rgb[c] - decoded[i][c]);
  if (best.err < current) store_be64(best.bits, block);
}

// Punch-through with holes (the opaque flag clear) and one visible colour:
// the differential mode's modifiers are then 0 (index 0) and +-b (indices 1
// and 3), index 2 a hole. The best base for each of those, both halves
// alike; `block` is replaced where that beats its error over the visible
// texels, whose error it returns.
long best_flat_holes_block(const std::uint8_t rgba[16][4], const int rgb[3], std::uint8_t block[8]) {
  const FlatTables& f = flat_tables();
  int visible = 0;
  for (int i = 0; i < 16; ++i) visible += rgba[i][3] >= 128;
  Candidate best;
  for (int option = 0; option < 17; ++option) {  // 0: modifier 0; then table t's +b and -b
    const int t = option == 0 ? 0 : (option - 1) / 2, idx = option == 0 ? 0 : (option - 1) % 2 ? 3 : 1;
    int q[3];
    long per_texel = 0;
    for (int c = 0; c < 3; ++c) {
      if (option == 0) {
        int e = std::numeric_limits<int>::max();
        for (int v = 0; v < 32; ++v) {
          const int d = rgb[c] - extend5(v);
          if (d * d < e) e = d * d, q[c] = v;
        }
        per_texel += e;
      } else {
        q[c] = f.base[1][t * 4 + idx][rgb[c]], per_texel += f.err[1][t * 4 + idx][rgb[c]];
      }
    }
    const long err = per_texel * visible;
    if (err >= best.err) continue;
    HalfFit h[2];
    for (int s = 0; s < 2; ++s) {
      std::memcpy(h[s].q, q, sizeof q);
      h[s].table = t;
      const HalfLayout& L = halves()[std::size_t(s)];
      for (int i = 0; i < 8; ++i) h[s].idx[i] = std::uint8_t(rgba[L.y[i] * 4 + L.x[i]][3] >= 128 ? idx : 2);
    }
    keep(best, err, pack_halves(h[0], h[1], false, true, 0));
  }
  Rgba8Block decoded;
  decode_colour(block, ColorMode::etc2_punch, decoded);
  long current = 0;
  for (int i = 0; i < 16; ++i)
    if (rgba[i][3] >= 128)
      for (int c = 0; c < 3; ++c) current += long(rgb[c] - decoded[i][c]) * (rgb[c] - decoded[i][c]);
  if (best.err >= current) return current;
  store_be64(best.bits, block);
  return best.err;
}

// ETC2 at `fast`: a block of exactly two colours (text, line art, UI
// edges) also tries the T and H modes, which hold two 4-bit colours; its
// ETC1 block shares one base and table between the halves' texels and
// leaves such blocks far off (44 times the error of `normal` on random
// pairs). The block is replaced where one wins.
void two_colour_t_h(const std::uint32_t texel[16][kEtcBatch], int k, ColorMode mode, std::uint8_t block[8]) {
  if (!two_colours(texel, k)) return;
  Texels tx;
  for (int i = 0; i < 16; ++i) {
    const std::uint32_t t = texel[i][k];
    tx.rgb[i][0] = tx.planes.r[i] = int(t & 255), tx.rgb[i][1] = tx.planes.g[i] = int(t >> 8 & 255);
    tx.rgb[i][2] = tx.planes.b[i] = int(t >> 16 & 255);
    tx.transparent[i] = false, tx.planes.transparent[i] = 0;
  }
  std::uint8_t rgba[16][4];
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) rgba[i][c] = std::uint8_t(texel[i][k] >> (8 * c));
  Candidate best;
  best.err = block_error(rgba, block, mode);
  best.bits = load_be64(block);
  search_t_h(tx, false, Quality::fast, best);
  store_be64(best.bits, block);
}

// Whether the 16 texels (R | G << 8 | B << 16 | A << 24) are one colour,
// opaque where `mode` reads alpha (punch-through); `rgb` gets it.
bool flat_colour(const std::uint32_t texel[16][kEtcBatch], int k, ColorMode mode, int rgb[3]) {
  const bool punch = mode == ColorMode::etc2_punch;
  const std::uint32_t first = texel[0][k];
  for (int i = 0; i < 16; ++i)
    if ((texel[i][k] & 0xFFFFFF) != (first & 0xFFFFFF) || (punch && (texel[i][k] >> 24) < 128)) return false;
  rgb[0] = int(first & 255), rgb[1] = int(first >> 8 & 255), rgb[2] = int(first >> 16 & 255);
  return true;
}

}  // namespace

long encode_color_block(const std::uint8_t rgba[16][4], ColorMode mode, Quality q, std::uint8_t out[8]) {
  const bool punch = mode == ColorMode::etc2_punch;
  const bool opaque = !punch || !any_transparent(rgba);
  std::uint32_t texel[16][kEtcBatch] = {};  // lane 0: this block, for the lanes
  for (int i = 0; i < 16; ++i) texel[i][0] = pack_texel(rgba[i]);
  if (etc_blocks_in_lanes(q) && opaque) {  // as whole images do: etc_lanes.h
    std::uint8_t block[1][8];
    long err = 0;
    if (q == Quality::fast) {
      etc1_fast_lanes(texel, 1, punch, block);
      err = block_error(rgba, block[0]);
    } else {
      std::int32_t e[1];
      etc1_search_lanes(texel, 1, q == Quality::high, punch, block, e);
      err = mode == ColorMode::etc1 ? e[0] : finish_etc2_block(texel, 0, e[0], q, block[0]);
    }
    int rgb[3];
    if (flat_colour(texel, 0, mode, rgb)) {
      best_flat_block(rgb, mode, block[0]);
      err = block_error(rgba, block[0], mode);
    } else if (q == Quality::fast && mode != ColorMode::etc1) {  // as compress_etc
      two_colour_t_h(texel, 0, mode, block[0]);
      err = block_error(rgba, block[0], mode);
    }
    std::memcpy(out, block[0], 8);
    return err;
  }
  const Texels tx = make_texels(rgba, mode);
  Candidate best;
  if (q == Quality::max && opaque) {  // never below `high`: its block is the first candidate
    std::uint8_t block[1][8];
    std::int32_t e[1];
    etc1_search_lanes(texel, 1, true, punch, block, e);
    best.err = e[0];
    best.bits = load_be64(block[0]);
  }
  const bool non_opaque = punch && tx.any_transparent;
  // Bit 33: the differential flag, or with punch-through the opaque flag.
  const int bit33 = punch ? (non_opaque ? 0 : 1) : 1;
  search_etc1_modes(tx, q, !punch, non_opaque, bit33, best);
  if (mode != ColorMode::etc1 && q != Quality::fast) {
    if (!non_opaque) search_planar(tx, q, best);
    search_t_h(tx, non_opaque, q, best);
  }
  store_be64(best.bits, out);
  int rgb[3];
  if (flat_colour(texel, 0, mode, rgb)) {
    best_flat_block(rgb, mode, out);
    return block_error(rgba, out, mode);
  }
  if (non_opaque) {  // holes: one visible colour?
    int first = 0;
    while (first < 16 && rgba[first][3] < 128) ++first;
    bool one = first < 16;
    for (int i = first; i < 16 && one; ++i)
      one = rgba[i][3] < 128 || (rgba[i][0] == rgba[first][0] && rgba[i][1] == rgba[first][1] && rgba[i][2] == rgba[first][2]);
    if (one) {
      const int c[3] = {rgba[first][0], rgba[first][1], rgba[first][2]};
      return best_flat_holes_block(rgba, c, out);
    }
  }
  return best.err;
}

namespace {

int eac_value(EacKind kind, int base, int mult, int m) {
  switch (kind) {
    case EacKind::alpha8: return clamp255(base + m * mult);
    case EacKind::r11: return std::clamp(base * 8 + 4 + (mult ? m * mult * 8 : m), 0, 2047);
    case EacKind::r11_signed: return std::clamp(base * 8 + (mult ? m * mult * 8 : m), -1023, 1023);
  }
  return 0;
}

struct EacCandidate {
  double err = std::numeric_limits<double>::max();
  int base = 0, mult = 0, table = 0;
  std::uint8_t idx[16] = {};
};

void eac_try(const double t[16], EacKind kind, int base, int mult, int table, EacCandidate& best) {
  double vals[8], errors[16];
  for (int k = 0; k < 8; ++k) vals[k] = eac_value(kind, base, mult, kEacModifiers[table][k]);
  std::uint8_t idx[16];
  bc4_nearest(t, vals, idx, errors);  // each value's nearest of the 8 (SIMD twins, as for BC4)
  double err = 0;
  for (int i = 0; i < 16; ++i) err += errors[i];
  if (err >= best.err) return;
  best.err = err;
  best.base = base, best.mult = mult, best.table = table;
  std::memcpy(best.idx, idx, 16);
}

}  // namespace

double encode_eac_block(const float targets[16], EacKind kind, Quality q, std::uint8_t out[8]) {
  if (q != Quality::max) {  // as whole images do: eac_lanes.h
    float v[16][kEacBatch] = {};
    for (int i = 0; i < 16; ++i) v[i][0] = targets[i];
    std::uint8_t block[1][8];
    float err[1];
    eac_encode_lanes(v, 1, kind, lane_level(q), block, err);
    std::memcpy(out, block[0], 8);
    return err[0];
  }
  // `max`: every multiplier and +-8 bases around each one's centring base.
  const double lo_end = kind == EacKind::r11_signed ? -1023 : 0, hi_end = kind == EacKind::alpha8 ? 255 : kind == EacKind::r11 ? 2047 : 1023;
  double t[16], lo = hi_end, hi = lo_end;
  for (int i = 0; i < 16; ++i) {
    t[i] = std::clamp(double(targets[i]), lo_end, hi_end);
    lo = std::min(lo, t[i]);
    hi = std::max(hi, t[i]);
  }
  const int base_lo = kind == EacKind::r11_signed ? -127 : 0, base_hi = kind == EacKind::r11_signed ? 127 : 255;
  const double unit = kind == EacKind::alpha8 ? 1.0 : 8.0, offset = kind == EacKind::r11 ? 4.0 : 0.0;
  const int base_r = q == Quality::fast ? 0 : q == Quality::normal ? 1 : q == Quality::high ? 2 : 8;
  const int mult_r = q == Quality::fast ? 0 : q == Quality::normal ? 1 : q == Quality::high ? 2 : 15;
  EacCandidate best;
  const double centre = (lo + hi) / 2;
  for (int table = 0; table < 16; ++table) {
    const int mn = kEacModifiers[table][3], mx = kEacModifiers[table][7];
    const double mf = (hi - lo) / ((mx - mn) * unit);
    const int m0 = int(std::lround(mf));
    for (int mult = std::max(0, m0 - mult_r); mult <= std::min(15, m0 + mult_r + (q == Quality::fast ? 0 : 1)); ++mult) {
      // Multiplier 0 steps by the modifiers themselves (R11: 1/8 of the
      // multiplier-1 step); for 8-bit alpha it is a constant block.
      const double step = mult == 0 ? (kind == EacKind::alpha8 ? 0.0 : 1.0) : mult * unit;
      const double bf = (centre - offset - (mn + mx) / 2.0 * step) / unit;
      const int b0 = std::clamp(int(std::lround(bf)), base_lo, base_hi);
      for (int base = std::max(base_lo, b0 - base_r); base <= std::min(base_hi, b0 + base_r); ++base) {
        eac_try(t, kind, base, mult, table, best);
      }
    }
  }
  std::uint64_t v = 0;
  put(v, 63, 8, best.base & 255);
  put(v, 55, 4, best.mult);
  put(v, 51, 4, best.table);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) put(v, 47 - 3 * (x * 4 + y), 3, best.idx[y * 4 + x]);
  store_be64(v, out);
  return best.err;
}

std::vector<std::uint8_t> compress_etc(const ImageView& img, TexelFormat format, Quality q, const EncodeOptions& options) {
  using F = TexelFormat;
  const FormatInfo& info = format_info(format);
  const int bw = (img.width + 3) / 4, bh = (img.height + 3) / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * std::size_t(info.block_bytes));
  const bool eac = format >= F::eac_r11_unorm;
  const bool snorm = format == F::eac_r11_snorm || format == F::eac_rg11_snorm;
  const int eac_channels = format == F::eac_rg11_unorm || format == F::eac_rg11_snorm ? 2 : 1;
  const bool rgba8 = format == F::etc2_rgba8_unorm || format == F::etc2_rgba8_srgb;
  const ColorMode mode = format == F::etc1_rgb                                           ? ColorMode::etc1
                         : format == F::etc2_rgba1_unorm || format == F::etc2_rgba1_srgb ? ColorMode::etc2_punch
                                                                                         : ColorMode::etc2;
  // Opaque colour: sixteen blocks at a time (etc_lanes.h); ETC2 then tries
  // its planar, T and H modes block by block.
  const bool batched = etc_blocks_in_lanes(q);
  const bool punch = mode == ColorMode::etc2_punch;
  const bool finish = batched && q != Quality::fast && mode != ColorMode::etc1;  // ETC2: planar, T, H per block
  const bool eac_lanes = q != Quality::max;
  for_each_row_block(bh, 4, [&](int by0, int by1) {
    std::int32_t errors[kEtcBatch];
    std::uint8_t rgba[kEtcBatch][16][4];
    std::uint32_t texel[16][kEtcBatch] = {};
    std::uint8_t color[kEtcBatch][8];
    float values[16];
    float eac_values[16][kEacBatch];  // EAC: sixteen blocks at a time below `max` (eac_lanes.h)
    std::uint8_t eac_out[kEacBatch][8];
    float eac_err[kEacBatch];
    // The EAC blocks of eac_values, written `offset` bytes into their blocks.
    auto eac_encode = [&](int by, int bx0, int count, EacKind kind, int offset) {
      if (eac_lanes) {
        eac_encode_lanes(eac_values, count, kind, lane_level(q), eac_out, eac_err);
      } else {
        for (int k = 0; k < count; ++k) {
          for (int i = 0; i < 16; ++i) values[i] = eac_values[i][k];
          encode_eac_block(values, kind, q, eac_out[k]);
        }
      }
      for (int k = 0; k < count; ++k)
        std::memcpy(out.data() + (std::size_t(by) * bw + bx0 + k) * std::size_t(info.block_bytes) + offset, eac_out[k], 8);
    };
    for (int by = by0; by < by1; ++by)
      for (int bx0 = 0; bx0 < bw; bx0 += kEtcBatch) {
        const int count = std::min(kEtcBatch, bw - bx0);
        if (eac) {
          for (int c = 0; c < eac_channels; ++c) {
            for (int k = 0; k < count; ++k)
              for (int i = 0; i < 16; ++i) {
                // Partial blocks: the edge texels repeat into the missing ones.
                const int x = std::min((bx0 + k) * 4 + i % 4, img.width - 1), y = std::min(by * 4 + i / 4, img.height - 1);
                const float u = texel_unit(img, x, y, c);
                eac_values[i][k] = snorm ? (u * 2.0f - 1.0f) * 1023.0f : u * 2047.0f;
              }
            eac_encode(by, bx0, count, snorm ? EacKind::r11_signed : EacKind::r11, 8 * c);
          }
          continue;
        }
        // RGBA8 texels straight from the rows where they can be.
        const bool rows_direct = batched && !rgba8 && !punch && gather_rows_rgba8(img, bx0, by, count, texel);
        bool lanes_block[kEtcBatch];  // punch-through: only opaque blocks take the lanes' block
        for (int k = 0; k < count && !rows_direct; ++k) {
          const int bx = bx0 + k;
          std::uint8_t* dst = out.data() + (std::size_t(by) * bw + bx) * std::size_t(info.block_bytes);
          gather_rgba8(img, bx, by, rgba[k]);
          if (rgba8)
            for (int i = 0; i < 16; ++i) eac_values[i][k] = rgba[k][i][3];
          lanes_block[k] = batched && !(punch && any_transparent(rgba[k]));
          if (batched)
            for (int i = 0; i < 16; ++i) texel[i][k] = pack_texel(rgba[k][i]);
          if (!lanes_block[k]) encode_color_block(rgba[k], mode, q, dst + (rgba8 ? 8 : 0));
        }
        if (rgba8) eac_encode(by, bx0, count, EacKind::alpha8, 0);
        if (!batched) continue;
        if (rows_direct) std::fill(lanes_block, lanes_block + count, true);
        if (q == Quality::fast) {
          etc1_fast_lanes(texel, count, punch, color);
        } else {
          etc1_search_lanes(texel, count, q == Quality::high, punch, color, errors);
          for (int k = 0; k < count && finish; ++k)
            if (lanes_block[k]) finish_etc2_block(texel, k, errors[k], q, color[k]);
        }
        for (int k = 0; k < count; ++k) {
          if (!lanes_block[k]) continue;
          int rgb[3];
          if (flat_colour(texel, k, mode, rgb)) {
            best_flat_block(rgb, mode, color[k]);  // one colour: the format's best
          } else if (q == Quality::fast && mode != ColorMode::etc1) {
            two_colour_t_h(texel, k, mode, color[k]);
          }
          std::memcpy(out.data() + (std::size_t(by) * bw + bx0 + k) * std::size_t(info.block_bytes) + (rgba8 ? 8 : 0), color[k], 8);
        }
      }
  }, options.progress);
  return out;
}

}  // namespace texproc::etc
