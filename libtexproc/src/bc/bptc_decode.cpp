// BC7 and BC6H block decoding, to the OpenGL extension
// ARB_texture_compression_bptc (the Khronos Data Format Specification's
// BPTC chapter says the same): the bit layout, partitions, anchors, p-bits,
// rotations and index selection of BC7; the fourteen modes, transformed
// endpoints, unquantization and final scaling of BC6H. Depends on nothing
// under the encoders.
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
    v >>= n, used += n;
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
    cpal[j] = std::uint32_t(px[0]) | std::uint32_t(px[1]) << 8 | std::uint32_t(px[2]) << 16 | std::uint32_t(px[3]) << 24;
  }
  for (int j = 0; j < 1 << alpha_bits; ++j) apal[j] = std::uint32_t(bptc::interpolate(e[0][0][3], e[0][1][3], wa[j])) << (8 * ra);
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

void decode_bc6h(const std::uint8_t* block, bool is_signed, std::uint16_t out[16][3]) {
  const int low2 = block[0] & 3;
  const int number = low2 < 2 ? low2 : block[0] & 31;
  const bc6h::Layouts& L = bc6h::layouts();
  const int k = L.by_number[number];
  if (k < 0) {  // reserved: (0, 0, 0)
    std::memset(out, 0, 96);
    return;
  }
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
  int e[4][3];  // endpoint (subset 0: 0, 1; subset 1: 2, 3), channel
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
  const int index_bits = ns == 2 ? 3 : 4;
  int idx[16];
  read_indices(r, index_bits, anchor, ns, idx);
  const std::uint8_t* w = bptc::weights(index_bits);
  // Each subset's palette once (8 or 16 entries), then a lookup a texel.
  std::uint16_t pal[2][16][3];
  for (int s = 0; s < ns; ++s)
    for (int j = 0; j < 1 << index_bits; ++j)
      for (int c = 0; c < 3; ++c) pal[s][j][c] = bc6h::finish_bits(bptc::interpolate(e[2 * s][c], e[2 * s + 1][c], w[j]), is_signed);
  const std::uint32_t part = ns == 2 ? bptc::kPartitions2[partition] : 0;
  for (int i = 0; i < 16; ++i) std::memcpy(out[i], pal[bptc::subset(part, i)][idx[i]], 6);
}

}  // namespace texproc::bc
