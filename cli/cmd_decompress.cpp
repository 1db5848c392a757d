// texproc decompress: a texture container's images back to image files.
#include <filesystem>
#include <optional>
#include <iostream>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "texproc/block_decode.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct DecompressArgs {
  BatchInputs io;
  std::string type;
  int level = 0, layer = 0, face = 0;
  bool all_levels = false;
  ChannelArgs channels;
  // From the options, once (validate):
  std::optional<PixelType> type_choice;
  WriteOptions write = cli_write_options();
};

void check_index(const std::string& input, const char* what, int value, std::uint32_t count) {
  if (value < 0 || std::uint32_t(value) >= count) {
    throw Error(ErrorCode::bad_arguments,
                input + ": " + what + " " + std::to_string(value) + " (valid: 0 to " + std::to_string(count - 1) + ")");
  }
}

std::vector<std::string> plan(const DecompressArgs& a, const std::string& input, std::string output) {
  // -o DIR/: HDR textures (half and float formats, ASTC HDR) go to OpenEXR,
  // where their values above 1 survive, instead of the folder default .png.
  // The texture is read here only when its format or levels decide the name.
  const bool folder = !a.io.output.empty() && (a.io.output.back() == '/' || fs::is_directory(a.io.output));
  const bool default_png = folder && fs::path(output).extension() == ".png";
  if (!default_png && !a.all_levels) return {output};
  const Texture t = read_texture(input, cli_read_options().limits);
  if (default_png && format_info(t.format).is_float) output = fs::path(output).replace_extension(".exr").string();
  if (!a.all_levels) return {output};
  // One level, or a file that holds a MIP chain (.exr, .tif): the one output.
  if (t.levels == 1 || holds_mip_levels(output)) return {output};
  return level_outputs(output, int(t.levels));
}

void run_decompress(const DecompressArgs& a, const std::string& input, const std::string& requested, FileReport& r) {
  // plan() may have chosen another name (.exr for HDR into a folder).
  const std::string output = r.outputs.size() == 1 ? r.outputs[0] : requested;
  WriteOptions w = a.write;
  const bool exr = fs::path(output).extension() == ".exr";
  std::optional<PixelType> type = a.type_choice;
  if (!type) {
    type = exr ? PixelType::f32 : PixelType::u8;
    w.half = exr;
  }
  PhaseTimer phases(r);
  const Texture t = read_texture(input, cli_read_options().limits);
  phases.read_done();
  check_index(input, "--level", a.level, t.levels);
  check_index(input, "--layer", a.layer, t.layers);
  check_index(input, "--face", a.face, t.faces);
  const std::uint32_t first = a.all_levels ? 0 : std::uint32_t(a.level), last = a.all_levels ? t.levels : first + 1;
  w.color_space = format_info(t.format).srgb ? "srgb" : "linear";
  w.red_green = format_info(t.format).channels == 2;  // BC5, EAC RG11, RG8/RG16: data, not grey + alpha
  // OpenEXR holds linear light: an sRGB texture's texels are decoded to linear
  // there (alpha as it is), and the file says linear.
  const bool to_linear = exr && format_info(t.format).srgb && *type == PixelType::f32;
  if (to_linear) w.color_space = "linear";
  auto decode = [&](std::uint32_t l) {
    Image img = decode_texture_image(t, l, std::uint32_t(a.layer), std::uint32_t(a.face), *type);
    if (to_linear) {
      std::vector<float> row(std::size_t(img.width()) * img.channels());
      for (int y = 0; y < img.height(); ++y) {
        ColorSpace::srgb().decode_row(img.row<float>(y), PixelType::f32, img.channels(), img.width(), row.data());
        std::copy(row.begin(), row.end(), img.row<float>(y));
      }
    }
    apply_channel_options(a.channels, img);
    return img;
  };
  if (a.all_levels && holds_mip_levels(output) && t.levels > 1) {
    std::vector<Image> levels;
    for (std::uint32_t l = 0; l < t.levels; ++l) levels.push_back(decode(l));
    phases.compute_done();
    write_mip_file(output, levels, w);  // one file with the whole chain
    phases.write_done();
  } else {
    // Each level decoded band by band as the writer asks for its rows.
    for (std::uint32_t l = first; l < last; ++l) {
      ImageView shape;
      shape.width = int(t.level_width(l));
      shape.height = int(t.level_height(l));
      const int decoded_channels = format_info(t.format).channels;
      shape.channels = mapped_channels(a.channels.map, decoded_channels);
      shape.type = *type;
      const bool mapped = !a.channels.map.identity();
      // Rows as decoded; with a channel map, a band decoded apart and then mapped into place.
      const RowSource decoded = [&](int y0, int y1, void* dst, std::size_t stride) {
        decode_texture_rows(t, l, std::uint32_t(a.layer), std::uint32_t(a.face), *type, y0, y1, dst, stride);
        if (!to_linear) return;
        std::vector<float> lin(std::size_t(shape.width) * decoded_channels);
        for (int y = y0; y < y1; ++y) {
          float* row = reinterpret_cast<float*>(static_cast<std::uint8_t*>(dst) + std::size_t(y - y0) * stride);
          ColorSpace::srgb().decode_row(row, PixelType::f32, decoded_channels, shape.width, lin.data());
          std::copy(lin.begin(), lin.end(), row);
        }
      };
      const RowSource rows = [&](int y0, int y1, void* dst, std::size_t stride) {
        if (!mapped) return decoded(y0, y1, dst, stride);
        Image band = Image::uninitialized(shape.width, y1 - y0, decoded_channels, *type);
        decoded(y0, y1, band.data(), band.row_stride());
        ImageView out = shape;
        out.data = dst;
        out.height = y1 - y0;
        out.row_stride = stride;
        map_channels(band.view(), out, a.channels.map);
      };
      write_image(a.all_levels && r.outputs.size() > 1 ? r.outputs.at(l) : output, shape, rows, w);
      phases.compute_done();
      phases.write_done();
    }
  }
  r.line = input + " -> " + r.outputs[0] + (r.outputs.size() > 1 ? " ..." : "") + ": " + format_info(t.format).name +
           ", " + std::to_string(last - first) + " level(s)";
  r.details["format"] = format_info(t.format).name;
  r.details["width"] = t.width;
  r.details["height"] = t.height;
  r.details["levels"] = last - first;
}

}  // namespace

void add_decompress_command(CLI::App& app) {
  auto args = std::make_shared<DecompressArgs>();
  CLI::App* cmd = app.add_subcommand("decompress", "Decode a DDS/KTX2/KTX1/PKM/.astc texture back to image files.");
  cmd->footer(
      "Every format texproc writes: BC1-BC5, ETC1/ETC2/EAC, ASTC (through astc-encoder's decoder) and the\n"
      "uncompressed ones. SNORM data goes to float (.exr, or --type f32) as [-1, 1], to 8/16-bit as the usual\n"
      "biased (v + 1) / 2. With -o DIR/, HDR textures (float formats, ASTC HDR) are written as .exr.");
  add_batch_inputs(*cmd, args->io, "Texture files (.dds, .ktx2, .ktx, .pkm, .astc)",
                   "Output image (.png, .exr, .tga, .tif), folder (DIR/: {stem}.png each, .exr for HDR) or template");
  cmd->add_option("--level", args->level, "Mip level to write (default 0)")->check(in_range(0, 31));
  cmd->add_flag("--all-levels", args->all_levels, "Write every level as {stem}_mip{L}.{ext}");
  cmd->add_option("--layer", args->layer, "Array layer (default 0)")->check(in_range(0, 65535));
  cmd->add_option("--face", args->face, "Cubemap face 0-5: +X, -X, +Y, -Y, +Z, -Z (default 0)")->check(in_range(0, 5));
  cmd->add_option("--type", args->type, "Output element type: u8, u16, f16, f32 (default u8; f16 for .exr)");
  add_channel_options(*cmd, args->channels);
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "decompress";
    c.default_extension = ".png";
    c.input_extensions = texture_extensions();
    c.validate = [args] {
      args->type_choice = parse_output_type(args->type, args->write);
      validate_channel_options(args->channels);
    };
    c.plan = [args](const InputFile& in, const std::string& out) { return plan(*args, in.path, out); };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_decompress(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
