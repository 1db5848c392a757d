// BC7's quality levels: one row per level, every knob a level sets.
// Changing a level is one edit here. What each knob buys, measured on the
// corpus: docs/design/encoders.md, "BC7 encoder".
#pragma once

#include "texproc/block_encode.h"

namespace texproc {

struct Bc7Level {
  // Two-subset partitions kept per block after the estimate (the residual
  // off each subset's principal axis), fitted in modes 1 and 3 (0: neither
  // mode); and whether mode 3 (7-bit endpoints, 2-bit indices) is fitted
  // beside mode 1 (6-bit, 3-bit indices).
  int partitions2;
  bool mode3;
  // How many of the 64 two-subset partitions the estimate looks at (the
  // first ones: the table's most useful shapes come first).
  int estimated2;
  // Three-subset partitions kept, fitted in mode 0 (of its 16) and mode 2
  // (of 64); 0: neither mode.
  int partitions3;
  // Blocks with alpha: how many of modes 4 and 5's rotations are tried
  // (1: none, the alpha channel as alpha; 4: every channel as the scalar
  // one), mode 4's index selection both ways, and mode 7 (two subsets with
  // alpha, on the partitions kept above).
  int rotations;
  bool index_selection;
  bool mode7;
  // Opaque blocks too: modes 4 and 5 with a colour channel rotated into
  // the scalar slot (rotations 1 to rotations - 1; alpha stays 255), for
  // blocks with one channel apart from the other two.
  bool opaque_rotated;
  // Least-squares endpoints for the indices, then indices for the quantized
  // endpoints, up to this many times while the error falls.
  int refine;
  // Indices from the projection onto the endpoints' line, then the
  // neighbouring index on each side tried against the exact palette.
  bool exact_indices;
  // After refinement: each endpoint code moved one step up and down, channel
  // by channel, kept where the exact error falls; up to this many rounds
  // while one helps (0: none).
  int perturb;
  // The same steps on the search's winner alone (modes with one set a
  // subset: 0-3, 6, 7), up to this many rounds: most of what the steps
  // buy, for one candidate's cost instead of every candidate's.
  int winner_steps;
  // Each round also moves a channel's two endpoint codes together: both
  // up, both down, apart, together (a shift or a stretch of the line).
  bool pair_steps;
  // Each quantization of the ends tries every p-bit choice (four for a
  // p-bit an endpoint, two for a shared one) against the exact error,
  // instead of the p-bit that quantizes each endpoint nearest.
  bool pbit_search;
  // The winner's pass (its assignment and steps) with the neighbouring
  // indices tried, where the candidates' fits go without (exact_indices off).
  bool exact_winner;
  // Each refinement's least-squares ends quantized jointly: for the indices
  // that gave them, every p-bit choice and, channel by channel, the two
  // codes either side of each end, scored by the error those indices would
  // give (a quadratic in the ends, so no texel is visited), the least kept;
  // instead of each end rounded to its nearest code.
  bool joint;
  // Seeds a fit starts from, each refined on its own, the first of least
  // error kept: the line's extent, then its ends moved out along the line
  // by one index step (the high end, the low end, both), so that the
  // extreme texels fall on an inner index.
  int seeds;
  // The winner's sets fitted again from the seeds after those (seeds to
  // winner_seeds - 1), each kept where its error is less, before its steps.
  int winner_seeds;
};

// Whether a level has a pass over the search's winners (steps or seeds).
inline constexpr bool has_winner_pass(const Bc7Level& l) { return l.winner_steps > 0 || l.winner_seeds > l.seeds; }

inline constexpr Bc7Level kBc7Levels[] = {
    //            p2  mode3 est2 p3  rot  isel  mode7 opaque-rot refine exact perturb winner pairs pbits exact-winner
    //            joint seeds winner-seeds
    /* fast   */ {1, false, 32, 0, 1, false, false, false, 1, false, 0, 0, false, false, false, false, 1, 1},
    /* normal */ {4, false, 64, 1, 1, false, true, false, 1, false, 0, 0, false, false, false, true, 1, 4},
    /* high   */ {12, false, 64, 2, 4, true, true, true, 1, false, 0, 2, true, false, true, true, 2, 4},
    /* max    */ {64, true, 64, 64, 4, true, true, true, 3, true, 0, 4, true, true, true, true, 4, 4},
};

inline const Bc7Level& bc7_level(Quality q) { return kBc7Levels[int(q)]; }

}  // namespace texproc
