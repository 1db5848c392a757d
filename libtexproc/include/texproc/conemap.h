// texproc/conemap.h: cone step maps (Dummer 2006) from heightmaps, and a CPU
// renderer that traces relief-mapped rays with them.
//
// Height 1 is the top of the relief, 0 the bottom; the relief is `depth`
// texture widths deep. The cone ratio of texel p is the smallest, over every
// texel q higher than p, of |p - q| / (depth * (h_q - h_p)), with |p - q| the
// distance between texel centres in texture coordinates (x / width, y / height),
// capped by max_ratio: the widest upward cone at p that no texel centre enters.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "texproc/filters.h"
#include "texproc/image.h"

namespace texproc {

// Conservative: no texel enters the cone (Dummer 2006). Relaxed (Policarpo
// and Oliveira, GPU Gems 3 chapter 18): the cone may contain relief, but a
// ray that enters the relief inside the cone cannot leave it there. Leaving
// needs a descent: a higher texel q with a lower 4-neighbour behind it, as
// seen from p (farther from p along that axis). The relaxed cone of p is the
// smallest ratio over those texels only, so it is never narrower than the
// conservative cone, and a relaxed step past the surface crosses it once:
// a binary search then finds the first hit.
enum class ConeMode { conservative, relaxed };

struct ConeMapOptions {
  float depth = 1.0f;                // relief depth in texture widths (> 0)
  float max_ratio = 1.0f;            // cap on the ratio (> 0); the map stores sqrt(ratio / max_ratio)
  WrapMode wrap = WrapMode::repeat;  // repeat: tiling reliefs see across the edges; clamp: they do not
  // Fast cones, never wider than exact, 0 = exact: the pyramid blocks next
  // to the texel's 8x8 cell are searched texel by texel, and a farther block
  // whose gap to the cell is at least fast_reach of its own sizes is not
  // opened: its highest texel (relaxed: its highest exit) counts at its
  // nearest texel. Larger reaches: wider cones, slower.
  int fast_reach = 0;
  ConeMode mode = ConeMode::conservative;
  // Conservative cones that stay safe when a renderer interpolates the
  // heights and the ratios bilinearly (see cone_ratios). Not with relaxed.
  bool bilinear_safe = false;
  // Where set: the fraction of the search done (rows of cells; brute force:
  // rows of texels), one call at a time from worker threads, rising to 1.
  std::function<void(double)> progress;
};

// Exact cone ratios (conservative or relaxed, o.mode) of a width x height
// field of heights in [0, 1] (row-major), by branch and bound over a maximum
// mip pyramid: a block is skipped when even its highest texel at its nearest
// point cannot narrow the cone found so far, and blocks are visited nearest
// first, so the bound tightens early. Cones are searched a cell of 8x8
// texels at a time, SIMD across the cell's texels. The result equals
// brute force bit for bit (tested), for any thread count and SIMD target.
//
// bilinear_safe: a renderer that samples the height and the ratio with
// bilinear filtering puts the apex between texel centres, on the bilinear
// surface, with a ratio mixed from four texels, and classic cones can then
// contain surface points. The ratio at p is made safe for every apex within
// one texel of p (each of the four texels mixed is safe there, so their mix
// is): surface within 3 texels of p is bounded by the largest height step
// between 4-neighbours there (a Lipschitz bound, ratio <= 1 / (depth * L));
// farther surface by its cell's highest corner, counted from the lowest of
// p's 3x3 texels at the texel distance less 2 texels per axis. Never wider
// than the classic cone (tested, with the safety itself, on the continuous
// bilinear surface).
//
// Throws Error{bad_arguments} for invalid options (mirror wrap is not
// supported; bilinear_safe is conservative only).
std::vector<float> cone_ratios(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o);

// cone_ratios a band of rows at a time, for maps too large to hold their
// ratios beside the heights: the search's pyramids are built once, and
// rows() computes only the rows asked for (bit for bit those rows of
// cone_ratios). bilinear_safe needs windows over the whole map: with it the
// ratios are computed whole at construction. `heights` must outlive the
// object; rows() may be called from one thread at a time.
class ConeRatioSearch {
 public:
  ConeRatioSearch(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o);
  ~ConeRatioSearch();
  ConeRatioSearch(const ConeRatioSearch&) = delete;
  ConeRatioSearch& operator=(const ConeRatioSearch&) = delete;
  // Ratios of rows [y0, y1) into out (width floats per row). o.progress
  // hears the fraction of the map's rows done up to y1.
  void rows(int y0, int y1, float* out) const;
  // Rows [y0, y1) of cone_map_image(heights, cone_ratios(...), ...), a band
  // of rows at a time, into `dst`, rows `row_stride` bytes apart. Where
  // `ratio_sum` is set, the rows' ratios are added to it in row order.
  void map_rows(PixelType type, int channels, int y0, int y1, void* dst, std::size_t row_stride,
                double* ratio_sum = nullptr) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// The O(N^2)-per-texel definition, for tests and small maps.
std::vector<float> cone_ratios_brute_force(const std::vector<float>& heights, int width, int height,
                                           const ConeMapOptions& o);

// A cone map image: R = height, G = sqrt(ratio / max_ratio), rounded down
// (so quantization never widens a cone), in `type` (u8, u16 or f32), with
// 2 (RG), 3 (B = 0) or 4 channels (B = 0, A = 1).
Image cone_map_image(const std::vector<float>& heights, const std::vector<float>& ratios, int width, int height,
                     const ConeMapOptions& o, PixelType type, int channels = 3);
// Rows [y0, y1) of that image into `dst`, rows `row_stride` bytes apart
// (for writers that take rows as they go: image.h's RowSource).
void cone_map_rows(const std::vector<float>& heights, const std::vector<float>& ratios, int width, int height,
                   const ConeMapOptions& o, PixelType type, int channels, int y0, int y1, void* dst,
                   std::size_t row_stride);

// Ray tracing through the relief, in texture space. A ray starts at (u, v)
// on the top plane (height 1) and moves by (du, dv) per unit of height
// descended (the view direction's horizontal part over its vertical part).
struct ReliefHit {
  float u = 0, v = 0, height = 0;
  int steps = 0;     // height-map lookups
  bool hit = false;  // false if the ray left the texture (clamp) without a hit
};

// The exact first hit on the texel-centre (nearest-texel) surface: a grid
// traversal that visits every texel the ray crosses. The tests' reference.
ReliefHit trace_exact(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o, float u,
                      float v, float du, float dv);
// What shaders do without a cone map: `linear_steps` equal steps down the
// depth, then a binary refinement. Can miss thin features.
ReliefHit trace_linear(const std::vector<float>& heights, int width, int height, const ConeMapOptions& o, float u,
                       float v, float du, float dv, int linear_steps = 64, int binary_steps = 8);
// Conservative cone stepping with `ratios` while the steps are longer than a
// tenth of a texel, then the exact grid traversal for the rest: the hit is
// the exact first hit as long as no cone step crossed the surface.
ReliefHit trace_cones(const std::vector<float>& heights, const std::vector<float>& ratios, int width, int height,
                      const ConeMapOptions& o, float u, float v, float du, float dv, int binary_steps = 8);

// Relaxed cone stepping (GPU Gems 3, chapter 18) with relaxed `ratios`: cone
// steps until a step ends below the surface, then `binary_steps` of binary
// search between the last point above and the first below. Relaxed cones
// let a step cross the surface once, so the search finds the first hit.
ReliefHit trace_relaxed(const std::vector<float>& heights, const std::vector<float>& ratios, int width, int height,
                        const ConeMapOptions& o, float u, float v, float du, float dv, int binary_steps = 16);

// A side-by-side preview: the relief lit and rendered at `view_angle_deg`
// from the normal by linear search (64 steps) + binary refinement, by cone
// stepping (conservative `ratios`) and, when `relaxed` is not empty, by
// relaxed cone stepping, each with a heat map of its height-map lookups per
// pixel below it (blue few, red many): an RGB8 image of 2 (or 3) x 2 panels
// of `size` x `size`.
Image render_preview(const std::vector<float>& heights, const std::vector<float>& ratios, int width, int height,
                     const ConeMapOptions& o, int size, float view_angle_deg, const std::vector<float>& relaxed = {});

}  // namespace texproc
