// Summed-area tables: two passes over strips of rows, so that threads work
// on disjoint rows and the bytes never depend on their number.
//
// Pass 1: each strip's column totals. Then, serially, the table row just
// above each strip (prefix over x of the running column totals). Pass 2:
// each strip walks its rows: S(x, y) = S(x, y - 1) + (row prefix of y)(x).
// Integer tables wrap modulo 2^32 or 2^64, which keeps every box sum exact
// while the true sum fits (the wrap-around cancels in the four-term
// difference). f32 tables are computed exactly (int64, or double for float
// input), the mean's share (x + 1)(y + 1) * mean subtracted (Hensley et al.,
// "Fast Summed-Area Table Generation and its Applications", 2005), and
// rounded once to float.
#include "texproc/sat.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

const char* to_string(SatPrecision p) {
  switch (p) {
    case SatPrecision::u32: return "u32";
    case SatPrecision::u64: return "u64";
    case SatPrecision::f32: return "f32";
    case SatPrecision::f64: return "f64";
  }
  return "?";
}

SatPrecision parse_sat_precision(std::string_view n) {
  if (n == "u32") return SatPrecision::u32;
  if (n == "u64") return SatPrecision::u64;
  if (n == "f32") return SatPrecision::f32;
  if (n == "f64") return SatPrecision::f64;
  throw Error(ErrorCode::bad_arguments, "unknown --precision '" + std::string(n) + "' (valid: u32, u64, f32, f64)");
}

namespace {
std::uint64_t max_code(PixelType t) { return t == PixelType::u8 ? 255 : 65535; }
}  // namespace

std::uint64_t sat_max_exact_box(SatPrecision p, PixelType input) {
  if (input == PixelType::f32) return 0;
  const std::uint64_t m = max_code(input);
  switch (p) {
    case SatPrecision::u32: return 0xFFFFFFFFull / m;
    case SatPrecision::u64: return std::numeric_limits<std::uint64_t>::max() / m;
    case SatPrecision::f64: return (std::uint64_t(1) << 53) / m;
    case SatPrecision::f32: return 0;
  }
  return 0;
}

SatPrecision default_sat_precision(PixelType input, int width, int height) {
  if (input == PixelType::f32) return SatPrecision::f64;
  const std::uint64_t area = std::uint64_t(width) * std::uint64_t(height);
  return area <= sat_max_exact_box(SatPrecision::u32, input) ? SatPrecision::u32 : SatPrecision::u64;
}

std::size_t SummedAreaTable::element_bytes() const {
  return precision == SatPrecision::u32 || precision == SatPrecision::f32 ? 4 : 8;
}

namespace {

template <typename T>
double entry(const SummedAreaTable& t, int x, int y, int c) {
  if (x < 0 || y < 0) return 0.0;
  T v;
  std::memcpy(&v, t.data.data() + ((std::size_t(y) * t.width + x) * t.channels + c) * sizeof(T), sizeof(T));
  return double(v);
}

template <typename T>
T entry_raw(const SummedAreaTable& t, int x, int y, int c) {
  if (x < 0 || y < 0) return T(0);
  T v;
  std::memcpy(&v, t.data.data() + ((std::size_t(y) * t.width + x) * t.channels + c) * sizeof(T), sizeof(T));
  return v;
}

template <typename T>
double integer_box(const SummedAreaTable& t, int x0, int y0, int x1, int y1, int c) {
  // Unsigned arithmetic wraps: the four-term difference is exact modulo 2^bits.
  const T s = T(entry_raw<T>(t, x1 - 1, y1 - 1, c) - entry_raw<T>(t, x0 - 1, y1 - 1, c) -
                entry_raw<T>(t, x1 - 1, y0 - 1, c) + entry_raw<T>(t, x0 - 1, y0 - 1, c));
  return double(s);
}

double ulp_of(double m, int mantissa_bits) {
  if (m <= 0.0) return 0.0;
  int e;
  std::frexp(m, &e);  // m = f * 2^e, f in [0.5, 1)
  return std::ldexp(1.0, e - mantissa_bits);
}

}  // namespace

void SummedAreaTable::box_sum(int x0, int y0, int x1, int y1, double* out) const {
  assert(0 <= x0 && x0 <= x1 && x1 <= width && 0 <= y0 && y0 <= y1 && y1 <= height);
  for (int c = 0; c < channels; ++c) {
    if (x0 == x1 || y0 == y1) {
      out[c] = 0.0;
      continue;
    }
    switch (precision) {
      case SatPrecision::u32: out[c] = integer_box<std::uint32_t>(*this, x0, y0, x1, y1, c); break;
      case SatPrecision::u64: out[c] = integer_box<std::uint64_t>(*this, x0, y0, x1, y1, c); break;
      case SatPrecision::f32: {
        const double r = entry<float>(*this, x1 - 1, y1 - 1, c) - entry<float>(*this, x0 - 1, y1 - 1, c) -
                         entry<float>(*this, x1 - 1, y0 - 1, c) + entry<float>(*this, x0 - 1, y0 - 1, c);
        const double m = model(x1 - 1, y1 - 1, c) - model(x0 - 1, y1 - 1, c) - model(x1 - 1, y0 - 1, c) +
                         model(x0 - 1, y0 - 1, c);
        out[c] = r + m;
        break;
      }
      case SatPrecision::f64:
        out[c] = entry<double>(*this, x1 - 1, y1 - 1, c) - entry<double>(*this, x0 - 1, y1 - 1, c) -
                 entry<double>(*this, x1 - 1, y0 - 1, c) + entry<double>(*this, x0 - 1, y0 - 1, c);
        break;
    }
  }
}

double SummedAreaTable::error_bound() const {
  switch (precision) {
    case SatPrecision::u32:
    case SatPrecision::u64: return 0.0;
    case SatPrecision::f32: return 4.0 * ulp_of(max_abs_entry, 24) / 2.0 + 8.0 * ulp_of(max_abs_model, 53);
    case SatPrecision::f64:
      // Integer input: every entry is an integer below 2^53, held exactly.
      if (source != PixelType::f32 && max_abs_entry < 9007199254740992.0) return 0.0;
      return 4.0 * ulp_of(max_abs_entry, 53) / 2.0;
  }
  return 0.0;
}

void SummedAreaTable::prepare_model() {
  full_.clear();
  col_.clear();
  row_.clear();
  if (block == 0) return;
  const int B = block, BW = (width + B - 1) / B, BH = (height + B - 1) / B, C = channels;
  const std::size_t stride = std::size_t(BW + 1) * C;
  full_.assign(std::size_t(BH + 1) * stride, 0.0);
  col_ = full_;
  row_ = full_;
  auto m = [&](int bx, int by, int c) { return block_means[(std::size_t(by) * BW + bx) * C + c]; };
  // Only whole B x B blocks enter full_ (index < floor(X / B)), so m * B * B
  // is their exact integer sum: B * B is a power of two.
  for (int by = 0; by <= BH; ++by)
    for (int bx = 0; bx <= BW; ++bx)
      for (int c = 0; c < C; ++c) {
        const std::size_t i = std::size_t(by) * stride + std::size_t(bx) * C + c;
        if (bx > 0 && by > 0) {
          full_[i] = full_[i - C] + full_[i - stride] - full_[i - stride - C] + m(bx - 1, by - 1, c) * B * B;
        }
        if (by > 0 && bx < BW) col_[i] = col_[i - stride] + m(bx, by - 1, c) * B;
        if (bx > 0 && by < BH) row_[i] = row_[i - C] + m(bx - 1, by, c) * B;
      }
}

double SummedAreaTable::model(int x, int y, int c) const {
  if (block == 0 || x < 0 || y < 0) return 0.0;
  const int B = block, BW = (width + B - 1) / B, C = channels;
  const int X = x + 1, Y = y + 1, fx = X / B, rx = X % B, fy = Y / B, ry = Y % B;
  const std::size_t i = (std::size_t(fy) * (BW + 1) + fx) * C + c;
  double v = full_[i] + rx * col_[i] + ry * row_[i];
  if (rx && ry) v += double(rx) * ry * block_means[(std::size_t(fy) * BW + fx) * C + c];
  return v;
}

namespace {

constexpr int kStripRows = 64;

template <typename In>
const In* in_row(const ImageView& img, int y) {
  return img.row<const In>(y);
}

// The strip pipeline for one accumulator type. `Emit` turns the exact row of
// sums (Acc) of row y into output entries.
template <typename In, typename Acc, typename Emit>
void run_strips(const ImageView& img, Emit emit) {
  const int W = img.width, H = img.height, C = img.channels;
  const std::size_t n = std::size_t(W) * C;
  const int strips = (H + kStripRows - 1) / kStripRows;

  // Pass 1: column totals of every strip.
  std::vector<std::vector<Acc>> totals(strips);
  for_each_row_block(strips, 1, [&](int s0, int s1) {
    for (int s = s0; s < s1; ++s) {
      std::vector<Acc>& t = totals[s];
      t.assign(n, Acc(0));
      for (int y = s * kStripRows; y < std::min(H, (s + 1) * kStripRows); ++y) {
        const In* r = in_row<In>(img, y);
        for (std::size_t i = 0; i < n; ++i) t[i] += Acc(r[i]);
      }
    }
  });
  // The column sums above each strip, in strip order (fixed: deterministic).
  std::vector<std::vector<Acc>> above(strips);
  above[0].assign(n, Acc(0));
  for (int s = 1; s < strips; ++s) {
    above[s] = above[s - 1];
    for (std::size_t i = 0; i < n; ++i) above[s][i] += totals[s - 1][i];
  }
  // Pass 2: running column sums down each strip; each table row is the
  // prefix over x of them.
  for_each_row_block(strips, 1, [&](int s0, int s1) {
    std::vector<Acc> col, row(n);
    for (int s = s0; s < s1; ++s) {
      col = above[s];
      for (int y = s * kStripRows; y < std::min(H, (s + 1) * kStripRows); ++y) {
        const In* r = in_row<In>(img, y);
        Acc run[4] = {Acc(0), Acc(0), Acc(0), Acc(0)};
        for (int x = 0; x < W; ++x) {
          for (int c = 0; c < C; ++c) {
            const std::size_t i = std::size_t(x) * C + c;
            col[i] += Acc(r[i]);
            run[c] += col[i];
            row[i] = run[c];
          }
        }
        emit(y, row.data());
      }
    }
  });
}

// Integer tables: the exact row, wrapped to the element type.
template <typename In, typename Out>
void build_integer(const ImageView& img, SummedAreaTable& t) {
  const std::size_t n = std::size_t(img.width) * img.channels;
  run_strips<In, Out>(img, [&](int y, const Out* row) {
    std::memcpy(t.data.data() + std::size_t(y) * n * sizeof(Out), row, n * sizeof(Out));
  });
}

// Float tables: S exact in Acc (int64 for integer input, double for float),
// minus the block-mean model M, rounded once to Out. Tracks the largest |entry|
// per strip of rows, combined after (max is order-free).
template <typename In, typename Acc, typename Out>
void build_float(const ImageView& img, SummedAreaTable& t) {
  const int W = img.width, C = img.channels;
  const std::size_t n = std::size_t(W) * C;
  std::vector<double> row_max(img.height, 0.0), model_max(img.height, 0.0);
  run_strips<In, Acc>(img, [&](int y, const Acc* row) {
    Out* out = reinterpret_cast<Out*>(t.data.data()) + std::size_t(y) * n;
    double m = 0.0, mm = 0.0;
    for (int x = 0; x < W; ++x) {
      for (int c = 0; c < C; ++c) {
        const double model = t.model(x, y, c);
        const Out v = Out(double(row[std::size_t(x) * C + c]) - model);
        out[std::size_t(x) * C + c] = v;
        m = std::max(m, std::abs(double(v)));
        mm = std::max(mm, std::abs(model));
      }
    }
    row_max[y] = m;
    model_max[y] = mm;
  });
  t.max_abs_entry = *std::max_element(row_max.begin(), row_max.end());
  t.max_abs_model = *std::max_element(model_max.begin(), model_max.end());
}

// Block means: exact sums (int64 for integer input, double in row order for
// float input) divided by the block's texel count.
template <typename In>
std::vector<double> block_means(const ImageView& img, int B) {
  const int C = img.channels, BW = (img.width + B - 1) / B, BH = (img.height + B - 1) / B;
  std::vector<double> means(std::size_t(BW) * BH * C, 0.0);
  for_each_row_block(BH, 1, [&](int b0, int b1) {
    for (int by = b0; by < b1; ++by) {
      const int y0 = by * B, y1 = std::min(img.height, y0 + B);
      for (int bx = 0; bx < BW; ++bx) {
        const int x0 = bx * B, x1 = std::min(img.width, x0 + B);
        for (int c = 0; c < C; ++c) {
          double sum = 0.0;  // exact: at most 256 values below 2^16 (or floats, in a fixed order)
          for (int y = y0; y < y1; ++y) {
            const In* r = img.row<const In>(y);
            for (int x = x0; x < x1; ++x) sum += double(r[x * C + c]);
          }
          means[(std::size_t(by) * BW + bx) * C + c] = sum / (double(x1 - x0) * (y1 - y0));
        }
      }
    }
  });
  return means;
}

template <typename In>
void build_typed(const ImageView& img, SummedAreaTable& t) {
  constexpr bool kInt = !std::is_same_v<In, float>;
  using Exact = std::conditional_t<kInt, std::int64_t, double>;
  switch (t.precision) {
    case SatPrecision::u32:
      if constexpr (kInt) build_integer<In, std::uint32_t>(img, t);
      break;
    case SatPrecision::u64:
      if constexpr (kInt) build_integer<In, std::uint64_t>(img, t);
      break;
    case SatPrecision::f32:
      t.block = SummedAreaTable::kBlock;
      t.block_means = block_means<In>(img, t.block);
      t.prepare_model();
      build_float<In, Exact, float>(img, t);
      break;
    case SatPrecision::f64: build_float<In, Exact, double>(img, t); break;
  }
}

}  // namespace

SummedAreaTable build_sat(const ImageView& img, SatPrecision p) {
  assert(img.data && img.width > 0 && img.height > 0 && img.channels >= 1 && img.channels <= 4);
  if (img.type == PixelType::f32 && (p == SatPrecision::u32 || p == SatPrecision::u64)) {
    throw Error(ErrorCode::bad_arguments, std::string("--precision ") + to_string(p) +
                                              " needs 8- or 16-bit integer input; this image is float (valid: f32, f64)");
  }
  SummedAreaTable t;
  t.width = img.width;
  t.height = img.height;
  t.channels = img.channels;
  t.precision = p;
  t.source = img.type;
  t.data.resize(std::size_t(img.width) * img.height * img.channels * t.element_bytes());
  switch (img.type) {
    case PixelType::u8: build_typed<std::uint8_t>(img, t); break;
    case PixelType::u16: build_typed<std::uint16_t>(img, t); break;
    case PixelType::f32: build_typed<float>(img, t); break;
  }
  return t;
}

}  // namespace texproc
