// The .sat file: a small fixed header, the block means of f32 tables, the table.
//
//   0  8 bytes  magic "TEXPSAT" and version byte 1
//   8  u32      width           (1 .. 1048576)
//  12  u32      height          (1 .. 1048576)
//  16  u32      channels        (1 .. 4)
//  20  u32      element type    0 u32, 1 u64, 2 f32, 3 f64
//  24  u32      source type     0 u8, 1 u16, 2 f32
//  28  u32      header bytes    64
//  32  f64      max |entry|     (f32/f64 tables: for the error bound)
//  40  u64      data bytes      width * height * channels * element size
//  48  u32      block           f32 tables: 16 (the block-mean model), else 0
//  52  u32      reserved, zero
//  56  f64      max |model|     f32 tables: for the error bound, else 0
//  64  f64 x ceil(W/block) x ceil(H/block) x channels: block means (f32 tables only)
//  ..  data                     row-major, channels interleaved, little-endian
// All integers little-endian. The reader checks every field against the file
// size before it reads the data, and rejects trailing bytes.
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/fd_writer.h"
#include "texproc/error.h"
#include "texproc/tools.h"
#include "texproc/sat.h"

namespace texproc {
namespace {

constexpr char kMagic[8] = {'T', 'E', 'X', 'P', 'S', 'A', 'T', 1};
constexpr std::uint32_t kHeaderBytes = 64;
constexpr std::uint32_t kMaxSide = 1u << 20;

template <typename T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // the format is little-endian, as every supported host
  out.append(b, sizeof(T));
}

template <typename T>
T get(const std::string& in, std::size_t at) {
  T v;
  std::memcpy(&v, in.data() + at, sizeof(T));
  return v;
}

[[noreturn]] void bad(const std::string& path, const std::string& what) {
  throw Error(ErrorCode::invalid_file, path + ": not a valid .sat file: " + what);
}

}  // namespace

void write_sat_file(const std::string& path, const SummedAreaTable& t) {
  std::string out;  // the header and the block means; the table goes to the file as it lies
  out.reserve(kHeaderBytes + 8 * t.block_means.size());
  out.append(kMagic, 8);
  put<std::uint32_t>(out, std::uint32_t(t.width));
  put<std::uint32_t>(out, std::uint32_t(t.height));
  put<std::uint32_t>(out, std::uint32_t(t.channels));
  put<std::uint32_t>(out, std::uint32_t(t.precision));
  put<std::uint32_t>(out, std::uint32_t(t.source));
  put<std::uint32_t>(out, kHeaderBytes);
  put<double>(out, t.max_abs_entry);
  put<std::uint64_t>(out, std::uint64_t(t.data.size()));
  put<std::uint32_t>(out, std::uint32_t(t.block));
  put<std::uint32_t>(out, 0);
  put<double>(out, t.max_abs_model);
  for (double m : t.block_means) put<double>(out, m);
  AtomicFile file(path);
  FdWriter writer(file.temp_path(), path);
  writer.write(out.data(), out.size());
  writer.write(t.data.data(), t.data.size());
  writer.close();
  file.commit();
}

SummedAreaTable read_sat_file(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error(ErrorCode::io, path + ": cannot open");
  std::string in((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  if (in.size() < kHeaderBytes) bad(path, "truncated header (" + std::to_string(in.size()) + " bytes)");
  if (std::memcmp(in.data(), kMagic, 7) != 0) bad(path, "wrong magic");
  if (in[7] != kMagic[7]) bad(path, "unsupported version " + std::to_string(int(in[7])));
  SummedAreaTable t;
  const std::uint32_t w = get<std::uint32_t>(in, 8), h = get<std::uint32_t>(in, 12), c = get<std::uint32_t>(in, 16);
  const std::uint32_t elem = get<std::uint32_t>(in, 20), src = get<std::uint32_t>(in, 24);
  if (w < 1 || w > kMaxSide) bad(path, "width " + std::to_string(w) + " (valid: 1 to 1048576)");
  if (h < 1 || h > kMaxSide) bad(path, "height " + std::to_string(h) + " (valid: 1 to 1048576)");
  if (c < 1 || c > 4) bad(path, "channels " + std::to_string(c) + " (valid: 1 to 4)");
  if (elem > 3) bad(path, "element type " + std::to_string(elem) + " (valid: 0 u32, 1 u64, 2 f32, 3 f64)");
  if (src > 2) bad(path, "source type " + std::to_string(src) + " (valid: 0 u8, 1 u16, 2 f32)");
  if (get<std::uint32_t>(in, 28) != kHeaderBytes) bad(path, "header size (valid: 64)");
  if (get<std::uint32_t>(in, 52) != 0) bad(path, "reserved header bytes are not zero");
  t.width = int(w);
  t.height = int(h);
  t.channels = int(c);
  t.precision = SatPrecision(elem);
  t.source = PixelType(src);
  if ((t.precision == SatPrecision::u32 || t.precision == SatPrecision::u64) && t.source == PixelType::f32) {
    bad(path, "an integer table of float input");
  }
  t.max_abs_entry = get<double>(in, 32);
  if (!(t.max_abs_entry >= 0.0) || !std::isfinite(t.max_abs_entry))
    bad(path, "max |entry| is not a finite number >= 0");
  const std::uint64_t data_bytes = get<std::uint64_t>(in, 40);
  // w, h <= 2^20 and c <= 4, element <= 8: the product fits in 64 bits.
  const std::uint64_t want = std::uint64_t(w) * h * c * t.element_bytes();
  if (data_bytes != want)
    bad(path, "data size " + std::to_string(data_bytes) + " (expected " + std::to_string(want) + ")");
  const std::uint32_t block = get<std::uint32_t>(in, 48);
  const std::uint32_t want_block = t.precision == SatPrecision::f32 ? SummedAreaTable::kBlock : 0;
  if (block != want_block)
    bad(path, "block " + std::to_string(block) + " (valid for this type: " + std::to_string(want_block) + ")");
  t.block = int(block);
  t.max_abs_model = get<double>(in, 56);
  if (!(t.max_abs_model >= 0.0) || !std::isfinite(t.max_abs_model))
    bad(path, "max |model| is not a finite number >= 0");
  const std::uint64_t means = block ? std::uint64_t((w + block - 1) / block) * ((h + block - 1) / block) * c : 0;
  const std::uint64_t total = kHeaderBytes + 8 * means + want;
  if (in.size() < total)
    bad(path, "truncated data (" + std::to_string(in.size()) + " of " + std::to_string(total) + " bytes)");
  if (in.size() > total) bad(path, std::to_string(in.size() - total) + " trailing bytes");
  t.block_means.resize(means);
  for (std::uint64_t i = 0; i < means; ++i) {
    t.block_means[i] = get<double>(in, kHeaderBytes + 8 * i);
    if (!std::isfinite(t.block_means[i])) bad(path, "block mean " + std::to_string(i) + " is not finite");
  }
  t.prepare_model();
  t.data.resize(want);
  std::memcpy(t.data.data(), in.data() + kHeaderBytes + 8 * means, want);
  return t;
}

}  // namespace texproc
