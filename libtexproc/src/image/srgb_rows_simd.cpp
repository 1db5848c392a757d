// SIMD twins of the RGBA8 sRGB row codecs: table lookups become gathers.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "image/srgb_rows_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include "image/srgb_rows.h"
#include "texproc/runtime.h"

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_TARGET == HWY_SCALAR
void DecodeRgba(const std::uint8_t* src, int pixels, float* dst) {
  ref::decode_srgb8_rgba_premultiplied(src, pixels, dst);
}
void EncodeRgba(const float* src, int pixels, std::uint8_t* dst) {
  ref::encode_srgb8_rgba_unpremultiplied(src, pixels, dst);
}
#else
void DecodeRgba(const std::uint8_t* src, int pixels, float* dst) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::Rebind<uint8_t, decltype(df)> du8;
  const int lanes = int(hn::Lanes(df));  // a multiple of 4: whole pixels
  const float* table = detail::srgb8_decode_table();
  const auto is_alpha = hn::Eq(hn::And(hn::Iota(di, 0), hn::Set(di, 3)), hn::Set(di, 3));
  const auto inv255 = hn::Set(df, 1.0f / 255.0f);
  const int n = pixels * 4;
  int i = 0;
  for (; i + lanes <= n; i += lanes) {
    const auto codes = hn::PromoteTo(di, hn::LoadU(du8, src + i));
    const auto color = hn::GatherIndex(df, table, codes);
    const auto alpha = hn::Mul(hn::ConvertTo(df, codes), inv255);
    const auto a = hn::Broadcast<3>(alpha);  // each pixel's alpha in its four lanes
    hn::StoreU(hn::IfThenElse(hn::RebindMask(df, is_alpha), alpha, hn::Mul(color, a)), df, dst + i);
  }
  if (i < n) ref::decode_srgb8_rgba_premultiplied(src + i, (n - i) / 4, dst + i);
}

void EncodeRgba(const float* src, int pixels, std::uint8_t* dst) {
  const hn::ScalableTag<float> df;
  const hn::RebindToSigned<decltype(df)> di;
  const hn::Rebind<uint8_t, decltype(df)> du8;
  const int lanes = int(hn::Lanes(df));
  const int32_t* packed = reinterpret_cast<const int32_t*>(detail::srgb8_encode_packed());
  const auto is_alpha = hn::RebindMask(df, hn::Eq(hn::And(hn::Iota(di, 0), hn::Set(di, 3)), hn::Set(di, 3)));
  const auto zero = hn::Zero(df), one = hn::Set(df, 1.0f);
  const int n = pixels * 4;
  int i = 0;
  for (; i + lanes <= n; i += lanes) {
    const auto v = hn::LoadU(df, src + i);
    const auto a = hn::Broadcast<3>(v);
    const auto inv = hn::IfThenElseZero(hn::Gt(a, zero), hn::Div(one, a));
    // Straight color, clamped to [0, 1] with NaN to 0, as the reference.
    auto x = hn::IfThenElse(is_alpha, v, hn::Mul(v, inv));
    x = hn::Min(hn::IfThenElseZero(hn::Gt(x, zero), x), one);
    // sRGB: bin from the float's bits, one threshold compare.
    const auto bits = hn::BitCast(di, x);
    const auto e = hn::Sub(hn::ShiftRight<23>(bits), hn::Set(di, 127 + detail::kSrgbEncodeMinExponent));
    const auto valid = hn::Gt(e, hn::Set(di, -1));
    const int kMask = (1 << detail::kSrgbEncodeMantissaBits) - 1;
    auto idx = hn::Or(hn::ShiftLeft<detail::kSrgbEncodeMantissaBits>(e),
                      hn::And(hn::ShiftRight<23 - detail::kSrgbEncodeMantissaBits>(bits), hn::Set(di, kMask)));
    idx = hn::IfThenElseZero(valid, idx);
    const auto bin = hn::GatherIndex(di, packed, idx);
    const auto lo = hn::And(bin, hn::Set(di, 255));
    const auto low = hn::ShiftRight<8>(bin);
    const auto xlow = hn::And(bits, hn::Set(di, (1 << (23 - detail::kSrgbEncodeMantissaBits)) - 1));
    // x >= threshold  <=>  xlow >= low  <=>  !(low > xlow)
    auto code = hn::IfThenElse(hn::Gt(low, xlow), lo, hn::Add(lo, hn::Set(di, 1)));
    code = hn::IfThenElseZero(valid, code);
    // Alpha: round(a * 255).
    const auto acode = hn::ConvertTo(di, hn::Add(hn::Mul(x, hn::Set(df, 255.0f)), hn::Set(df, 0.5f)));
    code = hn::IfThenElse(hn::RebindMask(di, is_alpha), acode, code);
    hn::StoreU(hn::DemoteTo(du8, code), du8, dst + i);
  }
  if (i < n) ref::encode_srgb8_rgba_unpremultiplied(src + i, (n - i) / 4, dst + i);
}
#endif

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc {
HWY_EXPORT(DecodeRgba);
HWY_EXPORT(EncodeRgba);

void decode_srgb8_rgba_premultiplied(const std::uint8_t* src, int pixels, float* dst) {
  if (force_scalar()) return ref::decode_srgb8_rgba_premultiplied(src, pixels, dst);
  HWY_DYNAMIC_DISPATCH(DecodeRgba)(src, pixels, dst);
}
void encode_srgb8_rgba_unpremultiplied(const float* src, int pixels, std::uint8_t* dst) {
  if (force_scalar()) return ref::encode_srgb8_rgba_unpremultiplied(src, pixels, dst);
  HWY_DYNAMIC_DISPATCH(EncodeRgba)(src, pixels, dst);
}
}  // namespace texproc
#endif
