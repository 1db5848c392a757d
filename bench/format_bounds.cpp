// What the formats allow: exhaustive searches that no encoder can beat, to
// read quality targets against. A plain program, not a timing benchmark
// (it takes about two minutes on two cores):
//
//   format_bounds [BC1_STRIDE [ETC1_STRIDE [EAC_STRIDE]]]
//   format_bounds --bc1-corpus [STRIDE]   (BC1 alone, every corpus albedo
//                                          and photo, default one block in 256)
//
// BC1: on every BC1_STRIDE-th block (default 32) of the benchmarks' colour
// textures, the least squared error of any BC1 block, by branch and bound
// over boxes of endpoint pairs: a box's bound is each texel's distance to
// the nearest of the boxes its four palette colours can fall in (the
// decoder's expansion and interpolation are monotonic in the endpoints), so
// a box is dropped when that reaches the best error found, starting from
// texproc `max`'s. Both modes; the three-colour mode's black index (which
// DXGI's BC1 reads as transparent) separately. Beside it libsquish (range,
// cluster and iterative cluster fit) and texproc at each quality.
//
// ETC1: on every ETC1_STRIDE-th block (default 64), the least squared error
// of any ETC1 block: both flips; the individual mode (each half's best 4-bit
// base and table, found independently); the differential mode (each half's
// best table for every 5-bit base, then the best pair of bases within the
// delta's reach). Beside it libetc1 (android-libetc1) and texproc at each
// quality, on the same blocks. PSNR over RGB.
//
// EAC R11: on every EAC_STRIDE-th block (default 4) of the six corpus
// heightmaps and of X and Y of five normal maps, the least error of any R11
// block (every table, multiplier and base that can matter), beside texproc's
// R11 `high` and BC4 `normal` and `high`. PSNR over [0, 1].
//
// All use the decoders' exact arithmetic (clamping and rounding included);
// a base outside the ranges searched is beaten by the nearest one inside
// (all of its palette lies on one side of the texels).
#include <squish.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_common.h"
#include "etc/etc_tables.h"
#include "libetc1_encode.h"
#include "texproc/block_encode.h"

using namespace texproc;

namespace {

constexpr int kHalf[4][8] = {
    {0, 1, 4, 5, 8, 9, 12, 13}, {2, 3, 6, 7, 10, 11, 14, 15}, {0, 1, 2, 3, 4, 5, 6, 7}, {8, 9, 10, 11, 12, 13, 14, 15}};
constexpr long kHuge = 1L << 50;

int extend(int q, int bits) { return bits == 5 ? etc::extend5(q) : etc::extend4(q); }

// Squared error of half h with base (r, g, b) (8-bit) and table t, each
// texel at its best modifier; stops once it reaches `stop`.
long half_error(const int px[16][3], int h, const int base[3], int t, long stop) {
  int pal[4][3];
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) pal[k][c] = etc::clamp255(base[c] + etc::kModifiers[t][k]);
  long e = 0;
  for (int i = 0; i < 8 && e < stop; ++i) {
    const int* p = px[kHalf[h][i]];
    int best = 1 << 30;
    for (int k = 0; k < 4; ++k) {
      const int dr = p[0] - pal[k][0], dg = p[1] - pal[k][1], db = p[2] - pal[k][2];
      best = std::min(best, dr * dr + dg * dg + db * db);
    }
    e += best;
  }
  return e;
}

// The least error of half h over every table and every base of `bits`
// bits (individual mode: the halves are independent).
long best_half(const int px[16][3], int h, int bits) {
  const int top = (1 << bits) - 1;
  int lo[3] = {255, 255, 255}, hi[3] = {0, 0, 0};
  for (int i = 0; i < 8; ++i)
    for (int c = 0; c < 3; ++c)
      lo[c] = std::min(lo[c], px[kHalf[h][i]][c]), hi[c] = std::max(hi[c], px[kHalf[h][i]][c]);
  long best = kHuge;
  for (int t = 0; t < 8; ++t) {
    const int far = etc::kModifiers[t][1];
    int q0[3], q1[3];  // bases whose palette reaches the texels' range
    for (int c = 0; c < 3; ++c) {
      q0[c] = 0;
      while (q0[c] < top && extend(q0[c] + 1, bits) + far <= lo[c]) ++q0[c];
      q1[c] = top;
      while (q1[c] > 0 && extend(q1[c] - 1, bits) - far >= hi[c]) --q1[c];
    }
    for (int r = q0[0]; r <= q1[0]; ++r)
      for (int g = q0[1]; g <= q1[1]; ++g)
        for (int b = q0[2]; b <= q1[2]; ++b) {
          const int base[3] = {extend(r, bits), extend(g, bits), extend(b, bits)};
          best = std::min(best, half_error(px, h, base, t, best));
        }
  }
  return best;
}

// Half h's least error over the tables for every 5-bit base (r << 10 | g << 5 | b).
std::vector<long> half_by_base(const int px[16][3], int h) {
  std::vector<long> e(32768, kHuge);
  for (int q = 0; q < 32768; ++q) {
    const int base[3] = {etc::extend5(q >> 10), etc::extend5(q >> 5 & 31), etc::extend5(q & 31)};
    for (int t = 0; t < 8; ++t)
      e[std::size_t(q)] = std::min(e[std::size_t(q)], half_error(px, h, base, t, e[std::size_t(q)]));
  }
  return e;
}

// m[q] = the least e over the bases q + delta, delta in [-4, 3] per channel
// (a separable minimum, one channel at a time).
std::vector<long> within_delta(std::vector<long> e) {
  std::vector<long> next(e.size());
  for (int shift : {10, 5, 0}) {
    for (int q = 0; q < 32768; ++q) {
      const int v = q >> shift & 31, rest = q & ~(31 << shift);
      long m = kHuge;
      for (int w = std::max(0, v - 4); w <= std::min(31, v + 3); ++w)
        m = std::min(m, e[std::size_t(rest | w << shift)]);
      next[std::size_t(q)] = m;
    }
    e.swap(next);
  }
  return e;
}

// The least squared error of any ETC1 block for these texels.
long best_etc1(const int px[16][3]) {
  long best = kHuge;
  for (int flip = 0; flip < 2; ++flip) {
    const int a = 2 * flip, b = a + 1;
    best = std::min(best, best_half(px, a, 4) + best_half(px, b, 4));
    const std::vector<long> ea = half_by_base(px, a), eb = within_delta(half_by_base(px, b));
    for (std::size_t q = 0; q < ea.size(); ++q) best = std::min(best, ea[q] + eb[q]);
  }
  return best;
}

// A box of BC1 endpoint pairs, in 5-6-5 units (r0 g0 b0 r1 g1 b1), and a
// lower bound of the error of every pair in it.
struct EndpointBox {
  int lo[6], hi[6];
  long bound;
};

int expand(int channel, int v) { return channel == 1 ? (v << 2 | v >> 4) : (v << 3 | v >> 2); }

// The least error of any pair in box b (exact for a single pair), as
// texproc's decoder decodes: `four` colours (2a + b + 1) / 3, or three
// ((a + b + 1) / 2) with or without `black` as the fourth.
long box_bound(const int px[16][3], const EndpointBox& b, bool four, bool black) {
  int lo[4][3], hi[4][3];
  for (int c = 0; c < 3; ++c) {
    const int l0 = expand(c, b.lo[c]), h0 = expand(c, b.hi[c]), l1 = expand(c, b.lo[3 + c]),
              h1 = expand(c, b.hi[3 + c]);
    lo[0][c] = l0;
    hi[0][c] = h0;
    lo[1][c] = l1;
    hi[1][c] = h1;
    if (four) {
      lo[2][c] = (2 * l0 + l1 + 1) / 3;
      hi[2][c] = (2 * h0 + h1 + 1) / 3;
      lo[3][c] = (l0 + 2 * l1 + 1) / 3;
      hi[3][c] = (h0 + 2 * h1 + 1) / 3;
    } else {
      lo[2][c] = (l0 + l1 + 1) / 2;
      hi[2][c] = (h0 + h1 + 1) / 2;
      lo[3][c] = black ? 0 : lo[2][c];
      hi[3][c] = black ? 0 : hi[2][c];
    }
  }
  long sum = 0;
  for (int i = 0; i < 16; ++i) {
    int best = 1 << 30;
    for (int k = 0; k < 4; ++k) {
      int d = 0;
      for (int c = 0; c < 3; ++c) {
        const int v = px[i][c], e = v < lo[k][c] ? lo[k][c] - v : v > hi[k][c] ? v - hi[k][c] : 0;
        d += e * e;
      }
      best = std::min(best, d);
    }
    sum += best;
  }
  return sum;
}

// The least error of any BC1 block below `known` (an error some block
// reaches), both modes; the palette is the same for either order of the
// endpoints, so the order is left free. Depth first, the lower child first.
long best_bc1(const int px[16][3], long known, bool black) {
  long best = known;
  for (int four = 0; four < 2; ++four) {
    std::vector<EndpointBox> stack;
    EndpointBox root{{0, 0, 0, 0, 0, 0}, {31, 63, 31, 31, 63, 31}, 0};
    root.bound = box_bound(px, root, four, black);
    stack.push_back(root);
    while (!stack.empty()) {
      const EndpointBox b = stack.back();
      stack.pop_back();
      if (b.bound >= best) continue;
      int dim = -1, width = 0;
      for (int k = 0; k < 6; ++k)
        if (b.hi[k] - b.lo[k] > width) width = b.hi[k] - b.lo[k], dim = k;
      if (dim < 0) {  // one pair: its bound is its error
        best = b.bound;
        continue;
      }
      EndpointBox low = b, high = b;
      low.hi[dim] = (b.lo[dim] + b.hi[dim]) / 2;
      high.lo[dim] = low.hi[dim] + 1;
      low.bound = box_bound(px, low, four, black);
      high.bound = box_bound(px, high, four, black);
      if (low.bound > high.bound) std::swap(low, high);
      if (high.bound < best) stack.push_back(high);
      if (low.bound < best) stack.push_back(low);
    }
  }
  return best;
}

// Squared RGB error of each block in `ids` (block index = by * (width / 4) + bx).
std::vector<long> block_errors(const Image& src, const Image& d, const std::vector<int>& ids) {
  const int bw = src.width() / 4;
  std::vector<long> out;
  for (int id : ids) {
    long se = 0;
    for (int i = 0; i < 16; ++i) {
      const int x = id % bw * 4 + i % 4, y = id / bw * 4 + i / 4;
      for (int c = 0; c < 3; ++c) {
        const int e = int(d.row<std::uint8_t>(y)[d.channels() * x + c]) - src.row<std::uint8_t>(y)[4 * x + c];
        se += e * e;
      }
    }
    out.push_back(se);
  }
  return out;
}

void bc1_bounds(int stride, const std::vector<Image>& textures) {
  std::printf("BC1, one block in %d of %zu colour textures: PSNR (dB)\n", stride, textures.size());
  const char* names[9] = {"range", "cluster", "iterative", "fast", "normal", "high", "max", "optimum", "+black"};
  std::printf("%-7s", "blocks");
  for (const char* n : names) std::printf(" %9s", n);
  std::printf("\n");
  double sum[9] = {};
  for (const Image& img : textures) {
    const int w = img.width(), h = img.height(), bw = w / 4, count = bw * (h / 4);
    std::vector<int> ids;
    for (int b = 0; b < count; b += stride) ids.push_back(b);
    auto decoded = [&](const std::vector<std::uint8_t>& blocks) {
      return block_errors(img, decompress_image(blocks, w, h, TexelFormat::bc1_rgb_unorm, PixelType::u8), ids);
    };
    std::vector<long> err[9];
    int k = 0;
    for (int fit : {squish::kColourRangeFit, squish::kColourClusterFit, squish::kColourIterativeClusterFit}) {
      std::vector<std::uint8_t> blocks(std::size_t(squish::GetStorageRequirements(w, h, squish::kDxt1)));
      squish::CompressImage(img.data(), w, h, blocks.data(), squish::kDxt1 | fit);  // metric 0: uniform weights
      err[k++] = decoded(blocks);
    }
    for (Quality q : {Quality::fast, Quality::normal, Quality::high, Quality::max})
      err[k++] = decoded(compress_image(img.view(), TexelFormat::bc1_rgb_unorm, q));
    err[7].resize(ids.size()), err[8].resize(ids.size());
    tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t j) {
      int px[16][3];
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
          px[i][c] = img.row<std::uint8_t>(ids[j] / bw * 4 + i / 4)[4 * (ids[j] % bw * 4 + i % 4) + c];
      err[7][j] = best_bc1(px, err[6][j] + 1, false);
      err[8][j] = best_bc1(px, err[7][j] + 1, true);
    });
    std::printf("%-7zu", ids.size());
    for (int m = 0; m < 9; ++m) {
      double se = 0;
      for (long e : err[m]) se += double(e);
      const double p = 10 * std::log10(255.0 * 255.0 / (se / (48.0 * double(ids.size()))));
      std::printf(" %9.3f", p);
      sum[m] += p;
    }
    std::printf("\n");
  }
  const double n = double(textures.size());
  std::printf("%-7s", "mean");
  for (double v : sum) std::printf(" %9.3f", v / n);
  std::printf(
      "\nagainst iterative cluster fit: high %+.3f, max %+.3f, optimum %+.3f, with black %+.3f dB; "
      "against cluster fit: normal %+.3f, optimum %+.3f dB\n\n",
      (sum[5] - sum[2]) / n, (sum[6] - sum[2]) / n, (sum[7] - sum[2]) / n, (sum[8] - sum[2]) / n, (sum[4] - sum[1]) / n,
      (sum[7] - sum[1]) / n);
}

void etc1_bounds(int stride) {
  std::printf("ETC1, one block in %d of the colour textures: PSNR (dB)\n", stride);
  std::printf("%-8s %9s %9s %9s %9s %9s\n", "blocks", "libetc1", "fast", "normal", "high", "optimum");
  const Quality levels[3] = {Quality::fast, Quality::normal, Quality::high};
  double sum[5] = {};
  for (const Image& img : bench::color_textures()) {
    const int bw = img.width() / 4, count = bw * (img.height() / 4);
    std::vector<int> ids;
    for (int b = 0; b < count; b += stride) ids.push_back(b);
    std::vector<long> best(ids.size());
    tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t j) {
      int px[16][3];
      for (int i = 0; i < 16; ++i)
        for (int c = 0; c < 3; ++c)
          px[i][c] = img.row<std::uint8_t>(ids[j] / bw * 4 + i / 4)[4 * (ids[j] % bw * 4 + i % 4) + c];
      best[j] = best_etc1(px);
    });
    const double n = 48.0 * double(ids.size());
    auto psnr = [&](double se) { return 10 * std::log10(255.0 * 255.0 / (se / n)); };
    auto of = [&](const std::vector<std::uint8_t>& blocks) {
      double se = 0;
      for (long e : block_errors(
               img, decompress_image(blocks, img.width(), img.height(), TexelFormat::etc1_rgb, PixelType::u8), ids))
        se += double(e);
      return psnr(se);
    };
    double p[5] = {of(bench::libetc1_encode(img))};
    for (int k = 0; k < 3; ++k) p[k + 1] = of(compress_image(img.view(), TexelFormat::etc1_rgb, levels[k]));
    double se = 0;
    for (long e : best) se += double(e);
    p[4] = psnr(se);
    std::printf("%-8zu %9.3f %9.3f %9.3f %9.3f %9.3f\n", ids.size(), p[0], p[1], p[2], p[3], p[4]);
    for (int k = 0; k < 5; ++k) sum[k] += p[k];
  }
  const double n = double(bench::color_textures().size());
  std::printf("%-8s %9.3f %9.3f %9.3f %9.3f %9.3f\n", "mean", sum[0] / n, sum[1] / n, sum[2] / n, sum[3] / n,
              sum[4] / n);
  std::printf("against libetc1: fast %+.3f, normal %+.3f, high %+.3f, optimum %+.3f dB\n\n", (sum[1] - sum[0]) / n,
              (sum[2] - sum[0]) / n, (sum[3] - sum[0]) / n, (sum[4] - sum[0]) / n);
}

// The least squared error of any R11 block for 16 values in [0, 2047].
double best_r11(const double v[16]) {
  const double lo = *std::min_element(v, v + 16), hi = *std::max_element(v, v + 16);
  double best = 1e300;
  for (int t = 0; t < 16; ++t) {
    const int* mod = etc::kEacModifiers[t];
    const int m_lo = *std::min_element(mod, mod + 8), m_hi = *std::max_element(mod, mod + 8);
    for (int mult = 0; mult < 16; ++mult) {
      const int scale = mult == 0 ? 1 : 8 * mult;  // multiplier 0: the modifiers unscaled
      const int b0 = std::max(0, int(std::floor((lo - 4 - m_hi * scale) / 8)) - 1);
      const int b1 = std::min(255, int(std::ceil((hi - 4 - m_lo * scale) / 8)) + 1);
      for (int base = b0; base <= b1; ++base) {
        int pal[8];
        for (int k = 0; k < 8; ++k) pal[k] = std::clamp(base * 8 + 4 + mod[k] * scale, 0, 2047);
        double e = 0;
        for (int i = 0; i < 16 && e < best; ++i) {
          double q = 1e300;
          for (int k = 0; k < 8; ++k) q = std::min(q, (pal[k] - v[i]) * (pal[k] - v[i]));
          e += q;
        }
        best = std::min(best, e);
      }
    }
  }
  return best / (2047.0 * 2047.0);
}

void eac_bounds(int stride) {
  std::printf("EAC R11 against BC4, one block in %d: PSNR (dB) over [0, 1]\n", stride);
  std::printf("%-56s %9s %9s %9s %9s\n", "", "R11 high", "optimum", "BC4 norm", "BC4 high");
  struct Job {
    std::string file;
    int channel;
  };
  std::vector<Job> jobs;
  for (const char* f : {"height/povray_mount1_250.png", "height/irrlicht_terrain_heightmap_256.bmp",
                        "height/scorched3d_denali_256.bmp", "height/stellarium_stein_mauerwerk_height_256.png",
                        "height/mpl_jacksboro_fault_dem_403x344_u16.png", "height/trigger_swiss_h_1024.png"})
    jobs.push_back({f, 0});
  for (const char* f : {"normal_ts/qt3d_copper_brushed_normal.png", "normal_ts/qt3d_water_normal_512.jpg",
                        "normal_ts/ufoai_door061_nm_alphaheight_512x602.png",
                        "normal_ts/stellarium_stein_mauerwerk_bump_256.png", "normal_ts/qt3d_moonnormal_1638x819.jpg"})
    for (int c = 0; c < 2; ++c) jobs.push_back({f, c});
  for (const Job& job : jobs) {
    const Image src = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + job.file);
    Image img(src.width() / 4 * 4, src.height() / 4 * 4, 1, PixelType::u16);
    for (int y = 0; y < img.height(); ++y)
      for (int x = 0; x < img.width(); ++x) img.set(x, y, 0, src.get(x, y, job.channel));
    const int bw = img.width() / 4, count = bw * (img.height() / 4);
    std::vector<int> ids;
    for (int b = 0; b < count; b += stride) ids.push_back(b);
    std::vector<double> best(ids.size());
    tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t j) {
      double v[16];
      for (int i = 0; i < 16; ++i) v[i] = img.get(ids[j] % bw * 4 + i % 4, ids[j] / bw * 4 + i / 4, 0) * 2047.0;
      best[j] = best_r11(v);
    });
    const double n = 16.0 * double(ids.size());
    auto psnr = [&](double se) { return 10 * std::log10(1.0 / (se / n)); };
    auto of = [&](TexelFormat f, Quality q) {
      const Image d = decompress_image(compress_image(img.view(), f, q), img.width(), img.height(), f, PixelType::f32);
      double se = 0;
      for (int id : ids)
        for (int i = 0; i < 16; ++i) {
          const int x = id % bw * 4 + i % 4, y = id / bw * 4 + i / 4;
          se += std::pow(double(d.get(x, y, 0)) - img.get(x, y, 0), 2);
        }
      return psnr(se);
    };
    double se = 0;
    for (double e : best) se += e;
    const std::string name = job.file + (job.file.rfind("normal_ts", 0) == 0 ? (job.channel ? " (Y)" : " (X)") : "");
    std::printf("%-56s %9.3f %9.3f %9.3f %9.3f\n", name.c_str(), of(TexelFormat::eac_r11_unorm, Quality::high),
                psnr(se), of(TexelFormat::bc4_unorm, Quality::normal), of(TexelFormat::bc4_unorm, Quality::high));
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--bc1-corpus") {
    const int stride = argc > 2 ? std::atoi(argv[2]) : 256;
    if (stride < 1) {
      std::fprintf(stderr, "usage: format_bounds --bc1-corpus [STRIDE] (a positive block stride)\n");
      return 2;
    }
    std::vector<Image> all;
    for (const std::string& path : bench::corpus_color_paths()) {
      std::printf("  %s\n", path.c_str());
      all.push_back(bench::color_crop(path));
    }
    bc1_bounds(stride, all);
    return 0;
  }
  const int bc1_stride = argc > 1 ? std::atoi(argv[1]) : 32, etc1_stride = argc > 2 ? std::atoi(argv[2]) : 64,
            eac_stride = argc > 3 ? std::atoi(argv[3]) : 4;
  if (bc1_stride < 1 || etc1_stride < 1 || eac_stride < 1) {
    std::fprintf(stderr,
                 "usage: format_bounds [BC1_STRIDE [ETC1_STRIDE [EAC_STRIDE]]] (positive block strides)\n"
                 "       format_bounds --bc1-corpus [STRIDE] (BC1 alone, on every corpus albedo and photo)\n");
    return 2;
  }
  bc1_bounds(bc1_stride, bench::color_textures());
  etc1_bounds(etc1_stride);
  eac_bounds(eac_stride);
  return 0;
}
