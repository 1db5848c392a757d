// texproc mip: gamma-correct mip chains.
#include <chrono>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"
#include "texproc/runtime.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct MipArgs {
  SizeArgs size;
  ChannelArgs channels;
  BatchInputs io;
  ChainArgs chain;
  std::string wrap = "clamp";
  std::string color_space, out_color_space;
  bool linear = false;
  std::string type;
  float alpha_coverage = -1.0f;
  bool normal_map = false;
  bool no_premultiply = false;
  std::string compression;
  std::string dds_header = "auto";
  int zstd = 0;
  bool report = false;
  // From the options, once (validate):
  MipOptions mip;
  WriteOptions write = cli_write_options();
  DdsHeader header = DdsHeader::automatic;
};

void validate(MipArgs& a) {
  validate_size_options(a.size);
  validate_channel_options(a.channels);
  MipOptions& o = a.mip;
  o.filter.kind = parse_filter_kind(a.chain.filter);
  o.filter.sigma = a.chain.sigma;
  o.wrap = parse_wrap_mode(a.wrap);
  o.color_space = a.linear ? "linear" : a.color_space;
  o.output_color_space = a.out_color_space;
  o.max_levels = a.chain.levels;
  o.min_size = a.chain.min_size;
  if (a.alpha_coverage >= 0.0f) o.alpha_coverage_ref = a.alpha_coverage;
  o.normal_map = a.normal_map;
  o.premultiplied_alpha = !a.no_premultiply;
  a.header = parse_dds_header(a.dds_header);
  a.write.compression = a.compression;
  o.output_type = parse_output_type(a.type, a.write);
  // An OpenColorIO config the color spaces come from is a dependency too.
  for (const std::string& name : {a.color_space, a.out_color_space}) {
    if (name.empty() || a.linear) continue;
    const std::string config = ColorSpace::from_name(name).config_path();
    if (!config.empty()) record_input(config);
  }
}

std::vector<std::string> plan(const MipArgs& a, const std::string& input, const std::string& output) {
  if (is_container_path(output)) return {output};
  const ImageFileInfo info = probe_image(input, cli_read_options());
  int width = info.width, height = info.height;
  apply_size_rule(a.size.rule, width, height);
  return level_outputs(output, mip_level_count(width, height, a.mip.max_levels, a.mip.min_size));
}

void report_mip(const MipArgs& a, const std::string& input, const std::string& output, const ImageFileInfo& info,
                std::size_t level_count, PixelType level_type, const MipChain& chain, FileReport& r);

void run_mip(const MipArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  MipOptions o = a.mip;
  WriteOptions w = a.write;
  const bool container = is_container_path(output);
  if (!o.output_type && fs::path(output).extension() == ".exr") {
    o.output_type = PixelType::f32;  // OpenEXR holds floats: write half
    w.half = true;
  }
  check_dds_header_fits(a.dds_header, output);
  zstd_level_for(a.zstd, output);  // checked before any work
  PhaseTimer phases(r);
  ImageFileInfo info;
  ImageArray in = read_image_array(input, &info, cli_read_options());
  for (Image& im : in.images) {
    read_as_finite(input, im, r.warnings);
    apply_channel_options(a.channels, im);
    apply_size_options(a.size, im, o.color_space, o.normal_map);
  }
  phases.read_done();
  check_surfaces_fit(input, in, output);
  // A half-float texture stays half float.
  if (!o.output_type && container && info.file_type == "rgba16_float") w.half = true;
  // GPU formats have no 16-bit sRGB: a 16-bit sRGB chain goes into a
  // container linear (r16/rg16/rgba16_unorm say linear), not sRGB values
  // labelled linear.
  const PixelType out_type = o.output_type ? *o.output_type : in.images[0].type();
  const bool srgb_in =
      o.color_space.empty() ? in.images[0].type() != PixelType::f32 : ColorSpace::from_name(o.color_space).is_srgb();
  if (container && out_type == PixelType::u16 && srgb_in && o.output_color_space.empty())
    o.output_color_space = "linear";
  const int width = in.images[0].width(), height = in.images[0].height();
  const std::size_t level_count = std::size_t(mip_level_count(width, height, o.max_levels, o.min_size));
  const PixelType level_type = out_type;
  MipChain chain;
  // One float OpenEXR chain down to 1x1: written band by band as the levels
  // are filtered, the chain never held.
  if (in.images.size() == 1 && out_type == PixelType::f32 && MipFileWriter::supports(output, w) &&
      level_count == std::size_t(mip_level_count(width, height))) {
    MipFileWriter file(output, width, height, in.images[0].channels(), w);
    struct Sink final : MipRowSink {
      MipFileWriter* file = nullptr;
      bool wants_level0() const override { return true; }
      void* row(int level, int y) override { return file->row(level, y); }
      void row_done(int level, int y) override { file->row_done(level, y); }
    } sink;
    sink.file = &file;
    chain = generate_mips_rows(in.images[0].view(), o, sink);
    phases.compute_done();
    file.commit();
    phases.write_done();
    report_mip(a, input, output, info, level_count, level_type, chain, r);
    return;
  }
  // A cubemap's faces and an array's layers are each mipped on their own.
  std::vector<std::vector<Image>> more;
  for (std::size_t s = 1; s < in.images.size(); ++s) more.push_back(generate_mips(std::move(in.images[s]), o).levels);
  chain = generate_mips(std::move(in.images[0]), o);
  phases.compute_done();
  w.color_space = chain.color_space == "srgb" ? "srgb" : chain.color_space == "linear" ? "linear" : "";
  if (container && !more.empty()) {
    std::vector<std::vector<Image>> chains;
    chains.push_back(std::move(chain.levels));
    for (auto& c : more) chains.push_back(std::move(c));
    write_texture(
        output,
        texture_from_surfaces(std::move(chains), in.layout(), {.srgb = chain.color_space == "srgb", .half = w.half}),
        a.header, zstd_level_for(a.zstd, output));
  } else if (container) {
    // Uncompressed GPU formats: r8/rg8/rgba8 (sRGB when the chain is), 16-bit, half or float;
    // the chain's pixel memory becomes the texture's.
    write_texture(output,
                  texture_from_levels(std::move(chain.levels), {.srgb = chain.color_space == "srgb", .half = w.half}),
                  a.header, zstd_level_for(a.zstd, output));
  } else {
    write_levels(output, chain.levels, w);
  }
  phases.write_done();
  report_mip(a, input, output, info, level_count, level_type, chain, r);
}

void report_mip(const MipArgs& a, const std::string& input, const std::string& output, const ImageFileInfo& info,
                std::size_t level_count, PixelType level_type, const MipChain& chain, FileReport& r) {
  std::ostringstream line;
  line << input << " -> " << (r.outputs.size() == 1 ? output : r.outputs[0] + " ...") << ": " << level_count
       << " levels, " << info.width << "x" << info.height << " " << to_string(level_type) << " " << chain.color_space
       << ", filter " << a.chain.filter << ", wrap " << a.wrap;
  if (run_options().verbose) {
    for (std::size_t l = 0; l < chain.alpha_coverage.size(); ++l) {
      line << "\n  level " << l << ": alpha coverage " << chain.alpha_coverage[l] << " (alpha x "
           << chain.alpha_scale[l] << ")";
    }
  }
  r.line = line.str();
  r.details["width"] = info.width;
  r.details["height"] = info.height;
  r.details["levels"] = Json::UInt(level_count);
  r.details["type"] = to_string(level_type);
  r.details["color_space"] = chain.color_space;
  if (a.report && !chain.alpha_coverage.empty()) {
    Json::Value cov(Json::arrayValue), scale(Json::arrayValue);
    for (std::size_t l = 0; l < chain.alpha_coverage.size(); ++l) {
      cov.append(chain.alpha_coverage[l]);
      scale.append(chain.alpha_scale[l]);
    }
    r.details["alpha_coverage"] = cov;
    r.details["alpha_scale"] = scale;
  }
}

}  // namespace

void add_mip_command(CLI::App& app) {
  auto args = std::make_shared<MipArgs>();
  CLI::App* cmd = app.add_subcommand("mip", "Build gamma-correct mip chains from images.");
  cmd->footer(
      "Outputs: .dds/.ktx2/.ktx write the chain as an uncompressed GPU texture (rgba8 sRGB or unorm,\n"
      "r8, rg8, 16-bit, half or float); .tif/.tiff/.exr write one MIP-mapped file (OpenImageIO reads the levels back, "
      "as from\n"
      "maketx); .png/.tga/.jpg/.bmp write one file per level, named {stem}_mip{L}.{ext}.\n"
      "Levels are max(1, floor(n/2)) per axis down to 1x1, each filtered from the previous level in\n"
      "linear premultiplied float. See docs/mip.md.");
  add_batch_inputs(*cmd, args->io, "Input images (any format OpenImageIO reads)",
                   "Output file, folder (DIR/: {stem}.dds each) or template ('out/{stem}.ktx2'); see below");
  add_chain_options(*cmd, args->chain, "Options");
  add_channel_options(*cmd, args->channels);
  add_size_options(*cmd, args->size);
  cmd->add_option("--wrap", args->wrap, "Texels past the edges: clamp, repeat, mirror")->capture_default_str();
  cmd->add_option("--colorspace", args->color_space,
                  "Source color space: srgb, linear, or an OpenColorIO name (default: srgb for 8/16-bit, "
                  "linear for float input)");
  cmd->add_flag("--linear", args->linear, "The input is data, not color: no transfer function (= --colorspace linear)");
  cmd->add_option("--out-colorspace", args->out_color_space,
                  "Color space of the written levels (default: the source's; linear for float output)");
  cmd->add_option("--type", args->type, "Output element type: u8, u16, f16, f32 (default: the input's; f16 for .exr)");
  cmd->add_option("--alpha-coverage", args->alpha_coverage,
                  "Keep the fraction of texels with alpha >= REF equal to level 0's (cutouts), 0 < REF <= 1")
      ->check(in_range(0, 1, true));
  cmd->add_flag("--normal-map", args->normal_map, "Input is a tangent-space normal map: renormalize each level");
  cmd->add_flag("--no-premultiply", args->no_premultiply, "Filter color without weighting it by alpha");
  cmd->add_option("--compression", args->compression,
                  "Output compression: TIFF zip:N (deflate level 1-12, default zip:1), none, lzw; EXR zip, piz, "
                  "dwaa... (OpenImageIO's names)");
  cmd->add_option("--dds-header", args->dds_header,
                  "DDS header: auto (legacy when a FourCC or masks can say the format, else DX10), dx9, dx10")
      ->capture_default_str();
  cmd->add_option("--zstd", args->zstd, "KTX2 output: Zstandard-supercompress each level at this level (1-22)")
      ->check(in_range(1, 22))
      ->group("Container");
  cmd->add_flag("--report", args->report, "With --json: alpha coverage and its scale per level (--alpha-coverage)");
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "mip";
    c.default_extension = ".dds";
    c.input_extensions = image_extensions();
    c.validate = [args] { validate(*args); };
    c.plan = [args](const InputFile& in, const std::string& out) { return plan(*args, in.path, out); };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_mip(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
