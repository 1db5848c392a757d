// The BC1 passes after a block is encoded: blocks of exactly two colours
// (their best palette positions) and the three-colour mode's black index
// for opaque BC1 (EncodeOptions::bc1_black). Each replaces the block only
// where its squared RGB error falls; bc1_encode.h describes them.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include "bc/bc1_block.h"
#include "bc/bc1_encode.h"
#include "block/block_gather.h"

namespace texproc {

using namespace bc1;  // the block as bc1_block.h defines it

namespace {
// Each texel's squared RGB error under `block` as the decoder reads it (the
// three-colour mode's index 3 as black); returns their sum.
long long block_errors(const std::uint8_t block[8], const std::uint8_t rgba[16][4], int err[16]) {
  const int c0 = block[0] | block[1] << 8, c1 = block[2] | block[3] << 8;
  Endpoints e;
  for (int k = 0; k < 2; ++k) {
    const int c = k ? c1 : c0;
    e.c[k][0] = c >> 11;
    e.c[k][1] = c >> 5 & 63;
    e.c[k][2] = c & 31;
  }
  int pal[4][3];
  palette(e, c0 > c1, pal);
  const std::uint32_t bits = std::uint32_t(block[4]) | std::uint32_t(block[5]) << 8 | std::uint32_t(block[6]) << 16 |
                             std::uint32_t(block[7]) << 24;
  long long total = 0;
  for (int i = 0; i < 16; ++i) {
    const int* p = pal[bits >> (2 * i) & 3];
    err[i] = 0;
    for (int c = 0; c < 3; ++c) err[i] += (rgba[i][c] - p[c]) * (rgba[i][c] - p[c]);
    total += err[i];
  }
  return total;
}
}  // namespace

void bc1_try_two_colours(const std::uint8_t rgba[16][4], Bc1Mode mode, std::uint8_t block[8]) {
  // Exactly two colours (block_gather.h), every texel opaque where alpha matters.
  std::uint32_t texel[16][kBlockBatch];
  for (int i = 0; i < 16; ++i) texel[i][0] = pack_texel(rgba[i]);
  std::uint32_t first = 0, second = 0;
  if (!two_colours(texel, 0, &first, &second)) return;
  for (int i = 0; i < 16; ++i)
    if (mode == Bc1Mode::bc1_punch_through && rgba[i][3] < 128) return;
  const int a[3] = {int(first & 255), int(first >> 8 & 255), int(first >> 16 & 255)};
  const int b[3] = {int(second & 255), int(second >> 8 & 255), int(second >> 16 & 255)};
  bool is_b[16] = {};
  int nb = 0;
  for (int i = 0; i < 16; ++i) {
    is_b[i] = (texel[i][0] & 0xFFFFFF) == second;
    nb += is_b[i] ? 1 : 0;
  }
  const int na = 16 - nb;
  Result best;
  best.error = -1;
  for (int four = 1; four >= 0; --four) {
    if (!four && mode == Bc1Mode::four_only) continue;
    const int den = four ? 3 : 2;
    // Palette positions in steps of 1/den from the first end, and their indices.
    auto index_of = [&](int pos) {
      return four ? (pos == 0 ? 0 : pos == 3 ? 1 : pos == 1 ? 2 : 3) : (pos == 0 ? 0 : pos == 2 ? 1 : 2);
    };
    for (int ta = 0; ta <= den; ++ta)
      for (int tb = ta + 1; tb <= den; ++tb) {
        Result r;
        r.four = four != 0;
        r.error = 0;
        for (int c = 0; c < 3; ++c) {
          const int bits = c == 1 ? 6 : 5, top = (1 << bits) - 1;
          auto ex = [&](int v) { return bits == 6 ? expand6(v) : expand5(v); };
          auto value = [&](int e0, int e1, int pos) {  // the decoder's palette entry
            const int x = ex(e0), y = ex(e1);
            if (pos == 0) return x;
            if (pos == den) return y;
            return four ? (pos == 1 ? (2 * x + y + 1) / 3 : (x + 2 * y + 1) / 3) : (x + y + 1) / 2;
          };
          // The ends that put a at ta and b at tb exactly, then the quantized
          // neighbours of each.
          const double span = double(b[c] - a[c]) * den / (tb - ta), e0 = a[c] - ta * span / den, e1 = e0 + span;
          const int q0 = std::clamp(int(std::lround(e0 * top / 255.0)), 0, top),
                    q1 = std::clamp(int(std::lround(e1 * top / 255.0)), 0, top);
          long channel = -1;
          for (int d0 = -1; d0 <= 1; ++d0)
            for (int d1 = -1; d1 <= 1; ++d1) {
              const int v0 = q0 + d0, v1 = q1 + d1;
              if (v0 < 0 || v0 > top || v1 < 0 || v1 > top) continue;
              const long da = a[c] - value(v0, v1, ta), db = b[c] - value(v0, v1, tb);
              const long e = na * da * da + nb * db * db;
              if (channel < 0 || e < channel) {
                channel = e;
                r.e.c[0][c] = v0;
                r.e.c[1][c] = v1;
              }
            }
          r.error += channel;
        }
        if (best.error >= 0 && r.error >= best.error) continue;
        for (int i = 0; i < 16; ++i) r.idx[i] = std::uint8_t(index_of(is_b[i] ? tb : ta));
        best = r;
      }
  }
  std::uint8_t candidate[8];
  write(best, candidate);
  int err[16];
  const long long current = block_errors(block, rgba, err), mine = block_errors(candidate, rgba, err);
  if (mine < current) std::memcpy(block, candidate, 8);
}

void bc1_try_black(const std::uint8_t rgba[16][4], Quality q, std::uint8_t block[8]) {
  int err[16], dark[16];
  long long total = block_errors(block, rgba, err);
  for (int i = 0; i < 16; ++i) dark[i] = rgba[i][0] * rgba[i][0] + rgba[i][1] * rgba[i][1] + rgba[i][2] * rgba[i][2];
  // The texel sets given index 3: those nearer black than to their colour
  // now, and those within a distance of black (about 4, 8 and 16 levels a
  // channel); then once more from the best block's colours.
  std::uint32_t tried[5];  // the sets tried, a bit per texel
  int n_tried = 0;
  auto attempt = [&](std::uint32_t set) {
    if (set == 0 || total == 0) return;
    for (int t = 0; t < n_tried; ++t)
      if (tried[t] == set) return;
    tried[n_tried++] = set;
    std::uint8_t marked[16][4];
    for (int i = 0; i < 16; ++i) {
      std::memcpy(marked[i], rgba[i], 3);
      marked[i][3] = set >> i & 1 ? 0 : 255;  // alpha 0: index 3, out of the fit
    }
    std::uint8_t candidate[8];
    encode_bc1_color_block_by_block(marked, Bc1Mode::bc1_punch_through, q, candidate);
    int cand_err[16];
    const long long cand_total = block_errors(candidate, rgba, cand_err);
    if (cand_total >= total) return;
    std::memcpy(block, candidate, 8);
    std::memcpy(err, cand_err, sizeof err);
    total = cand_total;
  };
  auto nearer_black = [&] {
    std::uint32_t set = 0;
    for (int i = 0; i < 16; ++i) set |= std::uint32_t(dark[i] < err[i]) << i;
    return set;
  };
  attempt(nearer_black());
  for (int within : {48, 192, 768}) {
    std::uint32_t set = 0;
    for (int i = 0; i < 16; ++i) set |= std::uint32_t(dark[i] <= within) << i;
    attempt(set);
  }
  attempt(nearer_black());
}

}  // namespace texproc
