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
#include "core/pixel_memory.h"
#include "texproc/sat.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstring>
#include <limits>

#include "sat/sat_rows.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc {

namespace ref {
template <typename In>
void sat_row_rgba_u32(const In* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  std::uint32_t run[4] = {0, 0, 0, 0};
  for (int x = 0; x < width; ++x)
    for (int c = 0; c < 4; ++c) {
      run[c] += in[4 * x + c];
      cur[4 * x + c] = prev[4 * x + c] + run[c];
    }
}
void sat_row_rgba8_u32(const std::uint8_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  sat_row_rgba_u32(in, width, prev, cur);
}
void sat_row_rgba16_u32(const std::uint16_t* in, int width, const std::uint32_t* prev, std::uint32_t* cur) {
  sat_row_rgba_u32(in, width, prev, cur);
}
}  // namespace ref

const char* to_string(SatPrecision p) {
  switch (p) {
    case SatPrecision::u32:
      return "u32";
    case SatPrecision::u64:
      return "u64";
    case SatPrecision::f32:
      return "f32";
    case SatPrecision::f64:
      return "f64";
  }
  return "?";
}

SatPrecision parse_sat_precision(std::string_view n) {
  if (n == "u32") return SatPrecision::u32;
  if (n == "u64") return SatPrecision::u64;
  if (n == "f32") return SatPrecision::f32;
  if (n == "f64") return SatPrecision::f64;
  throw Error(ErrorCode::bad_arguments, "unknown SatPrecision '" + std::string(n) + "' (valid: u32, u64, f32, f64)");
}

namespace {
std::uint64_t max_code(PixelType t) { return t == PixelType::u8 ? 255 : 65535; }
}  // namespace

std::uint64_t sat_max_exact_box(SatPrecision p, PixelType input) {
  if (input == PixelType::f32) return 0;
  const std::uint64_t m = max_code(input);
  switch (p) {
    case SatPrecision::u32:
      return 0xFFFFFFFFull / m;
    case SatPrecision::u64:
      return std::numeric_limits<std::uint64_t>::max() / m;
    case SatPrecision::f64:
      return (std::uint64_t(1) << 53) / m;
    case SatPrecision::f32:
      return 0;
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
      case SatPrecision::u32:
        out[c] = integer_box<std::uint32_t>(*this, x0, y0, x1, y1, c);
        break;
      case SatPrecision::u64:
        out[c] = integer_box<std::uint64_t>(*this, x0, y0, x1, y1, c);
        break;
      case SatPrecision::f32: {
        const double r = entry<float>(*this, x1 - 1, y1 - 1, c) - entry<float>(*this, x0 - 1, y1 - 1, c) -
                         entry<float>(*this, x1 - 1, y0 - 1, c) + entry<float>(*this, x0 - 1, y0 - 1, c);
        const double m =
            model(x1 - 1, y1 - 1, c) - model(x0 - 1, y1 - 1, c) - model(x1 - 1, y0 - 1, c) + model(x0 - 1, y0 - 1, c);
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
    case SatPrecision::u64:
      return 0.0;
    case SatPrecision::f32:
      return 4.0 * ulp_of(max_abs_entry, 24) / 2.0 + 8.0 * ulp_of(max_abs_model, 53);
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

void SummedAreaTable::model_row(int y, double* out) const {
  const int C = channels;
  if (block == 0) {
    std::fill(out, out + std::size_t(width) * C, 0.0);
    return;
  }
  constexpr int B = kBlock;  // a power of two: the divisions below are shifts
  assert(block == kBlock);
  const int BW = (width + B - 1) / B;
  const int Y = y + 1, fy = Y / B, ry = Y % B;
  const double* full = full_.data() + std::size_t(fy) * (BW + 1) * C;
  const double* col = col_.data() + std::size_t(fy) * (BW + 1) * C;
  const double* row = row_.data() + std::size_t(fy) * (BW + 1) * C;
  const double* means = block_means.data() + std::size_t(fy) * BW * C;
  for (int x = 0; x < width; ++x) {
    const int X = x + 1, fx = X / B, rx = X % B;
    const std::size_t i = std::size_t(fx) * C;
    for (int c = 0; c < C; ++c) {
      double v = full[i + c] + rx * col[i + c] + ry * row[i + c];
      if (rx && ry) v += double(rx) * ry * means[i + c];
      out[std::size_t(x) * C + c] = v;
    }
  }
}

namespace {

constexpr int kStripRows = 64;

// One table row from the row above: cur[i] = prev[i] + (prefix over x of
// this input row), per channel. C is a template argument so that the
// channel loop unrolls and the four running sums of RGBA vectorize.
template <int C, typename In, typename Acc>
void table_row(const In* in, int width, const Acc* prev, Acc* cur) {
  Acc run[C];
  for (int c = 0; c < C; ++c) run[c] = Acc(0);
  for (int x = 0; x < width; ++x) {
    for (int c = 0; c < C; ++c) {
      run[c] += Acc(in[x * C + c]);
      cur[x * C + c] = prev[x * C + c] + run[c];
    }
  }
}

template <typename In, typename Acc>
void table_row_any(int channels, const In* in, int width, const Acc* prev, Acc* cur) {
  if constexpr (std::is_same_v<Acc, std::uint32_t> && std::is_same_v<In, std::uint8_t>) {
    if (channels == 4) return sat_row_rgba8_u32(in, width, prev, cur);
  }
  if constexpr (std::is_same_v<Acc, std::uint32_t> && std::is_same_v<In, std::uint16_t>) {
    if (channels == 4) return sat_row_rgba16_u32(in, width, prev, cur);
  }
  switch (channels) {
    case 1:
      return table_row<1>(in, width, prev, cur);
    case 2:
      return table_row<2>(in, width, prev, cur);
    case 3:
      return table_row<3>(in, width, prev, cur);
    default:
      return table_row<4>(in, width, prev, cur);
  }
}

// The strip pipeline for one accumulator type. Pass 1 sums each strip's
// columns; a serial step turns them into the table row just above each strip;
// pass 2 walks each strip's rows. `row_buffer(y)` says where row y of exact
// sums (Acc) goes: straight into the table when Acc is the element type,
// else into scratch that `emit(y, row)` then converts.
template <typename In, typename Acc, typename RowBuffer, typename Emit>
void run_strips(const ConstImageView& img, RowBuffer row_buffer, Emit emit) {
  const int W = img.width, H = img.height, C = img.channels;
  const std::size_t n = std::size_t(W) * C;
  const int strips = (H + kStripRows - 1) / kStripRows;

  // totals of strip s at [s * n, (s + 1) * n), then the table row above
  // strip s at [(strips + s) * n, ...): one block from the pixel allocator,
  // which keeps large blocks for reuse (no fresh pages on every build).
  std::vector<Acc, detail::DefaultInitAllocator<Acc>> work(2 * std::size_t(strips) * n);
  Acc* totals = work.data();
  Acc* above = work.data() + std::size_t(strips) * n;
  for_each_row_block(strips, 1, [&](int s0, int s1) {
    for (int s = s0; s < s1; ++s) {
      Acc* t = totals + std::size_t(s) * n;
      std::fill(t, t + n, Acc(0));
      for (int y = s * kStripRows; y < std::min(H, (s + 1) * kStripRows); ++y) {
        const In* r = img.row<const In>(y);
        for (std::size_t i = 0; i < n; ++i) t[i] += Acc(r[i]);
      }
    }
  });
  // The table row just above strip s: prefix over x of the column sums of
  // every earlier strip, in strip order (deterministic). Strip s - 1's totals
  // become running column sums in place.
  for (int s = 0; s < strips; ++s) {
    Acc* a = above + std::size_t(s) * n;
    if (s == 0) {
      std::fill(a, a + n, Acc(0));
      continue;
    }
    Acc* columns = totals + std::size_t(s - 1) * n;
    if (s > 1) {
      const Acc* earlier = totals + std::size_t(s - 2) * n;
      for (std::size_t i = 0; i < n; ++i) columns[i] += earlier[i];
    }
    for (int c = 0; c < C; ++c) {
      Acc run(0);
      for (int x = 0; x < W; ++x) {
        run += columns[std::size_t(x) * C + c];
        a[std::size_t(x) * C + c] = run;
      }
    }
  }
  for_each_row_block(strips, 1, [&](int s0, int s1) {
    for (int s = s0; s < s1; ++s) {
      const Acc* prev = above + std::size_t(s) * n;
      for (int y = s * kStripRows; y < std::min(H, (s + 1) * kStripRows); ++y) {
        Acc* cur = row_buffer(y);
        table_row_any(C, img.row<const In>(y), W, prev, cur);
        emit(y, cur);
        prev = cur;
      }
    }
  });
}

// Integer tables: exact modulo 2^bits, written straight into the table.
template <typename In, typename Out>
void build_integer(const ConstImageView& img, SummedAreaTable& t) {
  const std::size_t n = std::size_t(img.width) * img.channels;
  Out* base = reinterpret_cast<Out*>(t.data.data());
  run_strips<In, Out>(
      img, [&](int y) { return base + std::size_t(y) * n; }, [](int, const Out*) {});
}

// Float tables: S exact in Acc (int64 for integer input, double for float),
// minus the block-mean model M, rounded once to Out. Each thread keeps two
// rows of exact sums (this one and the one above). The largest |entry| and
// |M| are kept per row and combined after (max is order-free).
template <typename In, typename Acc, typename Out>
void build_float(const ConstImageView& img, SummedAreaTable& t) {
  const std::size_t n = std::size_t(img.width) * img.channels;
  std::vector<double> row_max(img.height, 0.0), model_max(img.height, 0.0);
  run_strips<In, Acc>(
      img,
      [&](int y) {
        thread_local std::vector<Acc> rows[2];
        std::vector<Acc>& r = rows[y & 1];
        r.resize(n);
        return r.data();
      },
      [&](int y, const Acc* row) {
        Out* out = reinterpret_cast<Out*>(t.data.data()) + std::size_t(y) * n;
        thread_local std::vector<double> model;
        model.resize(n);
        t.model_row(y, model.data());
        double m = 0.0, mm = 0.0;
        for (std::size_t i = 0; i < n; ++i) {
          const Out v = Out(double(row[i]) - model[i]);
          out[i] = v;
          const double av = std::abs(double(v)), am = std::abs(model[i]);
          m = av > m ? av : m;  // the maxpd form: vectorizes
          mm = am > mm ? am : mm;
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
std::vector<double> block_means(const ConstImageView& img, int B) {
  const int C = img.channels, BW = (img.width + B - 1) / B, BH = (img.height + B - 1) / B;
  std::vector<double> means(std::size_t(BW) * BH * C, 0.0);
  for_each_row_block(BH, 1, [&](int b0, int b1) {
    for (int by = b0; by < b1; ++by) {
      const int y0 = by * B, y1 = std::min(img.height, y0 + B);
      for (int bx = 0; bx < BW; ++bx) {
        const int x0 = bx * B, x1 = std::min(img.width, x0 + B);
        // Exact: at most 256 values below 2^16 (or floats, in a fixed order).
        double sum[4] = {0.0, 0.0, 0.0, 0.0};
        for (int y = y0; y < y1; ++y) {
          const In* r = img.row<const In>(y) + std::size_t(x0) * C;
          for (int x = 0; x < x1 - x0; ++x, r += C) {
            sum[0] += double(r[0]);
            if (C > 1) sum[1] += double(r[1]);
            if (C > 2) sum[2] += double(r[2]);
            if (C > 3) sum[3] += double(r[3]);
          }
        }
        for (int c = 0; c < C; ++c) {
          means[(std::size_t(by) * BW + bx) * C + c] = sum[c] / (double(x1 - x0) * (y1 - y0));
        }
      }
    }
  });
  return means;
}

template <typename In, typename PrepareModel>
void build_typed(const ConstImageView& img, SummedAreaTable& t, PrepareModel&& prepare_model) {
  constexpr bool kInt = !std::is_same_v<In, float>;
  // Sums of 8- and 16-bit codes stay integers below 2^53 (65535 * 2^40
  // texels): double holds them exactly, and converts to float faster.
  if constexpr (kInt) {
    if (double(img.width) * img.height * 65535.0 >= 9007199254740992.0) {
      throw Error(ErrorCode::unsupported, "image too large for an exact float table");
    }
  }
  using Exact = double;
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
      prepare_model();
      build_float<In, Exact, float>(img, t);
      break;
    case SatPrecision::f64:
      build_float<In, Exact, double>(img, t);
      break;
  }
}

}  // namespace

SummedAreaTable build_sat(const ConstImageView& img, SatPrecision p) {
  SummedAreaTable t;
  build_sat(img, p, t);
  return t;
}

void build_sat(const ConstImageView& img, SatPrecision p, SummedAreaTable& t) {
  assert(img.data && img.width > 0 && img.height > 0 && img.channels >= 1 && img.channels <= 4);
  if (img.type == PixelType::f32 && (p == SatPrecision::u32 || p == SatPrecision::u64)) {
    throw Error(ErrorCode::bad_arguments,
                std::string("SatPrecision ") + to_string(p) +
                    " needs 8- or 16-bit integer input; this image is float (valid: f32, f64)");
  }
  t.block = 0;
  t.block_means.clear();
  t.max_abs_entry = t.max_abs_model = 0.0;
  t.prepare_model();
  t.width = img.width;
  t.height = img.height;
  t.channels = img.channels;
  t.precision = p;
  t.source = img.type;
  t.data.resize(std::size_t(img.width) * img.height * img.channels * t.element_bytes());
  const auto prepare = [&t] { t.prepare_model(); };
  switch (img.type) {
    case PixelType::u8:
      build_typed<std::uint8_t>(img, t, prepare);
      break;
    case PixelType::u16:
      build_typed<std::uint16_t>(img, t, prepare);
      break;
    case PixelType::f32:
      build_typed<float>(img, t, prepare);
      break;
  }
}

}  // namespace texproc
