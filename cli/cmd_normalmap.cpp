// texproc normalmap: tangent-space normal maps from heightmaps.
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/normalmap.h"
#include "texproc/runtime.h"

namespace texproc::cli {
namespace {

struct NormalMapArgs {
  SizeArgs size;
  BatchInputs io;
  ChainArgs chain;
  std::string kernel = "sobel3";
  std::string height_channel = "auto";
  bool invert = false;
  float height_scale = 8.0f;
  float strength = 1.0f;
  std::string wrap = "clamp";
  std::string y = "up";
  std::string channels = "xyz";
  std::vector<float> multiscale_weights = {0.5f, 0.3f, 0.2f};
  std::string type;
  bool mips = false;
  std::string compression;
  std::string dds_header = "auto";
  int zstd = 0;
  // From the options, once (validate):
  NormalMapOptions options;
  std::optional<PixelType> type_choice;      // --type (empty: from the input)
  WriteOptions write = cli_write_options();  // half, compression, linear
  DdsHeader header = DdsHeader::automatic;
  FilterKind filter = FilterKind::gaussian;
};

void validate(NormalMapArgs& a) {
  validate_size_options(a.size);
  NormalMapOptions& o = a.options;
  o.kernel = parse_gradient_kernel(a.kernel);
  o.height_channel = parse_height_channel(a.height_channel);
  o.invert = a.invert;
  o.height_scale = a.height_scale;
  o.strength = a.strength;
  o.wrap = parse_wrap_mode(a.wrap);
  if (a.y != "up" && a.y != "down") {
    throw Error(ErrorCode::bad_arguments, "unknown --y '" + a.y + "' (valid: up (OpenGL), down (DirectX))");
  }
  o.y_up = a.y == "up";
  o.channels = parse_normal_channels(a.channels);
  o.multiscale_weights = a.multiscale_weights;
  a.write.compression = a.compression;
  a.write.color_space = "linear";
  a.type_choice = parse_output_type(a.type, a.write);
  a.header = parse_dds_header(a.dds_header);
  a.filter = parse_filter_kind(a.chain.filter);
}

std::vector<std::string> plan(const NormalMapArgs& a, const std::string& input, const std::string& output) {
  if (!a.mips || is_container_path(output)) return {output};
  const ImageFileInfo info = probe_image(input, cli_read_options());
  return level_outputs(output, mip_level_count(info.width, info.height, a.chain.levels, a.chain.min_size));
}

void run_normalmap(const NormalMapArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  const NormalMapOptions& o = a.options;
  WriteOptions w = a.write;
  check_dds_header_fits(a.dds_header, output);
  zstd_level_for(a.zstd, output);  // checked before any work
  PhaseTimer phases(r);
  ImageFileInfo info;
  Image heights = read_image(input, &info, cli_read_options());
  read_as_finite(input, heights, r.warnings);
  apply_size_options(a.size, heights, "linear");  // heights are data
  phases.read_done();
  std::optional<PixelType> type = a.type_choice;
  if (!type) type = info.type == PixelType::u8 ? PixelType::u8 : PixelType::u16;
  if (a.type.empty() && std::filesystem::path(output).extension() == ".exr") {
    type = PixelType::f32;
    w.half = true;
  }
  const bool container = is_container_path(output);
  std::vector<Image> chain;
  if (!a.mips) {
    chain.push_back(normal_map(heights.view(), o, *type));
  } else {
    // Build the chain on unquantized vectors with the mip module's normal-map
    // mode (renormalized each level), then quantize; xy is cut from xyz.
    NormalMapOptions full = o;
    if (o.channels == NormalChannels::xy) full.channels = NormalChannels::xyz;
    Image level0 = normal_map(heights.view(), full, PixelType::f32);
    MipOptions m;
    m.normal_map = true;
    m.filter.kind = a.filter;
    m.filter.sigma = a.chain.sigma;
    m.wrap = o.wrap;
    m.max_levels = a.chain.levels;
    m.min_size = a.chain.min_size;
    m.output_type = *type;
    MipChain c = generate_mips(std::move(level0), m);
    for (Image& l : c.levels) {
      if (o.channels != NormalChannels::xy) {
        chain.push_back(std::move(l));
        continue;
      }
      Image xy = Image::uninitialized(l.width(), l.height(), 2, l.type());
      const std::size_t bpc = bytes_per_channel(l.type());
      for (int y = 0; y < l.height(); ++y)
        for (int x = 0; x < l.width(); ++x)
          std::memcpy(xy.row<std::uint8_t>(y) + x * 2 * bpc, l.row<std::uint8_t>(y) + x * 3 * bpc, 2 * bpc);
      chain.push_back(std::move(xy));
    }
  }
  phases.compute_done();
  const std::size_t level_count = chain.size();
  if (container) {
    // Uncompressed rg8/rgba8/16-bit/half/float (block compression in the same
    // call comes with `compress`); normals are data: linear formats.
    write_texture(output, texture_from_levels(std::move(chain), {.half = w.half}), a.header,
                  zstd_level_for(a.zstd, output));
  } else if (a.mips) {
    write_levels(output, chain, w);
  } else {
    write_image(output, chain[0].view(), w);
  }
  phases.write_done();
  std::ostringstream line;
  line << input << " -> " << r.outputs[0] << (r.outputs.size() > 1 ? " ..." : "") << ": " << a.kernel << ", "
       << a.channels << ", " << level_count << " level(s), " << info.width << "x" << info.height;
  r.line = line.str();
  r.details["width"] = info.width;
  r.details["height"] = info.height;
  r.details["levels"] = Json::UInt(level_count);
  r.details["kernel"] = a.kernel;
  r.details["channels"] = a.channels;
}

}  // namespace

void add_normalmap_command(CLI::App& app) {
  auto args = std::make_shared<NormalMapArgs>();
  CLI::App* cmd = app.add_subcommand("normalmap", "Derive a tangent-space normal map from a heightmap.");
  cmd->footer(
      "Heights are data in [0, 1] (never gamma-decoded). A height of 1.0 spans --height-scale texels, so a\n"
      "ramp rising 1/S per texel is a 45 degree slope for every kernel; --strength multiplies on top.\n"
      "Output: xyz = RGB (n * 0.5 + 0.5), xy = RG for BC5/EAC RG11 (z = sqrt(1 - x^2 - y^2)), xyzh = RGBA\n"
      "with the height in A. See docs/normalmap.md.");
  add_batch_inputs(*cmd, args->io, "Heightmaps (8, 16-bit or float, any format OpenImageIO reads)",
                   "Output image (.png, .tif, .exr...; with --mips as for `mip`), folder (DIR/: {stem}.png each) or "
                   "template ('out/{stem}_n.png')");
  cmd->add_option("--kernel", args->kernel,
                  "Gradient kernel: gather2x2, central, sobel3, sobel5, prewitt3, prewitt5, scharr3, multiscale")
      ->capture_default_str();
  cmd->add_option("--height-channel", args->height_channel,
                  "Height from: auto (gray, or luma of RGB), r, g, b, a, luma")
      ->capture_default_str();
  cmd->add_flag("--invert", args->invert, "Depth map: use 1 - h");
  cmd->add_option("--height-scale", args->height_scale, "Texels spanned by a height of 1.0 (> 0)")
      ->check(in_range(0, 1e9, true))
      ->capture_default_str();
  cmd->add_option("--strength", args->strength, "Slope multiplier for artists (> 0)")
      ->check(in_range(0, 1e9, true))
      ->capture_default_str();
  cmd->add_option("--wrap", args->wrap, "Texels past the edges: clamp, repeat (tiling), mirror")->capture_default_str();
  cmd->add_option("--y", args->y, "Green channel: up (OpenGL, default) or down (DirectX)")->capture_default_str();
  cmd->add_option("--channels", args->channels, "Output channels: xyz, xy, xyzh")->capture_default_str();
  cmd->add_option("--multiscale-weights", args->multiscale_weights,
                  "multiscale kernel: weights of scales 1, 2, 4, ... texels (normalized to sum 1)")
      ->delimiter(',')
      ->capture_default_str()
      ->check(in_range(0, 1e6));
  cmd->add_option("--type", args->type,
                  "Output element type: u8, u16, f16, f32 (default: u8 for 8-bit input, else u16)");
  cmd->add_flag("--mips", args->mips, "Write a mip chain, renormalized each level");
  add_chain_options(*cmd, args->chain);
  cmd->add_option("--compression", args->compression, "Output compression, as for `texproc mip`");
  cmd->add_option("--dds-header", args->dds_header, "DDS header for .dds output: auto, dx9, dx10")
      ->capture_default_str();
  cmd->add_option("--zstd", args->zstd, "KTX2 output: Zstandard-supercompress each level at this level (1-22)")
      ->check(in_range(1, 22))
      ->group("Container");
  add_size_options(*cmd, args->size);
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "normalmap";
    c.default_extension = ".png";
    c.input_extensions = image_extensions();
    c.validate = [args] { validate(*args); };
    c.plan = [args](const InputFile& in, const std::string& out) { return plan(*args, in.path, out); };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_normalmap(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
