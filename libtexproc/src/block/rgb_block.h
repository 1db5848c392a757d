// Shared block primitives for 16 RGB texels (BC1, BC2/BC3 colour, ETC2 T/H), SIMD and scalar twins with identical
// results: the block's colour moments, the range of its colours along an axis, each texel's nearest palette colour, and
// the sums of the least-squares endpoint fit. Sums are of integers (exact in any order); the one float expression (the
// projection onto an axis) is evaluated per texel in the same order by both twins, without FMA.
#pragma once

#include <cstdint>

namespace texproc {

// A block's texels as planes, prepared once per block.
struct RgbBlock;
struct RgbMoments;
struct RgbLsSums;

// The kernels below as the dispatched target's twins, or the references
// under force_scalar(), resolved once: a block's search calls through the
// table its texels carry instead of dispatching at every candidate.
struct RgbBlockKernels {
  void (*moments)(const RgbBlock&, RgbMoments&);
  void (*project_range)(const RgbBlock&, const float*, float&, float&);
  std::int32_t (*nearest)(const RgbBlock&, const int (*)[3], int, std::uint8_t*);
  void (*ls_sums)(const RgbBlock&, const std::uint8_t*, const int*, int, RgbLsSums&);
};
RgbBlockKernels rgb_block_kernels();

struct RgbBlock {
  std::int32_t r[16], g[16], b[16];
  std::int32_t transparent[16];             // 1: takes index 3 (three-colour mode), no error
  RgbBlockKernels k = rgb_block_kernels();  // resolved once per block
};

// Over the opaque texels: their count, colour sums and products
// (rr, rg, rb, gg, gb, bb).
struct RgbMoments {
  std::int32_t n = 0;
  std::int32_t sum[3] = {};
  std::int32_t sq[6] = {};
};

// Least-squares sums for codes with weights: a texel with code c pulls the
// second endpoint with weight w = weight[c] and the first with den - w
// (weight -1: the texel is left out). aa = sum (den - w)^2, ab, bb likewise;
// at/bt: the colour sums weighted by den - w and w.
struct RgbLsSums {
  std::int32_t aa = 0, ab = 0, bb = 0;
  std::int32_t at[3] = {}, bt[3] = {};
};

void rgb_moments(const RgbBlock& tx, RgbMoments& m);
// Least and greatest r*axis[0] + g*axis[1] + b*axis[2] over the opaque texels.
void rgb_project_range(const RgbBlock& tx, const float axis[3], float& lo, float& hi);
// candidates: 3 or 4 palette entries; codes[i] per texel (transparent: 3);
// returns the total squared RGB error.
std::int32_t rgb_palette_nearest(const RgbBlock& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]);
void rgb_ls_sums(const RgbBlock& tx, const std::uint8_t codes[16], const int weight[4], int den, RgbLsSums& s);

namespace ref {
void rgb_moments(const RgbBlock& tx, RgbMoments& m);
void rgb_project_range(const RgbBlock& tx, const float axis[3], float& lo, float& hi);
std::int32_t rgb_palette_nearest(const RgbBlock& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]);
void rgb_ls_sums(const RgbBlock& tx, const std::uint8_t codes[16], const int weight[4], int den, RgbLsSums& s);
}  // namespace ref

}  // namespace texproc
