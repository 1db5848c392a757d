// sRGB transfer functions and the ColorSpace row codecs.
#include "texproc/color.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "image/ocio.h"
#include "texproc/error.h"

namespace texproc {

double srgb_to_linear(double v) {
  return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double v) {
  return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

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
  // start[i]: the code of the linear value i / kBins; the true code is at most
  // two steps above it (the curve's steepest slope, 12.92 * 255 codes per unit,
  // is under one code per bin).
  static constexpr int kBins = 4096;
  std::array<std::uint8_t, kBins + 1> start{};

  Srgb8Tables() {
    for (int i = 0; i < 256; ++i) decode[i] = static_cast<float>(srgb_to_linear(i / 255.0));
    threshold[0] = -1.0f;
    for (int k = 1; k < 256; ++k) threshold[k] = float_at_or_above(srgb_to_linear((k - 0.5) / 255.0));
    threshold[256] = 2.0f;  // never reached: x is clamped to [0, 1]
    int code = 0;
    for (int i = 0; i <= kBins; ++i) {
      const float x = static_cast<float>(i) / kBins;
      while (x >= threshold[code + 1]) ++code;
      start[i] = static_cast<std::uint8_t>(code);
    }
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

inline std::uint8_t encode_srgb8(const Srgb8Tables& t, float x) {
  x = clamp01(x);
  int code = t.start[static_cast<int>(x * Srgb8Tables::kBins)];
  while (x >= t.threshold[code + 1]) ++code;
  return static_cast<std::uint8_t>(code);
}

inline std::uint8_t encode_unorm8(float x) { return static_cast<std::uint8_t>(clamp01(x) * 255.0f + 0.5f); }
inline std::uint16_t encode_unorm16(float x) {
  return static_cast<std::uint16_t>(clamp01(x) * 65535.0f + 0.5f);
}

bool is_color_channel(int c, int channels) { return !((channels == 2 || channels == 4) && c == channels - 1); }

}  // namespace

float srgb8_to_linear(std::uint8_t v) { return srgb8().decode[v]; }
std::uint8_t linear_to_srgb8(float x) { return encode_srgb8(srgb8(), x); }
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
      } else {
        for (int x = 0; x < width; ++x) {
          for (int c = 0; c < channels - 1; ++c) dst[x * channels + c] = table[s[x * channels + c]];
          dst[x * channels + channels - 1] = s[x * channels + channels - 1] * (1.0f / 255.0f);
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
        dst[i] = srgb && is_color_channel(i % channels, channels)
                     ? static_cast<float>(srgb_to_linear(s[i]))
                     : s[i];
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
      const Srgb8Tables& t = srgb8();
      if (!srgb) {
        for (int i = 0; i < n; ++i) d[i] = encode_unorm8(src[i]);
      } else if (channels == 1 || channels == 3) {
        for (int i = 0; i < n; ++i) d[i] = encode_srgb8(t, src[i]);
      } else {
        for (int x = 0; x < width; ++x) {
          for (int c = 0; c < channels - 1; ++c) d[x * channels + c] = encode_srgb8(t, src[x * channels + c]);
          d[x * channels + channels - 1] = encode_unorm8(src[x * channels + channels - 1]);
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
        d[i] = srgb && is_color_channel(i % channels, channels) ? static_cast<float>(linear_to_srgb(src[i]))
                                                                : src[i];
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
