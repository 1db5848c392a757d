// texproc conemap: cone step maps from heightmaps, and a preview that shows
// them at work.
#include <chrono>
#include <optional>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "texproc/conemap.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

namespace texproc::cli {
namespace {

struct ConeArgs {
  SizeArgs size;
  BatchInputs io;
  std::string preview;
  std::string height_channel = "auto";
  bool invert = false;
  float depth = 1.0f;
  float max_ratio = 1.0f;
  std::string wrap = "repeat";
  std::string type;
  std::string mode = "conservative";
  std::string channels = "rgb";
  bool brute_force = false;
  bool fast = false;
  bool bilinear_safe = false;
  int fast_reach = 2;
  int preview_size = 256;
  float view_angle = 60.0f;
  // From the options, once (validate):
  ConeMapOptions options;
  HeightChannel channel = HeightChannel::automatic;
  std::optional<PixelType> type_choice;
  WriteOptions write = cli_write_options();
};

void validate(ConeArgs& a) {
  validate_size_options(a.size);
  ConeMapOptions& o = a.options;
  o.depth = a.depth;
  o.max_ratio = a.max_ratio;
  o.wrap = parse_wrap_mode(a.wrap);
  if (a.fast && a.brute_force) throw Error(ErrorCode::bad_arguments, "--fast and --brute-force exclude each other");
  o.fast_reach = a.fast ? a.fast_reach : 0;
  a.channel = parse_height_channel(a.height_channel);
  if (a.mode != "conservative" && a.mode != "relaxed") {
    throw Error(ErrorCode::bad_arguments, "unknown --mode '" + a.mode + "' (valid: conservative, relaxed)");
  }
  o.mode = a.mode == "relaxed" ? ConeMode::relaxed : ConeMode::conservative;
  o.bilinear_safe = a.bilinear_safe;
  if (a.channels != "rg" && a.channels != "rgb" && a.channels != "rgba") {
    throw Error(ErrorCode::bad_arguments, "unknown --channels '" + a.channels + "' (valid: rg, rgb, rgba)");
  }
  if (a.bilinear_safe && o.mode == ConeMode::relaxed) {
    throw Error(ErrorCode::bad_arguments,
                "--bilinear-safe makes conservative cones; it does not combine with --mode relaxed");
  }
  if (a.preview_size < 8 || a.preview_size > 4096)
    throw Error(ErrorCode::bad_arguments, "--preview-size must be 8 to 4096");
  if (!(a.view_angle >= 0.0f && a.view_angle < 89.0f)) {
    throw Error(ErrorCode::bad_arguments, "--view-angle must be in [0, 89) degrees from the normal");
  }
  a.write.color_space = "linear";
  a.type_choice = parse_output_type(a.type, a.write);
}

void run_conemap(const ConeArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  ConeMapOptions o = a.options;
  // The progress line: the map, and with a preview the other kind of map as the second half.
  const double share = r.outputs.size() > 1 ? 0.5 : 1.0;
  if (r.progress) o.progress = [&r, share](double done) { r.progress(done * share); };
  const WriteOptions& w = a.write;
  PhaseTimer phases(r);
  ImageFileInfo info;
  Image img = read_image(input, &info, cli_read_options());
  read_as_finite(input, img, r.warnings);
  apply_size_options(a.size, img, "linear");  // heights are data
  phases.read_done();
  const int width = img.width(), height = img.height();
  const PixelType out_type =
      a.type_choice ? *a.type_choice : (img.type() == PixelType::u8 ? PixelType::u8 : PixelType::u16);
  // The heights are all that is read from here on: the image leaves memory as they are made.
  const std::vector<float> h = extract_height(std::move(img), a.channel, a.invert);
  release_cached_pixel_memory();
  const std::string preview = r.outputs.size() > 1 ? r.outputs[1] : "";
  // The map's rows made as the writer takes them: never the whole image.
  ImageView shape;
  shape.width = width;
  shape.height = height;
  shape.channels = int(a.channels.size());
  shape.type = out_type;
  const auto t0 = std::chrono::steady_clock::now();
  double seconds = 0, ratio_sum = 0;
  std::vector<float> ratios;  // whole only where the preview or brute force needs it
  if (preview.empty() && !a.brute_force) {
    // Ratios a band at a time, as the writer takes the rows: the search's
    // time is counted as it happens, inside the write.
    const ConeRatioSearch search(h, width, height, o);
    write_image(
        output, shape,
        [&](int y0, int y1, void* dst, std::size_t stride) {
          search.map_rows(out_type, shape.channels, y0, y1, dst, stride, &ratio_sum);
        },
        w);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    phases.compute_done();
    phases.write_done();
  } else {
    ratios = a.brute_force ? cone_ratios_brute_force(h, width, height, o) : cone_ratios(h, width, height, o);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    phases.compute_done();
    write_image(
        output, shape,
        [&](int y0, int y1, void* dst, std::size_t stride) {
          cone_map_rows(h, ratios, width, height, o, out_type, shape.channels, y0, y1, dst, stride);
        },
        w);
    phases.write_done();
  }
  if (!preview.empty()) {
    // The preview shows both kinds side by side: the other map is computed too.
    ConeMapOptions other = o;
    other.mode = o.mode == ConeMode::relaxed ? ConeMode::conservative : ConeMode::relaxed;
    other.bilinear_safe = false;  // relaxed cones are texel-centre cones
    if (r.progress) other.progress = [&r](double done) { r.progress(0.5 + 0.5 * done); };
    const std::vector<float> second = cone_ratios(h, width, height, other);
    const bool relaxed = o.mode == ConeMode::relaxed;
    const Image shown = render_preview(h, relaxed ? second : ratios, width, height, o, a.preview_size, a.view_angle,
                                       relaxed ? ratios : second);
    phases.compute_done();
    write_image(preview, shown.view(), cli_write_options());
    phases.write_done();
  }
  std::ostringstream line;
  line << input << " -> " << output << ": " << width << "x" << height << " " << a.mode
       << (a.bilinear_safe ? " bilinear-safe" : "") << " cones ("
       << (a.brute_force ? "brute force"
           : a.fast      ? "fast, never wider than exact"
                         : "exact, max-mip branch and bound")
       << ") in " << seconds << " s" << (preview.empty() ? "" : ", preview " + preview);
  r.line = line.str();
  for (float v : ratios) ratio_sum += v;
  r.details["width"] = width;
  r.details["height"] = height;
  r.details["cone_seconds"] = seconds;
  r.details["mean_ratio"] = ratio_sum / (double(width) * height);
  r.details["mode"] = a.mode;
  r.details["bilinear_safe"] = a.bilinear_safe;
  r.details["channels"] = a.channels;
}

}  // namespace

void add_conemap_command(CLI::App& app) {
  auto args = std::make_shared<ConeArgs>();
  CLI::App* cmd = app.add_subcommand("conemap", "Cone step maps from heightmaps (R = height, G = sqrt(cone ratio)).");
  cmd->footer(
      "The cone ratio of a texel is the smallest, over every higher texel, of their distance (texture\n"
      "widths) over depth times the height difference, capped by --max-ratio; G stores\n"
      "sqrt(ratio / max-ratio), rounded down. See docs/conemap.md.");
  add_batch_inputs(*cmd, args->io, "Heightmaps (8, 16-bit or float; height 1 is the top)",
                   "Output cone map (RGB: height, sqrt ratio, 0), folder (DIR/: {stem}.png each) or template");
  cmd->add_option("--height-channel", args->height_channel, "Height from: auto, r, g, b, a, luma")
      ->capture_default_str();
  cmd->add_flag("--invert", args->invert, "Depth map: use 1 - h");
  cmd->add_option("--depth", args->depth, "Relief depth in texture widths (> 0)")
      ->check(in_range(0, 1e6, true))
      ->capture_default_str();
  cmd->add_option("--max-ratio", args->max_ratio, "Cap on the cone ratio (> 0)")
      ->check(in_range(0, 1e6, true))
      ->capture_default_str();
  cmd->add_option("--wrap", args->wrap, "repeat (tiling reliefs see across edges) or clamp")->capture_default_str();
  cmd->add_option("--mode", args->mode,
                  "conservative (no relief inside a cone) or relaxed (a ray entering the relief inside a cone does not "
                  "leave it there: wider cones, then a binary search)")
      ->capture_default_str();
  cmd->add_option("--channels", args->channels,
                  "rgb (B = 0), rg (two channels, for BC5 / EAC RG11 / RG8 textures) or rgba (B = 0, A = 1)")
      ->capture_default_str();
  cmd->add_option("--type", args->type,
                  "Output element type: u8, u16, f16, f32 (default: u8 for 8-bit input, else u16)");
  cmd->add_flag("--bilinear-safe", args->bilinear_safe,
                "Conservative cones that stay safe when the renderer samples height and ratio with bilinear filtering "
                "(narrower than the texel-centre cones; see docs/conemap.md)");
  cmd->add_flag(
      "--fast", args->fast,
      "Faster, never wider cones: a pyramid block at least --fast-reach of its own sizes from a texel's 8x8 cell "
      "counts as one obstacle (its highest texel at its nearest point)");
  cmd->add_option("--fast-reach", args->fast_reach,
                  "With --fast: how many of its own sizes a block must be away to count as one obstacle (>= 1)")
      ->capture_default_str()
      ->check(CLI::Range(1, 64));
  cmd->add_flag("--brute-force", args->brute_force, "Use the O(N^2)-per-texel definition (slow; for checking)");
  cmd->add_option("--preview", args->preview,
                  "Also render a preview PNG: linear search, cone stepping and relaxed cone stepping, with "
                  "lookups-per-pixel heat maps "
                  "(a template such as 'previews/{stem}.png' for several inputs)");
  cmd->add_option("--preview-size", args->preview_size, "Preview panel size in pixels")
      ->check(in_range(16, 8192))
      ->capture_default_str();
  cmd->add_option("--view-angle", args->view_angle, "Preview view angle from the normal, degrees")
      ->check(in_range(0, 89))
      ->capture_default_str();
  add_size_options(*cmd, args->size);
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "conemap";
    c.default_extension = ".png";
    c.input_extensions = image_extensions();
    c.validate = [args] { validate(*args); };
    c.plan = [args](const InputFile& in, const std::string& out) {
      std::vector<std::string> outs{out};
      if (!args->preview.empty()) outs.push_back(expand_template(args->preview, in));
      return outs;
    };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_conemap(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
