// ETC1, ETC2 and EAC: a colour block's search over the modes (etc1_encode:
// individual and differential; etc2_modes: planar, T and H; the flat and
// two-colour shortcuts here), and the image driver that runs the lane
// encoders (etc_lanes, eac_lanes) sixteen blocks at a time and this search
// for `max` and the blocks the lanes leave. Every candidate is scored with
// the decoder's own arithmetic (clamping included), so the error the search
// minimizes is the error a GPU shows.
#include "etc/etc_encode.h"
#include "etc/eac_lanes.h"
#include "etc/etc_lanes.h"
#include "etc/etc_search.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "block/rgb_block.h"
#include "block/value_palette.h"
#include "block/block_gather.h"
#include "etc/etc_tables.h"
#include "texproc/error.h"
#include "texproc/runtime.h"

namespace texproc::etc {

namespace {

Texels make_texels(const std::uint8_t rgba[16][4], EtcMode mode) {
  Texels tx;
  for (int i = 0; i < 16; ++i) {
    for (int c = 0; c < 3; ++c) tx.rgb[i][c] = rgba[i][c];
    tx.transparent[i] = mode == EtcMode::etc2_punch && rgba[i][3] < 128;
    tx.any_transparent |= tx.transparent[i];
    tx.planes.r[i] = rgba[i][0];
    tx.planes.g[i] = rgba[i][1];
    tx.planes.b[i] = rgba[i][2];
    tx.planes.transparent[i] = 0;
  }
  for (int h = 0; h < 4; ++h) {
    const HalfLayout& L = halves()[std::size_t(h)];
    for (int i = 0; i < 8; ++i) {
      const int p = L.y[i] * 4 + L.x[i];
      tx.half[h].r[i] = tx.rgb[p][0];
      tx.half[h].g[i] = tx.rgb[p][1];
      tx.half[h].b[i] = tx.rgb[p][2];
      tx.half[h].sum[i] = tx.rgb[p][0] + tx.rgb[p][1] + tx.rgb[p][2];
      tx.half[h].transparent[i] = tx.transparent[p] ? 1 : 0;
    }
  }
  return tx;
}

// A colour block as `mode`'s decoder reads it (ETC1, ETC2, punch-through).
void decode_colour(const std::uint8_t block[8], EtcMode mode, Rgba8Block out) {
  if (mode == EtcMode::etc1) {
    decode_etc1(block, out);
  } else {
    decode_etc2(block, mode == EtcMode::etc2_punch, out);
  }
}

// Squared RGB error of a block (ETC1, or ETC2 in `mode`).
long block_error(const std::uint8_t rgba[16][4], const std::uint8_t block[8], EtcMode mode = EtcMode::etc1) {
  Rgba8Block decoded;
  decode_colour(block, mode, decoded);
  long err = 0;
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) err += long(rgba[i][c] - decoded[i][c]) * (rgba[i][c] - decoded[i][c]);
  return err;
}

// Opaque colour goes sixteen blocks at a time (etc_lanes.h) where the level
// says so (etc_levels.h: every level but `max`): every block of ETC1 and
// ETC2 RGB, and punch-through's opaque blocks (differential mode only: its
// bit 33 is the opaque flag).

// The lanes' ETC1 blocks at `lane`; `error` gets their squared RGB errors
// (not at `fast`, whose kernel does not count them).
void etc1_lanes(Etc1Lanes lane, const std::uint32_t texel[16][kEtcBatch], int count, bool punch, std::uint8_t out[][8],
                std::int32_t error[]) {
  if (lane == Etc1Lanes::fast) {
    etc1_fast_lanes(texel, count, punch, out);
  } else {
    etc1_search_lanes(texel, count, lane == Etc1Lanes::high, punch, out, error);
  }
}

// Punch-through's blocks with a texel of alpha below 128 (transparent).
bool any_transparent(const std::uint8_t rgba[16][4]) {
  for (int i = 0; i < 16; ++i)
    if (rgba[i][3] < 128) return true;
  return false;
}

// Block k of a lanes batch as opaque Texels (row by row, R | G << 8 | B << 16).
Texels lane_texels(const std::uint32_t texel[16][kEtcBatch], int k) {
  Texels tx;
  for (int i = 0; i < 16; ++i) {
    const std::uint32_t t = texel[i][k];
    tx.rgb[i][0] = tx.planes.r[i] = int(t & 255);
    tx.rgb[i][1] = tx.planes.g[i] = int(t >> 8 & 255);
    tx.rgb[i][2] = tx.planes.b[i] = int(t >> 16 & 255);
    tx.transparent[i] = false;
    tx.planes.transparent[i] = 0;
  }
  return tx;
}

// ETC2 above `fast`: the planar mode, and the T and H modes (only where the
// lanes' ETC1 block, its error `err`, leaves more than modes.t_h_above per
// texel, squared RGB), tried against it; the block is replaced if one wins.
long finish_etc2_block(const std::uint32_t texel[16][kEtcBatch], int k, long err, const Etc2Modes& modes,
                       std::uint8_t block[8]) {
  const Texels tx = lane_texels(texel, k);
  Candidate best;
  best.err = err;
  best.bits = load_be64(block);
  search_planar(tx, modes, best);
  if (modes.t_h_above == 0 || best.err > 16L * modes.t_h_above) search_t_h(tx, false, modes, best);
  store_be64(best.bits, block);
  return best.err;
}

// One colour: the least error of each channel value under a base of `bits`
// (4 or 5) plus each of the 32 modifiers (the tables' entries, clamped as
// the decoder does), and the base that reaches it (the first of equals);
// and in a planar channel of 6 or 7 bits: O, H and V within 2 of the
// nearest level (a slightly tilted plane rounds to values on both sides of
// the colour, less error in all than one flat level).
struct FlatTables {
  int err[2][32][256], base[2][32][256];          // [bits 4, 5][table * 4 + index][value]
  int planar_err[2][256], planar_ohv[2][256][3];  // [6 bits, 7 bits][value]
};
const FlatTables& flat_tables() {
  static const FlatTables* t = [] {
    auto* f = new FlatTables;
    for (int b = 0; b < 2; ++b)
      for (int m = 0; m < 32; ++m)
        for (int v = 0; v < 256; ++v) {
          int best = std::numeric_limits<int>::max(), base = 0;
          for (int q = 0; q < (b ? 32 : 16); ++q) {
            const int d = v - clamp255(expand(q, b ? 5 : 4) + kModifiers[m / 4][m % 4]);
            if (d * d < best) {
              best = d * d;
              base = q;
            }
          }
          f->err[b][m][v] = best;
          f->base[b][m][v] = base;
        }
    for (int b = 0; b < 2; ++b)
      for (int v = 0; v < 256; ++v) {
        const int top = b ? 127 : 63;
        auto ex = [&](int q) { return b ? extend7(q) : extend6(q); };
        int q0 = 0;
        for (int q = 1; q <= top; ++q)
          if (std::abs(v - ex(q)) < std::abs(v - ex(q0))) q0 = q;
        int best = std::numeric_limits<int>::max();
        for (int o = std::max(0, q0 - 2); o <= std::min(top, q0 + 2); ++o)
          for (int h = std::max(0, q0 - 2); h <= std::min(top, q0 + 2); ++h)
            for (int w = std::max(0, q0 - 2); w <= std::min(top, q0 + 2); ++w) {
              int e = 0;
              for (int i = 0; i < 16; ++i) {  // as the decoder's plane
                const int d =
                    clamp255(((i & 3) * (ex(h) - ex(o)) + (i >> 2) * (ex(w) - ex(o)) + 4 * ex(o) + 2) >> 2) - v;
                e += d * d;
              }
              if (e < best) {
                best = e;
                f->planar_ohv[b][v][0] = o;
                f->planar_ohv[b][v][1] = h;
                f->planar_ohv[b][v][2] = w;
              }
            }
        f->planar_err[b][v] = best;
      }
    return f;
  }();
  return *t;
}

// An opaque block of one colour (all 16 texels `rgb`): the least error the
// format allows it. Both halves share a base, a table and one modifier for
// every texel (the differential mode at 5 bits; the individual mode at 4,
// not with punch-through, whose bit 33 is the opaque flag), or, in ETC2, a
// flat plane. `block` is replaced where that beats its error.
void best_flat_block(const int rgb[3], EtcMode mode, std::uint8_t block[8]) {
  const FlatTables& f = flat_tables();
  Candidate best;
  for (int b = 1; b >= 0; --b) {
    if (b == 0 && mode == EtcMode::etc2_punch) continue;
    for (int m = 0; m < 32; ++m) {
      const long err = 16L * (f.err[b][m][rgb[0]] + f.err[b][m][rgb[1]] + f.err[b][m][rgb[2]]);
      if (err >= best.err) continue;
      HalfFit h;
      for (int c = 0; c < 3; ++c) h.q[c] = f.base[b][m][rgb[c]];
      h.table = m / 4;
      std::fill(h.idx, h.idx + 8, std::uint8_t(m % 4));
      keep(best, err, pack_halves(h, h, false, b == 1, b == 1 ? 1 : 0));
    }
  }
  if (mode != EtcMode::etc1) {
    int o[3], h[3], w[3];
    long err = 0;
    for (int c = 0; c < 3; ++c) {
      const int b = c == 1 ? 1 : 0;
      const int* ohv = f.planar_ohv[b][rgb[c]];
      o[c] = ohv[0];
      h[c] = ohv[1];
      w[c] = ohv[2];
      err += f.planar_err[b][rgb[c]];
    }
    keep(best, err, pack_planar(o, h, w));
  }
  Rgba8Block decoded;
  decode_colour(block, mode, decoded);
  long current = 0;
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 3; ++c) current += long(rgb[c] - decoded[i][c]) * (rgb[c] - decoded[i][c]);
  if (best.err < current) store_be64(best.bits, block);
}

// Punch-through with holes (the opaque flag clear) and one visible colour:
// the differential mode's modifiers are then 0 (index 0) and +-b (indices 1
// and 3), index 2 a hole. The best base for each of those, both halves
// alike; `block` is replaced where that beats its error over the visible
// texels, whose error it returns.
long best_flat_holes_block(const std::uint8_t rgba[16][4], const int rgb[3], std::uint8_t block[8]) {
  const FlatTables& f = flat_tables();
  int visible = 0;
  for (int i = 0; i < 16; ++i) visible += rgba[i][3] >= 128;
  Candidate best;
  for (int option = 0; option < 17; ++option) {  // 0: modifier 0; then table t's +b and -b
    const int t = option == 0 ? 0 : (option - 1) / 2, idx = option == 0 ? 0 : (option - 1) % 2 ? 3 : 1;
    int q[3];
    long per_texel = 0;
    for (int c = 0; c < 3; ++c) {
      if (option == 0) {
        int e = std::numeric_limits<int>::max();
        for (int v = 0; v < 32; ++v) {
          const int d = rgb[c] - extend5(v);
          if (d * d < e) {
            e = d * d;
            q[c] = v;
          }
        }
        per_texel += e;
      } else {
        q[c] = f.base[1][t * 4 + idx][rgb[c]];
        per_texel += f.err[1][t * 4 + idx][rgb[c]];
      }
    }
    const long err = per_texel * visible;
    if (err >= best.err) continue;
    HalfFit h[2];
    for (int s = 0; s < 2; ++s) {
      std::memcpy(h[s].q, q, sizeof q);
      h[s].table = t;
      const HalfLayout& L = halves()[std::size_t(s)];
      for (int i = 0; i < 8; ++i) h[s].idx[i] = std::uint8_t(rgba[L.y[i] * 4 + L.x[i]][3] >= 128 ? idx : 2);
    }
    keep(best, err, pack_halves(h[0], h[1], false, true, 0));
  }
  Rgba8Block decoded;
  decode_colour(block, EtcMode::etc2_punch, decoded);
  long current = 0;
  for (int i = 0; i < 16; ++i)
    if (rgba[i][3] >= 128)
      for (int c = 0; c < 3; ++c) current += long(rgb[c] - decoded[i][c]) * (rgb[c] - decoded[i][c]);
  if (best.err >= current) return current;
  store_be64(best.bits, block);
  return best.err;
}

// ETC2 at `fast`: a block of exactly two colours (text, line art, UI
// edges) also tries the T and H modes, which hold two 4-bit colours; its
// ETC1 block shares one base and table between the halves' texels and
// leaves such blocks far off (44 times the error of `normal` on random
// pairs). The block is replaced where one wins.
void two_colour_t_h(const std::uint32_t texel[16][kEtcBatch], int k, EtcMode mode, const Etc2Modes& modes,
                    std::uint8_t block[8]) {
  if (!two_colours(texel, k)) return;
  const Texels tx = lane_texels(texel, k);
  std::uint8_t rgba[16][4];
  for (int i = 0; i < 16; ++i)
    for (int c = 0; c < 4; ++c) rgba[i][c] = std::uint8_t(texel[i][k] >> (8 * c));
  Candidate best;
  best.err = block_error(rgba, block, mode);
  best.bits = load_be64(block);
  search_t_h(tx, false, modes, best);
  store_be64(best.bits, block);
}

// Whether the 16 texels (R | G << 8 | B << 16 | A << 24) are one colour,
// opaque where `mode` reads alpha (punch-through); `rgb` gets it.
bool flat_colour(const std::uint32_t texel[16][kEtcBatch], int k, EtcMode mode, int rgb[3]) {
  std::uint32_t c = 0;
  if (!one_colour(texel, k, mode == EtcMode::etc2_punch, &c)) return false;  // block_gather.h
  rgb[0] = int(c & 255);
  rgb[1] = int(c >> 8 & 255);
  rgb[2] = int(c >> 16 & 255);
  return true;
}

}  // namespace

long encode_color_block(const std::uint8_t rgba[16][4], EtcMode mode, Quality q, std::uint8_t out[8]) {
  const bool punch = mode == EtcMode::etc2_punch;
  const bool opaque = !punch || !any_transparent(rgba);
  std::uint32_t texel[16][kEtcBatch] = {};  // lane 0: this block, for the lanes
  for (int i = 0; i < 16; ++i) texel[i][0] = pack_texel(rgba[i]);
  const EtcLevel& level = etc_level(q);  // etc_levels.h
  if (level.lanes && opaque) {           // as whole images do: etc_lanes.h
    std::uint8_t block[1][8];
    std::int32_t e[1] = {};
    etc1_lanes(level.lane, texel, 1, punch, block, e);
    long err = level.lane == Etc1Lanes::fast ? block_error(rgba, block[0]) : e[0];
    if (mode != EtcMode::etc1 && level.etc2.search) err = finish_etc2_block(texel, 0, err, level.etc2, block[0]);
    int rgb[3];
    if (flat_colour(texel, 0, mode, rgb)) {
      best_flat_block(rgb, mode, block[0]);
      err = block_error(rgba, block[0], mode);
    } else if (level.etc2.two_colour_t_h && mode != EtcMode::etc1) {  // as compress_etc
      two_colour_t_h(texel, 0, mode, level.etc2, block[0]);
      err = block_error(rgba, block[0], mode);
    }
    std::memcpy(out, block[0], 8);
    return err;
  }
  const Texels tx = make_texels(rgba, mode);
  Candidate best;
  if (level.lane_candidate && opaque &&
      level.lane != Etc1Lanes::fast) {  // never below the lanes: their block is the first candidate
    std::uint8_t block[1][8];
    std::int32_t e[1];
    etc1_lanes(level.lane, texel, 1, punch, block, e);
    best.err = e[0];
    best.bits = load_be64(block[0]);
  }
  const bool non_opaque = punch && tx.any_transparent;
  // Bit 33: the differential flag, or with punch-through the opaque flag.
  const int bit33 = punch ? (non_opaque ? 0 : 1) : 1;
  search_etc1_modes(tx, level.block, !punch, non_opaque, bit33, best);
  if (mode != EtcMode::etc1 && level.etc2.search) {
    if (!non_opaque) search_planar(tx, level.etc2, best);
    search_t_h(tx, non_opaque, level.etc2, best);
  }
  store_be64(best.bits, out);
  int rgb[3];
  if (flat_colour(texel, 0, mode, rgb)) {
    best_flat_block(rgb, mode, out);
    return block_error(rgba, out, mode);
  }
  if (non_opaque) {  // holes: one visible colour?
    int first = 0;
    while (first < 16 && rgba[first][3] < 128) ++first;
    bool one = first < 16;
    for (int i = first; i < 16 && one; ++i)
      one = rgba[i][3] < 128 ||
            (rgba[i][0] == rgba[first][0] && rgba[i][1] == rgba[first][1] && rgba[i][2] == rgba[first][2]);
    if (one) {
      const int c[3] = {rgba[first][0], rgba[first][1], rgba[first][2]};
      return best_flat_holes_block(rgba, c, out);
    }
  }
  return best.err;
}

std::vector<std::uint8_t> compress_etc(const ConstImageView& img, TexelFormat format, Quality q,
                                       const EncodeOptions& options) {
  using F = TexelFormat;
  const FormatInfo& info = format_info(format);
  const int bw = (img.width + 3) / 4, bh = (img.height + 3) / 4;
  std::vector<std::uint8_t> out(std::size_t(bw) * bh * std::size_t(info.block_bytes));
  const bool eac = format_info(format).family == CodecFamily::eac;
  const bool snorm = format == F::eac_r11_snorm || format == F::eac_rg11_snorm;
  const int eac_channels = format == F::eac_rg11_unorm || format == F::eac_rg11_snorm ? 2 : 1;
  const bool rgba8 = format == F::etc2_rgba8_unorm || format == F::etc2_rgba8_srgb;
  const EtcMode mode = format == F::etc1_rgb                                           ? EtcMode::etc1
                       : format == F::etc2_rgba1_unorm || format == F::etc2_rgba1_srgb ? EtcMode::etc2_punch
                                                                                       : EtcMode::etc2;
  // Opaque colour: sixteen blocks at a time (etc_lanes.h); ETC2 then tries
  // its planar, T and H modes block by block.
  const EtcLevel& level = etc_level(q);   // etc_levels.h
  const EacLevel& eac_lv = eac_level(q);  // eac_levels.h
  const bool batched = level.lanes;
  const bool punch = mode == EtcMode::etc2_punch;
  const bool finish = batched && level.etc2.search && mode != EtcMode::etc1;  // ETC2: planar, T, H per block
  const bool eac_lanes = eac_lv.lanes;
  for_each_row_block(
      bh, 4,
      [&](int by0, int by1) {
        std::int32_t errors[kEtcBatch];
        std::uint8_t rgba[kEtcBatch][16][4];
        std::uint32_t texel[16][kEtcBatch] = {};
        std::uint8_t color[kEtcBatch][8];
        float values[16];
        float eac_values[16][kEacBatch];  // EAC: sixteen blocks at a time below `max` (eac_lanes.h)
        std::uint8_t eac_out[kEacBatch][8];
        float eac_err[kEacBatch];
        // The EAC blocks of eac_values, written `offset` bytes into their blocks.
        auto eac_encode = [&](int by, int bx0, int count, EacKind kind, int offset) {
          if (eac_lanes) {
            eac_encode_lanes(eac_values, count, kind, eac_lv.lanes_window, eac_out, eac_err);
          } else {
            for (int k = 0; k < count; ++k) {
              for (int i = 0; i < 16; ++i) values[i] = eac_values[i][k];
              encode_eac_block(values, kind, q, eac_out[k]);
            }
          }
          for (int k = 0; k < count; ++k)
            std::memcpy(out.data() + (std::size_t(by) * bw + bx0 + k) * std::size_t(info.block_bytes) + offset,
                        eac_out[k], 8);
        };
        for (int by = by0; by < by1; ++by)
          for (int bx0 = 0; bx0 < bw; bx0 += kEtcBatch) {
            const int count = std::min(kEtcBatch, bw - bx0);
            if (eac) {
              for (int c = 0; c < eac_channels; ++c) {
                for (int k = 0; k < count; ++k)
                  for (int i = 0; i < 16; ++i) {
                    // Partial blocks: the edge texels repeat into the missing ones.
                    const int x = std::min((bx0 + k) * 4 + i % 4, img.width - 1),
                              y = std::min(by * 4 + i / 4, img.height - 1);
                    const float u = texel_unit(img, x, y, c);
                    eac_values[i][k] = snorm ? (u * 2.0f - 1.0f) * 1023.0f : u * 2047.0f;
                  }
                eac_encode(by, bx0, count, snorm ? EacKind::r11_signed : EacKind::r11, 8 * c);
              }
              continue;
            }
            // RGBA8 texels straight from the rows where they can be.
            const bool rows_direct = batched && !rgba8 && !punch && gather_rows_rgba8(img, bx0, by, count, texel);
            bool lanes_block[kEtcBatch];  // punch-through: only opaque blocks take the lanes' block
            for (int k = 0; k < count && !rows_direct; ++k) {
              const int bx = bx0 + k;
              std::uint8_t* dst = out.data() + (std::size_t(by) * bw + bx) * std::size_t(info.block_bytes);
              gather_rgba8(img, bx, by, rgba[k]);
              if (rgba8)
                for (int i = 0; i < 16; ++i) eac_values[i][k] = rgba[k][i][3];
              lanes_block[k] = batched && !(punch && any_transparent(rgba[k]));
              if (batched)
                for (int i = 0; i < 16; ++i) texel[i][k] = pack_texel(rgba[k][i]);
              if (!lanes_block[k]) encode_color_block(rgba[k], mode, q, dst + (rgba8 ? 8 : 0));
            }
            if (rgba8) eac_encode(by, bx0, count, EacKind::alpha8, 0);
            if (!batched) continue;
            if (rows_direct) std::fill(lanes_block, lanes_block + count, true);
            etc1_lanes(level.lane, texel, count, punch, color, errors);
            for (int k = 0; k < count && finish; ++k)
              if (lanes_block[k]) finish_etc2_block(texel, k, errors[k], level.etc2, color[k]);
            for (int k = 0; k < count; ++k) {
              if (!lanes_block[k]) continue;
              int rgb[3];
              if (flat_colour(texel, k, mode, rgb)) {
                best_flat_block(rgb, mode, color[k]);  // one colour: the format's best
              } else if (level.etc2.two_colour_t_h && mode != EtcMode::etc1) {
                two_colour_t_h(texel, k, mode, level.etc2, color[k]);
              }
              std::memcpy(
                  out.data() + (std::size_t(by) * bw + bx0 + k) * std::size_t(info.block_bytes) + (rgba8 ? 8 : 0),
                  color[k], 8);
            }
          }
      },
      options.progress);
  return out;
}

}  // namespace texproc::etc
