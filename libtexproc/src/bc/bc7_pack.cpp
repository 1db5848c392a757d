// BC7 blocks from an encoder's Choice, in the bit layout of
// ARB_texture_compression_bptc (the order bptc_decode.cpp reads): mode,
// partition, rotation, index selection, the endpoints channel by channel,
// the p-bits, the primary then the secondary indices.
#include <utility>

#include "bc/bc7_shared.h"
#include "bc/bptc_bit_writer.h"

namespace texproc::bc7 {
namespace {

using bptc::BitWriter;

constexpr SolidPair solid_pair(int v) {
  SolidPair best{};
  int best_d = 1 << 20;
  for (int a = 0; a < 128; ++a)
    for (int b = 0; b < 128; ++b) {
      const int d = bptc::interpolate(expand(a, 7, -1), expand(b, 7, -1), 21) - v;
      if (d * d < best_d) best_d = d * d, best = {std::uint8_t(a), std::uint8_t(b)};
    }
  return best;
}

struct SolidTable {
  SolidPair p[256];
};

}  // namespace

// Built on first use (4M candidate pairs: a few milliseconds, paid only by
// BC7 encodes, not at start-up).
const SolidPair& solid5(int v) {
  static const SolidTable table = [] {
    SolidTable t{};
    for (int i = 0; i < 256; ++i) t.p[i] = solid_pair(i);
    return t;
  }();
  return table.p[v];
}

const std::int32_t* solid5_packed() {
  static const auto table = [] {
    struct Packed {
      std::int32_t v[256];
    } t{};
    for (int i = 0; i < 256; ++i) t.v[i] = solid5(i).e0 | solid5(i).e1 << 8;
    return t;
  }();
  return table.v;
}

constexpr QuantTable kQuant[5][3] = {
    {make_quant_table(4, -1), make_quant_table(4, 0), make_quant_table(4, 1)},
    {make_quant_table(5, -1), make_quant_table(5, 0), make_quant_table(5, 1)},
    {make_quant_table(6, -1), make_quant_table(6, 0), make_quant_table(6, 1)},
    {make_quant_table(7, -1), make_quant_table(7, 0), make_quant_table(7, 1)},
    {make_quant_table(8, -1), make_quant_table(8, -1), make_quant_table(8, -1)},  // 8 bits: no p-bit
};

struct QuantPairs {
  std::int32_t t[5][2][256];
};
constexpr QuantPairs make_pairs() {
  QuantPairs p{};
  auto packed = [](const Quantized& q) { return std::int32_t(q.code | q.value << 8); };
  for (int b = 0; b < 5; ++b)
    for (int v = 0; v < 256; ++v) {
      p.t[b][0][v] = packed(kQuant[b][0].q[v]) | packed(kQuant[b][0].q[v]) << 16;
      p.t[b][1][v] = packed(kQuant[b][1].q[v]) | packed(kQuant[b][2].q[v]) << 16;
    }
  return p;
}
constexpr QuantPairs kPairs = make_pairs();
const std::int32_t (&kQuantPairs)[5][2][256] = kPairs.t;

Choice solid_choice(const int rgba[4]) {
  Choice c;
  c.mode = 5;
  for (int a = 0; a < 3; ++a) {
    const SolidPair& p = solid5(rgba[a]);
    c.code[0][0][a] = p.e0;
    c.code[0][1][a] = p.e1;
  }
  c.code[0][0][3] = c.code[0][1][3] = rgba[3];
  for (int i = 0; i < 16; ++i) {
    c.color_index[i] = 1;
    c.alpha_index[i] = 0;
  }
  return c;
}

namespace {

// One mode's packing, the mode a constant (every field's place known when
// compiled).
template <int Mode>
void pack_mode(const Choice& in, std::uint8_t out[16]) {
  Choice c = in;
  constexpr bptc::Bc7Mode M = bptc::kBc7Modes[Mode];
  constexpr int ns = M.subsets;
  const bool swap_streams = Mode == 4 && c.index_selection != 0;
  const int color_bits = swap_streams ? M.index2_bits : M.index_bits;
  const int alpha_bits = swap_streams ? M.index_bits : M.index2_bits;
  const std::uint32_t part = ns == 2 ? bptc::kPartitions2[c.partition] : ns == 3 ? bptc::kPartitions3[c.partition] : 0;
  const int anchor[3] = {0,
                         ns == 2   ? bptc::kAnchor2[c.partition]
                         : ns == 3 ? bptc::kAnchor3a[c.partition]
                                   : -1,
                         ns == 3 ? bptc::kAnchor3b[c.partition] : -1};
  // Anchors' top index bits to 0: the subset's endpoints swapped (the
  // channels those indices weigh), its indices mirrored.
  const int color_channels = M.index2_bits ? 3 : 4;
  for (int s = 0; s < ns; ++s) {
    const int L = (1 << color_bits) - 1;
    if (c.color_index[anchor[s]] <= L / 2) continue;
    for (int ch = 0; ch < color_channels; ++ch) std::swap(c.code[s][0][ch], c.code[s][1][ch]);
    std::swap(c.pbit[s][0], c.pbit[s][1]);
    for (int i = 0; i < 16; ++i)
      if ((ns == 1 ? 0 : bptc::subset(part, i)) == s) c.color_index[i] = std::uint8_t(L - c.color_index[i]);
  }
  if (M.index2_bits) {
    const int L = (1 << alpha_bits) - 1;
    if (c.alpha_index[0] > L / 2) {
      std::swap(c.code[0][0][3], c.code[0][1][3]);
      for (int i = 0; i < 16; ++i) c.alpha_index[i] = std::uint8_t(L - c.alpha_index[i]);
    }
  }
  BitWriter w;
  w.write(1u << Mode, Mode + 1);
  w.write(std::uint32_t(c.partition), M.partition_bits);
  w.write(std::uint32_t(c.rotation), M.rotation_bits);
  w.write(std::uint32_t(c.index_selection), M.index_selection_bits);
  for (int ch = 0; ch < 3; ++ch)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) w.write(std::uint32_t(c.code[s][k][ch]), M.color_bits);
  if (M.alpha_bits)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) w.write(std::uint32_t(c.code[s][k][3]), M.alpha_bits);
  if (M.endpoint_pbits)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) w.write(std::uint32_t(c.pbit[s][k]), 1);
  if (M.shared_pbits)
    for (int s = 0; s < ns; ++s) w.write(std::uint32_t(c.pbit[s][0]), 1);
  const std::uint8_t* primary = swap_streams ? c.alpha_index : c.color_index;
  const std::uint8_t* secondary = swap_streams ? c.color_index : c.alpha_index;
  // Each index stream gathered into one word (at most 16 * 4 - 1 bits), then written whole.
  unsigned anchors = 0;
  for (int s = 0; s < ns; ++s) anchors |= 1u << anchor[s];
  auto stream = [&](const std::uint8_t* index, int bits, unsigned anchor_mask) {
    std::uint64_t acc = 0;
    int n = 0;
    for (int i = 0; i < 16; ++i) {
      acc |= std::uint64_t(index[i]) << n;
      n += bits - int(anchor_mask >> i & 1);
    }
    w.write64(acc, n);
  };
  stream(primary, M.index_bits, anchors);
  if (M.index2_bits) stream(secondary, M.index2_bits, 1u);
  w.store(out);
}

}  // namespace

void pack_block(const Choice& c, std::uint8_t out[16]) {
  switch (c.mode) {
    case 0:
      return pack_mode<0>(c, out);
    case 1:
      return pack_mode<1>(c, out);
    case 2:
      return pack_mode<2>(c, out);
    case 3:
      return pack_mode<3>(c, out);
    case 4:
      return pack_mode<4>(c, out);
    case 5:
      return pack_mode<5>(c, out);
    case 6:
      return pack_mode<6>(c, out);
    default:
      return pack_mode<7>(c, out);
  }
}

void pack_lanes(const LaneChoices& t, int count, std::uint8_t out[][16]) {
  for (int k = 0; k < count; ++k) {
    if (t.solid[k]) {
      const int rgba[4] = {t.x0[0][k], t.x0[1][k], t.x0[2][k], t.x0[3][k]};
      pack_block(solid_choice(rgba), out[k]);
      continue;
    }
    Choice c;
    c.mode = t.mode[k];
    c.partition = t.partition[k];
    c.rotation = t.rotation[k];
    c.index_selection = t.isel[k];
    for (int s = 0; s < 3; ++s)
      for (int e = 0; e < 2; ++e) {
        c.pbit[s][e] = t.pbit[s][e][k];
        for (int ch = 0; ch < 4; ++ch) c.code[s][e][ch] = t.code[s][e][ch][k];
      }
    for (int i = 0; i < 16; ++i) {
      c.color_index[i] = std::uint8_t(t.color_index[i][k]);
      c.alpha_index[i] = std::uint8_t(t.alpha_index[i][k]);
    }
    pack_block(c, out[k]);
  }
}

}  // namespace texproc::bc7
