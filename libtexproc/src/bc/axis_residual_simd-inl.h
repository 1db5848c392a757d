// bc/axis_residual.h's residual off the principal axis, a set a lane: the
// same steps in the same order (so the same floats as the scalar
// references), for BC7's and BC6H's SIMD partition estimates. Included once
// per Highway target, as Highway's -inl headers are.
#if defined(TEXPROC_AXIS_RESIDUAL_SIMD_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TEXPROC_AXIS_RESIDUAL_SIMD_INL_H_
#undef TEXPROC_AXIS_RESIDUAL_SIMD_INL_H_
#else
#define TEXPROC_AXIS_RESIDUAL_SIMD_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace {

// The scatter matrix's trace less its largest eigenvalue (one power step
// from the largest diagonal's column, then the Rayleigh quotient).
template <class DF, class VF = hwy::HWY_NAMESPACE::Vec<DF>>
HWY_INLINE VF axis_residual(DF df, VF c00, VF c01, VF c02, VF c11, VF c12, VF c22) {
  namespace hn = hwy::HWY_NAMESPACE;
  const VF trace = hn::Add(hn::Add(c00, c11), c22);
  VF v0 = c00, v1 = c01, v2 = c02;
  const auto col1 = hn::And(hn::Gt(c11, c00), hn::Ge(c11, c22));
  v0 = hn::IfThenElse(col1, c01, v0);
  v1 = hn::IfThenElse(col1, c11, v1);
  v2 = hn::IfThenElse(col1, c12, v2);
  const auto col2 = hn::And(hn::Gt(c22, c00), hn::Gt(c22, c11));
  v0 = hn::IfThenElse(col2, c02, v0);
  v1 = hn::IfThenElse(col2, c12, v1);
  v2 = hn::IfThenElse(col2, c22, v2);
  auto times_c = [&](VF a0, VF a1, VF a2, VF& w0, VF& w1, VF& w2) {
    w0 = hn::Add(hn::Add(hn::Mul(c00, a0), hn::Mul(c01, a1)), hn::Mul(c02, a2));
    w1 = hn::Add(hn::Add(hn::Mul(c01, a0), hn::Mul(c11, a1)), hn::Mul(c12, a2));
    w2 = hn::Add(hn::Add(hn::Mul(c02, a0), hn::Mul(c12, a1)), hn::Mul(c22, a2));
  };
  VF u0, u1, u2, w0, w1, w2;
  times_c(v0, v1, v2, u0, u1, u2);
  times_c(u0, u1, u2, w0, w1, w2);
  const VF uu = hn::Add(hn::Add(hn::Mul(u0, u0), hn::Mul(u1, u1)), hn::Mul(u2, u2));
  const VF ucu = hn::Add(hn::Add(hn::Mul(u0, w0), hn::Mul(u1, w1)), hn::Mul(u2, w2));
  const auto pos = hn::Gt(uu, hn::Zero(df));
  const VF lambda = hn::IfThenElseZero(pos, hn::Div(ucu, hn::IfThenElse(pos, uu, hn::Set(df, 1.0f))));
  return hn::Sub(trace, lambda);
}

}  // namespace

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#endif
