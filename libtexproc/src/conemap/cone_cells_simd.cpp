// The cone-map inner loops: the Highway twin of the scalar reference in cone_cells.cpp (lanes
// over the apex texels of a cell, in row order). The twin tests a candidate
// without a division first (d2 < best * dd * dh^2, with a margin far above
// rounding) and divides only where a lane may improve; the stored ratio is
// the same quotient the reference computes, so both give identical results.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "conemap/cone_cells_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "conemap/cone_cells.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc::detail {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

// Lanes run over the cell's texels in row order: a vector holds part of a
// row (4 lanes), a row (8) or two rows (16).
using DF = hn::CappedTag<float, 2 * kConeCell>;
using DI = hn::RebindToSigned<DF>;
using VF = hn::Vec<DF>;
using VI = hn::Vec<DI>;

// Axis distance term d * d * s per lane, after shrinking.
HWY_INLINE VF axis_term(const ConeGeometry& g, VI dist, float s) {
  const DF d;
  const DI di;
  dist = hn::Max(hn::Sub(dist, hn::Set(di, g.shrink)), hn::Zero(di));
  return hn::Mul(hn::ConvertTo(d, hn::Mul(dist, dist)), hn::Set(d, s));
}

// Distance from each lane's p to q along an axis of n texels.
HWY_INLINE VI texel_distance(VI p, int q, int n, bool repeat) {
  const DI di;
  VI dist = hn::Abs(hn::Sub(p, hn::Set(di, q)));
  if (repeat) dist = hn::Min(dist, hn::Sub(hn::Set(di, n), dist));
  return dist;
}

// Distance from each lane's p to the nearest texel of [lo, hi].
HWY_INLINE VI range_distance(VI p, int lo, int hi, int n, bool repeat) {
  const DI di;
  VI dist = hn::Max(hn::Max(hn::Sub(hn::Set(di, lo), p), hn::Sub(p, hn::Set(di, hi))), hn::Zero(di));
  if (repeat) dist = hn::Min(dist, hn::Min(hn::Sub(hn::Set(di, lo + n), p), hn::Add(p, hn::Set(di, n - hi))));
  return dist;
}

// The apex texels of vector v: columns and rows.
struct LanePos {
  VI px, py;
};
HWY_INLINE LanePos positions(const ConeCell& c, int v) {
  const DF d;
  const DI di;
  const VI flat = hn::Add(hn::Iota(di, 0), hn::Set(di, v * int(hn::Lanes(d))));
  return {hn::Add(hn::And(flat, hn::Set(di, kConeCell - 1)), hn::Set(di, c.x0)),
          hn::Add(hn::ShiftRight<3>(flat), hn::Set(di, c.y0))};
}

// Whether vector v covers a row marked in rows.
HWY_INLINE bool any_row(const bool* rows, int v, int lanes) {
  const int r0 = v * lanes / kConeCell, r1 = ((v + 1) * lanes - 1) / kConeCell;
  for (int r = r0; r <= r1; ++r)
    if (rows[r]) return true;
  return false;
}

// One obstacle of height hq for the lanes: best = min(best, r2) where it
// counts. bdd = best * dd * slack tests a candidate without dividing.
// Relaxed cones: where a lane may improve, the exit rule decides, per lane
// (rare once the cones have narrowed; cone_exits, as the reference).
struct Exits {
  const ConeGeometry* g = nullptr;  // null: conservative
  const ConeCell* c = nullptr;
  int v = 0, qx = 0, qy = 0;
};

template <bool kCheckZero>
HWY_INLINE bool update(VF& best, VF& bdd, VF hp, VF d2, VF hq, VF dd, VF slack, const Exits& ex = {}) {
  const DF d;
  const VF dh = hn::Sub(hq, hp);
  // dh * |dh|: dh^2 where the obstacle is higher, <= 0 where it is not (so
  // d2 >= 0 never passes there): one test for both conditions.
  auto may_improve = hn::Lt(d2, hn::Mul(bdd, hn::Mul(dh, hn::Abs(dh))));
  if (kCheckZero) may_improve = hn::And(may_improve, hn::Gt(d2, hn::Zero(d)));
  if (HWY_LIKELY(hn::AllFalse(d, may_improve))) return false;
  if (ex.g) {
    const int N = int(hn::Lanes(d));
    HWY_ALIGN float keep[2 * kConeCell];
    hn::Store(hn::IfThenElseZero(may_improve, hn::Set(d, 1.0f)), d, keep);
    for (int l = 0; l < N; ++l) {
      const int flat = ex.v * N + l;
      if (keep[l] != 0.0f &&
          !cone_exits(*ex.g, ex.c->x0 + (flat & (kConeCell - 1)), ex.c->y0 + (flat >> 3), ex.qx, ex.qy)) {
        keep[l] = 0.0f;
      }
    }
    may_improve = hn::Ne(hn::Load(d, keep), hn::Zero(d));
  }
  best = hn::IfThenElse(may_improve, hn::Min(best, hn::Div(d2, hn::Mul(dd, hn::Mul(dh, dh)))), best);
  bdd = hn::Mul(hn::Mul(best, dd), slack);
  return true;  // (or nearly: a lane within the margin may keep its value)
}

template <bool kCheckZero>
bool Texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
            const bool* rows) {
  const DF d;
  const int N = int(hn::Lanes(d));
  const int nq = bx1 - bx0 + 1;
  const VF dd = hn::Set(d, g.dd), slack = hn::Set(d, 1.0f + 1.0f / 65536);
  float* apex = &c.apex[0][0];
  float* best_all = &c.best[0][0];
  bool improved = false;
  for (int v = 0; v < kConeCell * kConeCell / N; ++v) {
    if (!any_row(rows, v, N)) continue;
    const LanePos pos = positions(c, v);
    VF dxt[kConeCell];
    for (int j = 0; j < nq; ++j) dxt[j] = axis_term(g, texel_distance(pos.px, bx0 + j, g.W, g.repeat), g.sx);
    const VF hp = hn::Load(d, apex + v * N);
    VF best = hn::Load(d, best_all + v * N);
    VF bdd = hn::Mul(hn::Mul(best, dd), slack);
    // An obstacle row is skipped when even its highest texel (row_max8), at
    // the nearest column for the lowest apex, cannot narrow the widest cone.
    const float lowest = hn::GetLane(hn::MinOfLanes(d, hp));
    VF dx_min = hn::Set(d, std::numeric_limits<float>::infinity());
    for (int j = 0; j < nq; ++j) dx_min = hn::Min(dx_min, dxt[j]);
    const std::size_t run_stride = std::size_t(g.W + 7) / 8;
    for (int qy = by0; qy <= by1; ++qy) {
      const VF dyt = axis_term(g, texel_distance(pos.py, qy, g.H, g.repeat), g.sy);
      if (g.row_max8) {
        const float dh = g.row_max8[std::size_t(qy) * run_stride + std::size_t(bx0 / 8)] - lowest;
        if (!(dh > 0.0f)) continue;
        const float d2 = hn::GetLane(hn::MinOfLanes(d, hn::Add(dx_min, dyt)));
        const float widest = hn::GetLane(hn::MaxOfLanes(d, best));
        if (d2 > widest * g.dd * (dh * dh) * (1.0f + 1.0f / 65536)) continue;
      }
      const float* hrow = heights + std::size_t(qy) * g.W + bx0;
      for (int j = 0; j < nq; ++j) {
        Exits ex;
        if (g.exit_bits) ex = {&g, &c, v, bx0 + j, qy};
        improved |= update<kCheckZero>(best, bdd, hp, hn::Add(dxt[j], dyt), hn::Set(d, hrow[j]), dd, slack, ex);
      }
    }
    hn::Store(best, d, best_all + v * N);
  }
  return improved;
}

}  // namespace

bool ConeCellTexels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                    const bool* rows) {
  if (g.shrink > 0) return Texels<true>(g, heights, c, bx0, bx1, by0, by1, rows);
  return Texels<false>(g, heights, c, bx0, bx1, by0, by1, rows);
}

bool ConeCellBlock(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M, const bool* rows) {
  const DF d;
  bool improved = false;
  const int N = int(hn::Lanes(d));
  const VF dd = hn::Set(d, g.dd), slack = hn::Set(d, 1.0f + 1.0f / 65536), hq = hn::Set(d, M);
  for (int v = 0; v < kConeCell * kConeCell / N; ++v) {
    if (!any_row(rows, v, N)) continue;
    const LanePos pos = positions(c, v);
    const VF d2 = hn::Add(axis_term(g, range_distance(pos.px, bx0, bx1, g.W, g.repeat), g.sx),
                          axis_term(g, range_distance(pos.py, by0, by1, g.H, g.repeat), g.sy));
    VF best = hn::Load(d, &c.best[0][0] + v * N);
    VF bdd = hn::Mul(hn::Mul(best, dd), slack);
    improved |= update<true>(best, bdd, hn::Load(d, &c.apex[0][0] + v * N), d2, hq, dd, slack);
    hn::Store(best, d, &c.best[0][0] + v * N);
  }
  return improved;
}

bool ConeCellClear(const ConeGeometry& g, const ConeCell& c, int bx0, int bx1, int by0, int by1, float M, int axis,
                   float rise, int extent) {
  const DF d;
  const int N = int(hn::Lanes(d));
  const VF m = hn::Set(d, M), zero = hn::Zero(d);
  const VF m0 = hn::Set(d, rise > 0.0f ? M - float(extent) * rise : M);
  const VF ddslack = hn::Set(d, g.dd * (1.0f + 1.0f / 65536));
  const VF inv_w = hn::Set(d, 1.0f / float(g.W)), inv_h = hn::Set(d, 1.0f / float(g.H));
  const VF deep = hn::Set(d, float(extent) / float(axis == 0 ? g.W : g.H));
  const DI di;
  for (int v = 0; v < kConeCell * kConeCell / N; ++v) {
    const LanePos pos = positions(c, v);
    const VF hp = hn::Load(d, &c.apex[0][0] + v * N);
    const VF lim = hn::Mul(hn::Load(d, &c.best[0][0] + v * N), ddslack);
    VI dxi = hn::Max(hn::Sub(range_distance(pos.px, bx0, bx1, g.W, g.repeat), hn::Set(di, g.shrink)), hn::Zero(di));
    VI dyi = hn::Max(hn::Sub(range_distance(pos.py, by0, by1, g.H, g.repeat), hn::Set(di, g.shrink)), hn::Zero(di));
    const VF vx = hn::Mul(hn::ConvertTo(d, dxi), inv_w), vy = hn::Mul(hn::ConvertTo(d, dyi), inv_h);
    const VF len2 = hn::Add(hn::Mul(vx, vx), hn::Mul(vy, vy));
    const VF dh0 = hn::Sub(m0, hp);
    // A lane is in the way when its apex is below M and a bound fails.
    auto bad = hn::And(hn::Gt(dh0, zero), hn::Not(hn::Gt(len2, hn::Mul(lim, hn::Mul(dh0, dh0)))));
    if (rise > 0.0f) {
      const VF len = hn::Sqrt(len2);
      const VF far = hn::Add(len, hn::Mul(hn::Div(axis == 0 ? vx : vy, len), deep));
      const VF dh = hn::Sub(m, hp);
      const auto below = hn::Gt(dh, zero);
      bad = hn::Or(bad, hn::And(below, hn::Not(hn::Gt(len, zero))));
      bad = hn::Or(bad, hn::And(below, hn::Not(hn::Gt(hn::Mul(far, far), hn::Mul(lim, hn::Mul(dh, dh))))));
    }
    if (!hn::AllFalse(d, bad)) return false;
  }
  return true;
}

float ConeCellReach(const ConeCell& c, float M) {
  const DF d;
  const int N = int(hn::Lanes(d));
  const VF m = hn::Set(d, M), zero = hn::Zero(d);
  VF most = zero;
  for (int v = 0; v < kConeCell * kConeCell / N; ++v) {
    const VF dh = hn::Max(hn::Sub(m, hn::Load(d, &c.apex[0][0] + v * N)), zero);
    most = hn::Max(most, hn::Mul(hn::Load(d, &c.best[0][0] + v * N), hn::Mul(dh, dh)));
  }
  return hn::GetLane(hn::MaxOfLanes(d, most));
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc::detail
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::detail {
HWY_EXPORT(ConeCellTexels);
HWY_EXPORT(ConeCellBlock);
HWY_EXPORT(ConeCellClear);
HWY_EXPORT(ConeCellReach);

float cone_cell_reach(const ConeCell& c, float M) {
  if (force_scalar()) return ref::cone_cell_reach(c, M);
  return HWY_DYNAMIC_DISPATCH(ConeCellReach)(c, M);
}

bool cone_cell_clear(const ConeGeometry& g, const ConeCell& c, int bx0, int bx1, int by0, int by1, float M, int axis,
                     float rise, int extent) {
  if (force_scalar()) return ref::cone_cell_clear(g, c, bx0, bx1, by0, by1, M, axis, rise, extent);
  return HWY_DYNAMIC_DISPATCH(ConeCellClear)(g, c, bx0, bx1, by0, by1, M, axis, rise, extent);
}

bool cone_cell_texels(const ConeGeometry& g, const float* heights, ConeCell& c, int bx0, int bx1, int by0, int by1,
                      const bool rows[kConeCell]) {
  if (force_scalar()) return ref::cone_cell_texels(g, heights, c, bx0, bx1, by0, by1, rows);
  return HWY_DYNAMIC_DISPATCH(ConeCellTexels)(g, heights, c, bx0, bx1, by0, by1, rows);
}

bool cone_cell_block(const ConeGeometry& g, ConeCell& c, int bx0, int bx1, int by0, int by1, float M,
                     const bool rows[kConeCell]) {
  if (force_scalar()) return ref::cone_cell_block(g, c, bx0, bx1, by0, by1, M, rows);
  return HWY_DYNAMIC_DISPATCH(ConeCellBlock)(g, c, bx0, bx1, by0, by1, M, rows);
}
}  // namespace texproc::detail
#endif
