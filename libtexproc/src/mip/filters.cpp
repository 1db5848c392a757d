// Filter kernels as data: each kind has its support and its curve.
#include "texproc/filters.h"

#include <cmath>
#include <numbers>

#include "texproc/error.h"

namespace texproc {
namespace {

double sinc(double x) {
  if (std::abs(x) < 1e-9) return 1.0;
  const double px = std::numbers::pi * x;
  return std::sin(px) / px;
}

// Modified Bessel function of the first kind, order 0 (series; converges fast
// for the arguments a Kaiser window uses).
double bessel_i0(double x) {
  double sum = 1.0, term = 1.0;
  const double q = x * x / 4.0;
  for (int k = 1; k < 64; ++k) {
    term *= q / (double(k) * k);
    sum += term;
    if (term < sum * 1e-17) break;
  }
  return sum;
}

double mitchell(double x, double b, double c) {
  x = std::abs(x);
  if (x < 1.0) {
    return ((12 - 9 * b - 6 * c) * x * x * x + (-18 + 12 * b + 6 * c) * x * x + (6 - 2 * b)) / 6.0;
  }
  if (x < 2.0) {
    return ((-b - 6 * c) * x * x * x + (6 * b + 30 * c) * x * x + (-12 * b - 48 * c) * x + (8 * b + 24 * c)) / 6.0;
  }
  return 0.0;
}

struct FilterEntry {
  FilterKind kind;
  const char* name;
  double support;  // for the Gaussian: in sigmas
};

constexpr FilterEntry kFilters[] = {
    {FilterKind::box, "box", 0.5},           {FilterKind::triangle, "triangle", 1.0},
    {FilterKind::gaussian, "gaussian", 4.0}, {FilterKind::kaiser, "kaiser", 3.0},
    {FilterKind::lanczos3, "lanczos3", 3.0}, {FilterKind::mitchell, "mitchell", 2.0},
};

constexpr double kKaiserAlpha = 4.0;  // NVTT's default window
constexpr double kMitchellB = 1.0 / 3.0, kMitchellC = 1.0 / 3.0;

struct WrapEntry {
  WrapMode mode;
  const char* name;
};
constexpr WrapEntry kWraps[] = {{WrapMode::clamp, "clamp"}, {WrapMode::repeat, "repeat"}, {WrapMode::mirror, "mirror"}};

}  // namespace

double filter_support(const Filter& f) {
  for (const auto& e : kFilters) {
    if (e.kind == f.kind) return f.kind == FilterKind::gaussian ? e.support * f.sigma : e.support;
  }
  return 0.0;
}

double filter_eval(const Filter& f, double x) {
  const double ax = std::abs(x);
  switch (f.kind) {
    case FilterKind::box:
      return ax <= 0.5 ? 1.0 : 0.0;
    case FilterKind::triangle:
      return ax < 1.0 ? 1.0 - ax : 0.0;
    case FilterKind::gaussian: {
      if (ax > 4.0 * f.sigma) return 0.0;
      return std::exp(-x * x / (2.0 * double(f.sigma) * f.sigma));
    }
    case FilterKind::kaiser: {
      if (ax >= 3.0) return 0.0;
      const double t = ax / 3.0;
      return sinc(x) * bessel_i0(kKaiserAlpha * std::sqrt(1.0 - t * t)) / bessel_i0(kKaiserAlpha);
    }
    case FilterKind::lanczos3:
      return ax < 3.0 ? sinc(x) * sinc(x / 3.0) : 0.0;
    case FilterKind::mitchell:
      return mitchell(x, kMitchellB, kMitchellC);
  }
  return 0.0;
}

std::vector<std::string> filter_kind_names() {
  std::vector<std::string> v;
  for (const auto& e : kFilters) v.emplace_back(e.name);
  return v;
}
std::vector<std::string> wrap_mode_names() {
  std::vector<std::string> v;
  for (const auto& e : kWraps) v.emplace_back(e.name);
  return v;
}

namespace {
std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}
}  // namespace

FilterKind parse_filter_kind(std::string_view name) {
  for (const auto& e : kFilters) {
    if (name == e.name) return e.kind;
  }
  if (name == "lanczos") return FilterKind::lanczos3;
  throw Error(ErrorCode::bad_arguments,
              "unknown filter '" + std::string(name) + "' (valid: " + join(filter_kind_names()) + ")");
}

WrapMode parse_wrap_mode(std::string_view name) {
  for (const auto& e : kWraps) {
    if (name == e.name) return e.mode;
  }
  if (name == "wrap" || name == "tile") return WrapMode::repeat;
  throw Error(ErrorCode::bad_arguments,
              "unknown wrap mode '" + std::string(name) + "' (valid: " + join(wrap_mode_names()) + ")");
}

const char* to_string(FilterKind k) {
  for (const auto& e : kFilters) {
    if (e.kind == k) return e.name;
  }
  return "?";
}
const char* to_string(WrapMode w) {
  for (const auto& e : kWraps) {
    if (e.mode == w) return e.name;
  }
  return "?";
}

int wrap_index(int i, int n, WrapMode wrap) {
  if (i >= 0 && i < n) return i;
  switch (wrap) {
    case WrapMode::clamp:
      return i < 0 ? 0 : n - 1;
    case WrapMode::repeat: {
      const int m = i % n;
      return m < 0 ? m + n : m;
    }
    case WrapMode::mirror: {
      // Period 2n: 0 1 .. n-1 n-1 .. 1 0 | 0 1 ...
      const int period = 2 * n;
      int m = i % period;
      if (m < 0) m += period;
      return m < n ? m : period - 1 - m;
    }
  }
  return 0;
}

}  // namespace texproc
