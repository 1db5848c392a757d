// ETC2's added modes, scored with the decoder's own arithmetic: planar (a
// least-squares plane per channel, quantized, with a +-1 search per value:
// channels are independent) and T and H (two clusters split along the
// principal axis, their centres quantized to 4 bits, every distance tried).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "block/rgb_block.h"
#include "etc/etc_search.h"

namespace texproc::etc {

// Planar: per channel a least-squares plane, quantized (6/7/6 bits), with a
// +-1 search of each of O, H, V (channels are scored independently).
void search_planar(const Texels& tx, const Etc2Modes& modes, Candidate& best) {
  int o[3], hq[3], vq[3];
  long total = 0;
  for (int c = 0; c < 3; ++c) {
    const std::int32_t* px = c == 0 ? tx.planes.r : c == 1 ? tx.planes.g : tx.planes.b;
    const int bits = c == 1 ? 7 : 6;
    // The plane through the texels' mean with slopes a (x) and b (y):
    // sums of integers, exact (sx, sy: twice the x and y moments about 1.5).
    int sum = 0, sx = 0, sy = 0;
    for (int i = 0; i < 16; ++i) {
      sum += px[i];
      sx += (2 * (i & 3) - 3) * px[i];
      sy += (2 * (i >> 2) - 3) * px[i];
    }
    const double a = sx / 40.0, b = sy / 40.0, O = sum / 16.0 - 1.5 * a - 1.5 * b;
    const int top = (1 << bits) - 1;
    auto qz = [&](double v) { return std::clamp(int(std::lround(v * top / 255.0)), 0, top); };
    auto ex = [&](int v) { return bits == 7 ? extend7(v) : extend6(v); };
    const int c0[3] = {qz(O), qz(O + 4 * a), qz(O + 4 * b)};
    int be = std::numeric_limits<int>::max();
    int bo = c0[0], bh = c0[1], bv = c0[2];
    const int r = modes.planar_radius;
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
          if (e < be) {
            be = e;
            bo = vo;
            bh = vh;
            bv = vv;
          }
        }
    o[c] = bo;
    hq[c] = bh;
    vq[c] = bv;
    total += be;
    if (total >= best.err) return;  // errors only add up: planar cannot win
  }
  keep(best, total, pack_planar(o, hq, vq));
}

// A planar block's bits for O, H and V (6/7/6 bits a channel).
std::uint64_t pack_planar(const int o[3], const int hq[3], const int vq[3]) {
  std::uint64_t v = 0;
  put(v, 62, 6, o[0]);
  put(v, 56, 1, o[1] >> 6);
  put(v, 54, 6, o[1] & 63);
  put(v, 48, 1, o[2] >> 5);
  put(v, 44, 2, o[2] >> 3 & 3);
  put(v, 41, 2, o[2] >> 1 & 3);
  put(v, 39, 1, o[2] & 1);
  put(v, 38, 5, hq[0] >> 1);
  put(v, 32, 1, hq[0] & 1);
  put(v, 31, 7, hq[1]);
  put(v, 24, 1, hq[2] >> 5);
  put(v, 23, 5, hq[2] & 31);
  put(v, 18, 6, vq[0]);
  put(v, 12, 7, vq[1]);
  put(v, 5, 6, vq[2]);
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
    put(v, 47, 3, 7);
    put(v, 42, 1, 0);
  } else {
    put(v, 47, 3, 0);
    put(v, 42, 1, 1);
  }
  return v;
}

namespace {

// The block's colours as two clusters: split by the sign of their
// projection on the principal axis, refined by k-means (three steps).
// False where there are not two (fewer than two visible texels, or a
// cluster empties).
bool two_clusters(const Texels& tx, bool non_opaque, double centre[2][3], bool side[16]) {
  int n = 0;
  double mean[3] = {0, 0, 0};
  for (int i = 0; i < 16; ++i) {
    if (non_opaque && tx.transparent[i]) continue;
    for (int c = 0; c < 3; ++c) mean[c] += tx.rgb[i][c];
    ++n;
  }
  if (n < 2) return false;
  for (double& m : mean) m /= n;
  double cov[3][3] = {};
  for (int i = 0; i < 16; ++i) {
    if (non_opaque && tx.transparent[i]) continue;
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = tx.rgb[i][c] - mean[c];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) cov[a][b] += d[a] * d[b];
  }
  // Power iteration in double from (1, 1, 1), normalized each step (ETC2's
  // own: the BC1 searches' float iterations differ in order and so in bytes).
  double axis[3] = {1, 1, 1};
  for (int it = 0; it < 8; ++it) {
    double nx[3] = {0, 0, 0};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) nx[a] += cov[a][b] * axis[b];
    const double len = std::sqrt(nx[0] * nx[0] + nx[1] * nx[1] + nx[2] * nx[2]);
    if (len < 1e-9) break;
    for (int a = 0; a < 3; ++a) axis[a] = nx[a] / len;
  }
  for (int i = 0; i < 16; ++i) {
    double p = 0;
    for (int c = 0; c < 3; ++c) p += (tx.rgb[i][c] - mean[c]) * axis[c];
    side[i] = p > 0;
  }
  for (int it = 0; it < 3; ++it) {
    int count[2] = {0, 0};
    std::memset(centre, 0, sizeof(double) * 6);
    for (int i = 0; i < 16; ++i) {
      if (non_opaque && tx.transparent[i]) continue;
      for (int c = 0; c < 3; ++c) centre[side[i]][c] += tx.rgb[i][c];
      ++count[side[i]];
    }
    if (count[0] == 0 || count[1] == 0) return false;
    for (int s = 0; s < 2; ++s)
      for (int c = 0; c < 3; ++c) centre[s][c] /= count[s];
    for (int i = 0; i < 16; ++i) {
      double d[2] = {0, 0};
      for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c) d[s] += (tx.rgb[i][c] - centre[s][c]) * (tx.rgb[i][c] - centre[s][c]);
      side[i] = d[1] < d[0];
    }
  }
  return true;
}

// T and H for pairs of 4-bit cluster colours, distances d_lo..d_hi; `best`
// replaced where one wins; th_min the least T or H error seen.
struct THSearch {
  const Texels& tx;
  bool non_opaque;
  int d_lo, d_hi;
  Candidate& best;
  long th_min = kNone;
  int opaque_bit() const {
    return non_opaque ? 0 : 1;
  }  // bit 33: the differential flag, or punch-through's opaque flag

  // Scores four paint colours: each texel's nearest (first of equals).
  long score(const int paint[4][3], std::uint8_t idx[16]) const {
    if (!non_opaque) {  // SIMD twins
      int pal[4][3];
      for (int k = 0; k < 4; ++k)
        for (int c = 0; c < 3; ++c) pal[k][c] = clamp255(paint[k][c]);
      return long(tx.planes.k.nearest(tx.planes, pal, 4, idx));
    }
    long err = 0;
    for (int i = 0; i < 16; ++i) {
      if (tx.transparent[i]) {
        idx[i] = 2;
        continue;
      }
      long be = kNone;
      int bk = 0;
      for (int k = 0; k < 4; ++k) {
        if (k == 2) continue;  // punch-through's transparent index
        long e = 0;
        for (int c = 0; c < 3; ++c) {
          const long d = clamp255(paint[k][c]) - tx.rgb[i][c];
          e += d * d;
        }
        if (e < be) {
          be = e;
          bk = k;
        }
      }
      idx[i] = std::uint8_t(bk);
      err += be;
    }
    return err;
  }
  static void put_indices(std::uint64_t& v, const std::uint8_t idx[16]) {
    for (int i = 0; i < 16; ++i) put_index(v, i % 4, i / 4, idx[i]);
  }

  // T: one cluster is the single colour C1, the other C2 +- d.
  void try_t(const int (&qc)[2][3]) {
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
        put(v, 60, 2, c1[0] >> 2);
        put(v, 57, 2, c1[0] & 3);
        put(v, 55, 4, c1[1]);
        put(v, 51, 4, c1[2]);
        put(v, 47, 4, c2[0]);
        put(v, 43, 4, c2[1]);
        put(v, 39, 4, c2[2]);
        put(v, 35, 2, di >> 1);
        put(v, 32, 1, di & 1);
        put(v, 33, 1, opaque_bit());
        if ((c1[0] >> 2) + (c1[0] & 3) > 3) {
          put(v, 63, 3, 7);
          put(v, 58, 1, 0);
        } else {
          put(v, 63, 3, 0);
          put(v, 58, 1, 1);
        }
        put_indices(v, idx);
        keep(best, e, v);
      }
    }
  }

  // H: C1 +- d and C2 +- d; the distance index's low bit is the order of
  // the two colours, so a colour pair in the wrong order is swapped.
  void try_h(const int (&qc)[2][3]) {
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
      put(v, 62, 4, c1[0]);
      put(v, 58, 3, c1[1] >> 1);
      put(v, 52, 1, c1[1] & 1);
      put(v, 51, 1, c1[2] >> 3);
      put(v, 49, 2, c1[2] >> 1 & 3);
      put(v, 47, 1, c1[2] & 1);
      put(v, 46, 4, c2[0]);
      put(v, 42, 3, c2[1] >> 1);
      put(v, 39, 1, c2[1] & 1);
      put(v, 38, 4, c2[2]);
      put(v, 34, 1, di >> 2);
      put(v, 32, 1, di >> 1 & 1);
      put(v, 33, 1, opaque_bit());
      // Red in range (bit 63), green out of range (bits 55-53 and 50).
      {
        const int s = c1[0] + ((c1[1] >> 1) >= 4 ? (c1[1] >> 1) - 8 : (c1[1] >> 1));
        put(v, 63, 1, s < 0 ? 1 : 0);
      }
      const int g = (c1[1] & 1) * 2 + (c1[2] >> 3), bb = c1[2] >> 1 & 3;
      if (g + bb > 3) {
        put(v, 55, 3, 7);
        put(v, 50, 1, 0);
      } else {
        put(v, 55, 3, 0);
        put(v, 50, 1, 1);
      }
      put_indices(v, idx);
      keep(best, e, v);
    }
  }

  void try_colours(const int (&qc)[2][3]) {
    try_t(qc);
    try_h(qc);
  }
};

}  // namespace

// T and H modes: two clusters along the principal axis.
void search_t_h(const Texels& tx, bool non_opaque, const Etc2Modes& modes, Candidate& best) {
  double centre[2][3] = {};
  bool side[16] = {};
  if (!two_clusters(tx, non_opaque, centre, side)) return;
  int q[2][3];
  for (int s = 0; s < 2; ++s)
    for (int c = 0; c < 3; ++c) q[s][c] = quantize(centre[s][c], 4);
  // Distances worth trying: at `normal`, the three nearest to the clusters'
  // spread about their centres (the mean absolute deviation along the
  // channels); `high` tries all eight.
  int d_lo = 0, d_hi = 7;
  if (!modes.t_h_every_distance) {
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
    d_lo = std::max(0, nearest - 1);
    d_hi = std::min(7, nearest + 1);
  }

  THSearch search{tx, non_opaque, d_lo, d_hi, best};
  const long before = best.err;  // the best of the other modes
  search.try_colours(q);
  // Where T or H came close to the other modes (within a quarter), at
  // `high`: the quantization's other neighbours too.
  if (modes.t_h_requantize && search.th_min < before + before / 4) {
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
        search.try_colours(alt);
      }
  }
}

}  // namespace texproc::etc
