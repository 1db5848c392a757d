// The scalar reference of bc6h_lanes.h (namespace ref), one block at a time,
// plainly: what bc6h_lanes_simd.cpp, its Highway twin, must equal byte for
// byte (tests compare them on every target).
#include "bc/bc6h_lanes.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>

#include "bc/axis_residual.h"
#include "bc/bc6h_shared.h"

namespace texproc::ref {
namespace {

using bc6h::Choice;

struct Block {
  int x[16][3];    // the targets (bc6h::target)
  float y[16][3];  // the fitting domain: the unquantized value / 64
  bool is_signed, solid;
};

// The centre of the unquantized values that finish to x, / 64.
float fit_value(int x, bool is_signed) {
  if (!is_signed) return float(2 * x + 1) / 62.0f;
  if (x == 0) return 0.0f;
  const float m = float(2 * std::abs(x) + 1) / 124.0f;
  return x < 0 ? -m : m;
}

// A region's mean and scatter matrix (C[0..5]: 00, 01, 02, 11, 12, 22),
// the deviations from the mean summed over its texels in order.
void region_scatter(const Block& b, unsigned members, float mean[3], float C[6]) {
  int cnt = 0;
  float S[3] = {};
  for (int i = 0; i < 16; ++i) {
    if (!(members >> i & 1)) continue;
    ++cnt;
    for (int c = 0; c < 3; ++c) S[c] += b.y[i][c];
  }
  for (int c = 0; c < 3; ++c) mean[c] = S[c] / float(cnt);
  for (int q = 0; q < 6; ++q) C[q] = 0.0f;
  for (int i = 0; i < 16; ++i) {
    if (!(members >> i & 1)) continue;
    const float d0 = b.y[i][0] - mean[0], d1 = b.y[i][1] - mean[1], d2 = b.y[i][2] - mean[2];
    C[0] += d0 * d0;
    C[1] += d0 * d1;
    C[2] += d0 * d2;
    C[3] += d1 * d1;
    C[4] += d1 * d2;
    C[5] += d2 * d2;
  }
}

// A region's ends: its texels' extent along their principal axis, the end
// nearer the anchor texel first (the mean twice for one colour).
void line_ends(const Block& b, unsigned members, int anchor, float e[2][3]) {
  float mean[3], c6[6];
  region_scatter(b, members, mean, c6);
  const float C[3][3] = {{c6[0], c6[1], c6[2]}, {c6[1], c6[3], c6[4]}, {c6[2], c6[4], c6[5]}};
  int jmax = 0;
  for (int c = 1; c < 3; ++c)
    if (C[c][c] > C[jmax][jmax]) jmax = c;
  if (C[jmax][jmax] == 0.0f) {
    for (int c = 0; c < 3; ++c) e[0][c] = e[1][c] = mean[c];
    return;
  }
  float v[3];
  for (int c = 0; c < 3; ++c) v[c] = C[c][jmax];
  for (int it = 0; it < 3; ++it) {
    float w[3], m = 0.0f;
    for (int p = 0; p < 3; ++p) {
      w[p] = C[p][0] * v[0] + C[p][1] * v[1] + C[p][2] * v[2];
      m = std::max(m, std::fabs(w[p]));
    }
    if (m == 0.0f) break;
    const float inv = 1.0f / m;
    for (int p = 0; p < 3; ++p) v[p] = w[p] * inv;
  }
  float tmin = INFINITY, tmax = -INFINITY, ta = 0.0f;
  for (int i = 0; i < 16; ++i) {
    if (!(members >> i & 1)) continue;
    const float t = v[0] * (b.y[i][0] - mean[0]) + v[1] * (b.y[i][1] - mean[1]) + v[2] * (b.y[i][2] - mean[2]);
    tmin = std::min(tmin, t);
    tmax = std::max(tmax, t);
    if (i == anchor) ta = t;
  }
  const float vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  float s0 = tmin / vv, s1 = tmax / vv;
  if (ta + ta > tmin + tmax) std::swap(s0, s1);
  for (int c = 0; c < 3; ++c) {
    e[0][c] = mean[c] + s0 * v[c];
    e[1][c] = mean[c] + s1 * v[c];
  }
}

// Least-squares ends for a region's indices (weights out of 64); false
// where they are not determined (every index the same).
bool lsq_ends(const Block& b, unsigned members, const std::uint8_t index[16], int bits, float e[2][3]) {
  int AA = 0, AB = 0, BB = 0;
  float RA[3] = {}, RB[3] = {};
  for (int i = 0; i < 16; ++i) {
    if (!(members >> i & 1)) continue;
    const int wb = bptc::weights(bits)[index[i]], wa = 64 - wb;
    AA += wa * wa;
    AB += wa * wb;
    BB += wb * wb;
    for (int c = 0; c < 3; ++c) {
      RA[c] += float(wa) * b.y[i][c];
      RB[c] += float(wb) * b.y[i][c];
    }
  }
  const float det = float(AA) * float(BB) - float(AB) * float(AB);
  if (!(det > 0.0f)) return false;
  const float inv = 64.0f / det;
  for (int c = 0; c < 3; ++c) {
    e[0][c] = (RA[c] * float(BB) - RB[c] * float(AB)) * inv;
    e[1][c] = (RB[c] * float(AA) - RA[c] * float(AB)) * inv;
  }
  return true;
}

// The ends to mode k's codes.
void quantize_ends(int k, const float e[4][3], bool is_signed, int code[4][3]) {
  const bptc::Bc6hMode& M = bptc::kBc6hModes[k];
  const int n = 2 * bc6h::regions(k);
  for (int j = 0; j < n; ++j)
    for (int c = 0; c < 3; ++c) code[j][c] = bc6h::quantize(e[j][c] * 64.0f, M.endpoint_bits, is_signed);
  if (M.transformed)
    for (int j = 1; j < n; ++j)
      for (int c = 0; c < 3; ++c)
        code[j][c] = bc6h::limit_delta(code[0][c], code[j][c], M.endpoint_bits, M.delta_bits[c]);
}

int texel_error(const int a[3], const int x[3]) {
  int t = 0;
  for (int c = 0; c < 3; ++c) {
    const int d = std::min(std::abs(a[c] - x[c]), bc6h::kErrorLimit);
    t += d * d;
  }
  return t;
}

// Each texel's index for mode k's codes from the exact palette (the first
// of least error; an anchor texel's among the lower half); the block's error.
int assign(const Block& b, int k, int partition, const int code[4][3], std::uint8_t index[16]) {
  const bptc::Bc6hMode& M = bptc::kBc6hModes[k];
  const int ns = bc6h::regions(k), bits = bc6h::index_bits(k), L = (1 << bits) - 1;
  const std::uint8_t* w = bptc::weights(bits);
  int pal[2][16][3];
  for (int s = 0; s < ns; ++s)
    for (int c = 0; c < 3; ++c) {
      const int u0 = bc6h::unquantize(code[2 * s][c], M.endpoint_bits, b.is_signed);
      const int u1 = bc6h::unquantize(code[2 * s + 1][c], M.endpoint_bits, b.is_signed);
      for (int j = 0; j <= L; ++j) pal[s][j][c] = bc6h::finish(bptc::interpolate(u0, u1, w[j]), b.is_signed);
    }
  const std::uint32_t part = ns == 2 ? bptc::kPartitions2[partition] : 0;
  const int anchor1 = ns == 2 ? bptc::kAnchor2[partition] : -1;
  int error = 0;
  for (int i = 0; i < 16; ++i) {
    const int s = bptc::subset(part, i);
    const int top = i == 0 || i == anchor1 ? L >> 1 : L;
    int best = 0, be = texel_error(pal[s][0], b.x[i]);
    for (int j = 1; j <= top; ++j) {
      const int e = texel_error(pal[s][j], b.x[i]);
      if (e < be) {
        be = e;
        best = j;
      }
    }
    index[i] = std::uint8_t(best);
    error += be;
  }
  return error;
}

struct Best {
  Choice choice;
  int error = INT_MAX;
};

// Mode k on the partition's fitted ends, refined; kept where it is better.
void try_mode(const Block& b, int k, int partition, const unsigned members[2], const float ends[4][3],
              const Bc6hLevel& level, Best& best) {
  const int ns = bc6h::regions(k), bits = bc6h::index_bits(k);
  Choice c;
  c.mode = k;
  c.partition = ns == 2 ? partition : 0;
  quantize_ends(k, ends, b.is_signed, c.code);
  int error = assign(b, k, partition, c.code, c.index);
  float cur[4][3];
  std::copy(&ends[0][0], &ends[0][0] + 12, &cur[0][0]);
  for (int pass = 0; pass < level.refine && error > 0; ++pass) {
    float next[4][3];
    std::copy(&cur[0][0], &cur[0][0] + 12, &next[0][0]);
    bool any = false;
    for (int s = 0; s < ns; ++s) any = lsq_ends(b, members[s], c.index, bits, &next[2 * s]) || any;
    if (!any) break;
    Choice n = c;
    quantize_ends(k, next, b.is_signed, n.code);
    const int e = assign(b, k, partition, n.code, n.index);
    if (e >= error) break;
    c = n;
    error = e;
    std::copy(&next[0][0], &next[0][0] + 12, &cur[0][0]);
  }
  if (error < best.error) {
    best.choice = c;
    best.error = error;
  }
}

// The partition estimate of one region: the squared residual of its
// texels off their principal axis. The scatter's entries are at most
// 16 * 512^2 (y spans 1024), so axis_residual's u'Cu stays below 1.2e35.
float region_residual(const Block& b, unsigned members) {
  float mean[3], C[6];
  region_scatter(b, members, mean, C);
  return bc::axis_residual(C[0], C[1], C[2], C[3], C[4], C[5]);
}

unsigned region_members(int partition, int s) {
  unsigned m = 0;
  for (int i = 0; i < 16; ++i) m |= unsigned(bptc::subset(bptc::kPartitions2[partition], i) == s) << i;
  return m;
}

Choice encode_block(const Block& b, const Bc6hLevel& level) {
  Best best;
  const unsigned all[2] = {0xFFFF, 0};
  const unsigned modes = b.solid ? 1u << 13 : level.modes;
  if (modes >> bc6h::kOneRegion) {
    float e[4][3] = {};
    line_ends(b, 0xFFFF, 0, e);
    for (int k = bc6h::kOneRegion; k < 14; ++k)
      if (modes >> k & 1) try_mode(b, k, 0, all, e, level, best);
  }
  if ((modes & ((1u << bc6h::kOneRegion) - 1)) && level.partitions > 0) {
    // The partitions of least estimate, in order (ties: the lower one).
    float est[32];
    int ranked[32];
    const int keep = std::min(level.partitions, 32);
    for (int j = 0; j < keep; ++j) {
      est[j] = INFINITY;
      ranked[j] = 0;
    }
    for (int p = 0; p < 32; ++p) {
      float e = region_residual(b, region_members(p, 0)) + region_residual(b, region_members(p, 1));
      int q = p;
      for (int j = 0; j < keep; ++j)
        if (e < est[j]) std::swap(e, est[j]), std::swap(q, ranked[j]);
    }
    for (int r = 0; r < keep; ++r) {
      const int p = ranked[r];
      const unsigned members[2] = {region_members(p, 0), region_members(p, 1)};
      float e[4][3];
      line_ends(b, members[0], 0, e);
      line_ends(b, members[1], bptc::kAnchor2[p], e + 2);
      for (int k = 0; k < bc6h::kOneRegion; ++k)
        if (modes >> k & 1) try_mode(b, k, p, members, e, level, best);
    }
  }
  return best.choice;
}

}  // namespace

void bc6h_encode_lanes(const std::int32_t texel[16][3][kBc6hBatch], int count, bool is_signed, const Bc6hLevel& level,
                       std::uint8_t out[][16]) {
  for (int k = 0; k < count; ++k) {
    Block b{};
    b.is_signed = is_signed;
    b.solid = true;
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 3; ++c) {
        b.x[i][c] = texel[i][c][k];
        b.y[i][c] = fit_value(b.x[i][c], is_signed);
        b.solid = b.solid && b.x[i][c] == b.x[0][c];
      }
    bc6h::pack_block(encode_block(b, level), out[k]);
  }
}

}  // namespace texproc::ref
