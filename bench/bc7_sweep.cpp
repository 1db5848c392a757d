// BC7's knob space, measured: each row of knobs (bc7_levels.h's Bc7Level)
// encodes bench_bc7's images (256x256 centred crops of the corpus's 15 colour
// images, opaque) on one thread and prints its speed (the median of
// --reps timings, MPix/s) and PSNR over RGB pooled over every crop. The
// rows come from the command line, one argument a row of fourteen numbers
// in Bc7Level's order (`2,1,64,1,1,0,1,0,2,1,0,0,0,0`), or, with none, the
// grid below: the knobs one at a time from each level, and their pairs,
// which is how the levels' rows were chosen (docs/compression.md).
// Rows are timed interleaved, rep by rep, so that a slow spell of a busy
// machine falls on every row alike.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bc/bc7_lanes.h"
#include "bench_common.h"
#include "block/block_gather.h"

using namespace texproc;

namespace {

struct Crop {
  const Image* image;
  std::vector<std::uint32_t> texel;  // [batch][16][kBc7Batch]
  int blocks;
};

Crop gather(const Image& img) {
  Crop c{&img, {}, (img.width() / 4) * (img.height() / 4)};
  const int bw = img.width() / 4, batches = (c.blocks + kBc7Batch - 1) / kBc7Batch;
  c.texel.assign(std::size_t(batches) * 16 * kBc7Batch, 0);
  for (int b = 0; b < c.blocks; ++b) {
    const int bx = b % bw, by = b / bw;
    for (int i = 0; i < 16; ++i) {
      const std::uint8_t* px = img.row<const std::uint8_t>(4 * by + i / 4) + 4 * (4 * bx + i % 4);
      c.texel[(std::size_t(b / kBc7Batch) * 16 + i) * kBc7Batch + b % kBc7Batch] = pack_texel(px);
    }
  }
  return c;
}

std::vector<std::uint8_t> encode(const Crop& c, const Bc7Level& level) {
  std::vector<std::uint8_t> out(std::size_t(c.blocks) * 16);
  bc7_encode_lanes(reinterpret_cast<const Bc7Texels*>(c.texel.data()), c.blocks, level, reinterpret_cast<std::uint8_t(*)[16]>(out.data()));
  return out;
}

bool parse(const std::string& s, Bc7Level& l) {
  std::vector<int> v;
  std::stringstream in(s);
  for (std::string f; std::getline(in, f, ',');) v.push_back(std::atoi(f.c_str()));
  if (v.size() != 14) return false;
  l = Bc7Level{v[0], v[1] != 0, v[2], v[3], v[4], v[5] != 0, v[6] != 0, v[7] != 0, v[8], v[9] != 0, v[10], v[11], v[12] != 0, v[13] != 0};
  return true;
}

std::string row(const Bc7Level& l) {
  char b[96];
  std::snprintf(b, sizeof b, "%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d", l.partitions2, l.mode3, l.estimated2, l.partitions3, l.rotations,
                l.index_selection, l.mode7, l.opaque_rotated, l.refine, l.exact_indices, l.perturb, l.winner_steps, l.pair_steps,
                l.pbit_search);
  return b;
}

// Each level, and each level with one knob moved a step either way.
std::vector<Bc7Level> grid() {
  std::vector<Bc7Level> g;
  for (const Bc7Level& base : kBc7Levels) {
    if (&base == &kBc7Levels[3]) break;  // max: too slow to sweep
    g.push_back(base);
    auto add = [&](auto edit) {
      Bc7Level l = base;
      edit(l);
      if (row(l) != row(base)) g.push_back(l);
    };
    add([](Bc7Level& l) { l.partitions2 = std::max(1, l.partitions2 / 2); });
    add([](Bc7Level& l) { l.partitions2 = std::min(64, l.partitions2 * 2); });
    add([](Bc7Level& l) { l.estimated2 = l.estimated2 == 64 ? 32 : 64; });
    add([](Bc7Level& l) { l.partitions3 = std::max(0, l.partitions3 / 2); });
    add([](Bc7Level& l) { l.partitions3 = std::min(64, std::max(1, l.partitions3 * 2)); });
    add([](Bc7Level& l) { l.mode3 = !l.mode3; });
    add([](Bc7Level& l) { l.refine = std::max(0, l.refine - 1); });
    add([](Bc7Level& l) { l.refine = l.refine + 1; });
    add([](Bc7Level& l) { l.exact_indices = !l.exact_indices; });
    add([](Bc7Level& l) { l.winner_steps = l.winner_steps ? 0 : 1; });
    add([](Bc7Level& l) { l.winner_steps = l.winner_steps ? l.winner_steps / 2 : 2; });
    add([](Bc7Level& l) { l.opaque_rotated = !l.opaque_rotated, l.rotations = l.opaque_rotated ? 4 : l.rotations; });
    add([](Bc7Level& l) { l.pbit_search = !l.pbit_search; });
    add([](Bc7Level& l) { l.pair_steps = !l.pair_steps; });
  }
  return g;
}

}  // namespace

int main(int argc, char** argv) {
  int reps = 3;
  std::vector<Bc7Level> rows;
  for (int a = 1; a < argc; ++a) {
    const std::string s = argv[a];
    Bc7Level l{};
    if (s.rfind("--reps=", 0) == 0) {
      reps = std::max(1, std::atoi(s.c_str() + 7));
    } else if (parse(s, l)) {
      rows.push_back(l);
    } else {
      std::fprintf(stderr, "bc7_sweep: '%s' is not a row of 14 comma-separated knobs (bc7_levels.h's order) or --reps=N\n", s.c_str());
      return 2;
    }
  }
  if (rows.empty()) rows = grid();
  std::vector<Crop> crops;
  double pixels = 0;
  for (const Image& img : bench::centred_crops()) crops.push_back(gather(img)), pixels += double(img.width()) * img.height();
  std::vector<std::vector<double>> seconds(rows.size());
  std::vector<double> se(rows.size(), 0);
  for (int r = 0; r < reps; ++r)
    for (std::size_t k = 0; k < rows.size(); ++k) {
      double t = 0;
      for (const Crop& c : crops) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<std::uint8_t> blocks = encode(c, rows[k]);
        t += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (r == 0) se[k] += bench::squared_error_rgb(*c.image, TexelFormat::bc7_unorm, blocks);
      }
      seconds[k].push_back(t);
    }
  std::printf("%-40s %9s %8s\n", "knobs (bc7_levels.h order)", "MPix/s", "PSNR");
  for (std::size_t k = 0; k < rows.size(); ++k) {
    std::sort(seconds[k].begin(), seconds[k].end());
    const double psnr = 10 * std::log10(255.0 * 255.0 / (se[k] / (3.0 * pixels)));
    std::printf("%-40s %9.3f %8.3f\n", row(rows[k]).c_str(), pixels / seconds[k][seconds[k].size() / 2] / 1e6, psnr);
  }
  return 0;
}
