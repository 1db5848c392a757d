// BC1's per-texel work, SIMD and scalar twins with identical results: the
// block's colour moments, the range of its colours along an axis, each
// texel's nearest palette colour, and the sums of the least-squares endpoint
// fit. Sums are of integers (exact in any order); the one float expression
// (the projection onto an axis) is evaluated per texel in the same order by
// both twins, without FMA.
#pragma once

#include <cstdint>

namespace texproc {

// A block's texels as planes, prepared once per block.
struct Bc1Texels;
struct Bc1Moments;
struct Bc1LsSums;

// The kernels below as the dispatched target's twins, or the references
// under force_scalar(), resolved once: a block's search calls through the
// table its texels carry instead of dispatching at every candidate.
struct Bc1Kernels {
  void (*moments)(const Bc1Texels&, Bc1Moments&);
  void (*project_range)(const Bc1Texels&, const float*, float&, float&);
  std::int32_t (*nearest)(const Bc1Texels&, const int (*)[3], int, std::uint8_t*);
  void (*ls_sums)(const Bc1Texels&, const std::uint8_t*, const int*, int, Bc1LsSums&);
};
Bc1Kernels bc1_kernels();

struct Bc1Texels {
  std::int32_t r[16], g[16], b[16];
  std::int32_t transparent[16];  // 1: takes index 3 (three-colour mode), no error
  Bc1Kernels k = bc1_kernels();  // resolved once per block
};

// Over the opaque texels: their count, colour sums and products
// (rr, rg, rb, gg, gb, bb).
struct Bc1Moments {
  std::int32_t n = 0;
  std::int32_t sum[3] = {};
  std::int32_t sq[6] = {};
};

// Least-squares sums for codes with weights: a texel with code c pulls the
// second endpoint with weight w = weight[c] and the first with den - w
// (weight -1: the texel is left out). aa = sum (den - w)^2, ab, bb likewise;
// at/bt: the colour sums weighted by den - w and w.
struct Bc1LsSums {
  std::int32_t aa = 0, ab = 0, bb = 0;
  std::int32_t at[3] = {}, bt[3] = {};
};

void bc1_moments(const Bc1Texels& tx, Bc1Moments& m);
// Least and greatest r*axis[0] + g*axis[1] + b*axis[2] over the opaque texels.
void bc1_project_range(const Bc1Texels& tx, const float axis[3], float& lo, float& hi);
// candidates: 3 or 4 palette entries; codes[i] per texel (transparent: 3);
// returns the total squared RGB error.
std::int32_t bc1_nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]);
void bc1_ls_sums(const Bc1Texels& tx, const std::uint8_t codes[16], const int weight[4], int den, Bc1LsSums& s);

namespace ref {
void bc1_moments(const Bc1Texels& tx, Bc1Moments& m);
void bc1_project_range(const Bc1Texels& tx, const float axis[3], float& lo, float& hi);
std::int32_t bc1_nearest(const Bc1Texels& tx, const int pal[4][3], int candidates, std::uint8_t codes[16]);
void bc1_ls_sums(const Bc1Texels& tx, const std::uint8_t codes[16], const int weight[4], int den, Bc1LsSums& s);
}  // namespace ref

}  // namespace texproc
