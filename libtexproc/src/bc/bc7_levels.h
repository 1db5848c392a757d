// BC7's quality levels: one row per level, every knob a level sets.
// Changing a level is one edit here. What each knob buys, measured on the
// corpus: docs/compression.md, "BC7 encoder".
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
};

inline constexpr Bc7Level kBc7Levels[] = {
    //            p2  mode3 est2 p3  rot  isel  mode7 refine exact perturb
    /* fast   */ {1, false, 32, 0, 1, false, false, 1, false, 0},
    /* normal */ {2, true, 64, 1, 1, false, true, 2, true, 0},
    /* high   */ {12, true, 64, 4, 4, true, true, 3, true, 1},
    /* max    */ {64, true, 64, 64, 4, true, true, 6, true, 4},
};

inline const Bc7Level& bc7_level(Quality q) { return kBc7Levels[int(q)]; }

}  // namespace texproc
