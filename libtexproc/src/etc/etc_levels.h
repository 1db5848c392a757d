// ETC1's and ETC2's quality levels (ETC1 RGB, ETC2 RGB, ETC2 RGBA's colour,
// ETC2 punch-through): one row per level, every knob a level sets. Changing
// a level is one edit here. What each knob buys, measured on the corpus:
// docs/design/encoders.md, "ETC1, ETC2 and EAC" and "Measured (ETC)".
#pragma once

#include "texproc/block_encode.h"

namespace texproc::etc {

// The lanes' ETC1 search for opaque blocks, sixteen at a time (etc_lanes.h).
enum class Etc1Lanes {
  fast,    // etc1_fast_lanes: three tables at the half's mean (229 MPix/s, 32.90 dB on bench_etc's textures)
  normal,  // etc1_search_lanes: every table exactly, the best two seeded and re-centred (40.6, 33.72)
  high,    // etc1_search_lanes, high: every table seeded, +-1 bases, every delta pair (5.7, 34.00)
};

// The ETC1 modes block by block (etc1_encode.cpp: fit_half, search_etc1_modes):
// punch-through blocks with transparent texels at every level, and `max`.
struct Etc1BlockSearch {
  bool all_tables;                         // every table scored at the mean; else the three nearest the half's spread
  int refined_tables;                      // the best of them seeded from the extremes and re-centred
  int seeds;                               // seeds a refined table: 2 (+-its far modifier), 4 (+-both)
  int neighbour_tables, neighbour_radius;  // the best tables' bases searched within +-radius per channel
  bool individual_always;                  // the individual mode tried even where the differential delta reaches
};

// ETC2's planar, T and H modes (etc2_modes.cpp).
struct Etc2Modes {
  bool search;  // tried against the ETC1 block (`fast`: ETC1's modes only, 228 MPix/s, 32.90 dB)
  // After the lanes' ETC1 block, T and H only where it leaves more than this
  // squared RGB error per texel (`normal`: 120 against 75 costs 0.005 dB for
  // a fifth more speed); 0: always.
  int t_h_above;
  int planar_radius;        // O, H and V searched within +-radius of the least-squares plane
  bool t_h_every_distance;  // all eight T/H distances; else the three nearest the clusters' spread
  // Where T or H come within a quarter of the other modes' error, each
  // centre also rounded down and up (+0.09 dB at `high`).
  bool t_h_requantize;
  // `fast`: blocks of exactly two colours try T and H (random pairs: 40
  // times less error; whole textures +0.01 to +0.06 dB at the same speed).
  bool two_colour_t_h;
};

struct EtcLevel {
  bool lanes;  // opaque blocks sixteen at a time; false: every block block by block (`max`)
  Etc1Lanes lane;
  // `max`: the lanes' block (at `lane`) is the first candidate, so it is never below `high`.
  bool lane_candidate;
  Etc1BlockSearch block;
  Etc2Modes etc2;
};

inline constexpr EtcLevel kEtcLevels[] = {
    // lanes, lane, lane_candidate,
    //   {all_tables, refined, seeds, neighbour_tables, radius, individual_always},
    //   {etc2 search, t_h_above, planar_radius, every_distance, requantize, two_colour_t_h}
    /* fast   */ {true, Etc1Lanes::fast, false, {false, 0, 0, 0, 0, false}, {false, 0, 0, false, false, true}},
    /* normal */ {true, Etc1Lanes::normal, false, {true, 3, 2, 0, 0, false}, {true, 120, 0, false, false, false}},
    /* high   */ {true, Etc1Lanes::high, false, {true, 8, 4, 2, 1, true}, {true, 0, 1, true, true, false}},
    /* max    */ {false, Etc1Lanes::high, true, {true, 8, 4, 8, 2, true}, {true, 0, 1, true, true, false}},
};

inline const EtcLevel& etc_level(Quality q) { return kEtcLevels[int(q)]; }

}  // namespace texproc::etc
