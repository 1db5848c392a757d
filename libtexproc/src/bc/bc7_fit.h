// BC7's endpoint fit, one index set at a time: the scalar reference of
// bc7_fit_simd-inl.h (seeds, quantization, index assignment, least-squares
// refinement, endpoint steps), used by bc7_lanes.cpp's block search.
#pragma once

#include <cstdint>

#include "bc/bc7_levels.h"
#include "bc/bc7_shared.h"

namespace texproc::ref::bc7_fit {

// One index set's fit: endpoint codes, p-bits and 8-bit values (channels
// c0..c0 + n - 1), each member texel's index, the squared error over those
// channels.
struct SetFit {
  int code[2][4] = {}, pbit[2] = {}, value[2][4] = {};
  std::uint8_t index[16] = {};
  int error = 0;
};

// A set of texels: the block's (possibly rotated) texels, which of them
// (members, a bit each), and which channels.
struct Set {
  const int (*x)[4];
  unsigned members;
  int c0, n;
  bool has(int i) const { return members >> i & 1; }
};

// The endpoints from the set's principal axis: the texels' extent along it.
void line_ends(const Set& s, float e[2][4]);
// Each member's index for the fit's endpoints: its projection onto their
// line, rounded; with `exact`, the neighbouring index on either side where
// it decodes closer (the lower one tried first). The error over the set.
void assign(const Set& s, int bits, bool exact, SetFit& fit);
// One index set fitted from one seed (0: the line's ends; 1-3: its ends
// moved out by an index step), then least-squares rounds while the error falls.
SetFit fit_seed(const Set& s, const float line[2][4], int seed, bc7::EndpointFormat f, int bits, bool force_p1,
                const Bc7Level& level);
// One index set fitted from each of level.seeds seeds, the best kept, then
// its steps (level.perturb).
SetFit fit_set(const Set& s, bc7::EndpointFormat f, int bits, bool force_p1, const Bc7Level& level);
// Each code one step either way, channel by channel, kept where it helps;
// up to `rounds` rounds while one does.
void step_ends(const Set& s, bc7::EndpointFormat f, int bits, const Bc7Level& level, bool exact, int rounds,
               SetFit& best);

}  // namespace texproc::ref::bc7_fit
