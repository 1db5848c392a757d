// BC7 and BC6H block decoding, to the OpenGL extension
// ARB_texture_compression_bptc (the Khronos Data Format Specification's
// BPTC chapter says the same): the bit layout, partitions, anchors, p-bits,
// rotations and index selection of BC7; the fourteen modes, transformed
// endpoints, unquantization and final scaling of BC6H. Depends on nothing
// under the encoders.
#include <Imath/half.h>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include <cstring>
#include <utility>

#include "bc/bc_decode.h"
#include "bc/bc6h_shared.h"
#include "bc/bptc_tables.h"

namespace texproc::bc {
namespace {

__extension__ typedef unsigned __int128 u128;  // GCC's and Clang's 128-bit integer

// The block's 128 bits, read from the lowest up (one 128-bit shift a read).
class BitReader {
 public:
  explicit BitReader(const std::uint8_t* block) {
    std::uint64_t lo, hi;
    std::memcpy(&lo, block, 8);  // little-endian hosts (as the rest of texproc)
    std::memcpy(&hi, block + 8, 8);
    bits_ = u128(hi) << 64 | lo;
  }
  std::uint32_t read(int n) {  // n <= 32
    const std::uint32_t v = std::uint32_t(bits_ >> pos_) & std::uint32_t((std::uint64_t(1) << n) - 1);
    pos_ += n;
    return v;
  }
  std::uint64_t peek64() const { return std::uint64_t(bits_ >> pos_); }  // the next 64 bits (0 past the end)
  void skip(int n) { pos_ += n; }

 private:
  u128 bits_;
  int pos_ = 0;
};

// The anchor texels of a partition (subset 0's is texel 0).
void anchors(int subsets, int partition, int anchor[3]) {
  anchor[0] = 0;
  anchor[1] = subsets == 2 ? bptc::kAnchor2[partition] : subsets == 3 ? bptc::kAnchor3a[partition] : -1;
  anchor[2] = subsets == 3 ? bptc::kAnchor3b[partition] : -1;
}

// 16 indices of `bits` bits, one bit less at each anchor texel.
void read_indices(BitReader& r, int bits, const int anchor[3], int subsets, int out[16]) {
  unsigned anchors = 0;
  for (int s = 0; s < subsets; ++s) anchors |= 1u << anchor[s];
  // Every index stream fits in 64 bits (at most 16 * 4 - 1): one read, then shifts.
  std::uint64_t v = r.peek64();
  int used = 0;
  for (int i = 0; i < 16; ++i) {
    const int n = bits - int(anchors >> i & 1);
    out[i] = int(v & ((std::uint64_t(1) << n) - 1));
    v >>= n;
    used += n;
  }
  r.skip(used);
}

}  // namespace

namespace {

// A BC7 block's texels as RGBA8 words (R in the low byte), row by row.
void bc7_words(const std::uint8_t* block, std::uint32_t out[16]) {
  const int mode = block[0] == 0 ? 8 : __builtin_ctz(block[0]);
  if (mode == 8) {  // reserved: every texel 0 (as Direct3D decodes it)
    std::memset(out, 0, 64);
    return;
  }
  const bptc::Bc7Mode& M = bptc::kBc7Modes[mode];
  BitReader r(block);
  r.read(mode + 1);
  const int partition = int(r.read(M.partition_bits));
  const int rotation = int(r.read(M.rotation_bits));
  const int index_selection = int(r.read(M.index_selection_bits));
  const int ns = M.subsets;
  int e[3][2][4];  // subset, endpoint, channel
  for (int c = 0; c < 3; ++c)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) e[s][k][c] = int(r.read(M.color_bits));
  for (int s = 0; s < ns; ++s)
    for (int k = 0; k < 2; ++k) e[s][k][3] = M.alpha_bits ? int(r.read(M.alpha_bits)) : 255;
  int pbit[3][2] = {};
  if (M.endpoint_pbits) {
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) pbit[s][k] = int(r.read(1));
  } else if (M.shared_pbits) {
    for (int s = 0; s < ns; ++s) pbit[s][0] = pbit[s][1] = int(r.read(1));
  }
  const int has_p = M.endpoint_pbits || M.shared_pbits ? 1 : 0;
  // Endpoints to 8 bits: the p-bit below the stored bits, the top bits
  // replicated into the rest.
  for (int s = 0; s < ns; ++s)
    for (int k = 0; k < 2; ++k)
      for (int c = 0; c < 4; ++c) {
        const int stored = c < 3 ? M.color_bits : M.alpha_bits;
        if (stored == 0) continue;  // alpha 255
        const int n = stored + has_p;
        const int v = e[s][k][c] << has_p | pbit[s][k];
        e[s][k][c] = (v << (8 - n) | v >> (2 * n - 8)) & 255;
      }
  int anchor[3];
  anchors(ns, partition, anchor);
  int primary[16], secondary[16];
  read_indices(r, M.index_bits, anchor, ns, primary);
  if (M.index2_bits) read_indices(r, M.index2_bits, anchor, 1, secondary);
  const std::uint32_t part = ns == 2 ? bptc::kPartitions2[partition] : ns == 3 ? bptc::kPartitions3[partition] : 0;
  // Colour from the secondary indices where the index selection bit is set,
  // alpha from the secondary ones where there are any and it is not. The
  // palettes once (as words; a rotation's channel swap folded into them),
  // then a lookup a texel.
  const bool swap = index_selection != 0;
  const int color_bits = swap ? M.index2_bits : M.index_bits;
  const std::uint8_t* wc = bptc::weights(color_bits);
  if (!M.index2_bits) {
    std::uint32_t pal[3][16];
    for (int s = 0; s < ns; ++s)
      for (int j = 0; j < 1 << color_bits; ++j) {
        std::uint32_t w = 0;
        for (int c = 0; c < 4; ++c) w |= std::uint32_t(bptc::interpolate(e[s][0][c], e[s][1][c], wc[j])) << (8 * c);
        pal[s][j] = w;
      }
    for (int i = 0; i < 16; ++i) out[i] = pal[ns == 1 ? 0 : bptc::subset(part, i)][primary[i]];
    return;
  }
  const int alpha_bits = swap ? M.index_bits : M.index2_bits;
  const std::uint8_t* wa = bptc::weights(alpha_bits);
  // The interpolated alpha goes to channel `ra`, channel `ra` of the colour to alpha.
  const int ra = rotation ? rotation - 1 : 3;
  std::uint32_t cpal[8], apal[8];
  for (int j = 0; j < 1 << color_bits; ++j) {
    int px[4];
    for (int c = 0; c < 3; ++c) px[c] = bptc::interpolate(e[0][0][c], e[0][1][c], wc[j]);
    px[3] = 0;
    std::swap(px[3], px[ra]);  // ra == 3: nothing moves
    cpal[j] =
        std::uint32_t(px[0]) | std::uint32_t(px[1]) << 8 | std::uint32_t(px[2]) << 16 | std::uint32_t(px[3]) << 24;
  }
  for (int j = 0; j < 1 << alpha_bits; ++j)
    apal[j] = std::uint32_t(bptc::interpolate(e[0][0][3], e[0][1][3], wa[j])) << (8 * ra);
  for (int i = 0; i < 16; ++i) out[i] = cpal[swap ? secondary[i] : primary[i]] | apal[swap ? primary[i] : secondary[i]];
}

}  // namespace

void decode_bc7(const std::uint8_t* block, std::uint8_t out[16][4]) {
  std::uint32_t w[16];
  bc7_words(block, w);
  std::memcpy(out, w, 64);
}

void decode_bc7_run(const std::uint8_t* blocks, int count, std::uint8_t* dst, std::size_t stride) {
  for (int k = 0; k < count; ++k) {
    std::uint32_t t[16];
    bc7_words(blocks + std::size_t(k) * 16, t);
    for (int r = 0; r < 4; ++r) {
      const std::uint32_t* q = t + 4 * r;
      // Whole words built in registers and stored once (see bc_decode.cpp's rows).
      const std::uint64_t lo = q[0] | std::uint64_t(q[1]) << 32, hi = q[2] | std::uint64_t(q[3]) << 32;
      std::uint8_t* row = dst + std::size_t(k) * 16 + r * stride;
      std::memcpy(row, &lo, 8);
      std::memcpy(row + 8, &hi, 8);
    }
  }
}

namespace {
// A BC6H block as each subset's unquantized endpoints, the partition's
// subset mask and each texel's index; false for a reserved mode.
struct Bc6hTexels {
  int e[4][3];  // endpoint (subset 0: 0, 1; subset 1: 2, 3), channel
  int index_bits;
  std::uint32_t part;  // the two-subset partition's mask (0: one subset)
  int idx[16];
};

inline __attribute__((always_inline)) bool bc6h_texels(const std::uint8_t* block, bool is_signed, Bc6hTexels& t) {
  const int low2 = block[0] & 3;
  const int number = low2 < 2 ? low2 : block[0] & 31;
  const bc6h::Layouts& L = bc6h::layouts();
  const int k = L.by_number[number];
  if (k < 0) return false;
  const bptc::Bc6hMode& M = bptc::kBc6hModes[k];
  BitReader r(block);
  int v[13] = {};
  for (int f = 0; f < L.modes[k].n; ++f) {
    const bc6h::Field& fd = L.modes[k].fields[f];
    if (fd.step == 1) {  // the bits in order: one read
      v[fd.var] |= int(r.read(fd.count)) << fd.first;
    } else {  // reversed (modes 12 and 15's top bits): bit by bit
      for (int b = 0; b < fd.count; ++b) v[fd.var] |= int(r.read(1)) << (fd.first - b);
    }
  }
  const int ns = M.partition_bits ? 2 : 1;
  const int partition = int(r.read(M.partition_bits));
  const int nend = 2 * ns;
  int(&e)[4][3] = t.e;
  for (int c = 0; c < 3; ++c)
    for (int j = 0; j < nend; ++j) e[j][c] = v[1 + 4 * c + j];
  const int eb = M.endpoint_bits;
  for (int c = 0; c < 3; ++c) {
    if (is_signed) e[0][c] = bc6h::sign_extend(e[0][c], eb);
    for (int j = 1; j < nend; ++j) {
      if (M.transformed) {
        e[j][c] = bc6h::sign_extend(e[j][c], M.delta_bits[c]);
        e[j][c] = (e[0][c] + e[j][c]) & ((1 << eb) - 1);
        if (is_signed) e[j][c] = bc6h::sign_extend(e[j][c], eb);
      } else if (is_signed) {
        e[j][c] = bc6h::sign_extend(e[j][c], eb);
      }
    }
    for (int j = 0; j < nend; ++j) e[j][c] = bc6h::unquantize(e[j][c], eb, is_signed);
  }
  int anchor[3];
  anchors(ns, partition, anchor);
  t.index_bits = ns == 2 ? 3 : 4;
  read_indices(r, t.index_bits, anchor, ns, t.idx);
  t.part = ns == 2 ? bptc::kPartitions2[partition] : 0;
  return true;
}

// Subset s's palette as half bits (the specification's arithmetic).
void bc6h_palette(const Bc6hTexels& t, int s, bool is_signed, std::uint16_t pal[16][3]) {
  const std::uint8_t* w = bptc::weights(t.index_bits);
  for (int j = 0; j < 1 << t.index_bits; ++j)
    for (int c = 0; c < 3; ++c)
      pal[j][c] = bc6h::finish_bits(bptc::interpolate(t.e[2 * s][c], t.e[2 * s + 1][c], w[j]), is_signed);
}

#if defined(__SSE2__)
// The index weights as 16-bit pairs (64 - w, w), one a 32-bit lane.
struct WeightPairs {
  alignas(16) std::int32_t v3[8][4], v4[16][4];
  WeightPairs() {
    for (int j = 0; j < 16; ++j) {
      const int w4 = bptc::weights(4)[j];
      for (int c = 0; c < 4; ++c) v4[j][c] = (64 - w4) | w4 << 16;
      if (j < 8) {
        const int w3 = bptc::weights(3)[j];
        for (int c = 0; c < 4; ++c) v3[j][c] = (64 - w3) | w3 << 16;
      }
    }
  }
};
const WeightPairs& weight_pairs() {
  static const WeightPairs w;
  return w;
}

// Subset s's palette as floats (RGB, 0), an entry a vector: the same
// interpolation, final scaling and half-to-float conversion as
// bc6h_palette's halves through Imath::half, in 32-bit lanes. The pairs
// (e0, e1) times (64 - w, w) is one multiply-add of 16-bit lanes (UF16's
// endpoints offset by -32768 into 16 bits; the weights sum to 64, so
// 64 * 32768 comes back). A half's float: its magnitude bits 13 up times
// 2^112 (exact for every finite half, subnormals included), its sign bit 16
// up.
void bc6h_palette_f32(const Bc6hTexels& t, int s, bool is_signed, float pal[16][4]) {
  const int* e0 = t.e[2 * s];
  const int* e1 = t.e[2 * s + 1];
  const int off = is_signed ? 0 : 32768;
  auto pair = [&](int c) {
    return std::int32_t(std::uint16_t(e0[c] - off) | std::uint32_t(std::uint16_t(e1[c] - off)) << 16);
  };
  const __m128i ends = _mm_setr_epi32(pair(0), pair(1), pair(2), 0);
  const __m128i round = _mm_set1_epi32(is_signed ? 32 : 64 * 32768 + 32);
  const __m128 scale = _mm_castsi128_ps(_mm_set1_epi32((127 + 112) << 23));
  const WeightPairs& W = weight_pairs();
  const std::int32_t(*wp)[4] = t.index_bits == 3 ? W.v3 : W.v4;
  const __m128i lane3 = _mm_setr_epi32(-1, -1, -1, 0);
  for (int j = 0; j < 1 << t.index_bits; ++j) {
    const __m128i wj = _mm_load_si128(reinterpret_cast<const __m128i*>(wp[j]));
    const __m128i v = _mm_srai_epi32(_mm_add_epi32(_mm_madd_epi16(ends, wj), round), 6);
    __m128i mag, extra;
    if (!is_signed) {  // (v * 31) >> 6, at most 0x7BFF
      mag = _mm_srli_epi32(_mm_sub_epi32(_mm_slli_epi32(v, 5), v), 6);
      extra = _mm_setzero_si128();
    } else {  // |v| * 31 >> 5, the sign apart
      const __m128i m = _mm_srai_epi32(v, 31);
      const __m128i a = _mm_sub_epi32(_mm_xor_si128(v, m), m);
      mag = _mm_srli_epi32(_mm_sub_epi32(_mm_slli_epi32(a, 5), a), 5);
      // The sign; and the one magnitude past the finite halves, 0x7C00 (mode
      // 14's endpoint -32768), an infinity: its product 65536 ORed with the
      // exponent's bits.
      extra = _mm_or_si128(_mm_slli_epi32(m, 31),
                           _mm_and_si128(_mm_cmpeq_epi32(mag, _mm_set1_epi32(0x7C00)), _mm_set1_epi32(0x7F800000)));
    }
    const __m128 f = _mm_mul_ps(_mm_castsi128_ps(_mm_slli_epi32(mag, 13)), scale);
    const __m128i sign = extra;
    _mm_storeu_ps(pal[j], _mm_and_ps(_mm_or_ps(f, _mm_castsi128_ps(sign)), _mm_castsi128_ps(lane3)));
  }
}
#endif
}  // namespace

void decode_bc6h(const std::uint8_t* block, bool is_signed, std::uint16_t out[16][3]) {
  Bc6hTexels t;
  if (!bc6h_texels(block, is_signed, t)) {  // reserved: (0, 0, 0)
    std::memset(out, 0, 96);
    return;
  }
  // Each subset's palette once (8 or 16 entries), then a lookup a texel.
  std::uint16_t pal[2][16][3];
  bc6h_palette(t, 0, is_signed, pal[0]);
  if (t.part) bc6h_palette(t, 1, is_signed, pal[1]);
  for (int i = 0; i < 16; ++i) std::memcpy(out[i], pal[bptc::subset(t.part, i)][t.idx[i]], 6);
}

void decode_bc6h_f32_rows(const std::uint8_t* block, bool is_signed, float* dst, std::size_t stride) {
  Bc6hTexels t;
  if (!bc6h_texels(block, is_signed, t)) {
    for (int r = 0; r < 4; ++r) std::memset(dst + r * stride, 0, 48);
    return;
  }
  // Each palette entry as floats once, a fourth lane so that a texel is one
  // 16-byte row of the table.
  float pf[2][16][4];
  const int ns = t.part ? 2 : 1;
  for (int s = 0; s < ns; ++s) {
#if defined(__SSE2__)
    bc6h_palette_f32(t, s, is_signed, pf[s]);
#else
    std::uint16_t pal[16][3];
    bc6h_palette(t, s, is_signed, pal);
    for (int j = 0; j < 1 << t.index_bits; ++j) {
      for (int c = 0; c < 3; ++c) {
        Imath::half h;
        h.setBits(pal[j][c]);
        pf[s][j][c] = float(h);
      }
      pf[s][j][3] = 0.0f;
    }
#endif
  }
  for (int r = 0; r < 4; ++r) {
    float* row = dst + r * stride;
    for (int x = 0; x < 4; ++x) {
      const int i = 4 * r + x;
      std::memcpy(row + 3 * x, pf[bptc::subset(t.part, i)][t.idx[i]], 12);
    }
  }
}

}  // namespace texproc::bc
