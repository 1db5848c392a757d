// BC6H's quality levels: one row per level, every knob a level sets.
// Changing a level is one edit here. What each knob buys, measured on the
// corpus's HDR images: docs/design/encoders.md, "BC6H encoder".
#pragma once

#include "texproc/block_encode.h"

namespace texproc {

struct Bc6hLevel {
  // The modes tried: bit k for bptc::kBc6hModes[k] (0-9: two regions,
  // 10-13: one region). Blocks of one colour always get mode 13 (16-bit
  // endpoints: exact for every half) and nothing else.
  unsigned modes;
  // Two-region partitions kept per block after the estimate (the residual
  // off each region's principal axis, all 32 scanned), each fitted once and
  // quantized in every two-region mode tried.
  int partitions;
  // Least-squares endpoints for the indices, then indices for the quantized
  // endpoints, up to this many times while the error falls.
  int refine;
};

inline constexpr unsigned kBc6hAllModes = 0x3FFF;

inline constexpr Bc6hLevel kBc6hLevels[] = {
    //             modes    partitions refine
    /* fast   */ {0x3E23, 1, 0},  // one region: all; two: 0, 1, 5, 9 (numbers 0, 1, 14, 30)
    /* normal */ {0x3FFF, 2, 1},
    /* high   */ {0x3FFF, 8, 2},
    /* max    */ {0x3FFF, 32, 4},
};

inline const Bc6hLevel& bc6h_level(Quality q) { return kBc6hLevels[int(q)]; }

}  // namespace texproc
