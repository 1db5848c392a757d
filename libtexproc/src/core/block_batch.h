// How many blocks the lane encoders (BC1, BC4, ETC1, EAC) take at a time:
// one block per SIMD lane, sixteen whatever the vector width, so that every
// target runs the same search in the same order. The one definition.
#pragma once

namespace texproc {
constexpr int kBlockBatch = 16;
}  // namespace texproc
