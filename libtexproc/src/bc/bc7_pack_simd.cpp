// The SIMD twin of bc7::pack_lanes (bc7_pack.cpp): a batch of the encoder's
// choices packed into BC7 blocks a lane each, the 128 bits as four 32-bit
// words per lane. Each mode present in the batch is packed with its field
// positions known when compiled, for every lane, and kept in that mode's
// lanes. The anchor fix-up is pack_block's: a subset whose anchor index
// has its top bit set gets its endpoints swapped and its indices mirrored.
// Index positions after a partition's second or third anchor move down a
// bit a lane at a time (per-lane shifts). Tests compare it with pack_lanes
// on random choices of every mode, partition, rotation and selection.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "bc/bc7_pack_simd.cpp"
#include <hwy/foreach_target.h>  // must come before highway.h
#include <hwy/highway.h>

#include <algorithm>
#include <cstring>

#include "bc/bc7_shared.h"
#include "block/block_lanes_simd-inl.h"
#include "texproc/runtime.h"

#ifndef TEXPROC_BC7_PACK_TABLES_ONCE
#define TEXPROC_BC7_PACK_TABLES_ONCE
namespace texproc::bc7 {
// The anchor tables as int32 for gathers: kAnchorTable[0] the second
// subset's of two, [1] and [2] the second and third of three.
struct AnchorTables {
  std::int32_t t[3][64];
};
constexpr AnchorTables make_anchor_tables() {
  AnchorTables a{};
  for (int p = 0; p < 64; ++p) {
    a.t[0][p] = bptc::kAnchor2[p];
    a.t[1][p] = bptc::kAnchor3a[p];
    a.t[2][p] = bptc::kAnchor3b[p];
  }
  return a;
}
inline constexpr AnchorTables kAnchorTables = make_anchor_tables();
}  // namespace texproc::bc7
#endif

HWY_BEFORE_NAMESPACE();
namespace texproc {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace {

// One lane's choice fields, loaded.
struct Fields {
  V mode, partition, rotation, isel;
  V code[3][2][4], pbit[3][2];
  V color[16], alpha[16];
};

// The block's four words, a lane each, written from the lowest bit up.
struct Words {
  VU w[4];
};

// `v` (< 2^n) at bit `pos` of every lane's block.
HWY_INLINE void put(Words& b, VU v, int pos, int n) {
  const int q = pos / 32, r = pos % 32;
  b.w[q] = hn::Or(b.w[q], hn::ShiftLeftSame(v, r));
  if (r + n > 32) b.w[q + 1] = hn::Or(b.w[q + 1], hn::ShiftRightSame(v, 32 - r));
}

// A 64-bit stream (lo, hi) at bit `pos`.
HWY_INLINE void put64(Words& b, VU lo, VU hi, int pos) {
  const int q = pos / 32, r = pos % 32;
  if (r == 0) {
    b.w[q] = hn::Or(b.w[q], lo);
    if (q + 1 < 4) b.w[q + 1] = hn::Or(b.w[q + 1], hi);
    return;
  }
  b.w[q] = hn::Or(b.w[q], hn::ShiftLeftSame(lo, r));
  if (q + 1 < 4) b.w[q + 1] = hn::Or(b.w[q + 1], hn::Or(hn::ShiftRightSame(lo, 32 - r), hn::ShiftLeftSame(hi, r)));
  if (q + 2 < 4) b.w[q + 2] = hn::Or(b.w[q + 2], hn::ShiftRightSame(hi, 32 - r));
}

// An index stream of `bits` an index, the anchors' top bits left out:
// texel i at bit i bits - (anchors before or at i, texel 0 counted from
// texel 1 on) of a 64-bit word (lo, hi), a lane's positions its own.
HWY_INLINE void stream(const DI d, const V* index, int bits, const V anchor[3], int ns, VU& lo, VU& hi) {
  const DU du;
  lo = hn::Zero(du);
  hi = hn::Zero(du);
  for (int i = 0; i < 16; ++i) {
    V pos = hn::Set(d, i * bits - (i > 0 ? 1 : 0));
    for (int s = 1; s < ns; ++s)
      pos = hn::Add(pos, hn::VecFromMask(d, hn::Lt(anchor[s], hn::Set(d, i))));  // -1 past each anchor
    const VU v = hn::BitCast(du, index[i]);
    const M low = hn::Lt(pos, hn::Set(d, 32));
    const VU p = hn::BitCast(du, hn::And(pos, hn::Set(d, 31)));
    const VU shifted = hn::Shl(v, p);
    lo = hn::Or(lo, hn::IfThenElseZero(hn::RebindMask(du, low), shifted));
    hi = hn::Or(hi, hn::IfThenElseZero(hn::RebindMask(du, hn::Not(low)), shifted));
    // The part of an index that crosses bit 32.
    const M cross = hn::And(low, hn::Gt(hn::Add(pos, hn::Set(d, bits)), hn::Set(d, 32)));
    const VU back = hn::BitCast(du, hn::And(hn::Sub(hn::Set(d, 32), pos), hn::Set(d, 31)));
    hi = hn::Or(hi, hn::IfThenElseZero(hn::RebindMask(du, cross), hn::Shr(v, back)));
  }
}

// Mode `Mode`'s block for every lane, from a copy of the fields (the
// fix-up changes them).
template <int Mode>
HWY_INLINE Words pack_mode(const DI d, Fields c) {
  const DU du;
  constexpr bptc::Bc7Mode Md = bptc::kBc7Modes[Mode];
  constexpr int ns = Md.subsets;
  const M swap_streams = Mode == 4 ? hn::Ne(c.isel, hn::Zero(d)) : hn::FirstN(d, 0);
  const V color_L =
      hn::IfThenElse(swap_streams, hn::Set(d, (1 << Md.index2_bits) - 1), hn::Set(d, (1 << Md.index_bits) - 1));
  V part = hn::Zero(d), anchor[3] = {hn::Zero(d), hn::Zero(d), hn::Zero(d)};
  if (ns == 2) {
    part = hn::GatherIndex(d, reinterpret_cast<const std::int32_t*>(bptc::kPartitions2), c.partition);
    anchor[1] = hn::GatherIndex(d, bc7::kAnchorTables.t[0], c.partition);
  } else if (ns == 3) {
    part = hn::GatherIndex(d, reinterpret_cast<const std::int32_t*>(bptc::kPartitions3), c.partition);
    anchor[1] = hn::GatherIndex(d, bc7::kAnchorTables.t[1], c.partition);
    anchor[2] = hn::GatherIndex(d, bc7::kAnchorTables.t[2], c.partition);
  }
  // Anchors' top index bits to 0.
  constexpr int color_channels = Md.index2_bits ? 3 : 4;
  const V half = hn::ShiftRight<1>(color_L);
  M flip[3];
  for (int s = 0; s < ns; ++s) {
    V at = c.color[0];
    if (s > 0)
      for (int i = 1; i < 16; ++i) at = hn::IfThenElse(hn::Eq(anchor[s], hn::Set(d, i)), c.color[i], at);
    flip[s] = hn::Gt(at, half);
    for (int ch = 0; ch < color_channels; ++ch) {
      const V e0 = c.code[s][0][ch];
      c.code[s][0][ch] = hn::IfThenElse(flip[s], c.code[s][1][ch], e0);
      c.code[s][1][ch] = hn::IfThenElse(flip[s], e0, c.code[s][1][ch]);
    }
    const V p0 = c.pbit[s][0];
    c.pbit[s][0] = hn::IfThenElse(flip[s], c.pbit[s][1], p0);
    c.pbit[s][1] = hn::IfThenElse(flip[s], p0, c.pbit[s][1]);
  }
  for (int i = 0; i < 16; ++i) {
    M m = flip[0];
    if (ns > 1) {
      const V sub = hn::And(hn::ShiftRightSame(part, 2 * i), hn::Set(d, 3));
      m = hn::And(flip[0], hn::Eq(sub, hn::Zero(d)));
      for (int s = 1; s < ns; ++s) m = hn::Or(m, hn::And(flip[s], hn::Eq(sub, hn::Set(d, s))));
    }
    c.color[i] = hn::IfThenElse(m, hn::Sub(color_L, c.color[i]), c.color[i]);
  }
  if (Md.index2_bits) {
    const V alpha_L =
        hn::IfThenElse(swap_streams, hn::Set(d, (1 << Md.index_bits) - 1), hn::Set(d, (1 << Md.index2_bits) - 1));
    const M f = hn::Gt(c.alpha[0], hn::ShiftRight<1>(alpha_L));
    const V a0 = c.code[0][0][3];
    c.code[0][0][3] = hn::IfThenElse(f, c.code[0][1][3], a0);
    c.code[0][1][3] = hn::IfThenElse(f, a0, c.code[0][1][3]);
    for (int i = 0; i < 16; ++i) c.alpha[i] = hn::IfThenElse(f, hn::Sub(alpha_L, c.alpha[i]), c.alpha[i]);
  }
  Words b;
  for (auto& w : b.w) w = hn::Zero(du);
  int pos = 0;
  auto field = [&](V v, int n) {
    if (n) put(b, hn::BitCast(du, v), pos, n);
    pos += n;
  };
  field(hn::Set(d, 1 << Mode), Mode + 1);
  field(c.partition, Md.partition_bits);
  field(c.rotation, Md.rotation_bits);
  field(c.isel, Md.index_selection_bits);
  for (int ch = 0; ch < 3; ++ch)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) field(c.code[s][k][ch], Md.color_bits);
  if (Md.alpha_bits)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) field(c.code[s][k][3], Md.alpha_bits);
  if (Md.endpoint_pbits)
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) field(c.pbit[s][k], 1);
  if (Md.shared_pbits)
    for (int s = 0; s < ns; ++s) field(c.pbit[s][0], 1);
  V primary[16], secondary[16];
  for (int i = 0; i < 16; ++i) {
    primary[i] = hn::IfThenElse(swap_streams, c.alpha[i], c.color[i]);
    secondary[i] = hn::IfThenElse(swap_streams, c.color[i], c.alpha[i]);
  }
  VU lo, hi;
  stream(d, primary, Md.index_bits, anchor, ns, lo, hi);
  put64(b, lo, hi, pos);
  pos += 16 * Md.index_bits - ns;
  if (Md.index2_bits) {
    stream(d, secondary, Md.index2_bits, anchor, 1, lo, hi);
    put64(b, lo, hi, pos);
  }
  return b;
}

template <int Mode>
HWY_INLINE void pack_if_present(const DI d, const Fields& c, Words& out) {
  const M here = hn::Eq(c.mode, hn::Set(d, Mode));
  if (hn::AllFalse(d, here)) return;
  const Words b = pack_mode<Mode>(d, c);
  for (int q = 0; q < 4; ++q) out.w[q] = hn::IfThenElse(hn::RebindMask(DU(), here), b.w[q], out.w[q]);
}

}  // namespace

void Bc7PackLanes(const bc7::LaneChoices& t, int count, std::uint8_t out[][16]) {
  const DI d;
  const DU du;
  const int N = int(hn::Lanes(d));
  const std::int32_t* solid = bc7::solid5_packed();
  for (int k0 = 0; k0 < count; k0 += N) {
    Fields c;
    c.mode = hn::LoadU(d, t.mode + k0);
    c.partition = hn::And(hn::LoadU(d, t.partition + k0), hn::Set(d, 63));
    c.rotation = hn::LoadU(d, t.rotation + k0);
    c.isel = hn::LoadU(d, t.isel + k0);
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 2; ++k) {
        c.pbit[s][k] = hn::LoadU(d, t.pbit[s][k] + k0);
        for (int ch = 0; ch < 4; ++ch) c.code[s][k][ch] = hn::LoadU(d, t.code[s][k][ch] + k0);
      }
    for (int i = 0; i < 16; ++i) {
      c.color[i] = hn::LoadU(d, t.color_index[i] + k0);
      c.alpha[i] = hn::LoadU(d, t.alpha_index[i] + k0);
    }
    // One colour: bc7::solid_choice's mode 5 block.
    const M one = hn::Ne(hn::LoadU(d, t.solid + k0), hn::Zero(d));
    if (!hn::AllFalse(d, one)) {
      c.mode = hn::IfThenElse(one, hn::Set(d, 5), c.mode);
      c.rotation = hn::IfThenElseZero(hn::Not(one), c.rotation);
      for (int ch = 0; ch < 4; ++ch) {
        const V x = hn::And(hn::LoadU(d, t.x0[ch] + k0), hn::Set(d, 255));
        const V pair = ch < 3 ? hn::GatherIndex(d, solid, x) : hn::Or(x, hn::ShiftLeft<8>(x));
        c.code[0][0][ch] = hn::IfThenElse(one, hn::And(pair, hn::Set(d, 255)), c.code[0][0][ch]);
        c.code[0][1][ch] = hn::IfThenElse(one, hn::ShiftRight<8>(pair), c.code[0][1][ch]);
      }
      for (int i = 0; i < 16; ++i) {
        c.color[i] = hn::IfThenElse(one, hn::Set(d, 1), c.color[i]);
        c.alpha[i] = hn::IfThenElseZero(hn::Not(one), c.alpha[i]);
      }
    }
    Words b;
    for (auto& w : b.w) w = hn::Zero(du);
    pack_if_present<0>(d, c, b);
    pack_if_present<1>(d, c, b);
    pack_if_present<2>(d, c, b);
    pack_if_present<3>(d, c, b);
    pack_if_present<4>(d, c, b);
    pack_if_present<5>(d, c, b);
    pack_if_present<6>(d, c, b);
    pack_if_present<7>(d, c, b);
    const int lanes = std::min(N, count - k0);
    if (lanes == N) {
      hn::StoreInterleaved4(b.w[0], b.w[1], b.w[2], b.w[3], du, reinterpret_cast<std::uint32_t*>(out[k0]));
    } else {
      alignas(64) std::uint32_t words[4 * kBlockBatch];
      hn::StoreInterleaved4(b.w[0], b.w[1], b.w[2], b.w[3], du, words);
      std::memcpy(out[k0], words, 16 * std::size_t(lanes));
    }
  }
}

}  // namespace HWY_NAMESPACE
}  // namespace texproc
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace texproc::bc7 {
HWY_EXPORT(Bc7PackLanes);

void pack_lanes_simd(const LaneChoices& t, int count, std::uint8_t out[][16]) {
  if (force_scalar()) return pack_lanes(t, count, out);
  HWY_DYNAMIC_DISPATCH(Bc7PackLanes)(t, count, out);
}
}  // namespace texproc::bc7
#endif
