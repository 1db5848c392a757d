// sRGB transfer functions and the ColorSpace row codecs.
#include "texproc/color.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstring>

#include "image/ocio.h"
#include "image/srgb_rows.h"
#include "texproc/error.h"

namespace texproc {

double srgb_to_linear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

double linear_to_srgb(double v) { return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

namespace {

// The smallest float f with (double)f >= d: comparing a float x >= f is then
// exactly comparing x >= d, so thresholds never round the wrong way.
float float_at_or_above(double d) {
  float f = static_cast<float>(d);
  if (static_cast<double>(f) < d) f = std::nextafter(f, 2.0f);
  return f;
}

struct Srgb8Tables {
  std::array<float, 256> decode{};
  // threshold[k] (k = 1..255): the smallest linear value that encodes to k,
  // i.e. srgb_to_linear((k - 0.5) / 255) rounded up to a float.
  std::array<float, 257> threshold{};

  Srgb8Tables() {
    for (int i = 0; i < 256; ++i) decode[i] = static_cast<float>(srgb_to_linear(i / 255.0));
    threshold[0] = -1.0f;
    for (int k = 1; k < 256; ++k) threshold[k] = float_at_or_above(srgb_to_linear((k - 0.5) / 255.0));
    threshold[256] = 4.0f;  // never reached: x is clamped to [0, 1]
  }
};

const Srgb8Tables& srgb8() {
  static const Srgb8Tables tables;
  return tables;
}

const std::array<float, 65536>& srgb16_decode() {
  static const auto table = [] {
    std::array<float, 65536> t{};
    for (int i = 0; i < 65536; ++i) t[i] = static_cast<float>(srgb_to_linear(i / 65535.0));
    return t;
  }();
  return table;
}

inline float clamp01(float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; }  // NaN -> 0

// Encoding by the float's bits: x in [2^-13, 2) is split into bins by its
// exponent and the top kMantissaBits of its mantissa. The sRGB curve rises by
// at most 0.11 codes across a bin (112 codes per unit of ln x at x = 1, and a
// bin spans 2^-10 of ln x), so a bin holds at most one rounding threshold:
// code = lo + (x >= threshold), exact, with one lookup and no loop. Below
// 2^-13 every value encodes to 0 (the first threshold is 1.5e-4).
struct Srgb8Encoder {
  static constexpr int kMantissaBits = detail::kSrgbEncodeMantissaBits;
  static constexpr int kMinExponent = detail::kSrgbEncodeMinExponent;
  static constexpr int kExponents = 14;  // -13 .. 0 ([1, 2) encodes to 255)
  struct Bin {
    float threshold;
    std::uint32_t lo;
  };
  static_assert(sizeof(Bin) == 8, "the SIMD encoder gathers bins as float pairs");
  std::array<Bin, kExponents << kMantissaBits> bins{};
  // The same bins packed for one SIMD gather: lo | low << 8, where `low` is
  // the threshold's mantissa bits below the bin index (x and the threshold
  // share everything above them, so comparing these bits compares the
  // floats), or 1 << 13, above any such bits, where the bin has none.
  std::array<std::uint32_t, kExponents << kMantissaBits> packed{};

  explicit Srgb8Encoder(const Srgb8Tables& t) {
    for (std::size_t i = 0; i < bins.size(); ++i) {
      const std::uint32_t bits = std::uint32_t(127 + kMinExponent + int(i >> kMantissaBits)) << 23 |
                                 std::uint32_t(i & ((1u << kMantissaBits) - 1)) << (23 - kMantissaBits);
      float lo_x, hi_x;
      std::memcpy(&lo_x, &bits, 4);
      const std::uint32_t next = bits + (1u << (23 - kMantissaBits));
      std::memcpy(&hi_x, &next, 4);
      int code = 0;
      while (code < 255 && lo_x >= t.threshold[code + 1]) ++code;
      bins[i].lo = std::uint32_t(code);
      bins[i].threshold = 4.0f;  // never reached
      std::uint32_t low = 1u << (23 - kMantissaBits);
      if (code < 255 && t.threshold[code + 1] < hi_x) {
        bins[i].threshold = t.threshold[code + 1];
        assert(code + 2 > 255 || t.threshold[code + 2] >= hi_x);  // one threshold per bin
        std::uint32_t tb;
        std::memcpy(&tb, &bins[i].threshold, 4);
        low = tb & ((1u << (23 - kMantissaBits)) - 1);
      }
      packed[i] = std::uint32_t(code) | low << 8;
    }
  }
};

const Srgb8Encoder& srgb8_encoder() {
  static const Srgb8Encoder encoder(srgb8());
  return encoder;
}

inline std::uint8_t encode_srgb8(const Srgb8Encoder& e, float x) {
  x = x > 0.0f ? x : 0.0f;  // NaN -> 0
  x = x < 1.0f ? x : 1.0f;
  std::uint32_t bits;
  std::memcpy(&bits, &x, 4);
  const int exponent = int(bits >> 23) - 127 - Srgb8Encoder::kMinExponent;
  if (exponent < 0) return 0;
  const auto& bin = e.bins[std::uint32_t(exponent) << Srgb8Encoder::kMantissaBits |
                           (bits >> (23 - Srgb8Encoder::kMantissaBits) & ((1u << Srgb8Encoder::kMantissaBits) - 1))];
  return std::uint8_t(bin.lo + (x >= bin.threshold));
}

inline std::uint8_t encode_unorm8(float x) { return static_cast<std::uint8_t>(clamp01(x) * 255.0f + 0.5f); }
inline std::uint16_t encode_unorm16(float x) { return static_cast<std::uint16_t>(clamp01(x) * 65535.0f + 0.5f); }

bool is_color_channel(int c, int channels) { return !((channels == 2 || channels == 4) && c == channels - 1); }

}  // namespace

float srgb8_to_linear(std::uint8_t v) { return srgb8().decode[v]; }

namespace detail {
const float* srgb8_decode_table() { return srgb8().decode.data(); }
const std::uint32_t* srgb8_encode_packed() { return srgb8_encoder().packed.data(); }
}  // namespace detail

namespace ref {
void decode_srgb8_rgba_premultiplied(const std::uint8_t* src, int pixels, float* dst) {
  const float* table = srgb8().decode.data();
  for (int x = 0; x < pixels; ++x, src += 4, dst += 4) {
    const float a = src[3] * (1.0f / 255.0f);
    dst[0] = table[src[0]] * a;
    dst[1] = table[src[1]] * a;
    dst[2] = table[src[2]] * a;
    dst[3] = a;
  }
}

void encode_srgb8_rgba_unpremultiplied(const float* src, int pixels, std::uint8_t* dst) {
  const Srgb8Encoder& e = srgb8_encoder();
  for (int x = 0; x < pixels; ++x, src += 4, dst += 4) {
    const float a = src[3];
    const float inv = a > 0.0f ? 1.0f / a : 0.0f;
    dst[0] = encode_srgb8(e, src[0] * inv);
    dst[1] = encode_srgb8(e, src[1] * inv);
    dst[2] = encode_srgb8(e, src[2] * inv);
    dst[3] = encode_unorm8(a);
  }
}
}  // namespace ref
std::uint8_t linear_to_srgb8(float x) { return encode_srgb8(srgb8_encoder(), x); }
float srgb16_to_linear(std::uint16_t v) { return srgb16_decode()[v]; }
std::uint16_t linear_to_srgb16(float x) {
  const double e = linear_to_srgb(clamp01(x));
  return static_cast<std::uint16_t>(std::lround(e * 65535.0));
}

enum class TransferKind { linear, srgb, ocio };

struct ColorSpace::Impl {
  std::string name;
  TransferKind kind = TransferKind::linear;
  std::shared_ptr<const OcioTransform> ocio;  // kind == ocio only
};

ColorSpace ColorSpace::linear() {
  static const auto impl = std::make_shared<const Impl>(Impl{"linear", TransferKind::linear, nullptr});
  return ColorSpace(impl);
}

ColorSpace ColorSpace::srgb() {
  static const auto impl = std::make_shared<const Impl>(Impl{"srgb", TransferKind::srgb, nullptr});
  return ColorSpace(impl);
}

namespace {
std::string lower(std::string s) {
  for (auto& ch : s) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return s;
}
}  // namespace

ColorSpace ColorSpace::from_name(const std::string& name) {
  const std::string l = lower(name);
  if (l == "linear" || l == "raw" || l == "data" || l == "lin") return linear();
  if (l == "srgb") return srgb();
  auto transform = OcioTransform::create(name);  // throws with the valid names
  return ColorSpace(std::make_shared<const Impl>(Impl{name, TransferKind::ocio, std::move(transform)}));
}

const std::string& ColorSpace::name() const { return impl_->name; }
bool ColorSpace::is_linear() const { return impl_->kind == TransferKind::linear; }
bool ColorSpace::is_srgb() const { return impl_->kind == TransferKind::srgb; }
const std::string& ColorSpace::config_path() const {
  static const std::string none;
  return impl_->ocio ? impl_->ocio->config_path() : none;
}

void ColorSpace::decode_row(const void* src, PixelType type, int channels, int width, float* dst) const {
  const int n = width * channels;
  const bool srgb = impl_->kind == TransferKind::srgb;
  switch (type) {
    case PixelType::u8: {
      const auto* s = static_cast<const std::uint8_t*>(src);
      const float* table = srgb8().decode.data();
      if (!srgb) {
        for (int i = 0; i < n; ++i) dst[i] = s[i] * (1.0f / 255.0f);
      } else if (channels == 1 || channels == 3) {
        for (int i = 0; i < n; ++i) dst[i] = table[s[i]];
      } else if (channels == 4) {
        for (int x = 0; x < width; ++x, s += 4, dst += 4) {
          dst[0] = table[s[0]];
          dst[1] = table[s[1]];
          dst[2] = table[s[2]];
          dst[3] = s[3] * (1.0f / 255.0f);
        }
      } else {
        for (int x = 0; x < width; ++x) {
          dst[2 * x] = table[s[2 * x]];
          dst[2 * x + 1] = s[2 * x + 1] * (1.0f / 255.0f);
        }
      }
      break;
    }
    case PixelType::u16: {
      const auto* s = static_cast<const std::uint16_t*>(src);
      const float* table = srgb16_decode().data();
      for (int i = 0; i < n; ++i) {
        dst[i] = srgb && is_color_channel(i % channels, channels) ? table[s[i]] : s[i] * (1.0f / 65535.0f);
      }
      break;
    }
    case PixelType::f32: {
      const auto* s = static_cast<const float*>(src);
      for (int i = 0; i < n; ++i) {
        dst[i] = srgb && is_color_channel(i % channels, channels) ? static_cast<float>(srgb_to_linear(s[i])) : s[i];
      }
      break;
    }
  }
  if (impl_->kind == TransferKind::ocio) impl_->ocio->to_linear(dst, channels, width);
}

void ColorSpace::encode_row(float* src, int channels, int width, void* dst, PixelType type) const {
  if (impl_->kind == TransferKind::ocio) impl_->ocio->from_linear(src, channels, width);
  const int n = width * channels;
  const bool srgb = impl_->kind == TransferKind::srgb;
  switch (type) {
    case PixelType::u8: {
      auto* d = static_cast<std::uint8_t*>(dst);
      const Srgb8Encoder& e = srgb8_encoder();
      if (!srgb) {
        for (int i = 0; i < n; ++i) d[i] = encode_unorm8(src[i]);
      } else if (channels == 1 || channels == 3) {
        for (int i = 0; i < n; ++i) d[i] = encode_srgb8(e, src[i]);
      } else if (channels == 4) {
        const float* p = src;
        for (int x = 0; x < width; ++x, p += 4, d += 4) {
          d[0] = encode_srgb8(e, p[0]);
          d[1] = encode_srgb8(e, p[1]);
          d[2] = encode_srgb8(e, p[2]);
          d[3] = encode_unorm8(p[3]);
        }
      } else {
        for (int x = 0; x < width; ++x) {
          d[2 * x] = encode_srgb8(e, src[2 * x]);
          d[2 * x + 1] = encode_unorm8(src[2 * x + 1]);
        }
      }
      break;
    }
    case PixelType::u16: {
      auto* d = static_cast<std::uint16_t*>(dst);
      for (int i = 0; i < n; ++i) {
        d[i] = srgb && is_color_channel(i % channels, channels) ? linear_to_srgb16(src[i]) : encode_unorm16(src[i]);
      }
      break;
    }
    case PixelType::f32: {
      auto* d = static_cast<float*>(dst);
      for (int i = 0; i < n; ++i) {
        d[i] = srgb && is_color_channel(i % channels, channels) ? static_cast<float>(linear_to_srgb(src[i])) : src[i];
      }
      break;
    }
  }
}

std::vector<std::string> color_space_names() {
  std::vector<std::string> names = {"linear", "srgb"};
  for (auto& n : OcioTransform::names()) names.push_back(n);
  return names;
}

}  // namespace texproc
