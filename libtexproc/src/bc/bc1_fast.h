// BC1's `fast` and `normal` encoders for opaque blocks, sixteen blocks at a
// time (a block per SIMD lane), SIMD and scalar twins with identical bytes.
//
// `fast`, per block: the principal axis of the colours (power iteration on the
// covariance, from its row of greatest variance), the colours' extent along
// it as endpoints, each texel's nearest colour of the four-colour palette,
// then one least-squares refit of the endpoints for those indices, kept
// where it lowers the error. `normal` adds a second refit, then nudges each
// quantized endpoint channel by one step while that lowers the error (at
// most four passes over the twelve moves), and, with `three`, tries the
// three-colour mode (no black) from the principal-axis ends refitted once.
// Integer sums, and float expressions evaluated
// in the same order by both twins (no FMA; divisions and square roots are
// correctly rounded on every target).
#pragma once

#include <cstdint>

namespace texproc {

constexpr int kBc1Batch = 16;

// texel[i][k]: texel i (row by row) of block k as R | G << 8 | B << 16
// (alpha ignored). Blocks of one colour are left to the caller
// (`handled[k]` false; their bytes are not written): the single-colour
// tables encode them.
void bc1_fast_blocks(const std::uint32_t texel[16][kBc1Batch], int count, int level, bool three,
                     std::uint8_t out[][8], bool handled[]);

namespace ref {
void bc1_fast_blocks(const std::uint32_t texel[16][kBc1Batch], int count, int level, bool three,
                     std::uint8_t out[][8], bool handled[]);
}  // namespace ref

}  // namespace texproc
