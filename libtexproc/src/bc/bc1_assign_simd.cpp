// BC1 index assignment: the scalar reference and its Highway twin (lanes over
// the 16 texels, 32-bit integers: identical results).
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc1_assign_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "bc/bc1_assign.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_BC1_ASSIGN_REF
#define TEXPROC_BC1_ASSIGN_REF
namespace texproc::ref {
void bc1_nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16],
                 std::int32_t errors[16]) {
  for (int i = 0; i < 16; ++i) {
    if (tx.transparent[i]) {
      codes[i] = 3;
      errors[i] = 0;
      continue;
    }
    int best = 0;
    std::int32_t be = -1;
    for (int k = 0; k < candidates; ++k) {
      const std::int32_t dr = tx.r[i] - pal[k][0], dg = tx.g[i] - pal[k][1], db = tx.b[i] - pal[k][2];
      const std::int32_t d = dr * dr + dg * dg + db * db;
      if (be < 0 || d < be) be = d, best = k;
    }
    codes[i] = std::uint8_t(best);
    errors[i] = be;
  }
}
}  // namespace texproc::ref
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

void Bc1Nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16],
                std::int32_t errors[16]) {
  const hn::CappedTag<std::int32_t, 16> d;
  const int lanes = int(hn::Lanes(d));
  HWY_ALIGN std::int32_t code_out[16];
  for (int i = 0; i < 16; i += lanes) {
    const auto r = hn::LoadU(d, tx.r + i), g = hn::LoadU(d, tx.g + i), b = hn::LoadU(d, tx.b + i);
    auto error_of = [&](int k) {
      const auto dr = hn::Sub(r, hn::Set(d, pal[k][0])), dg = hn::Sub(g, hn::Set(d, pal[k][1])),
                 db = hn::Sub(b, hn::Set(d, pal[k][2]));
      return hn::Add(hn::Add(hn::Mul(dr, dr), hn::Mul(dg, dg)), hn::Mul(db, db));
    };
    auto be = error_of(0);
    auto best = hn::Zero(d);
    for (int k = 1; k < candidates; ++k) {
      const auto e = error_of(k);
      const auto better = hn::Lt(e, be);
      be = hn::IfThenElse(better, e, be);
      best = hn::IfThenElse(better, hn::Set(d, k), best);
    }
    const auto transparent = hn::Ne(hn::LoadU(d, tx.transparent + i), hn::Zero(d));
    be = hn::IfThenElse(transparent, hn::Zero(d), be);
    best = hn::IfThenElse(transparent, hn::Set(d, 3), best);
    hn::StoreU(be, d, errors + i);
    hn::StoreU(best, d, code_out + i);
  }
  for (int i = 0; i < 16; ++i) codes[i] = std::uint8_t(code_out[i]);
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(Bc1Nearest);

void bc1_nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16],
                 std::int32_t errors[16]) {
  if (force_scalar()) return ref::bc1_nearest(tx, pal, candidates, codes, errors);
  HWY_DYNAMIC_DISPATCH(Bc1Nearest)(tx, pal, candidates, codes, errors);
}
}  // namespace texproc
#endif
