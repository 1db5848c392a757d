// texproc decompress: a texture container's images back to image files.
#include <filesystem>
#include <optional>
#include <iostream>

#include "commands.h"
#include "common.h"
#include "texproc/block_decode.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/runtime.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct DecompressArgs {
  CommonOptions common;
  std::string input, output, type;
  int level = 0, layer = 0, face = 0;
  bool all_levels = false;
};

int run_decompress(const DecompressArgs& a) {
  ThreadLimit threads(a.common.threads);
  WriteOptions w;
  const bool exr = fs::path(a.output).extension() == ".exr";
  std::optional<PixelType> type = parse_output_type(a.type, w);
  if (!type) {
    type = exr ? PixelType::f32 : PixelType::u8;
    w.half = exr;
  }
  const Texture t = read_texture(a.input);
  if (a.level < 0 || std::uint32_t(a.level) >= t.levels) {
    throw Error(ErrorCode::bad_arguments, a.input + ": --level " + std::to_string(a.level) + " (valid: 0 to " +
                                              std::to_string(t.levels - 1) + ")");
  }
  if (a.layer < 0 || std::uint32_t(a.layer) >= t.layers) {
    throw Error(ErrorCode::bad_arguments, a.input + ": --layer " + std::to_string(a.layer) + " (valid: 0 to " +
                                              std::to_string(t.layers - 1) + ")");
  }
  if (a.face < 0 || std::uint32_t(a.face) >= t.faces) {
    throw Error(ErrorCode::bad_arguments, a.input + ": --face " + std::to_string(a.face) + " (valid: 0 to " +
                                              std::to_string(t.faces - 1) + ")");
  }
  const std::uint32_t first = a.all_levels ? 0 : std::uint32_t(a.level), last = a.all_levels ? t.levels : first + 1;
  std::vector<std::string> outputs;
  if (a.all_levels) {
    outputs = level_outputs(a.output, int(t.levels));
    if (outputs.size() == 1) {
      throw Error(ErrorCode::unsupported, a.output + ": --all-levels writes one file per level (use .png, .exr, .tga)");
    }
  } else {
    outputs = {a.output};
  }
  for (const auto& o : outputs) check_output(o, {a.input}, a.common.force);
  if (stop_for_dry_run()) return 0;
  w.color_space = format_info(t.format).srgb ? "srgb" : "linear";
  for (std::uint32_t l = first; l < last; ++l) {
    const Image img = decode_texture_image(t, l, std::uint32_t(a.layer), std::uint32_t(a.face), *type);
    write_image(outputs[a.all_levels ? l : 0], img.view(), w);
  }
  if (!a.common.quiet) {
    std::cout << a.input << " -> " << outputs[0] << (outputs.size() > 1 ? " ..." : "") << ": "
              << format_info(t.format).name << ", " << (last - first) << " level(s)\n";
  }
  return 0;
}

}  // namespace

void add_decompress_command(CLI::App& app) {
  auto args = std::make_shared<DecompressArgs>();
  CLI::App* cmd = app.add_subcommand("decompress", "Decode a DDS/KTX2/KTX1/PKM texture back to image files.");
  cmd->footer(
      "BC1-BC5 and uncompressed formats (ETC decoding comes with the ETC codecs). SNORM data goes to float\n"
      "(.exr, or --type f32) as [-1, 1], to 8/16-bit as the usual biased (v + 1) / 2.");
  cmd->add_option("input", args->input, "Texture file")->required();
  cmd->add_option("-o,--output", args->output, "Output image (.png, .exr, .tga, .tif)")->required();
  cmd->add_option("--level", args->level, "Mip level to write (default 0)");
  cmd->add_flag("--all-levels", args->all_levels, "Write every level as {stem}_mip{L}.{ext}");
  cmd->add_option("--layer", args->layer, "Array layer (default 0)");
  cmd->add_option("--face", args->face, "Cubemap face 0-5: +X, -X, +Y, -Y, +Z, -Z (default 0)");
  cmd->add_option("--type", args->type, "Output element type: u8, u16, f16, f32 (default u8; f16 for .exr)");
  add_common_options(*cmd, args->common);
  set_runner(*cmd, [args] { return run_decompress(*args); });
}

}  // namespace texproc::cli
