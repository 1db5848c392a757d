// texproc convert: a texture moved from one container to another (DDS,
// KTX2 with or without Zstandard, KTX1, PKM, .astc) with its blocks, levels,
// faces and layers byte for byte: nothing is decoded or encoded.
#include <filesystem>

#include "batch.h"
#include "commands.h"
#include "common.h"
#include "texproc/container.h"
#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct ConvertArgs {
  BatchInputs io;
  std::string dds_header = "auto";
  int zstd = 0;
};

std::string shape_of(const Texture& t) {
  std::string s =
      std::to_string(t.width) + "x" + std::to_string(t.height) + ", " + std::to_string(t.levels) + " level(s)";
  if (t.faces > 1) s += ", " + std::to_string(t.faces) + " faces";
  if (t.layers > 1 || t.is_array) s += ", " + std::to_string(t.layers) + " layer(s)";
  return s;
}

void run_convert(const ConvertArgs& a, const std::string& input, const std::string& output, FileReport& r) {
  PhaseTimer phases(r);
  const Texture t = read_texture(input, cli_read_options().limits);
  phases.read_done();
  // The target container refuses what it cannot hold (BC in PKM, mips in
  // .astc, ETC in DDS...) with the reason, naming the output; nothing is
  // written then.
  write_texture(output, t, parse_dds_header(a.dds_header), zstd_level_for(a.zstd, output));
  phases.write_done();
  if (format_info(t.format).srgb && fs::path(output).extension() == ".astc") {
    r.warnings.push_back(output + ": .astc files carry no colour space: the sRGB mark of " + input +
                         " is not kept (the file reads back as UNORM; .ktx2 or .ktx keep it)");
  }
  r.line = input + " -> " + output + ": " + format_info(t.format).name + ", " + shape_of(t) + ", blocks unchanged";
  r.details["format"] = format_info(t.format).name;
  r.details["width"] = t.width;
  r.details["height"] = t.height;
  r.details["levels"] = t.levels;
  r.details["faces"] = t.faces;
  r.details["layers"] = t.layers;
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto args = std::make_shared<ConvertArgs>();
  CLI::App* cmd = app.add_subcommand(
      "convert", "Move a texture to another container (DDS, KTX2, KTX1, PKM, .astc) without decoding it.");
  cmd->footer(
      "The blocks, levels, faces and layers are written byte for byte in the container the output's extension\n"
      "names; a container that cannot hold the texture is refused with the reason (PKM holds one ETC1/ETC2 RGB\n"
      "level, .astc one ASTC level, DDS no ETC or ASTC). KTX2 input may be Zstandard- or zlib-supercompressed;\n"
      "--zstd supercompresses a KTX2 output.");
  add_batch_inputs(*cmd, args->io, "Texture files (.dds, .ktx2, .ktx, .pkm, .astc)",
                   "Output texture (.dds, .ktx2, .ktx, .pkm, .astc), folder (DIR/: {stem}.ktx2 each) or template "
                   "('out/{stem}.dds')");
  cmd->add_option("--zstd", args->zstd, "KTX2 output: Zstandard-supercompress each level at this level (1-22)")
      ->check(in_range(1, 22));
  cmd->add_option("--dds-header", args->dds_header, "DDS output: auto, dx9, dx10")->capture_default_str();
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "convert";
    c.default_extension = ".ktx2";
    c.input_extensions = texture_extensions();
    c.validate = [args] {
      parse_dds_header(args->dds_header);
      const std::string& out = args->io.output;
      const bool folder = !out.empty() && (out.back() == '/' || fs::is_directory(out));
      if (!folder && out.find('{') == std::string::npos) {
        zstd_level_for(args->zstd, out);
        check_dds_header_fits(args->dds_header, out);
        if (!is_container_path(out)) {
          throw Error(ErrorCode::bad_arguments,
                      out + ": not a texture container (valid: .dds, .ktx2, .ktx, .pkm, .astc)");
        }
      }
    };
    c.plan = [](const InputFile&, const std::string& out) { return std::vector<std::string>{out}; };
    c.run = [args](const std::string& in, const std::string& out, FileReport& r) { run_convert(*args, in, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
