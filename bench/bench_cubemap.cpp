// texproc cubemap: speed of the panorama-to-cube, seamless-mip and IBL
// paths, and, printed before the timings, the quality figures that go with
// them: seams at every level against per-face
// filtering, the specular prefilter against a brute-force convolution, the
// spherical harmonics against a brute-force integral.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "bench_common.h"
#include "texproc/cubemap.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

namespace texproc {
namespace {

const char* kPanoramas[] = {"hdr/blender_world_forest.exr", "hdr/blender_world_city.exr",
                            "hdr/blender_world_courtyard.exr", "hdr/blender_world_night.exr"};

Image linear_panorama(const std::string& corpus_path) {
  const Image img = read_image(std::string(TEXPROC_CORPUS_DIR) + "/" + corpus_path);
  return to_linear_rgba(img.view(), img.type() == PixelType::f32 ? ColorSpace::linear() : ColorSpace::srgb());
}

// The 4096 x 2048 panorama of the speed target: the corpus' starfield (the
// one real 4096 x 2048 sphere), linear float.
const Image& big_panorama() {
  static const Image p = linear_panorama("albedo_srgb/qt3d_galaxy_starfield_4096x2048.jpg");
  return p;
}

void unit_dir(int face, int n, int i, int j, double d[3]) {
  cube_direction(face, 2.0 * (i + 0.5) / n - 1.0, 2.0 * (j + 0.5) / n - 1.0, d);
  const double l = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (int k = 0; k < 3; ++k) d[k] /= l;
}

// GGX D(h) (n.l) over every texel of `src`, in double: texel (i, j) of face
// f of an n x n output, alpha^2 = a2.
void brute_ggx(const CubeLevel& src, int f, int n, int i, int j, double a2, double out[3]) {
  const int s = src.size;
  double N[3], acc[3] = {0, 0, 0}, ws = 0;
  unit_dir(f, n, i, j, N);
  for (int sf = 0; sf < 6; ++sf)
    for (int sj = 0; sj < s; ++sj)
      for (int si = 0; si < s; ++si) {
        double L[3];
        unit_dir(sf, s, si, sj, L);
        const double c = N[0] * L[0] + N[1] * L[1] + N[2] * L[2];
        if (c <= 0) continue;
        const double nh2 = (1 + c) / 2, q = nh2 * (a2 - 1) + 1;
        const double w = a2 / (q * q) * c * cube_texel_solid_angle(s, si, sj);
        for (int k = 0; k < 3; ++k) acc[k] += w * src.faces[sf].row<float>(sj)[4 * si + k];
        ws += w;
      }
  for (int k = 0; k < 3; ++k) out[k] = acc[k] / ws;
}

void report_seams() {
  std::printf(
      "Seams: mean |RGB step| across the 12 face edges (edge), from each edge texel to its inward neighbour (near),\n"
      "between neighbours anywhere inside the faces (inner). Seamless chain against per-face filtering (texproc mip\n"
      "on each face: Gaussian, box) and against the same level sampled straight from the panorama, which has no\n"
      "seam by construction (its edge/inner ratio is the content's).\n");
  std::printf("%-17s %5s %5s | %-23s | %-13s | %-13s | %-13s\n", "panorama", "level", "size",
              "seamless edge near inner", "gauss edge", "box edge", "direct edge");
  int levels = 0, below_inner = 0, below_gauss = 0, within_direct = 0, direct_below_inner = 0, both_fail = 0;
  double worst_vs_direct = 0, worst_gauss = 0;
  for (const char* path : kPanoramas) {
    const Image p = linear_panorama(path);
    Cubemap c = cubemap_from_equirect(p.view(), 256);
    generate_cube_mips(c);
    std::array<MipChain, 6> gauss, box;
    MipOptions mo;
    mo.color_space = "linear";
    MipOptions mb = mo;
    mb.filter.kind = FilterKind::box;
    for (int f = 0; f < 6; ++f) {
      gauss[f] = generate_mips(c.levels[0].faces[f].view(), mo);
      box[f] = generate_mips(c.levels[0].faces[f].view(), mb);
    }
    for (std::size_t k = 1; k < c.levels.size() && c.levels[k].size >= 2; ++k) {
      CubeLevel g, b;
      g.size = b.size = c.levels[k].size;
      for (int f = 0; f < 6; ++f) {
        g.faces[f] = gauss[f].levels[k];
        b.faces[f] = box[f].levels[k];
      }
      const SeamStats s = measure_seams(c.levels[k]), sg = measure_seams(g), sb = measure_seams(b);
      const SeamStats sd = measure_seams(cubemap_from_equirect(p.view(), c.levels[k].size).levels[0]);
      std::printf("%-17s %5zu %5d | %.4f %.4f %.4f %s | %.4f (%4.2fx) | %.4f (%4.2fx) | %.4f (%4.2fx)\n", path + 17, k,
                  c.levels[k].size, s.edge_step, s.near_edge_step, s.interior_step,
                  s.edge_step <= s.interior_step ? " " : "*", sg.edge_step, sg.edge_step / s.edge_step, sb.edge_step,
                  sb.edge_step / s.edge_step, sd.edge_step, sd.edge_step / s.edge_step);
      ++levels;
      below_inner += s.edge_step <= s.interior_step;
      below_gauss += s.edge_step <= sg.edge_step;
      within_direct += s.edge_step <= 1.05 * sd.edge_step;
      direct_below_inner += sd.edge_step <= sd.interior_step;
      both_fail += s.edge_step > s.interior_step && sd.edge_step > sd.interior_step;
      worst_vs_direct = std::max(worst_vs_direct, s.edge_step / sd.edge_step);
      worst_gauss = std::max(worst_gauss, sg.edge_step / s.edge_step);
    }
  }
  std::printf(
      "levels: %d; seamless edge <= inner: %d (direct sampling: %d; both above inner: %d); seamless edge <= "
      "per-face gaussian's: %d (gaussian up to %.2fx); seamless edge within 5%% of direct sampling's: %d (at most "
      "%.2fx)  (* marks edge > inner)\n",
      levels, below_inner, direct_below_inner, both_fail, below_gauss, worst_gauss, within_direct, worst_vs_direct);
}

void report_ibl_accuracy() {
  const Image p = linear_panorama(kPanoramas[0]);
  const Cubemap src = cubemap_from_equirect(p.view(), 32);
  SpecularOptions all;
  all.min_size = 1;
  const Cubemap spec = prefilter_specular(src, all);
  SpecularOptions so = all;
  so.exact_budget = 0;
  const Cubemap sampled = prefilter_specular(src, so);
  std::printf("\nGGX prefilter of a 32 cube (forest) against brute force over every texel (relative RMS):\n");
  const int levels = int(spec.levels.size());
  for (int m = 1; m < levels; ++m) {
    const double a2 = std::pow(specular_roughness(m, levels), 4.0);
    const int n = spec.levels[m].size;
    double e = 0, es = 0, ref2 = 0;
    for (int f = 0; f < 6; ++f)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          double r3[3];
          brute_ggx(src.levels[0], f, n, i, j, a2, r3);
          for (int k = 0; k < 3; ++k) {
            const double r = r3[k];
            e += std::pow(spec.levels[m].faces[f].row<float>(j)[4 * i + k] - r, 2);
            es += std::pow(sampled.levels[m].faces[f].row<float>(j)[4 * i + k] - r, 2);
            ref2 += r * r;
          }
        }
    std::printf("  level %d roughness %.2f: shipped %.4f%%, importance-sampled only %.4f%%\n", m,
                specular_roughness(m, levels), 100 * std::sqrt(e / ref2), 100 * std::sqrt(es / ref2));
  }
  // Where importance sampling is what ships (the fine levels of a 256 chain,
  // whose exact convolution would cost 10^10 texel pairs): 600 texels of
  // each such level against brute force over the 256 source.
  {
    const Cubemap src256 = cubemap_from_equirect(p.view(), 256);
    SpecularOptions every;
    every.min_size = 1;
    const Cubemap s256 = prefilter_specular(src256, every);
    const int levels256 = int(s256.levels.size());
    std::printf(
        "GGX prefilter of a 256 cube (forest), importance-sampled levels, 600 texels each against brute force:\n");
    for (int m = 1; m <= 3; ++m) {
      const double a2 = std::pow(specular_roughness(m, levels256), 4.0);
      const int n = s256.levels[m].size;
      double e = 0, ref2 = 0;
      for (int t = 0; t < 600; ++t) {
        const int f = t % 6, i = (t * 7919) % n, j = (t * 104729 / 6) % n;
        double r3[3];
        brute_ggx(src256.levels[0], f, n, i, j, a2, r3);
        for (int k = 0; k < 3; ++k) {
          const double r = r3[k];
          e += std::pow(s256.levels[m].faces[f].row<float>(j)[4 * i + k] - r, 2);
          ref2 += r * r;
        }
      }
      std::printf("  level %d roughness %.3f: %.4f%%\n", m, specular_roughness(m, levels256),
                  100 * std::sqrt(e / ref2));
    }
  }
  // Spherical harmonics: project_sh9 (from the level with <= 128 faces)
  // against every texel of a 1024 cube, in double.
  const Image big = linear_panorama(kPanoramas[0]);
  const Cubemap c = cubemap_from_equirect(big.view(), 1024);
  const SphericalHarmonics9 sh = project_sh9(c);
  std::array<std::array<double, 3>, 9> ref{};
  const int n = c.size();
  for (int f = 0; f < 6; ++f)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        double d[3], y[9];
        unit_dir(f, n, i, j, d);
        sh9_basis(d, y);
        const double w = cube_texel_solid_angle(n, i, j);
        for (int k = 0; k < 9; ++k)
          for (int ch = 0; ch < 3; ++ch) ref[k][ch] += y[k] * w * c.levels[0].faces[f].row<float>(j)[4 * i + ch];
      }
  double worst = 0, norm = 0;
  for (int k = 0; k < 9; ++k)
    for (int ch = 0; ch < 3; ++ch) norm = std::max(norm, std::fabs(ref[k][ch]));
  for (int k = 0; k < 9; ++k)
    for (int ch = 0; ch < 3; ++ch) worst = std::max(worst, std::fabs(sh.radiance[k][ch] - ref[k][ch]) / norm);
  std::printf(
      "\nSH9 of a 1024 cube (forest): largest coefficient error against every texel's integral: %.4f%% of "
      "the largest coefficient (L00 %.5f vs %.5f)\n",
      100 * worst, sh.radiance[0][0], ref[0][0]);
}

void panorama_phases(benchmark::State& state, int threads) {
  ThreadLimit limit(threads);
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    Cubemap c = cubemap_from_equirect(big_panorama().view(), 1024);
    const auto t1 = std::chrono::steady_clock::now();
    generate_cube_mips(c);
    const auto t2 = std::chrono::steady_clock::now();
    state.counters["faces_ms"] = std::chrono::duration<double, std::milli>(t1 - t0).count();
    state.counters["mips_ms"] = std::chrono::duration<double, std::milli>(t2 - t1).count();
  }
}

void panorama_to_cube(benchmark::State& state, int threads) {
  ThreadLimit limit(threads);
  for (auto _ : state) {
    Cubemap c = cubemap_from_equirect(big_panorama().view(), 1024);
    generate_cube_mips(c);
    benchmark::DoNotOptimize(c.levels.back().faces[0].data());
  }
  state.counters["MPix_out_per_s"] =
      benchmark::Counter(6.0 * 1024 * 1024 * 4 / 3, benchmark::Counter::kIsIterationInvariantRate);
}

void specular_256(benchmark::State& state, int threads) {
  ThreadLimit limit(threads);
  const Image p = linear_panorama(kPanoramas[0]);
  const Cubemap src = cubemap_from_equirect(p.view(), 256);
  SpecularOptions every;  // all levels, down to 1x1
  every.min_size = 1;
  for (auto _ : state) {
    const Cubemap s = prefilter_specular(src, every);
    benchmark::DoNotOptimize(s.levels.back().faces[0].data());
  }
}

void irradiance_32(benchmark::State& state, int threads) {
  ThreadLimit limit(threads);
  const Image p = linear_panorama(kPanoramas[0]);
  const Cubemap src = cubemap_from_equirect(p.view(), 256);
  for (auto _ : state) {
    const Cubemap s = irradiance_cubemap(src, 32);
    const SphericalHarmonics9 sh = project_sh9(src);
    benchmark::DoNotOptimize(s.levels[0].faces[0].data());
    benchmark::DoNotOptimize(sh.radiance[0][0]);
  }
}

}  // namespace
}  // namespace texproc

int main(int argc, char** argv) {
  using namespace texproc;
  benchmark::Initialize(&argc, argv);
  bool quality = true;
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--no-quality") quality = false;
  if (quality) {
    report_seams();
    report_ibl_accuracy();
  }
  for (int t : {1, 2}) {
    benchmark::RegisterBenchmark(("phases/threads:" + std::to_string(t)).c_str(),
                                 [t](benchmark::State& s) { panorama_phases(s, t); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("panorama_4096x2048_to_cube_1024_mips/threads:" + std::to_string(t)).c_str(),
                                 [t](benchmark::State& s) { panorama_to_cube(s, t); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3)
        ->Repetitions(3)
        ->ReportAggregatesOnly(true)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("ggx_specular_256_all_levels/threads:" + std::to_string(t)).c_str(),
                                 [t](benchmark::State& s) { specular_256(s, t); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(3)
        ->ReportAggregatesOnly(true)
        ->UseRealTime();
    benchmark::RegisterBenchmark(("irradiance_32_and_sh9_from_256/threads:" + std::to_string(t)).c_str(),
                                 [t](benchmark::State& s) { irradiance_32(s, t); })
        ->Unit(benchmark::kMillisecond)
        ->Iterations(3)
        ->Repetitions(3)
        ->ReportAggregatesOnly(true)
        ->UseRealTime();
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
