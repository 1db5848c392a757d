// BC1's quality levels (also the colour half of BC2 and BC3): one row per
// level, every knob a level sets. Changing a level is one edit here. What
// each knob buys, measured on the corpus: docs/design/encoders.md, "BC1 encoder"
// and "Measured (BC1)".
#pragma once

#include "texproc/block_encode.h"

namespace texproc {

// The search sixteen blocks at a time (bc1_lanes.h).
struct Bc1LaneSearch {
  // Each texel at the nearest third of the extent along the principal axis,
  // one least-squares fit (`fast`: 627 MPix/s, 33.03 dB on bench_bc1's six
  // textures). Otherwise the extent's ends, two refits, the partition
  // variants below, one-step nudges and the three-colour mode (no black):
  // `normal` 64 MPix/s, 33.59 dB.
  bool thirds_fit;
  // Partition variants along the axis: the thirds shifted by -offsets..
  // offsets steps of 0.15 and stretched by -stretches..stretches steps of
  // 15%, (2 offsets + 1) x (2 stretches + 1) least-squares fits. 15 at
  // `normal` lift it from 33.46 to 33.59 dB for a fifth of its time.
  int variant_offsets, variant_stretches;
  // Every variant scored exactly and refitted once (`high`: 45 of them
  // match a full cluster fit at 15x its speed, 18.6 MPix/s, 33.62 dB);
  // otherwise the variants are ranked by their unquantized error and the
  // best two scored exactly.
  bool score_every_variant;
  // Punch-through (bc1a) blocks with transparent texels: 45 variants on
  // halves of the extent, then nudges, in the three-colour mode (35.10 dB
  // against 34.90 without, on the striped astronaut photo).
  bool punch_variants;
};

// The search one block at a time (bc1_encode.cpp): every block at `max`;
// at every level the blocks the lanes leave (one opaque colour) and the
// three-colour candidates of EncodeOptions::bc1_black.
struct Bc1BlockSearch {
  int refinements;     // least-squares refits from the principal axis' extent, each kept while it helps
  int cluster_rounds;  // cluster fits (969 splits for 16 texels), each along the best endpoints' axis so far
  int cluster_kept;    // the splits of each round scored exactly
  bool nudge;          // each quantized endpoint channel moved by one step while that helps
  // The lanes' block at this row's lane settings competes, so `max` is never
  // below `high` (it was, by 0.013 dB on a photo crop, before).
  bool lane_candidate;
};

struct Bc1Level {
  bool lanes;  // sixteen blocks at a time; false: block by block (`max`: 0.4 MPix/s, 33.625 dB)
  Bc1LaneSearch lane;
  Bc1BlockSearch block;
  // Blocks of exactly two colours try every pair of palette positions for
  // them (bc1_try_two_colours): 0.76-0.94 of the error on random pairs,
  // +0.00-0.02 dB on whole textures; `fast` keeps its speed.
  bool two_colours;
};

inline constexpr Bc1Level kBc1Levels[] = {
    //        lanes   thirds  offsets stretches every  punch    refine rounds kept nudge  lane_cand  two
    /* fast   */ {true, {true, 0, 0, false, false}, {1, 0, 0, false, false}, false},
    /* normal */ {true, {false, 2, 1, false, false}, {2, 0, 0, false, false}, true},
    /* high   */ {true, {false, 4, 2, true, true}, {4, 1, 3, true, false}, true},
    /* max    */ {false, {false, 4, 2, true, true}, {4, 3, 8, true, true}, true},
};

inline const Bc1Level& bc1_level(Quality q) { return kBc1Levels[int(q)]; }

}  // namespace texproc
