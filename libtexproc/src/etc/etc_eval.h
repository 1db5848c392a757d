// Scoring one ETC half block (8 texels) against a base colour and an
// intensity table: the encoder's inner loop, SIMD and scalar twins with
// identical results.
#pragma once

#include <cstdint>

namespace texproc::etc {

// The 8 texels of a half block, as planes.
struct HalfTexels;
// eval_half as the dispatched target's twin, or the reference under
// force_scalar(), resolved once: a half's search calls through the pointer
// its texels carry instead of dispatching at every base and table.
using EvalHalfFn = long (*)(const HalfTexels&, const int*, int, bool, std::uint8_t*);
EvalHalfFn eval_half_kernel();

struct HalfTexels {
  std::int32_t r[8], g[8], b[8];
  std::int32_t sum[8];                   // r + g + b
  std::int32_t transparent[8];           // 1: punch-through transparent (index 2, no error)
  EvalHalfFn eval = eval_half_kernel();  // resolved once per block
};

// Squared RGB error of the half against base `col` (8-bit) with table `t`,
// each texel's best index into idx. `non_opaque`: punch-through with
// transparent texels (modifiers +-a are 0, index 2 is transparent). When no
// palette entry clamps, a texel's index comes from three threshold tests on
// the sum of its channels (the squared error is a parabola in the
// modifier); otherwise every index is scored and the first least one wins.
long eval_half(const HalfTexels& tx, const int col[3], int t, bool non_opaque, std::uint8_t idx[8]);

namespace ref {
long eval_half(const HalfTexels& tx, const int col[3], int t, bool non_opaque, std::uint8_t idx[8]);
}  // namespace ref

}  // namespace texproc::etc
