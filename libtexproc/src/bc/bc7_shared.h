// What both twins of the BC7 encoder use (bc7_lanes.cpp, the scalar
// reference, and bc7_lanes_simd.cpp): the encoding a search settles on
// (Bc7Choice) and its packing into the block's 128 bits, the endpoint
// quantizers, and the one-colour table.
#pragma once

#include <cstdint>

#include "bc/bptc_tables.h"
#include "core/block_batch.h"

namespace texproc::bc7 {

// One block's encoding, before packing: endpoint codes as stored (the
// p-bit apart), in the block's channel order (after any rotation), and the
// indices of each texel. Packing (pack_block) makes each anchor index's top
// bit 0 by swapping that subset's endpoints and mirroring its indices,
// which decodes to the same texels (the weights are symmetric:
// w[L - j] = 64 - w[j]).
struct Choice {
  int mode = 6, partition = 0, rotation = 0, index_selection = 0;
  int code[3][2][4] = {};  // subset, endpoint, channel
  int pbit[3][2] = {};     // per endpoint; mode 1's shared bit in both
  std::uint8_t color_index[16] = {};
  std::uint8_t alpha_index[16] = {};  // modes 4 and 5 only
};

void pack_block(const Choice& c, std::uint8_t out[16]);

// The SIMD twin's choices for a batch of blocks, a field at a time (lane k
// of each), as its vectors store them; `solid` lanes are one colour, x0.
struct LaneChoices {
  static constexpr int N = kBlockBatch;
  std::int32_t solid[N], x0[4][N], mode[N], partition[N], rotation[N], isel[N];
  std::int32_t code[3][2][4][N], pbit[3][2][N], color_index[16][N], alpha_index[16][N];
};
// Lane j of `to` made lane k of `from`, every field.
inline void copy_lane(const LaneChoices& from, int k, LaneChoices& to, int j) {
  to.solid[j] = from.solid[k];
  to.mode[j] = from.mode[k];
  to.partition[j] = from.partition[k];
  to.rotation[j] = from.rotation[k];
  to.isel[j] = from.isel[k];
  for (int c = 0; c < 4; ++c) to.x0[c][j] = from.x0[c][k];
  for (int s = 0; s < 3; ++s)
    for (int e = 0; e < 2; ++e) {
      to.pbit[s][e][j] = from.pbit[s][e][k];
      for (int c = 0; c < 4; ++c) to.code[s][e][c][j] = from.code[s][e][c][k];
    }
  for (int i = 0; i < 16; ++i) {
    to.color_index[i][j] = from.color_index[i][k];
    to.alpha_index[i][j] = from.alpha_index[i][k];
  }
}
// Lanes 0 to count - 1 packed, lane k into out[k]: block by block
// (pack_lanes, the reference), or a SIMD lane a block (pack_lanes_simd,
// bc7_pack_simd.cpp, the same bytes; the reference under force_scalar).
void pack_lanes(const LaneChoices& t, int count, std::uint8_t out[][16]);
void pack_lanes_simd(const LaneChoices& t, int count, std::uint8_t out[][16]);

// How a set of endpoints is stored: bits a channel, and the p-bit (none,
// one an endpoint, or one shared by a subset's two endpoints).
enum class Pbit { none, unique, shared };
struct EndpointFormat {
  int bits;
  Pbit pbit;
};

// An 8-bit value's nearest stored code for `bits` bits and p-bit p (-1:
// none), and that code's value expanded to 8 bits as the decoder does (the
// p-bit below the code, the top bits replicated); the lower code on a tie.
struct Quantized {
  std::uint8_t code, value;
};
inline constexpr int expand(int code, int bits, int p) {
  const int n = bits + (p >= 0 ? 1 : 0);
  const int v = p >= 0 ? code << 1 | p : code;
  return (v << (8 - n) | v >> (2 * n - 8)) & 255;
}
struct QuantTable {
  Quantized q[256];
};
constexpr QuantTable make_quant_table(int bits, int p) {
  QuantTable t{};
  for (int v = 0; v < 256; ++v) {
    int best = 0, best_d = 1 << 20;
    for (int c = 0; c < (1 << bits); ++c) {
      const int d = expand(c, bits, p) - v;
      if (d * d < best_d) {
        best_d = d * d;
        best = c;
      }
    }
    t.q[v] = {std::uint8_t(best), std::uint8_t(expand(best, bits, p))};
  }
  return t;
}
// Table for (bits, p): kQuant[bits - 4][p + 1], bits 4-8, p -1, 0, 1.
extern const QuantTable kQuant[5][3];
inline const Quantized& quantize(int bits, int p, int v) { return kQuant[bits - 4][p + 1].q[v]; }

// The same for the SIMD twin's gathers, both p-bits in one int32 (one
// gather a value): kQuantPairs[bits - 4][with_p][v] holds p = 0's
// (code | value << 8) in its low 16 bits and p = 1's in its high 16
// (with_p 1), or p = -1's in both halves (with_p 0).
extern const std::int32_t (&kQuantPairs)[5][2][256];

// One colour exactly: mode 5's 7-bit endpoints (e0, e1) whose index-1
// texel (weight 21) decodes to the value, for every 8-bit value (checked
// exhaustively in the tests; alpha's 8-bit endpoints are exact already).
struct SolidPair {
  std::uint8_t e0, e1;
};
const SolidPair& solid5(int v);
// The same pairs as e0 | e1 << 8, 256 of them, for gathers.
const std::int32_t* solid5_packed();
// A block of one RGBA colour: mode 5, the pairs above at index 1, alpha's
// endpoints the alpha itself.
Choice solid_choice(const int rgba[4]);

// The encoder's view of BC7's modes: how each set of endpoints is stored.
inline EndpointFormat color_format(int mode) {
  switch (mode) {
    case 0:
      return {4, Pbit::unique};
    case 1:
      return {6, Pbit::shared};
    case 2:
      return {5, Pbit::none};
    case 3:
      return {7, Pbit::unique};
    case 4:
      return {5, Pbit::none};
    case 5:
      return {7, Pbit::none};
    case 6:
      return {7, Pbit::unique};
    default:
      return {5, Pbit::unique};
  }
}

}  // namespace texproc::bc7
