// BC7's span of blocks, for bc7_lanes_simd.cpp (included once per Highway
// target, as Highway's -inl headers are): the winners' endpoint steps, each
// mode's winners gathered from the span's batches into full vectors. Batch is
// bc7_lanes_simd.cpp's Bc7Batch (load, load_choices, step_mode, store).
#if defined(TEXPROC_BC7_SPAN_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TEXPROC_BC7_SPAN_SIMD_INL_H_
#undef TEXPROC_BC7_SPAN_SIMD_INL_H_
#else
#define TEXPROC_BC7_SPAN_SIMD_INL_H_
#endif

#include <hwy/highway.h>

#include <algorithm>
#include <cstdint>

#include "bc/bc7_lanes.h"
#include "bc/bc7_shared.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The winners' endpoint steps (as ref::step_winner), mode by mode over the
// span's blocks: each mode's winners gathered into full vectors, so that a
// pass runs once for every Lanes() winners of a mode, not once for every
// batch that has one (a lane's result does not depend on its neighbours).
template <class Batch>
HWY_INLINE void step_winners(Batch& batch, const Bc7Texels* texel, bc7::LaneChoices* t, int count) {
  const int lanes = int(hn::Lanes(batch.d));
  for (const int mode : {0, 1, 2, 3, 6, 7}) {
    int ids[kBc7Span], n = 0;
    for (int b = 0; b < count; ++b)
      if (!t[b / kBc7Batch].solid[b % kBc7Batch] && t[b / kBc7Batch].mode[b % kBc7Batch] == mode) ids[n++] = b;
    for (int j0 = 0; j0 < n; j0 += lanes) {
      const int m = std::min(lanes, n - j0);
      bc7::LaneChoices c{};  // lanes m on are read, not used
      std::uint32_t tex[16][kBc7Batch] = {};
      for (int j = 0; j < m; ++j) {
        const int b = ids[j0 + j];
        bc7::copy_lane(t[b / kBc7Batch], b % kBc7Batch, c, j);
        for (int i = 0; i < 16; ++i) tex[i][j] = texel[b / kBc7Batch][i][b % kBc7Batch];
      }
      batch.load(tex, 0);
      batch.load_choices(c);
      batch.step_mode(mode, hn::FirstN(batch.d, std::size_t(m)));
      batch.store(c, 0);
      for (int j = 0; j < m; ++j) bc7::copy_lane(c, j, t[ids[j0 + j] / kBc7Batch], ids[j0 + j] % kBc7Batch);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#endif  // TEXPROC_BC7_SPAN_SIMD_INL_H_
