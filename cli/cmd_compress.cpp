// texproc compress: block compression into DDS, KTX2 or KTX1, optionally
// with a mip chain. So far the RGTC formats (BC4, BC5).
#include <chrono>
#include <iostream>
#include <map>

#include "commands.h"
#include "common.h"
#include "texproc/block_encode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"
#include "texproc/transparent_color.h"

namespace texproc::cli {
namespace {

struct CompressArgs {
  CommonOptions common;
  ChainArgs chain;
  std::string input, output, format, quality = "normal", wrap = "clamp", dds_header = "auto";
  std::string transparent_color = "keep";
  bool mips = false, normal_map = false, linear = false, srgb = false;
};

// --format and the colour space: BC1-BC3 take the sRGB variant for colour
// (the default for 8/16-bit input) and UNORM with --linear; BC4/BC5 hold data.
TexelFormat format_for(const std::string& f, bool srgb) {
  using F = TexelFormat;
  static const std::map<std::string, std::pair<F, F>> k = {
      {"bc1", {F::bc1_rgb_unorm, F::bc1_rgb_srgb}},   {"bc1a", {F::bc1_rgba_unorm, F::bc1_rgba_srgb}},
      {"bc2", {F::bc2_unorm, F::bc2_srgb}},           {"bc3", {F::bc3_unorm, F::bc3_srgb}},
      {"bc4", {F::bc4_unorm, F::bc4_unorm}},          {"bc4s", {F::bc4_snorm, F::bc4_snorm}},
      {"bc5", {F::bc5_unorm, F::bc5_unorm}},          {"bc5s", {F::bc5_snorm, F::bc5_snorm}}};
  auto it = k.find(f);
  if (it != k.end()) return srgb ? it->second.second : it->second.first;
  for (const char* later : {"etc1", "etc2", "etc2a1", "etc2a", "eac-r11", "eac-r11s", "eac-rg11", "eac-rg11s"}) {
    if (f == later) throw Error(ErrorCode::unsupported, "--format " + f + " is not implemented yet (so far: bc1-bc5)");
  }
  throw Error(ErrorCode::bad_arguments,
              "unknown --format '" + f + "' (valid: bc1, bc1a, bc2, bc3, bc4, bc4s, bc5, bc5s)");
}

int run_compress(const CompressArgs& a) {
  ThreadLimit threads(a.common.threads);
  if (a.linear && a.srgb) throw Error(ErrorCode::bad_arguments, "--srgb and --linear contradict each other");
  const Quality q = parse_quality(a.quality);
  const DdsHeader header = parse_dds_header(a.dds_header);
  const TransparentColor transparent = parse_transparent_color(a.transparent_color);
  container_for_path(a.output);  // a container extension, or an error now
  check_output(a.output, {a.input}, a.common.force);
  if (stop_for_dry_run()) return 0;
  Image img = read_image(a.input);
  // Colour is sRGB unless --linear, a normal map, or float input.
  const bool srgb = a.srgb || (!a.linear && !a.normal_map && img.type() != PixelType::f32);
  const TexelFormat format = format_for(a.format, srgb);
  std::vector<Image> levels;
  if (a.mips) {
    MipOptions m;
    m.filter.kind = parse_filter_kind(a.chain.filter);
    m.filter.sigma = a.chain.sigma;
    m.wrap = parse_wrap_mode(a.wrap);
    m.max_levels = a.chain.levels;
    m.min_size = a.chain.min_size;
    m.normal_map = a.normal_map;
    m.color_space = format_info(format).srgb ? "srgb" : "linear";
    MipChain c = generate_mips(std::move(img), m);
    levels = std::move(c.levels);
  } else {
    levels.push_back(std::move(img));
  }
  Texture t;
  t.format = format;
  t.width = std::uint32_t(levels[0].width());
  t.height = std::uint32_t(levels[0].height());
  t.levels = std::uint32_t(levels.size());
  const auto t0 = std::chrono::steady_clock::now();
  for (Image& l : levels) {
    // The policy applies to each stored level (the chain itself was filtered
    // premultiplied, so it has no fringes; the GPU's filtering of straight
    // alpha would add them back from the colour under alpha 0).
    if (format_info(format).channels == 4) apply_transparent_color(l, transparent);
    t.images.push_back(compress_image(l.view(), format, q));
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_texture(a.output, t, header);
  if (!a.common.quiet) {
    std::cout << a.input << " -> " << a.output << ": " << format_info(format).name << ", " << t.levels
              << " level(s), quality " << a.quality << ", encoded in " << s << " s\n";
  }
  return 0;
}

}  // namespace

void add_compress_command(CLI::App& app) {
  auto args = std::make_shared<CompressArgs>();
  CLI::App* cmd = app.add_subcommand("compress", "Block-compress an image into DDS, KTX2 or KTX1 (BC1-BC5 so far).");
  cmd->footer(
      "BC4 stores one channel, BC5 two (the red and green of the input; for a normal map its X and Y, the\n"
      "shader rebuilds Z). SNORM variants map the stored [0, 1] to [-1, 1]. Values are data: no transfer\n"
      "function. ETC is in progress. See docs/compression.md.");
  cmd->add_option("input", args->input, "Input image")->required();
  cmd->add_option("-o,--output", args->output, "Output texture: .dds, .ktx2, .ktx")->required();
  cmd->add_option("--format", args->format, "bc1, bc1a (1-bit alpha), bc2, bc3, bc4, bc4s, bc5, bc5s")->required();
  cmd->add_flag("--srgb", args->srgb, "BC1-BC3: write the sRGB format (the default for 8/16-bit colour input)");
  cmd->add_flag("--linear", args->linear, "The input is data: UNORM formats, linear mip filtering");
  cmd->add_option("--quality", args->quality, "fast, normal, high, max (exhaustive)")->capture_default_str();
  cmd->add_flag("--mips", args->mips, "Compress a whole mip chain (mip options below)");
  cmd->add_flag("--normal-map", args->normal_map, "With --mips: the input is a normal map (renormalized per level)");
  cmd->add_option("--wrap", args->wrap, "Mip filter taps past the edges: clamp, repeat, mirror")->capture_default_str();
  add_chain_options(*cmd, args->chain);
  cmd->add_option("--dds-header", args->dds_header, "auto, dx9, dx10")->capture_default_str();
  cmd->add_option("--transparent-color", args->transparent_color,
                  "Colour under alpha 0 (bc1a, bc2, bc3): keep, bleed (from the visible texels), zero")
      ->capture_default_str();
  add_common_options(*cmd, args->common);
  set_runner(*cmd, [args] { return run_compress(*args); });
}

}  // namespace texproc::cli
