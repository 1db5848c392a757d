// texproc conemap: cone step maps from heightmaps, and a preview that shows
// them at work.
#include <chrono>
#include <optional>
#include <iostream>

#include "commands.h"
#include "common.h"
#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

namespace texproc::cli {
namespace {

struct ConeArgs {
  CommonOptions common;
  std::string input, output, preview;
  std::string height_channel = "auto";
  bool invert = false;
  float depth = 1.0f;
  float max_ratio = 1.0f;
  std::string wrap = "repeat";
  std::string type;
  std::string mode = "conservative";
  bool brute_force = false;
  bool fast = false;
  int fast_reach = 2;
  int preview_size = 256;
  float view_angle = 60.0f;
};

int run_conemap(const ConeArgs& a) {
  ThreadLimit threads(a.common.threads);
  ConeMapOptions o;
  o.depth = a.depth;
  o.max_ratio = a.max_ratio;
  o.wrap = parse_wrap_mode(a.wrap);
  if (a.fast && a.brute_force) throw Error(ErrorCode::bad_arguments, "--fast and --brute-force exclude each other");
  o.fast_reach = a.fast ? a.fast_reach : 0;
  const HeightChannel channel = parse_height_channel(a.height_channel);
  if (a.mode != "conservative") {
    throw Error(ErrorCode::unsupported, "--mode " + a.mode + ": only conservative cones are implemented so far (valid: conservative)");
  }
  if (a.preview_size < 8 || a.preview_size > 4096) throw Error(ErrorCode::bad_arguments, "--preview-size must be 8 to 4096");
  if (!(a.view_angle >= 0.0f && a.view_angle < 89.0f)) {
    throw Error(ErrorCode::bad_arguments, "--view-angle must be in [0, 89) degrees from the normal");
  }
  WriteOptions w;
  w.color_space = "linear";
  std::optional<PixelType> type = parse_output_type(a.type, w);
  std::vector<std::string> inputs{a.input};
  check_output(a.output, inputs, a.common.force);
  if (!a.preview.empty()) check_output(a.preview, inputs, a.common.force);
  if (stop_for_dry_run()) return 0;

  ImageFileInfo info;
  const Image img = read_image(a.input, &info);
  const std::vector<float> h = extract_height(img.view(), channel, a.invert);
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<float> ratios = a.brute_force ? cone_ratios_brute_force(h, img.width(), img.height(), o)
                                                  : cone_ratios(h, img.width(), img.height(), o);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const PixelType out_type = type ? *type : (img.type() == PixelType::u8 ? PixelType::u8 : PixelType::u16);
  write_image(a.output, cone_map_image(h, ratios, img.width(), img.height(), o, out_type).view(), w);
  if (!a.preview.empty()) {
    write_image(a.preview, render_preview(h, ratios, img.width(), img.height(), o, a.preview_size, a.view_angle).view());
  }
  if (!a.common.quiet) {
    std::cout << a.input << " -> " << a.output << ": " << img.width() << "x" << img.height() << " conservative cones ("
              << (a.brute_force ? "brute force"
                  : a.fast      ? "fast, never wider than exact"
                                : "exact, max-mip branch and bound")
              << ") in " << seconds << " s"
              << (a.preview.empty() ? "" : ", preview " + a.preview) << "\n";
  }
  return 0;
}

}  // namespace

void add_conemap_command(CLI::App& app) {
  auto args = std::make_shared<ConeArgs>();
  CLI::App* cmd = app.add_subcommand("conemap", "Cone step maps from heightmaps (R = height, G = sqrt(cone ratio)).");
  cmd->footer(
      "The cone ratio of a texel is the smallest, over every higher texel, of their distance (texture\n"
      "widths) over depth times the height difference, capped by --max-ratio; G stores\n"
      "sqrt(ratio / max-ratio), rounded down. See docs/conemap.md.");
  cmd->add_option("input", args->input, "Heightmap (8, 16-bit or float; height 1 is the top)")->required();
  cmd->add_option("-o,--output", args->output, "Output cone map (RGB: height, sqrt ratio, 0)")->required();
  cmd->add_option("--height-channel", args->height_channel, "Height from: auto, r, g, b, a, luma")->capture_default_str();
  cmd->add_flag("--invert", args->invert, "Depth map: use 1 - h");
  cmd->add_option("--depth", args->depth, "Relief depth in texture widths (> 0)")->capture_default_str();
  cmd->add_option("--max-ratio", args->max_ratio, "Cap on the cone ratio (> 0)")->capture_default_str();
  cmd->add_option("--wrap", args->wrap, "repeat (tiling reliefs see across edges) or clamp")->capture_default_str();
  cmd->add_option("--mode", args->mode, "conservative (relaxed cones are not implemented yet)")->capture_default_str();
  cmd->add_option("--type", args->type, "Output element type: u8, u16, f16, f32 (default: u8 for 8-bit input, else u16)");
  cmd->add_flag("--fast", args->fast,
                "Faster, never wider cones: pyramid blocks >= --fast-reach block sizes away count as one obstacle");
  cmd->add_option("--fast-reach", args->fast_reach, "With --fast: distance, in block sizes, at which blocks stay closed (>= 1)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--brute-force", args->brute_force, "Use the O(N^2)-per-texel definition (slow; for checking)");
  cmd->add_option("--preview", args->preview,
                  "Also render a preview PNG: linear search vs cone stepping, with lookups-per-pixel heat maps");
  cmd->add_option("--preview-size", args->preview_size, "Preview panel size in pixels")->capture_default_str();
  cmd->add_option("--view-angle", args->view_angle, "Preview view angle from the normal, degrees")->capture_default_str();
  add_common_options(*cmd, args->common);
  set_runner(*cmd, [args] { return run_conemap(*args); });
}

}  // namespace texproc::cli
