// EAC's quality levels (R11, RG11, signed, and ETC2 RGBA's 8-bit alpha):
// one row per level, every knob a level sets. Changing a level is one edit
// here. What each knob buys, measured on the corpus: docs/design/encoders.md,
// "ETC1, ETC2 and EAC" (the EAC item) and "What the formats allow".
#pragma once

#include "texproc/block_encode.h"

namespace texproc::etc {

// For each of the 16 tables the multiplier m0 is estimated from the block's
// range and the base b0 from its centre; the search tries multipliers
// m0 - mult_below .. m0 + mult_above (within 0..15) and, for each, bases
// within +-base_radius of the base that centres it.
struct EacWindow {
  int mult_below, mult_above, base_radius;
};

struct EacLevel {
  // Sixteen blocks at a time (eac_lanes.h), searching `lanes_window`; false:
  // block by block, `block_window` (`max`: every multiplier, +-8 bases).
  bool lanes;
  EacWindow lanes_window;
  EacWindow block_window;
};

// `normal`'s 0..+1 with +-2 bases and `high`'s -1..+2 with +-5 (on a coarse
// 8-bit grid of skewed values the best base is often 3-5 from the centred
// one) gave 0.08 and 0.16 dB more on the heightmaps than the windows before
// them (-1..+2 with +-1, -2..+3 with +-2).
inline constexpr EacLevel kEacLevels[] = {
    //            lanes   lanes window   block window
    /* fast   */ {true, {0, 0, 0}, {0, 0, 0}},
    /* normal */ {true, {0, 1, 2}, {0, 0, 0}},
    /* high   */ {true, {1, 2, 5}, {0, 0, 0}},
    /* max    */ {false, {1, 2, 5}, {15, 16, 8}},
};

inline const EacLevel& eac_level(Quality q) { return kEacLevels[int(q)]; }

}  // namespace texproc::etc
