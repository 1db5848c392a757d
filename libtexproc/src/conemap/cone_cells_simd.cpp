// The cone-map inner loops: the scalar reference and its Highway twin (lanes
// over the apex texels of a cell row). The twin tests a candidate without a
// division first (d2 < best * den, with a margin far above rounding) and
// divides only where a lane may improve; the stored ratio is the same
// quotient the reference computes, so both give identical results.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "conemap/cone_cells_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "conemap/cone_cells.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_CONE_CELLS_REF
#define TEXPROC_CONE_CELLS_REF
namespace texproc::detail::ref {

namespace {
void update(const ConeGeometry& g, float hq, float d2, float hp, float& best) {
  if (hq > hp && d2 > 0.0f) {
    const float r2 = cone_r2(g, d2, hq - hp);
    if (r2 < best) best = r2;
  }
}
}  // namespace

void cone_cell_texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                      const bool rows[kConeCell]) {
  for (int r = 0; r < kConeCell; ++r) {
    if (!rows[r]) continue;
    const int py = c.y0 + r;
    for (int qy = by0; qy <= by1; ++qy) {
      const int dy = cone_axis_distance(py, qy, qy, g.H, g.repeat);
      const float* hrow = heights + std::size_t(qy) * g.W;
      for (int qx = bx0; qx <= bx1; ++qx)
        for (int l = 0; l < kConeCell; ++l) {
          const float d2 = cone_d2(g, cone_axis_distance(c.x0 + l, qx, qx, g.W, g.repeat), dy);
          update(g, hrow[qx], d2, c.apex[r][l], c.best[r][l]);
        }
    }
  }
}

void cone_cell_block(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M,
                     const bool rows[kConeCell]) {
  for (int r = 0; r < kConeCell; ++r) {
    if (!rows[r]) continue;
    const int dy = cone_axis_distance(c.y0 + r, by0, by1, g.H, g.repeat);
    for (int l = 0; l < kConeCell; ++l) {
      const float d2 = cone_d2(g, cone_axis_distance(c.x0 + l, bx0, bx1, g.W, g.repeat), dy);
      update(g, M, d2, c.apex[r][l], c.best[r][l]);
    }
  }
}

}  // namespace texproc::detail::ref
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using DF = hn::CappedTag<float, kConeCell>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;

// dx * dx * sx per lane, after shrinking (the lanes' own distances vi).
HWY_INLINE VF DxTerm(const ConeGeometry& g, VI dx) {
  const DF d;
  const DI di;
  dx = hn::Max(hn::Sub(dx, hn::Set(di, g.shrink)), hn::Zero(di));
  return hn::Mul(hn::ConvertTo(d, hn::Mul(dx, dx)), hn::Set(d, g.sx));
}

// One obstacle of height hq for the lanes: best = min(best, r2) where counted.
HWY_INLINE VF Update(VF best, VF hp, VF d2, float hq_s, VF dd, VF slack) {
  const DF d;
  const VF hq = hn::Set(d, hq_s);
  const VF dh = hn::Sub(hq, hp);
  const VF den = hn::Mul(dd, hn::Mul(dh, dh));
  const auto counted = hn::And(hn::Gt(hq, hp), hn::Gt(d2, hn::Zero(d)));
  const auto may_improve = hn::And(counted, hn::Lt(d2, hn::Mul(hn::Mul(best, den), slack)));
  if (hn::AllFalse(d, may_improve)) return best;
  return hn::IfThenElse(may_improve, hn::Min(best, hn::Div(d2, den)), best);
}

void ConeCellTexels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                    const bool* rows) {
  const DF d;
  const DI di;
  const int N = int(hn::Lanes(d));
  const int nq = bx1 - bx0 + 1;
  const VF dd = hn::Set(d, g.dd), slack = hn::Set(d, 1.0f + 1.0f / 65536);
  for (int l0 = 0; l0 < kConeCell; l0 += N) {
    const VI px = hn::Add(hn::Iota(di, 0), hn::Set(di, c.x0 + l0));
    VF dxt[kConeCell];
    for (int j = 0; j < nq; ++j) {
      VI dx = hn::Abs(hn::Sub(px, hn::Set(di, bx0 + j)));
      if (g.repeat) dx = hn::Min(dx, hn::Sub(hn::Set(di, g.W), dx));
      dxt[j] = DxTerm(g, dx);
    }
    for (int r = 0; r < kConeCell; ++r) {
      if (!rows[r]) continue;
      const int py = c.y0 + r;
      const VF hp = hn::Load(d, &c.apex[r][l0]);
      VF best = hn::Load(d, &c.best[r][l0]);
      for (int qy = by0; qy <= by1; ++qy) {
        const VF d2y = hn::Set(d, cone_d2(g, 0, cone_axis_distance(py, qy, qy, g.H, g.repeat)));
        const float* hrow = heights + std::size_t(qy) * g.W + bx0;
        for (int j = 0; j < nq; ++j) best = Update(best, hp, hn::Add(dxt[j], d2y), hrow[j], dd, slack);
      }
      hn::Store(best, d, &c.best[r][l0]);
    }
  }
}

void ConeCellBlock(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M, const bool* rows) {
  const DF d;
  const DI di;
  const int N = int(hn::Lanes(d));
  const VF dd = hn::Set(d, g.dd), slack = hn::Set(d, 1.0f + 1.0f / 65536);
  for (int l0 = 0; l0 < kConeCell; l0 += N) {
    const VI px = hn::Add(hn::Iota(di, 0), hn::Set(di, c.x0 + l0));
    const VI zero = hn::Zero(di);
    VI dx = hn::Max(hn::Max(hn::Sub(hn::Set(di, bx0), px), hn::Sub(px, hn::Set(di, bx1))), zero);
    if (g.repeat) {
      dx = hn::Min(dx, hn::Min(hn::Sub(hn::Set(di, bx0 + g.W), px), hn::Add(px, hn::Set(di, g.W - bx1))));
    }
    const VF dxt = DxTerm(g, dx);
    for (int r = 0; r < kConeCell; ++r) {
      if (!rows[r]) continue;
      const VF d2y = hn::Set(d, cone_d2(g, 0, cone_axis_distance(c.y0 + r, by0, by1, g.H, g.repeat)));
      const VF best = Update(hn::Load(d, &c.best[r][l0]), hn::Load(d, &c.apex[r][l0]), hn::Add(dxt, d2y), M, dd, slack);
      hn::Store(best, d, &c.best[r][l0]);
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::detail {
HWY_EXPORT(ConeCellTexels);
HWY_EXPORT(ConeCellBlock);

void cone_cell_texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                      const bool rows[kConeCell]) {
  if (force_scalar()) return ref::cone_cell_texels(g, heights, c, bx0, bx1, by0, by1, rows);
  HWY_DYNAMIC_DISPATCH(ConeCellTexels)(g, heights, c, bx0, bx1, by0, by1, rows);
}

void cone_cell_block(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M,
                     const bool rows[kConeCell]) {
  if (force_scalar()) return ref::cone_cell_block(g, c, bx0, bx1, by0, by1, M, rows);
  HWY_DYNAMIC_DISPATCH(ConeCellBlock)(g, c, bx0, bx1, by0, by1, M, rows);
}
}  // namespace texproc::detail
#endif
