// The scalar reference of bc7_lanes.h (namespace ref), one block at a time,
// plainly: what bc7_lanes_simd.cpp, its Highway twin, must equal byte for
// byte (tests compare them on every target).
#include "bc/bc7_lanes.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <utility>

#include "bc/axis_residual.h"
#include "bc/bc7_fit.h"
#include "bc/bc7_shared.h"

namespace texproc::ref {
namespace {

using bc7::Choice;
using bc7::EndpointFormat;
using bc7::Pbit;
using bc7_fit::Set;
using bc7_fit::SetFit;

// The partition estimate of one subset from its sums: the squared residual
// off its principal axis.
float subset_residual(int cnt, const int S[3], const int Q[6]) {
  if (cnt == 0) return 0.0f;
  const float c00 = float(cnt * Q[0] - S[0] * S[0]), c01 = float(cnt * Q[1] - S[0] * S[1]),
              c02 = float(cnt * Q[2] - S[0] * S[2]), c11 = float(cnt * Q[3] - S[1] * S[1]),
              c12 = float(cnt * Q[4] - S[1] * S[2]), c22 = float(cnt * Q[5] - S[2] * S[2]);
  // C's entries are at most 16^2 times a variance, 4.2e6, so u'Cu stays below 1.2e35.
  return bc::axis_residual(c00, c01, c02, c11, c12, c22) * (1.0f / float(cnt));
}

// The K partitions of least estimate, in order (ties: the lower partition).
struct Ranked {
  float est[64];
  int partition[64];
  int k = 0;
  void init(int keep) {
    k = keep;
    for (int j = 0; j < k; ++j) {
      est[j] = INFINITY;
      partition[j] = 0;
    }
  }
  void insert(float e, int p) {
    for (int j = 0; j < k; ++j)
      if (e < est[j]) std::swap(e, est[j]), std::swap(p, partition[j]);
  }
};

struct Block {
  int x[16][4];
  int alpha_error;  // modes 0-3's: every alpha decodes to 255
  bool opaque, solid;
};

// Rank the partitions of `subsets` subsets by the estimate: subset sums
// over RGB, the last subset's by subtraction from the block's.
void rank_partitions(const Block& b, int subsets, int scanned, Ranked& all, Ranked* first16) {
  int tS[3] = {}, tQ[6] = {};
  int prod[16][6];
  for (int i = 0; i < 16; ++i) {
    const int* x = b.x[i];
    const int p[6] = {x[0] * x[0], x[0] * x[1], x[0] * x[2], x[1] * x[1], x[1] * x[2], x[2] * x[2]};
    for (int c = 0; c < 3; ++c) tS[c] += x[c];
    for (int q = 0; q < 6; ++q) {
      prod[i][q] = p[q];
      tQ[q] += p[q];
    }
  }
  for (int part = 0; part < scanned; ++part) {
    const std::uint32_t bits = subsets == 2 ? bptc::kPartitions2[part] : bptc::kPartitions3[part];
    int cnt[3] = {}, S[3][3] = {}, Q[3][6] = {};
    for (int i = 0; i < 16; ++i) {
      const int s = bptc::subset(bits, i);
      if (s == subsets - 1) continue;
      ++cnt[s];
      for (int c = 0; c < 3; ++c) S[s][c] += b.x[i][c];
      for (int q = 0; q < 6; ++q) Q[s][q] += prod[i][q];
    }
    const int last = subsets - 1;
    cnt[last] = 16;
    for (int c = 0; c < 3; ++c) S[last][c] = tS[c];
    for (int q = 0; q < 6; ++q) Q[last][q] = tQ[q];
    for (int s = 0; s < last; ++s) {
      cnt[last] -= cnt[s];
      for (int c = 0; c < 3; ++c) S[last][c] -= S[s][c];
      for (int q = 0; q < 6; ++q) Q[last][q] -= Q[s][q];
    }
    float est = 0.0f;
    for (int s = 0; s < subsets; ++s) est += subset_residual(cnt[s], S[s], Q[s]);
    all.insert(est, part);
    if (first16 && part < 16) first16->insert(est, part);
  }
}

// The candidates' Choice and error, kept where the error is less.
struct Best {
  Choice choice;
  int error = INT_MAX;
  void offer(const Choice& c, int e) {
    if (e < error) {
      choice = c;
      error = e;
    }
  }
};

// A partitioned mode (0, 1, 2, 3 or 7) on one partition: each subset fitted.
void try_partitioned(const Block& b, int mode, int part, const Bc7Level& level, Best& best) {
  const bptc::Bc7Mode& M = bptc::kBc7Modes[mode];
  const std::uint32_t bits = M.subsets == 2 ? bptc::kPartitions2[part] : bptc::kPartitions3[part];
  const int n = M.alpha_bits ? 4 : 3;
  Choice c;
  c.mode = mode;
  c.partition = part;
  int error = n == 3 ? b.alpha_error : 0;
  for (int s = 0; s < M.subsets; ++s) {
    unsigned members = 0;
    for (int i = 0; i < 16; ++i) members |= unsigned(bptc::subset(bits, i) == s) << i;
    const Set set{b.x, members, 0, n};
    const SetFit f = fit_set(set, bc7::color_format(mode), M.index_bits, b.opaque && n == 4, level);
    error += f.error;
    for (int k = 0; k < 2; ++k) {
      c.pbit[s][k] = f.pbit[k];
      for (int a = 0; a < n; ++a) c.code[s][k][a] = f.code[k][a];
    }
    for (int i = 0; i < 16; ++i)
      if (set.has(i)) c.color_index[i] = f.index[i];
  }
  best.offer(c, error);
}

// Mode 4 or 5 with a rotation (the scalar channel swapped with alpha) and
// index selection: a colour set and an alpha set.
void try_rotated(const Block& b, int mode, int rotation, int isel, const Bc7Level& level, Best& best) {
  const bptc::Bc7Mode& M = bptc::kBc7Modes[mode];
  int y[16][4];
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 4; ++c) y[i][c] = b.x[i][c];
    if (rotation) std::swap(y[i][3], y[i][rotation - 1]);
  }
  const int color_bits = isel ? M.index2_bits : M.index_bits, alpha_bits = isel ? M.index_bits : M.index2_bits;
  const SetFit rgb = fit_set(Set{y, 0xFFFF, 0, 3}, {M.color_bits, Pbit::none}, color_bits, false, level);
  const SetFit alpha = fit_set(Set{y, 0xFFFF, 3, 1}, {M.alpha_bits, Pbit::none}, alpha_bits, false, level);
  Choice c;
  c.mode = mode;
  c.rotation = rotation;
  c.index_selection = isel;
  for (int k = 0; k < 2; ++k) {
    for (int a = 0; a < 3; ++a) c.code[0][k][a] = rgb.code[k][a];
    c.code[0][k][3] = alpha.code[k][3];
  }
  for (int i = 0; i < 16; ++i) {
    c.color_index[i] = rgb.index[i];
    c.alpha_index[i] = alpha.index[i];
  }
  best.offer(c, rgb.error + alpha.error);
}

// The winner's endpoints stepped (level.winner_steps rounds), subset by
// subset, from its codes and the indices they assign.
void step_winner(const Block& b, const Bc7Level& level, Choice& c) {
  if (!has_winner_pass(level) || c.mode == 4 || c.mode == 5) return;
  const bptc::Bc7Mode& M = bptc::kBc7Modes[c.mode];
  const std::uint32_t bits = M.subsets == 2   ? bptc::kPartitions2[c.partition]
                             : M.subsets == 3 ? bptc::kPartitions3[c.partition]
                                              : 0;
  const int n = M.alpha_bits ? 4 : 3;
  const EndpointFormat f = bc7::color_format(c.mode);
  for (int s = 0; s < M.subsets; ++s) {
    unsigned members = 0;
    for (int i = 0; i < 16; ++i) members |= unsigned(bptc::subset(bits, i) == s) << i;
    const Set set{b.x, members, 0, n};
    SetFit fit;
    for (int k = 0; k < 2; ++k) {
      fit.pbit[k] = c.pbit[s][k];
      for (int a = 0; a < n; ++a) {
        fit.code[k][a] = c.code[s][k][a];
        fit.value[k][a] = bc7::expand(fit.code[k][a], f.bits, f.pbit == Pbit::none ? -1 : fit.pbit[k]);
      }
    }
    const bool exact = level.exact_indices || level.exact_winner;
    assign(set, M.index_bits, exact, fit);
    if (level.winner_seeds > level.seeds) {
      float line[2][4] = {};
      line_ends(set, line);
      for (int seed = std::max(level.seeds, 1); seed < level.winner_seeds; ++seed) {
        SetFit next = fit_seed(set, line, seed, f, M.index_bits, b.opaque && n == 4, level);
        if (exact != level.exact_indices)
          assign(set, M.index_bits, exact, next);  // else next's indices are already these
        if (next.error < fit.error) fit = next;
      }
    }
    step_ends(set, f, M.index_bits, level, exact, level.winner_steps, fit);
    for (int k = 0; k < 2; ++k) {
      c.pbit[s][k] = fit.pbit[k];
      for (int a = 0; a < n; ++a) c.code[s][k][a] = fit.code[k][a];
    }
    for (int i = 0; i < 16; ++i)
      if (set.has(i)) c.color_index[i] = fit.index[i];
  }
}

Choice encode_block(const Block& b, const Bc7Level& level) {
  if (b.solid) return bc7::solid_choice(b.x[0]);
  Best best;
  {
    const SetFit f = fit_set(Set{b.x, 0xFFFF, 0, 4}, bc7::color_format(6), 4, b.opaque, level);
    Choice c;
    c.mode = 6;
    for (int k = 0; k < 2; ++k) {
      c.pbit[0][k] = f.pbit[k];
      for (int a = 0; a < 4; ++a) c.code[0][k][a] = f.code[k][a];
    }
    for (int i = 0; i < 16; ++i) c.color_index[i] = f.index[i];
    best.offer(c, f.error);
  }
  Ranked two;
  two.init(std::min(level.partitions2, level.estimated2));
  if (level.partitions2 > 0) {
    rank_partitions(b, 2, level.estimated2, two, nullptr);
    for (int r = 0; r < two.k; ++r) {
      try_partitioned(b, 1, two.partition[r], level, best);
      if (level.mode3) try_partitioned(b, 3, two.partition[r], level, best);
    }
  }
  if (level.partitions3 > 0) {
    Ranked three, three16;
    three.init(std::min(level.partitions3, 64));
    three16.init(std::min(level.partitions3, 16));
    rank_partitions(b, 3, 64, three, &three16);
    for (int r = 0; r < three16.k; ++r) try_partitioned(b, 0, three16.partition[r], level, best);
    for (int r = 0; r < three.k; ++r) try_partitioned(b, 2, three.partition[r], level, best);
  }
  if (!b.opaque || level.opaque_rotated) {
    const int first = b.opaque ? 1 : 0;  // an opaque block's rotation 0 would index a constant alpha
    for (int rot = first; rot < level.rotations; ++rot) try_rotated(b, 5, rot, 0, level, best);
    for (int rot = first; rot < level.rotations; ++rot)
      for (int isel = 0; isel < (level.index_selection ? 2 : 1); ++isel) try_rotated(b, 4, rot, isel, level, best);
  }
  if (!b.opaque) {
    if (level.mode7)
      for (int r = 0; r < two.k; ++r) try_partitioned(b, 7, two.partition[r], level, best);
  }
  step_winner(b, level, best.choice);
  return best.choice;
}

}  // namespace

void bc7_encode_lanes(const Bc7Texels* batches, int count, const Bc7Level& level, std::uint8_t out[][16]) {
  for (int n = 0; n < count; ++n) {
    const Bc7Texels& texel = batches[n / kBc7Batch];
    const int k = n % kBc7Batch;
    Block b{};
    b.opaque = b.solid = true;
    for (int i = 0; i < 16; ++i) {
      for (int c = 0; c < 4; ++c) b.x[i][c] = int(texel[i][k] >> (8 * c) & 255);
      b.opaque = b.opaque && b.x[i][3] == 255;
      b.solid = b.solid && texel[i][k] == texel[0][k];
      b.alpha_error += (255 - b.x[i][3]) * (255 - b.x[i][3]);
    }
    bc7::pack_block(encode_block(b, level), out[n]);
  }
}

}  // namespace texproc::ref
