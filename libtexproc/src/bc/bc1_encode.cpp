// BC1 colour blocks (and the colour half of BC2 and BC3): principal-axis
// endpoints, least-squares refinement, both BC1 modes, and optimal
// single-colour blocks. Errors are squared RGB differences in the stored
// (8-bit, usually sRGB-encoded) values, decoded exactly as bc_decode.cpp
// does (5/6-bit endpoints expanded by bit replication, interpolation rounded
// to nearest).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "bc/bc1_encode.h"
#include "bc/bc1_block.h"
#include "block/rgb_block.h"
#include "bc/bc1_cluster.h"
#include "bc/bc1_lanes.h"
#include "block/block_gather.h"
#include "block/principal_axis.h"
#include "block/quantize.h"

namespace texproc {

using namespace bc1;  // the block as bc1_block.h defines it

namespace {

std::uint16_t pack(const int q[3]) { return std::uint16_t(q[0] << 11 | q[1] << 5 | q[2]); }

// Best index per texel for endpoints in a mode; `transparent[i]` texels take
// index 3 of the three-colour mode; `allow_black`: opaque texels may use it.
void assign(const RgbBlock& tx, const Endpoints& e, bool four, bool allow_black, Result& r) {
  int pal[4][3];
  palette(e, four, pal);
  r.e = e;
  r.four = four;
  r.error = tx.k.nearest(tx, pal, four ? 4 : (allow_black ? 4 : 3), r.idx);  // SIMD twins
}

int quantize(float v, int bits) { return quantize_channel(v, (1 << bits) - 1); }  // block/quantize.h

Endpoints quantize(const float a[3], const float b[3]) {
  Endpoints e;
  for (int k = 0; k < 2; ++k) {
    const float* src = k ? b : a;
    e.c[k][0] = quantize(src[0], 5);
    e.c[k][1] = quantize(src[1], 6);
    e.c[k][2] = quantize(src[2], 5);
  }
  return e;
}

// Least-squares endpoints for the current indices (weights along c0 -> c1
// for the palette positions, in thirds or halves: integer sums, exact).
// False if singular (all texels at one end).
bool refit(const RgbBlock& tx, const Result& r, float a[3], float b[3]) {
  static constexpr int kFour[4] = {0, 3, 1, 2}, kThree[4] = {0, 2, 1, -1};
  const int den = r.four ? 3 : 2;
  RgbLsSums s;
  tx.k.ls_sums(tx, r.idx, r.four ? kFour : kThree, den, s);  // SIMD twins
  const double det = double(s.aa) * s.bb - double(s.ab) * s.ab;
  if (det == 0) return false;
  const double scale = den / det;
  for (int ch = 0; ch < 3; ++ch) {
    a[ch] = float(std::clamp((double(s.at[ch]) * s.bb - double(s.bt[ch]) * s.ab) * scale, 0.0, 255.0));
    b[ch] = float(std::clamp((double(s.bt[ch]) * s.aa - double(s.at[ch]) * s.ab) * scale, 0.0, 255.0));
  }
  return true;
}

// For every 8-bit value, the endpoint pair (5 or 6 bits) whose 2/3-1/3
// interpolation (index 2 of the four-colour mode) comes closest; the
// optimal encoding of a one-colour block (as stb_dxt's and rgbcx's tables).
// And the same for the three-colour mode's average (a + b + 1) / 2. A
// one-colour block uses one index in every channel, so it is one of these
// two (indices 0, 1 and 3 are the same entries with equal or swapped ends).
struct SingleColorTables {
  // [mode][value] = endpoint pair; mode 0: four-colour index 2, 1: average.
  std::array<std::array<std::array<std::uint8_t, 2>, 256>, 2> five{}, six{};
  // The pair found first, in (a, b) order, at the least distance: each
  // pair's value is computed once, then each target looks at the values
  // nearest it (the same pairs as scanning every pair for every target, in
  // 1/256 of the time: this runs at the first BC1 encode of a process).
  SingleColorTables() {
    for (int mode = 0; mode < 2; ++mode)
      for (int bits : {5, 6}) {
        const int n = 1 << bits;
        auto& table = (bits == 5 ? five : six)[std::size_t(mode)];  // named once (see bc1_lanes_simd.cpp's nudge)
        std::array<int, 256> first;  // value -> index a * n + b of the first pair giving it, -1 if none
        first.fill(-1);
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b) {
            const int ea = bits == 5 ? expand5(a) : expand6(a), eb = bits == 5 ? expand5(b) : expand6(b);
            const int value = mode == 0 ? (2 * ea + eb + 1) / 3 : (ea + eb + 1) / 2;
            if (first[std::size_t(value)] < 0) first[std::size_t(value)] = a * n + b;
          }
        for (int v = 0; v < 256; ++v) {
          for (int d = 0; d < 256; ++d) {
            const int lo = v - d >= 0 ? first[std::size_t(v - d)] : -1;
            const int hi = d > 0 && v + d < 256 ? first[std::size_t(v + d)] : -1;
            if (lo < 0 && hi < 0) continue;
            const int pair = lo < 0 ? hi : hi < 0 ? lo : std::min(lo, hi);
            table[std::size_t(v)] = {std::uint8_t(pair / n), std::uint8_t(pair % n)};
            break;
          }
        }
      }
  }
};

const SingleColorTables& single() {
  static const SingleColorTables t;
  return t;
}

// Cluster fit (as libsquish's, with every candidate scored exactly): the
// opaque texels ordered along `axis` are split into consecutive clusters,
// one per palette entry (four: a, 2/3 a + 1/3 b, 1/3 a + 2/3 b, b; three: a,
// (a + b) / 2, b); each split's least-squares endpoints come in closed form
// from prefix sums. The `keep_best` splits with the least unquantized error
// are quantized and scored under the exact decoding.
void cluster_fit(const std::uint8_t rgb[16][3], const bool transparent[16], const double axis[3], bool four,
                 int keep_best, std::vector<Endpoints>& out) {
  int order[16], n = 0;
  double proj[16];
  for (int i = 0; i < 16; ++i) {
    if (transparent[i]) continue;
    proj[i] = rgb[i][0] * axis[0] + rgb[i][1] * axis[1] + rgb[i][2] * axis[2];
    order[n++] = i;
  }
  std::stable_sort(order, order + n, [&](int x, int y) { return proj[x] < proj[y]; });
  // Prefix sums of the colours in that order.
  double pre[17][3] = {};
  double total_sq = 0;
  for (int k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) pre[k + 1][c] = pre[k][c] + rgb[order[k]][c];
    for (int c = 0; c < 3; ++c) total_sq += double(rgb[order[k]][c]) * rgb[order[k]][c];
  }
  struct Split {
    double err;
    float a[3], b[3];
  };
  Split best[8];
  int kept = 0;
  keep_best = std::min(keep_best, 8);
  double worst_err = 1e300;  // the error a split must beat once `keep_best` are kept
  auto insert = [&](const Split& sp) {
    if (kept < keep_best) {
      best[kept++] = sp;
    } else if (sp.err < worst_err) {
      int w = 0;
      for (int m = 1; m < kept; ++m)
        if (best[m].err > best[w].err) w = m;
      best[w] = sp;
    } else {
      return;
    }
    if (kept == keep_best) {
      worst_err = best[0].err;
      for (int m = 1; m < kept; ++m) worst_err = std::max(worst_err, best[m].err);
    }
  };
  auto consider = [&](const double w_a[4], const double w_b[4], const int bounds[5], int clusters) {
    double aa = 0, ab = 0, bb = 0, xa[3] = {}, xb[3] = {};
    for (int k = 0; k < clusters; ++k) {
      const int cnt = bounds[k + 1] - bounds[k];
      if (cnt == 0) continue;
      aa += cnt * w_a[k] * w_a[k];
      ab += cnt * w_a[k] * w_b[k];
      bb += cnt * w_b[k] * w_b[k];
      for (int c = 0; c < 3; ++c) {
        const double sum = pre[bounds[k + 1]][c] - pre[bounds[k]][c];
        xa[c] += w_a[k] * sum;
        xb[c] += w_b[k] * sum;
      }
    }
    const double det = aa * bb - ab * ab;
    if (std::abs(det) < 1e-9) return;
    Split sp;
    double err = total_sq;
    for (int c = 0; c < 3; ++c) {
      const double a = std::clamp((xa[c] * bb - xb[c] * ab) / det, 0.0, 255.0);
      const double b = std::clamp((xb[c] * aa - xa[c] * ab) / det, 0.0, 255.0);
      sp.a[c] = float(a);
      sp.b[c] = float(b);
      err += -2 * (a * xa[c] + b * xb[c]) + a * a * aa + 2 * a * b * ab + b * b * bb;
    }
    sp.err = err;
    insert(sp);
  };
  if (four) {
    // The four-cluster splits, a row of k at a time (SIMD twins).
    ClusterRow row;
    for (int i = 0; i <= n; ++i)
      for (int j = i; j <= n; ++j) {
        cluster_splits(pre, total_sq, n, i, j, row);
        for (int k = j; k <= n; ++k) {
          const double err = row.err[k - j];
          if (err == std::numeric_limits<double>::infinity()) continue;
          if (kept == keep_best && err >= worst_err) continue;
          Split sp;
          sp.err = err;
          for (int c = 0; c < 3; ++c) {
            sp.a[c] = float(row.a[k - j][c]);
            sp.b[c] = float(row.b[k - j][c]);
          }
          insert(sp);
        }
      }
  } else {
    static constexpr double wa[3] = {1.0, 0.5, 0.0}, wb[3] = {0.0, 0.5, 1.0};
    for (int i = 0; i <= n; ++i)
      for (int j = i; j <= n; ++j) {
        const int bounds[5] = {0, i, j, n, n};
        consider(wa, wb, bounds, 3);
      }
  }
  // Least error first (insertion sort: at most eight).
  for (int a = 1; a < kept; ++a)
    for (int b = a; b > 0 && best[b].err < best[b - 1].err; --b) std::swap(best[b], best[b - 1]);
  for (int k = 0; k < kept; ++k) out.push_back(quantize(best[k].a, best[k].b));
}

void keep_better(Result& best, const Result& r) {
  if (best.error < 0 || r.error < best.error) best = r;
}

bool is_one_opaque_colour(const RgbBlock& tx) {
  bool one = !tx.transparent[0];
  for (int i = 1; i < 16 && one; ++i)
    one = !tx.transparent[i] && tx.r[i] == tx.r[0] && tx.g[i] == tx.g[0] && tx.b[i] == tx.b[0];
  return one;
}

// One opaque colour (most of what the lanes leave here): the optimal
// single-colour pair through index 2, each mode's palette entry nearest
// the colour (the first of equals, as rgb_palette_nearest picks) for all 16.
Result one_colour_block(const RgbBlock& tx, bool three_allowed) {
  Result best;
  best.error = -1;
  const SingleColorTables& s = single();
  const int c[3] = {tx.r[0], tx.g[0], tx.b[0]};
  for (int md = 0; md < (three_allowed ? 2 : 1); ++md) {
    Result r;
    for (int k = 0; k < 2; ++k) {
      r.e.c[k][0] = s.five[md][c[0]][k];
      r.e.c[k][1] = s.six[md][c[1]][k];
      r.e.c[k][2] = s.five[md][c[2]][k];
    }
    r.four = md == 0;
    int pal[4][3], nearest = 0, least = -1;
    palette(r.e, r.four, pal);
    for (int k = 0; k < (r.four ? 4 : 3); ++k) {
      const int d = (c[0] - pal[k][0]) * (c[0] - pal[k][0]) + (c[1] - pal[k][1]) * (c[1] - pal[k][1]) +
                    (c[2] - pal[k][2]) * (c[2] - pal[k][2]);
      if (least < 0 || d < least) {
        least = d;
        nearest = k;
      }
    }
    std::fill(r.idx, r.idx + 16, std::uint8_t(nearest));
    r.error = 16LL * least;
    keep_better(best, r);
  }
  return best;
}

// One opaque colour among transparent texels (punch-through: the
// three-colour mode): the single-colour pair through the average (index
// 2), or both ends at the colour's nearest 5:6:5 value (index 0),
// whichever leaves less error; the holes take index 3.
Result punch_one_colour_block(const RgbBlock& tx) {
  Result best;
  best.error = -1;
  int first = 0;
  while (tx.transparent[first]) ++first;
  const int c[3] = {tx.r[first], tx.g[first], tx.b[first]};
  const SingleColorTables& s = single();
  Endpoints through, ends;
  for (int k = 0; k < 2; ++k) {
    through.c[k][0] = s.five[1][c[0]][k];
    through.c[k][1] = s.six[1][c[1]][k];
    through.c[k][2] = s.five[1][c[2]][k];
    for (int ch = 0; ch < 3; ++ch) {
      const int bits = ch == 1 ? 6 : 5;
      int nearest_q = 0;
      for (int v = 1; v < (1 << bits); ++v)
        if (std::abs((bits == 6 ? expand6(v) : expand5(v)) - c[ch]) <
            std::abs((bits == 6 ? expand6(nearest_q) : expand5(nearest_q)) - c[ch]))
          nearest_q = v;
      ends.c[k][ch] = nearest_q;
    }
  }
  for (const Endpoints& e : {through, ends}) {
    Result r;
    assign(tx, e, false, false, r);
    keep_better(best, r);
  }
  return best;
}

// Principal axis of the opaque colours from their covariance (times n^2),
// each power-iteration step divided by its largest component
// (block/principal_axis.h: the lanes multiply by its reciprocal instead).
void colour_axis(const std::int64_t cov_n2[6], float axis[3]) {
  const float cov[6] = {float(cov_n2[0]), float(cov_n2[1]), float(cov_n2[2]),
                        float(cov_n2[3]), float(cov_n2[4]), float(cov_n2[5])};
  principal_axis<AxisScaling::divide>(cov, axis);
}

// A block's texels as the cluster fit takes them, and its principal axis.
struct ClusterInput {
  std::uint8_t rgb[16][3];
  bool transparent[16];
  double axis[3];
};

// The search in one mode (four or three colours) from the extent's ends a,
// b: least-squares refits, then the cluster fits and the nudges the level
// asks for (Bc1BlockSearch, bc1_levels.h).
Result search_mode(const RgbBlock& tx, bool four, const float a[3], const float b[3], const ClusterInput& in,
                   const Bc1BlockSearch& search) {
  Result r;
  assign(tx, quantize(a, b), four, false, r);
  for (int it = 0; it < search.refinements; ++it) {
    float ra[3], rb[3];
    if (!refit(tx, r, ra, rb)) break;
    Result n2;
    assign(tx, quantize(ra, rb), four, false, n2);
    if (n2.error >= r.error) break;
    r = n2;
  }
  // Cluster fit along the principal axis (and, iterated, along the best
  // endpoints' axis): its best splits compete under the exact decoding.
  double fit_axis[3] = {in.axis[0], in.axis[1], in.axis[2]};
  for (int round = 0; round < search.cluster_rounds; ++round) {
    std::vector<Endpoints> cands;
    cluster_fit(in.rgb, in.transparent, fit_axis, four, search.cluster_kept, cands);
    for (const Endpoints& e : cands) {
      Result n2;
      assign(tx, e, four, false, n2);
      if (n2.error < r.error) r = n2;
    }
    double d[3], len = 0;
    for (int c = 0; c < 3; ++c) {
      const int hi_ch = c == 1 ? expand6(r.e.c[1][c]) : expand5(r.e.c[1][c]);
      const int lo_ch = c == 1 ? expand6(r.e.c[0][c]) : expand5(r.e.c[0][c]);
      d[c] = hi_ch - lo_ch;
      len += d[c] * d[c];
    }
    if (len < 1e-9) break;
    for (int c = 0; c < 3; ++c) fit_axis[c] = d[c] / std::sqrt(len);
  }
  // Nudge each quantized endpoint channel by one step while it helps.
  bool improved = search.nudge;  // off: no pass
  for (int pass = 0; improved && pass < 4; ++pass) {
    improved = false;
    for (int k = 0; k < 2; ++k)
      for (int ch = 0; ch < 3; ++ch)
        for (int d : {-1, 1}) {
          Endpoints e = r.e;
          e.c[k][ch] += d;
          if (e.c[k][ch] < 0 || e.c[k][ch] > (ch == 1 ? 63 : 31)) continue;
          Result n2;
          assign(tx, e, four, false, n2);
          if (n2.error < r.error) {
            r = n2;
            improved = true;
          }
        }
  }
  return r;
}

// The lanes' block for these texels at `lane` as a candidate (where the
// lanes take the block and its mode is one the block may use).
void keep_lane_block(const RgbBlock& tx, Bc1Mode mode, const Bc1LaneSearch& lane, bool any_transparent, Result& best) {
  const bool three_allowed = mode != Bc1Mode::four_only;
  std::uint32_t texel[16][kBc1Batch] = {};
  for (int i = 0; i < 16; ++i) {
    const std::uint8_t px[4] = {std::uint8_t(tx.r[i]), std::uint8_t(tx.g[i]), std::uint8_t(tx.b[i]),
                                std::uint8_t(tx.transparent[i] ? 0 : 255)};
    texel[i][0] = pack_texel(px);
  }
  std::uint8_t block[1][8];
  bool handled = false;
  bc1_encode_lanes(texel, 1, lane, three_allowed, mode == Bc1Mode::bc1_punch_through, block, &handled);
  if (!handled) return;
  const std::uint16_t c0 = std::uint16_t(block[0][0] | block[0][1] << 8),
                      c1 = std::uint16_t(block[0][2] | block[0][3] << 8);
  const bool four = mode == Bc1Mode::four_only || c0 > c1;
  if (!(four || three_allowed) || (four && any_transparent)) return;
  Endpoints e;
  for (int k = 0; k < 2; ++k) {
    const int c = k ? c1 : c0;
    e.c[k][0] = c >> 11;
    e.c[k][1] = c >> 5 & 63;
    e.c[k][2] = c & 31;
  }
  Result r;
  assign(tx, e, four, false, r);
  keep_better(best, r);
}

// Block by block: `max`, and the blocks the lanes leave (one opaque colour,
// with or without transparent texels, or none opaque).
void encode_block_by_block(const RgbBlock& tx, Bc1Mode mode, const Bc1Level& level, std::uint8_t out[8]) {
  const bool three_allowed = mode != Bc1Mode::four_only;
  if (is_one_opaque_colour(tx)) return write(one_colour_block(tx, three_allowed), out);

  // Opaque texels only decide the endpoints.
  RgbMoments m;
  tx.k.moments(tx, m);  // SIMD twins
  const int n = m.n;
  const bool any_transparent = n < 16;
  if (n == 0) {  // fully transparent: any endpoints, every index 3
    Result r;
    r.four = false;
    std::memset(&r.e, 0, sizeof r.e);
    std::fill(r.idx, r.idx + 16, std::uint8_t(3));
    write(r, out);
    return;
  }
  // Covariance (times n^2, exact) and mean.
  const std::int64_t cov_n2[6] = {std::int64_t(m.sq[0]) * n - std::int64_t(m.sum[0]) * m.sum[0],
                                  std::int64_t(m.sq[1]) * n - std::int64_t(m.sum[0]) * m.sum[1],
                                  std::int64_t(m.sq[2]) * n - std::int64_t(m.sum[0]) * m.sum[2],
                                  std::int64_t(m.sq[3]) * n - std::int64_t(m.sum[1]) * m.sum[1],
                                  std::int64_t(m.sq[4]) * n - std::int64_t(m.sum[1]) * m.sum[2],
                                  std::int64_t(m.sq[5]) * n - std::int64_t(m.sum[2]) * m.sum[2]};
  float mean[3];
  for (int ch = 0; ch < 3; ++ch) mean[ch] = float(m.sum[ch]) / float(n);
  if (cov_n2[0] == 0 && cov_n2[3] == 0 && cov_n2[5] == 0 && any_transparent)
    return write(punch_one_colour_block(tx), out);

  float axis[3];
  colour_axis(cov_n2, axis);
  float lo, hi;
  tx.k.project_range(tx, axis, lo, hi);  // SIMD twins
  const float mean_p = mean[0] * axis[0] + mean[1] * axis[1] + mean[2] * axis[2];
  float a[3], b[3];
  for (int ch = 0; ch < 3; ++ch) {
    a[ch] = std::clamp(mean[ch] + (hi - mean_p) * axis[ch], 0.0f, 255.0f);
    b[ch] = std::clamp(mean[ch] + (lo - mean_p) * axis[ch], 0.0f, 255.0f);
  }
  // The cluster fit works on double colours.
  ClusterInput in;
  for (int i = 0; i < 16; ++i) {
    in.rgb[i][0] = std::uint8_t(tx.r[i]);
    in.rgb[i][1] = std::uint8_t(tx.g[i]);
    in.rgb[i][2] = std::uint8_t(tx.b[i]);
    in.transparent[i] = tx.transparent[i] != 0;
  }
  for (int ch = 0; ch < 3; ++ch) in.axis[ch] = axis[ch];
  Result best;
  best.error = -1;
  for (int four = 1; four >= 0; --four) {
    if (!four && !three_allowed) continue;
    if (four && any_transparent) continue;  // transparent texels need the three-colour mode
    keep_better(best, search_mode(tx, four != 0, a, b, in, level.block));
  }
  // Never below the lanes' search: its endpoints compete too.
  if (level.block.lane_candidate) keep_lane_block(tx, mode, level.lane, any_transparent, best);
  write(best, out);
}

}  // namespace

void encode_bc1_color(const std::uint8_t rgba[16][4], Bc1Mode mode, Quality q, std::uint8_t out[8]) {
  if (bc1_level(q).lanes) {  // as whole images do: bc1_lanes.h
    std::uint32_t texel[16][kBc1Batch] = {};
    for (int i = 0; i < 16; ++i) texel[i][0] = pack_texel(rgba[i]);
    std::uint8_t block[1][8];
    bool handled = false;
    bc1_encode_lanes(texel, 1, bc1_level(q).lane, mode != Bc1Mode::four_only, mode == Bc1Mode::bc1_punch_through, block,
                     &handled);
    if (handled) {
      std::memcpy(out, block[0], 8);
      return;
    }
  }
  encode_bc1_color_block_by_block(rgba, mode, q, out);
}

void encode_bc1_color_block_by_block(const std::uint8_t rgba[16][4], Bc1Mode mode, Quality q, std::uint8_t out[8]) {
  RgbBlock tx;
  for (int i = 0; i < 16; ++i) {
    tx.r[i] = rgba[i][0];
    tx.g[i] = rgba[i][1];
    tx.b[i] = rgba[i][2];
    tx.transparent[i] = mode == Bc1Mode::bc1_punch_through && rgba[i][3] < 128 ? 1 : 0;
  }
  encode_block_by_block(tx, mode, bc1_level(q), out);
}

void bc1::write(const Result& r, std::uint8_t out[8]) {
  Endpoints e = r.e;
  std::uint8_t idx[16];
  std::memcpy(idx, r.idx, 16);
  std::uint16_t c0 = pack(e.c[0]), c1 = pack(e.c[1]);
  if (r.four) {
    if (c0 < c1) {
      std::swap(c0, c1);
      for (auto& i : idx) i = std::uint8_t(i < 2 ? 1 - i : 5 - i);  // 0<->1, 2<->3
    } else if (c0 == c1) {
      for (auto& i : idx) i = 0;  // a flat block: every index may be c0
      // c0 == c1 reads as the three-colour mode; index 0 is c0 there too.
    }
  } else if (c0 > c1) {
    std::swap(c0, c1);
    for (auto& i : idx) i = std::uint8_t(i == 0 ? 1 : i == 1 ? 0 : i);  // 0<->1; 2 (average) and 3 stay
  }
  out[0] = std::uint8_t(c0);
  out[1] = std::uint8_t(c0 >> 8);
  out[2] = std::uint8_t(c1);
  out[3] = std::uint8_t(c1 >> 8);
  std::uint32_t bits = 0;
  for (int i = 0; i < 16; ++i) bits |= std::uint32_t(idx[i]) << (2 * i);
  for (int b = 0; b < 4; ++b) out[4 + b] = std::uint8_t(bits >> (8 * b));
}

}  // namespace texproc
