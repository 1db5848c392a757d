// The cone map's branch and bound (conemap.cpp describes it): the maximum
// pyramid, the relaxed cones' exit pyramids, and the walk of the pyramid one
// 8x8 cell of apex texels at a time (cone_search.cpp), scanning the blocks
// that survive with the SIMD kernels of cone_cells.h.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "conemap/cone_cells.h"
#include "texproc/conemap.h"

namespace texproc::cone {

// Relaxed cones count a higher texel q only if a 4-neighbour behind it, as
// seen from p (one step farther from p along x or y; both ways when p and q
// share that coordinate), is lower: the ray can leave the relief there.
// With clamp, no neighbour exists past the edge (a ray leaves the texture).
struct Behind {
  const std::vector<float>& h;
  int W, H;
  bool repeat;
  bool lower(int qx, int qy, float hq, int sx, int sy) const {
    int nx = qx + sx, ny = qy + sy;
    if (repeat) {
      nx = (nx + W) % W;
      ny = (ny + H) % H;
    } else if (nx < 0 || ny < 0 || nx >= W || ny >= H) {
      return false;
    }
    return h[std::size_t(ny) * W + nx] < hq;
  }
  // The rule of exit_directions (cone_cells.h), on the heights themselves.
  bool exits(int px, int py, int qx, int qy, float hq) const {
    const unsigned d = detail::exit_directions(px, py, qx, qy, W, H, repeat);
    return ((d & 1) && lower(qx, qy, hq, 1, 0)) || ((d & 2) && lower(qx, qy, hq, -1, 0)) ||
           ((d & 4) && lower(qx, qy, hq, 0, 1)) || ((d & 8) && lower(qx, qy, hq, 0, -1));
  }
};

// The SIMD kernels' view of the map and options (cone_cells.h); `shrink`:
// texels taken off each axis distance (--bilinear-safe).
detail::ConeGeometry geometry(int W, int H, const ConeMapOptions& o, int shrink);

struct Pyramid {
  const float* base = nullptr;          // level 0: the heights (not copied)
  std::vector<std::vector<float>> max;  // levels 1 and up (max[0] unused)
  std::vector<int> w, h;
  const float* level(int k) const { return k == 0 ? base : max[std::size_t(k)].data(); }
  int levels() const { return int(w.size()); }
};

// `heights` must outlive the pyramid.
Pyramid build_pyramid(const std::vector<float>& heights, int W, int H);

// Relaxed cones on the cell walk: the exit rule per texel, and four maximum
// pyramids of the texels with a lower +x, -x, +y or -y neighbour (-1
// elsewhere). A block wholly on one side of the cell along an axis can only
// hold exits that way for every apex of the cell, so its bound height takes
// the maximum of the matching pyramids.
struct RelaxedBounds {
  std::vector<unsigned char> exit_bits;
  std::vector<std::vector<float>> exit_heights;  // level 0 of each pyramid
  std::vector<Pyramid> exit_pyr;
};
RelaxedBounds relaxed_bounds(const std::vector<float>& heights, int W, int H, bool repeat);

// Squared cone ratios, a cell of 8x8 apex texels at a time: one walk of the
// pyramid per cell, nearest block first, a block skipped when even the
// cell's lowest apex at the cell's nearest point could not narrow the widest
// cone in the cell, or no apex with its own cone and distance could be
// narrowed (and, for classic cones, by the slope bound); the blocks of 8x8
// texels that survive are scanned against every apex row that a row-wise
// bound cannot rule out, SIMD across the cell (cone_cells.h). With
// o.fast_reach, the blocks next to the cell are still scanned, but a farther
// block whose gap to the cell is at least fast_reach of its own sizes counts
// as one obstacle. `apex`: the apex heights (the heights, or their 3x3
// minima for --bilinear-safe, with distances shrunk by `shrink`);
// `relaxed`: relaxed cones (their exits and bound heights).
std::vector<float> cell_cones(const std::vector<float>& heights, const std::vector<float>& apex, int W, int H,
                              const ConeMapOptions& o, const Pyramid& pyr, int shrink,
                              const RelaxedBounds* relaxed = nullptr);

// cell_cones a band of cell rows at a time: the search's bounds are built
// once, and each call fills the squared ratios of texel rows 8 cy0 up to
// 8 cy1 (or the map's end) into `out`, rows of W floats from row 8 cy0.
// Every argument of the constructor must outlive the object.
class CellCones {
 public:
  CellCones(const std::vector<float>& heights, const std::vector<float>& apex, int W, int H, const ConeMapOptions& o,
            const Pyramid& pyr, int shrink, const RelaxedBounds* relaxed = nullptr);
  ~CellCones();
  int cell_rows() const;
  void rows(int cy0, int cy1, float* out, const std::function<void(double)>& progress) const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace texproc::cone
