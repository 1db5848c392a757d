// BC6H blocks from an encoder's Choice, in the bit layout of
// ARB_texture_compression_bptc (the order bptc_decode.cpp reads): the mode's
// fields as its layout string places them, the partition bits, then the
// indices (an anchor texel's one bit shorter).
#include <cassert>

#include "bc/bc6h_shared.h"
#include "bc/bptc_bit_writer.h"

namespace texproc::bc6h {

void pack_block(const Choice& c, std::uint8_t out[16]) {
  const bptc::Bc6hMode& M = bptc::kBc6hModes[c.mode];
  const Layout& L = layouts().modes[c.mode];
  const int ns = regions(c.mode), eb = M.endpoint_bits, emask = (1 << eb) - 1;
  int v[13] = {};
  v[0] = M.number;
  for (int ch = 0; ch < 3; ++ch)
    for (int j = 0; j < 2 * ns; ++j) {
      if (j == 0 || !M.transformed) {
        v[1 + 4 * ch + j] = c.code[j][ch] & emask;  // two's complement for SF16
        continue;
      }
      // The delta that takes the base to the code, wrapped as the decoder
      // wraps it (limit_delta made sure one fits).
      const int half = 1 << (eb - 1);
      const int delta = ((c.code[j][ch] - c.code[0][ch] + half) & emask) - half;
      assert(delta >= -(1 << (M.delta_bits[ch] - 1)) && delta < (1 << (M.delta_bits[ch] - 1)));
      v[1 + 4 * ch + j] = delta & ((1 << M.delta_bits[ch]) - 1);
    }
  bptc::BitWriter w;
  for (int f = 0; f < L.n; ++f) {
    const Field& fd = L.fields[f];
    for (int b = 0; b < fd.count; ++b) w.write(std::uint32_t(v[fd.var] >> (fd.first + fd.step * b) & 1), 1);
  }
  w.write(std::uint32_t(c.partition), M.partition_bits);
  const int bits = index_bits(c.mode);
  const int anchor1 = ns == 2 ? bptc::kAnchor2[c.partition] : -1;
  for (int i = 0; i < 16; ++i) {
    const int n = i == 0 || i == anchor1 ? bits - 1 : bits;
    assert(c.index[i] < (1 << n));
    w.write(c.index[i], n);
  }
  assert(w.position() == 128);
  w.store(out);
}

}  // namespace texproc::bc6h
