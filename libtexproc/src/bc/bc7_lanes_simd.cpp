// BC7, a block per lane: the Highway twin of the scalar reference in
// bc7_lanes.cpp. Both evaluate the same expressions in the same order (see
// bc7_lanes.h); where the reference stops early for a block (a refinement
// that no longer helps), the lane stops updating. Lanes with one colour are
// packed from bc7_shared.h's table, as the reference does.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc7_lanes_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <climits>
#include <memory>

#include "bc/bc7_lanes.h"
#include "bc/bc7_shared.h"
#include "bc/bc7_estimate_simd-inl.h"
#include "bc/bc7_fit_simd-inl.h"
#include "bc/bc7_span_simd-inl.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
// Not in an anonymous namespace (nor are bc7_*_simd-inl.h): with internal
// linkage GCC 12 inlines the search differently and BC7 `normal` ran 10-20%
// slower (bench/compare_builds.py, 5 rounds interleaved, twice).

// The lanes' best candidate so far (the reference's Best and Choice).
struct BestV {
  V error, mode, partition, rotation, isel;
  V code[3][2][4], pbit[3][2];
  V color_index[16], alpha_index[16];
};

struct Bc7Batch : Bc7FitLanes {
  V x[16][4];
  PairsV xp[16];
  M opaque, solid;
  V alpha_error;
  BestV best;
  M all_members[16];

  HWY_ATTR explicit Bc7Batch(const Bc7Level& l) : Bc7FitLanes(l) {
    for (auto& m : all_members) m = hn::FirstN(d, kBc7Batch);
  }

  HWY_INLINE void load(const std::uint32_t texel[16][kBc7Batch], int k0) {
    opaque = hn::FirstN(d, kBc7Batch);
    solid = opaque;
    alpha_error = hn::Zero(d);
    const V first = hn::LoadU(d, reinterpret_cast<const std::int32_t*>(texel[0]) + k0);
    for (int i = 0; i < 16; ++i) {
      const V t = hn::LoadU(d, reinterpret_cast<const std::int32_t*>(texel[i]) + k0);
      for (int c = 0; c < 4; ++c)
        x[i][c] = hn::And(hn::ShiftRightSame(t, 8 * c), hn::Set(d, 255));  // masked: the shift is arithmetic
      make_pairs(x[i], xp[i]);
      opaque = hn::And(opaque, hn::Eq(x[i][3], hn::Set(d, 255)));
      solid = hn::And(solid, hn::Eq(t, first));
      const V da = hn::Sub(hn::Set(d, 255), x[i][3]);
      alpha_error = hn::Add(alpha_error, hn::Mul(da, da));
    }
    best.error = hn::IfThenElse(solid, hn::Zero(d), hn::Set(d, INT_MAX));
  }

  // A candidate's mode, partition, rotation and index selection, a lane each.
  struct Header {
    V mode, partition, rotation, isel;
  };

  // As ref::Best::offer: the candidate replaces the best where `allowed` and its error is less.
  HWY_INLINE void offer(M allowed, V error, const Header& h, const V code[3][2][4], const V pbit[3][2],
                        const V* color_index, const V* alpha_index) {
    const M take = hn::And(allowed, hn::Lt(error, best.error));
    if (hn::AllFalse(d, take)) return;
    best.error = hn::IfThenElse(take, error, best.error);
    best.mode = hn::IfThenElse(take, h.mode, best.mode);
    best.partition = hn::IfThenElse(take, h.partition, best.partition);
    best.rotation = hn::IfThenElse(take, h.rotation, best.rotation);
    best.isel = hn::IfThenElse(take, h.isel, best.isel);
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 2; ++k) {
        best.pbit[s][k] = hn::IfThenElse(take, pbit[s][k], best.pbit[s][k]);
        for (int c = 0; c < 4; ++c) best.code[s][k][c] = hn::IfThenElse(take, code[s][k][c], best.code[s][k][c]);
      }
    for (int i = 0; i < 16; ++i) {
      best.color_index[i] = hn::IfThenElse(take, color_index[i], best.color_index[i]);
      best.alpha_index[i] = hn::IfThenElse(take, alpha_index[i], best.alpha_index[i]);
    }
  }

  // Mode 6 (as the reference's first candidate). With every lane opaque,
  // alpha is left out of the fit: its covariance row is zero (R, G and B
  // get the same floats), its ends 255 (code 127, p-bit 1, as forced).
  HWY_INLINE void try_mode6() {
    SetFitV fit;
    const bool rgb = hn::AllTrue(d, opaque);
    fit_set(SetV{x, all_members, 0, rgb ? 3 : 4, xp}, bc7::color_format(6), 4, opaque, fit);
    if (rgb)
      for (int k = 0; k < 2; ++k) fit.code[k][3] = hn::Set(d, 127), fit.value[k][3] = hn::Set(d, 255);
    V code[3][2][4], pbit[3][2], zero[16];
    zero_candidate(code, pbit, zero);
    for (int k = 0; k < 2; ++k) {
      pbit[0][k] = fit.pbit[k];
      for (int a = 0; a < 4; ++a) code[0][k][a] = fit.code[k][a];
    }
    const Header header{hn::Set(d, 6), hn::Zero(d), hn::Zero(d), hn::Zero(d)};
    offer(hn::FirstN(d, kBc7Batch), fit.error, header, code, pbit, fit.index, zero);
  }

  HWY_INLINE void zero_candidate(V code[3][2][4], V pbit[3][2], V zero[16]) const {
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 2; ++k) {
        pbit[s][k] = hn::Zero(d);
        for (int c = 0; c < 4; ++c) code[s][k][c] = hn::Zero(d);
      }
    for (int i = 0; i < 16; ++i) zero[i] = hn::Zero(d);
  }

  // As ref::try_partitioned; the partition per lane.
  HWY_INLINE void try_partitioned(int mode, V part, M allowed) {
    const bptc::Bc7Mode& Md = bptc::kBc7Modes[mode];
    const std::int32_t* table =
        reinterpret_cast<const std::int32_t*>(Md.subsets == 2 ? bptc::kPartitions2 : bptc::kPartitions3);
    const V bits = hn::GatherIndex(d, table, part);
    const int n = Md.alpha_bits ? 4 : 3;
    V code[3][2][4], pbit[3][2], color_index[16], zero[16];
    zero_candidate(code, pbit, zero);
    for (int i = 0; i < 16; ++i) color_index[i] = hn::Zero(d);
    V error = n == 3 ? alpha_error : hn::Zero(d);
    const M force = n == 4 ? opaque : hn::FirstN(d, 0);
    for (int s = 0; s < Md.subsets; ++s) {
      M member[16];
      for (int i = 0; i < 16; ++i)
        member[i] = hn::Eq(hn::And(hn::ShiftRightSame(bits, 2 * i), hn::Set(d, 3)), hn::Set(d, s));
      SetFitV fit;
      fit_set(SetV{x, member, 0, n, xp}, bc7::color_format(mode), Md.index_bits, force, fit);
      error = hn::Add(error, fit.error);
      for (int k = 0; k < 2; ++k) {
        pbit[s][k] = fit.pbit[k];
        for (int a = 0; a < n; ++a) code[s][k][a] = fit.code[k][a];
      }
      for (int i = 0; i < 16; ++i) color_index[i] = hn::IfThenElse(member[i], fit.index[i], color_index[i]);
    }
    const Header header{hn::Set(d, mode), part, hn::Zero(d), hn::Zero(d)};
    offer(allowed, error, header, code, pbit, color_index, zero);
  }

  // As ref::try_rotated.
  HWY_INLINE void try_rotated(int mode, int rotation, int isel, M allowed) {
    if (hn::AllFalse(d, hn::AndNot(solid, allowed))) return;
    const bptc::Bc7Mode& Md = bptc::kBc7Modes[mode];
    V y[16][4];
    PairsV yp[16];
    for (int i = 0; i < 16; ++i) {
      for (int c = 0; c < 4; ++c) y[i][c] = x[i][c];
      if (rotation) std::swap(y[i][3], y[i][rotation - 1]);
      make_pairs(y[i], yp[i]);
    }
    const int color_bits = isel ? Md.index2_bits : Md.index_bits, alpha_bits = isel ? Md.index_bits : Md.index2_bits;
    const M none = hn::FirstN(d, 0);
    SetFitV rgb, alpha;
    fit_set(SetV{y, all_members, 0, 3, yp}, {Md.color_bits, Pbit::none}, color_bits, none, rgb);
    fit_set(SetV{y, all_members, 3, 1, yp}, {Md.alpha_bits, Pbit::none}, alpha_bits, none, alpha);
    V code[3][2][4], pbit[3][2], zero[16];
    zero_candidate(code, pbit, zero);
    for (int k = 0; k < 2; ++k) {
      for (int a = 0; a < 3; ++a) code[0][k][a] = rgb.code[k][a];
      code[0][k][3] = alpha.code[k][3];
    }
    const Header header{hn::Set(d, mode), hn::Zero(d), hn::Set(d, rotation), hn::Set(d, isel)};
    offer(allowed, hn::Add(rgb.error, alpha.error), header, code, pbit, rgb.index, alpha.index);
  }

  // As ref::step_winner, on the lanes `here`, whose winner is `mode`.
  HWY_INLINE void step_mode(int mode, M here) {
    const bptc::Bc7Mode& Md = bptc::kBc7Modes[mode];
    const EndpointFormat fmt = bc7::color_format(mode);
    const int n = Md.alpha_bits ? 4 : 3;
    V bits = hn::Zero(d);
    if (Md.subsets > 1) {
      const std::int32_t* table =
          reinterpret_cast<const std::int32_t*>(Md.subsets == 2 ? bptc::kPartitions2 : bptc::kPartitions3);
      bits = hn::GatherIndex(d, table, hn::And(best.partition, hn::Set(d, 63)));
    }
    for (int s = 0; s < Md.subsets; ++s) {
      M member[16];
      for (int i = 0; i < 16; ++i)
        member[i] = hn::Eq(hn::And(hn::ShiftRightSame(bits, 2 * i), hn::Set(d, 3)), hn::Set(d, s));
      const SetV set{x, member, 0, n, xp};
      SetFitV fit;
      for (int k = 0; k < 2; ++k) {
        fit.pbit[k] = best.pbit[s][k];
        for (int a = 0; a < n; ++a) {
          fit.code[k][a] = best.code[s][k][a];
          fit.value[k][a] = expand(fit.code[k][a], fit.pbit[k], fmt);
        }
      }
      for (int i = 0; i < 16; ++i) fit.index[i] = best.color_index[i];
      const bool exact = level.exact_indices || level.exact_winner;
      assign(set, Md.index_bits, exact, fit);
      if (level.winner_seeds > level.seeds) {
        VF line[2][4];
        line_ends(set, line);
        const M force = n == 4 ? opaque : hn::FirstN(d, 0);
        for (int seed = std::max(level.seeds, 1); seed < level.winner_seeds; ++seed) {
          SetFitV next;
          fit_seed(set, line, seed, fmt, Md.index_bits, force, next);
          if (exact != level.exact_indices)
            assign(set, Md.index_bits, exact, next);  // else next's indices are already these
          select_fit(hn::Lt(next.error, fit.error), next, fit, set);
        }
      }
      step_ends(set, fmt, Md.index_bits, exact, level.winner_steps, here, fit);
      for (int k = 0; k < 2; ++k) {
        best.pbit[s][k] = hn::IfThenElse(here, fit.pbit[k], best.pbit[s][k]);
        for (int a = 0; a < n; ++a) best.code[s][k][a] = hn::IfThenElse(here, fit.code[k][a], best.code[s][k][a]);
      }
      for (int i = 0; i < 16; ++i)
        best.color_index[i] = hn::IfThenElse(hn::And(here, member[i]), fit.index[i], best.color_index[i]);
    }
  }

  // As ref::encode_block, the lanes together; lanes of one colour are
  // packed by the caller.
  HWY_INLINE void search() {
    best.mode = best.partition = best.rotation = best.isel = hn::Zero(d);
    zero_candidate(best.code, best.pbit, best.color_index);
    for (auto& v : best.alpha_index) v = hn::Zero(d);
    const M all = hn::FirstN(d, kBc7Batch);
    try_mode6();
    RankedV two;
    init(two, std::min(level.partitions2, level.estimated2));
    VF residuals2[2 * 64];
    const int scanned2 = level.partitions2 > 0 ? level.estimated2 : 0;
    if (level.partitions2 > 0) {
      rank_partitions(x, 2, level.estimated2, two, nullptr, residuals2, 0);
      for (int r = 0; r < two.k; ++r) {
        try_partitioned(1, two.partition[r], all);
        if (level.mode3) try_partitioned(3, two.partition[r], all);
      }
    }
    if (level.partitions3 > 0) {
      RankedV three, three16;
      init(three, std::min(level.partitions3, 64));
      init(three16, std::min(level.partitions3, 16));
      rank_partitions(x, 3, 64, three, &three16, residuals2, scanned2);
      for (int r = 0; r < three16.k; ++r) try_partitioned(0, three16.partition[r], all);
      for (int r = 0; r < three.k; ++r) try_partitioned(2, three.partition[r], all);
    }
    const M with_alpha = hn::Not(opaque), rotated = level.opaque_rotated ? hn::FirstN(d, kBc7Batch) : with_alpha;
    if (hn::AllFalse(d, hn::AndNot(solid, rotated))) return;
    for (int rot = 0; rot < level.rotations; ++rot) try_rotated(5, rot, 0, rot ? rotated : with_alpha);
    for (int rot = 0; rot < level.rotations; ++rot)
      for (int isel = 0; isel < (level.index_selection ? 2 : 1); ++isel)
        try_rotated(4, rot, isel, rot ? rotated : with_alpha);
    if (level.mode7 && !hn::AllFalse(d, hn::AndNot(solid, with_alpha)))
      for (int r = 0; r < two.k; ++r) try_partitioned(7, two.partition[r], with_alpha);
  }

  // The lanes' choices into t's lanes k0 on (every field stored once; the
  // packer reads them a lane a block), and back.
  HWY_INLINE void store(bc7::LaneChoices& t, int k0) const {
    hn::StoreU(hn::VecFromMask(d, solid), d, t.solid + k0);
    for (int c = 0; c < 4; ++c) hn::StoreU(x[0][c], d, t.x0[c] + k0);
    hn::StoreU(best.mode, d, t.mode + k0);
    hn::StoreU(best.partition, d, t.partition + k0);
    hn::StoreU(best.rotation, d, t.rotation + k0);
    hn::StoreU(best.isel, d, t.isel + k0);
    for (int s = 0; s < 3; ++s)
      for (int e = 0; e < 2; ++e) {
        hn::StoreU(best.pbit[s][e], d, t.pbit[s][e] + k0);
        for (int ch = 0; ch < 4; ++ch) hn::StoreU(best.code[s][e][ch], d, t.code[s][e][ch] + k0);
      }
    for (int i = 0; i < 16; ++i) {
      hn::StoreU(best.color_index[i], d, t.color_index[i] + k0);
      hn::StoreU(best.alpha_index[i], d, t.alpha_index[i] + k0);
    }
  }
  HWY_INLINE void load_choices(const bc7::LaneChoices& t) {
    best.mode = hn::LoadU(d, t.mode);
    best.partition = hn::LoadU(d, t.partition);
    best.rotation = hn::LoadU(d, t.rotation);
    best.isel = hn::LoadU(d, t.isel);
    for (int s = 0; s < 3; ++s)
      for (int e = 0; e < 2; ++e) {
        best.pbit[s][e] = hn::LoadU(d, t.pbit[s][e]);
        for (int ch = 0; ch < 4; ++ch) best.code[s][e][ch] = hn::LoadU(d, t.code[s][e][ch]);
      }
    for (int i = 0; i < 16; ++i) {
      best.color_index[i] = hn::LoadU(d, t.color_index[i]);
      best.alpha_index[i] = hn::LoadU(d, t.alpha_index[i]);
    }
  }
};

void Bc7EncodeLanes(const Bc7Texels* texel, int count, const Bc7Level& level, std::uint8_t out[][16]) {
  Bc7Batch batch(level);
  const int step = int(hn::Lanes(batch.d));
  // Without winner steps a batch is packed as soon as it is searched (its
  // choices still in cache); with them, a span's choices wait for the steps.
  // Not zeroed: only the lanes searched are read.
  const bool stepped = has_winner_pass(level);
  const std::unique_ptr<bc7::LaneChoices[]> t(new bc7::LaneChoices[stepped ? kBc7Span / kBc7Batch : 1]);
  for (int s0 = 0; s0 < count; s0 += kBc7Span) {
    const int span = std::min(kBc7Span, count - s0);
    for (int b = 0; b * kBc7Batch < span; ++b) {
      bc7::LaneChoices& tb = t[stepped ? b : 0];
      for (int k0 = 0; k0 < kBc7Batch && b * kBc7Batch + k0 < span; k0 += step) {
        batch.load(texel[s0 / kBc7Batch + b], k0);
        if (!hn::AllTrue(batch.d, batch.solid)) batch.search();
        batch.store(tb, k0);
      }
      if (!stepped) bc7::pack_lanes_simd(tb, std::min(kBc7Batch, span - b * kBc7Batch), out + s0 + b * kBc7Batch);
    }
    if (!stepped) continue;
    step_winners(batch, texel + s0 / kBc7Batch, t.get(), span);
    for (int b = 0; b * kBc7Batch < span; ++b)
      bc7::pack_lanes_simd(t[b], std::min(kBc7Batch, span - b * kBc7Batch), out + s0 + b * kBc7Batch);
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc7EncodeLanes);

void bc7_encode_lanes(const Bc7Texels* texel, int count, const Bc7Level& level, std::uint8_t out[][16]) {
  if (force_scalar()) return ref::bc7_encode_lanes(texel, count, level, out);
  HWY_DYNAMIC_DISPATCH(Bc7EncodeLanes)(texel, count, level, out);
}
}  // namespace texproc
#endif
