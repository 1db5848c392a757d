// BC7's knob space, measured: each row of knobs (bc7_levels.h's Bc7Level)
// encodes bench_bc7's images (256x256 centred crops of the corpus's 15 colour
// images, opaque) on one thread and prints its speed (the median of
// --reps timings, MPix/s) and PSNR over RGB pooled over every crop. The
// rows come from the command line, one argument a row of eighteen numbers
// in Bc7Level's order (`4,0,64,1,1,0,1,0,1,0,0,0,0,0,0,1,1,4`), or a grid
// (--grid=normal, --grid=high: every combination of the search knobs near
// a level; --grid=seeds-normal, --grid=seeds-high: the fit's seeds, joint
// quantization and winner seeds beside them; below), or, with none, the
// levels fast, normal and high.
// Rows are timed interleaved, rep by rep, so that a slow spell of a busy
// machine falls on every row alike.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iterator>
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
  bc7_encode_lanes(reinterpret_cast<const Bc7Texels*>(c.texel.data()), c.blocks, level,
                   reinterpret_cast<std::uint8_t(*)[16]>(out.data()));
  return out;
}

bool parse(const std::string& s, Bc7Level& l) {
  std::vector<int> v;
  std::stringstream in(s);
  for (std::string f; std::getline(in, f, ',');) v.push_back(std::atoi(f.c_str()));
  if (v.size() != 18) return false;
  l = Bc7Level{v[0],      v[1] != 0, v[2],  v[3],       v[4],       v[5] != 0,  v[6] != 0,  v[7] != 0, v[8],
               v[9] != 0, v[10],     v[11], v[12] != 0, v[13] != 0, v[14] != 0, v[15] != 0, v[16],     v[17]};
  return true;
}

std::string row(const Bc7Level& l) {
  char b[96];
  std::snprintf(b, sizeof b, "%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d,%d", l.partitions2, l.mode3,
                l.estimated2, l.partitions3, l.rotations, l.index_selection, l.mode7, l.opaque_rotated, l.refine,
                l.exact_indices, l.perturb, l.winner_steps, l.pair_steps, l.pbit_search, l.exact_winner, l.joint,
                l.seeds, l.winner_seeds);
  return b;
}

// The knob space around a level, every combination (a factorial grid): the
// rows whose Pareto front docs/compression.md shows and the levels were
// chosen from. `normal`: one rotation set or all four (opaque), 1-4
// two-subset partitions with and without mode 3, 0-2 three-subset ones, 1-2
// refinements, 0-2 rounds of winner steps with and without exact indices
// there (the candidates' fits without). `high`: 6-24 / 2-8 partitions,
// mode 3, 2-3 refinements, exact indices in the fits or in the winner's
// pass only, pair steps, p-bit search (every rotation and index selection,
// two rounds of winner steps).
std::vector<Bc7Level> grid(const std::string& name) {
  std::vector<Bc7Level> g;
  auto level = [](int p2, bool m3, int p3, int rot, bool isel, bool orot, int refine, bool exact, int winner,
                  bool pairs, bool pbits, bool ew) {
    return Bc7Level{p2, m3, 64, p3, rot, isel, true, orot, refine, exact, 0, winner, pairs, pbits, ew, false, 1, 1};
  };
  if (name == "normal") {
    for (int p2 : {1, 2, 4})
      for (bool m3 : {false, true})
        for (int p3 : {0, 1, 2})
          for (int refine : {1, 2})
            for (int winner : {0, 1, 2})
              for (bool ew : {false, true})
                for (bool orot : {false, true})
                  if (winner > 0 || !ew)
                    g.push_back(level(p2, m3, p3, orot ? 4 : 1, false, orot, refine, false, winner, false, false, ew));
  } else if (name == "seeds-normal") {  // the fit's knobs around `normal`
    for (int p2 : {1, 2, 4})
      for (int winner : {0, 1})
        for (bool ew : {false, true})
          for (bool joint : {false, true})
            for (int seeds : {1, 2})
              for (int ws : {0, 3, 4})
                if (winner > 0 || !ew) {
                  Bc7Level l = level(p2, false, 1, 1, false, false, 1, false, winner, false, false, ew);
                  l.joint = joint;
                  l.seeds = seeds;
                  l.winner_seeds = ws ? ws : seeds;
                  g.push_back(l);
                }
  } else if (name == "seeds-high") {  // and around `high`
    for (int p2 : {6, 12})
      for (bool m3 : {false, true})
        for (int p3 : {2, 4})
          for (int refine : {1, 2})
            for (bool joint : {false, true})
              for (int seeds : {2, 3, 4}) {
                Bc7Level l = level(p2, m3, p3, 4, true, true, refine, false, 2, true, false, true);
                l.joint = joint;
                l.seeds = seeds;
                l.winner_seeds = 4;
                g.push_back(l);
              }
  } else if (name == "high") {
    for (int p2 : {6, 12, 24})
      for (int p3 : {2, 4, 8})
        for (int refine : {2, 3})
          for (bool pairs : {false, true})
            for (bool pbits : {false, true})
              for (bool exact : {false, true})
                for (bool m3 : {false, true})
                  g.push_back(level(p2, m3, p3, 4, true, true, refine, exact, 2, pairs, pbits, true));
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
    } else if (s.rfind("--grid=", 0) == 0) {
      const std::vector<Bc7Level> g = grid(s.substr(7));
      if (g.empty()) {
        std::fprintf(stderr, "bc7_sweep: no grid '%s' (normal, high, seeds-normal, seeds-high)\n", s.c_str() + 7);
        return 2;
      }
      rows.insert(rows.end(), g.begin(), g.end());
    } else if (parse(s, l)) {
      rows.push_back(l);
    } else {
      std::fprintf(
          stderr,
          "bc7_sweep: '%s' is not a row of 18 comma-separated knobs (bc7_levels.h's order), --grid=NAME or --reps=N\n",
          s.c_str());
      return 2;
    }
  }
  if (rows.empty()) rows.assign(std::begin(kBc7Levels), std::end(kBc7Levels) - 1);  // max: too slow to repeat
  std::vector<Crop> crops;
  double pixels = 0;
  for (const Image& img : bench::centred_crops()) {
    crops.push_back(gather(img));
    pixels += double(img.width()) * img.height();
  }
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
  // Each row's speed and PSNR; `*`: on the Pareto front (no row both faster and better).
  std::vector<double> speed(rows.size()), psnr(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    std::sort(seconds[k].begin(), seconds[k].end());
    speed[k] = pixels / seconds[k][seconds[k].size() / 2] / 1e6;
    psnr[k] = 10 * std::log10(255.0 * 255.0 / (se[k] / (3.0 * pixels)));
  }
  std::printf("%-44s %9s %8s\n", "knobs (bc7_levels.h order)", "MPix/s", "PSNR");
  for (std::size_t k = 0; k < rows.size(); ++k) {
    bool front = true;
    for (std::size_t j = 0; j < rows.size(); ++j) front = front && !(speed[j] > speed[k] && psnr[j] > psnr[k]);
    std::printf("%-44s %9.3f %8.3f%s\n", row(rows[k]).c_str(), speed[k], psnr[k], front ? " *" : "");
  }
  return 0;
}
