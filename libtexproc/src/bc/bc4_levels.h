// BC4's quality levels (also BC5's two channels and BC3's alpha): one row
// per level, every knob a level sets. Changing a level is one edit here.
// What each knob buys, measured on the corpus: docs/design/encoders.md, "BC4/BC5
// encoder" and "Measured (BC4, BC5)".
#pragma once

#include "texproc/block_encode.h"

namespace texproc {

// The search sixteen blocks at a time (bc4_lanes.h). Every level starts from
// the values' range rounded outwards (with the narrow-range and six-value
// candidates): `fast`, 682 MPix/s, 50.35 dB on bench_bc4's heightmaps.
struct Bc4LaneSearch {
  // Per mode, least-squares endpoints for the codes, twice while that helps
  // (`normal`: 236 MPix/s, 51.71 dB).
  bool refine;
  // Every pair within +-window of the refined endpoints, same mode (+-1:
  // 0.53 dB below the exact optimum on 7,427 heightmap blocks; +-2 alone
  // 0.41 dB).
  int window;
  // Partition variants per mode: the values on the mode's grid, the grid
  // shifted by -offsets..offsets steps of 0.15 and stretched by
  // -stretches..stretches steps of 10%, each a least-squares fit (`high`'s
  // 45 a mode with +-2: 0.021 dB below the optimum, 34.7 MPix/s, 52.21 dB).
  bool variants;
  int variant_offsets, variant_stretches;
};

struct Bc4Level {
  // Sixteen blocks at a time. False: every endpoint pair in both modes
  // (65,536), pruned by partial sums from just above the error of the
  // block `lane` gives (so never below it), block by block.
  bool lanes;
  Bc4LaneSearch lane;
};

inline constexpr Bc4Level kBc4Levels[] = {
    //            lanes   refine window variants offsets stretches
    /* fast   */ {true, {false, 0, false, 0, 0}},
    /* normal */ {true, {true, 1, false, 0, 0}},
    /* high   */ {true, {true, 2, true, 4, 2}},
    /* max    */ {false, {true, 2, true, 4, 2}},
};

inline const Bc4Level& bc4_level(Quality q) { return kBc4Levels[int(q)]; }

}  // namespace texproc
