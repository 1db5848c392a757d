// How the SIMD twin of the BC7 encoder (bc7_lanes_simd.cpp) builds the
// partition estimate's subset sums: a plan computed at compile time from
// the partition tables, the same on every Highway target (so outside the
// per-target code). The scalar reference sums each subset texel by texel;
// the sums are integers, so both get the same values.
#pragma once

#include <cstdint>

#include "bc/bptc_tables.h"

namespace texproc::bc7 {
// How the SIMD partition estimate builds each subset's sums (every subset
// but a partition's last): from the sums of an earlier subset, of an
// earlier partition or this one's first (`parent`, slot 2 p + s; -1: from
// zero), plus the texels this subset has and that one lacks (`add`), minus
// those it lacks and that one has (`sub`). The parent is the one that
// differs in the fewest texels: on the first 32 two-subset partitions, 80
// texels added or taken instead of 286.
struct SumStep {
  int parent;
  unsigned add, sub;
  int count;
};
struct SumPlan {
  SumStep step[64][2];
};
constexpr unsigned subset_mask(std::uint32_t bits, int s) {
  unsigned m = 0;
  for (int i = 0; i < 16; ++i) m |= unsigned(int(bits >> (2 * i) & 3) == s) << i;
  return m;
}
constexpr int ones(unsigned m) {
  int n = 0;
  for (; m; m &= m - 1) ++n;
  return n;
}
constexpr SumPlan make_sum_plan(const std::uint32_t (&table)[64], int subsets) {
  SumPlan plan{};
  for (int p = 0; p < 64; ++p)
    for (int s = 0; s < subsets - 1; ++s) {
      const unsigned m = subset_mask(table[p], s);
      SumStep best{-1, m, 0, ones(m)};
      int cost = ones(m);
      for (int slot = 0; slot < 2 * p + s; ++slot) {
        if (slot % 2 >= subsets - 1) continue;
        const unsigned o = subset_mask(table[slot / 2], slot % 2);
        if (ones(m ^ o) < cost) cost = ones(m ^ o), best = {slot, m & ~o, o & ~m, ones(m)};
      }
      plan.step[p][s] = best;
    }
  return plan;
}
inline constexpr SumPlan kSumPlan2 = make_sum_plan(bptc::kPartitions2, 2);
inline constexpr SumPlan kSumPlan3 = make_sum_plan(bptc::kPartitions3, 3);

// Where the estimate finds a three-subset partition's subset residual
// already computed: 62 of the 192 subsets are a two-subset partition's
// subset (`two`: slot 2 p + s of the two-subset pass, -1: none) and 16
// more an earlier three-subset partition's (`three`: slot 3 p + s, -1:
// none). A residual is a function of the subset's integer sums alone, so
// the same float either way: 242 residuals instead of 320.
struct ResidualReuse {
  int two[64][3], three[64][3];
};
constexpr ResidualReuse make_residual_reuse() {
  ResidualReuse r{};
  for (int p = 0; p < 64; ++p)
    for (int s = 0; s < 3; ++s) {
      const unsigned m = subset_mask(bptc::kPartitions3[p], s);
      r.two[p][s] = r.three[p][s] = -1;
      for (int slot = 0; slot < 2 * 64 && r.two[p][s] < 0; ++slot)
        if (subset_mask(bptc::kPartitions2[slot / 2], slot % 2) == m) r.two[p][s] = slot;
      for (int slot = 0; slot < 3 * p + s && r.three[p][s] < 0; ++slot)
        if (subset_mask(bptc::kPartitions3[slot / 3], slot % 3) == m) r.three[p][s] = slot;
    }
  return r;
}
inline constexpr ResidualReuse kResidualReuse = make_residual_reuse();
constexpr int residuals_computed(const ResidualReuse& r) {
  int n = 0;
  for (int p = 0; p < 64; ++p)
    for (int s = 0; s < 3; ++s) n += r.two[p][s] < 0 && r.three[p][s] < 0;
  return n;
}
static_assert(2 * 64 + residuals_computed(kResidualReuse) == 242,
              "the estimate's distinct subsets, as the comment above counts them");
}  // namespace texproc::bc7
