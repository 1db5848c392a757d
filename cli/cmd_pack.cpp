// texproc pack: one texture from channels of several images (the ORM
// texture glTF and Unreal use: occlusion, roughness, metalness), written as
// an image or block-compressed.
#include <algorithm>
#include <array>
#include <cctype>
#include <cstring>
#include <sstream>

#include "batch.h"
#include "commands.h"
#include "common.h"
#include "texproc/block_encode.h"
#include "texproc/channels.h"
#include "texproc/color.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

namespace texproc::cli {
namespace {

constexpr const char* kSlots = "rgba";

// One output channel's source: a channel of a file, or a constant.
struct Source {
  std::string file;  // empty: the constant
  int channel = 0;   // 0-3 of the file read as RGBA
  float constant = 0.0f;
};

struct PackArgs {
  std::array<std::string, 4> specs;  // -r, -g, -b, -a as given
  BatchInputs io;
  SizeArgs size;
  std::string format, quality = "normal";
  bool srgb = false, mips = false;
  int zstd = 0;
  // From the options, once (validate):
  std::array<Source, 4> sources;
  int channels = 0;  // the output's: up to the last slot given
};

// "0", "1", "FILE" (the slot's own channel; a grey image's grey) or "FILE:CH".
Source parse_source(const std::string& spec, int slot) {
  Source s;
  if (spec == "0" || spec == "1") {
    s.constant = spec == "1" ? 1.0f : 0.0f;
    return s;
  }
  s.file = spec;
  s.channel = slot;
  const auto colon = spec.rfind(':');
  if (colon != std::string::npos && colon + 2 == spec.size()) {
    const char c = char(std::tolower(static_cast<unsigned char>(spec.back())));
    const char* at = std::strchr(kSlots, c);
    if (!at || c == 0) {
      throw Error(ErrorCode::bad_arguments, std::string("-") + kSlots[slot] + " " + spec + ": '" +
                                                std::string(1, spec.back()) + "' is not one of r, g, b, a");
    }
    s.file = spec.substr(0, colon);
    s.channel = int(at - kSlots);
  }
  return s;
}

void validate(PackArgs& a) {
  validate_size_options(a.size);
  a.channels = 0;
  for (int k = 0; k < 4; ++k) {
    if (a.specs[k].empty()) continue;
    a.sources[k] = parse_source(a.specs[k], k);
    a.channels = k + 1;
    if (!a.sources[k].file.empty()) record_input(a.sources[k].file);
  }
  if (a.channels == 0) throw Error(ErrorCode::bad_arguments, "pack: name at least one channel (-r, -g, -b, -a)");
  for (int k = 0; k < a.channels; ++k) {
    if (a.specs[k].empty()) {
      throw Error(ErrorCode::bad_arguments, std::string("pack: -") + kSlots[k] + " is missing before -" +
                                                kSlots[a.channels - 1] + " (0 or 1 for a constant)");
    }
  }
  if (!a.format.empty()) block_format_for(a.format, a.srgb);  // an unknown name fails now
  parse_quality(a.quality);
  if ((a.mips || a.zstd) && a.format.empty() && !a.io.output.empty() && !is_container_path(a.io.output)) {
    throw Error(ErrorCode::bad_arguments, "pack: --mips and --zstd write a texture (.ktx2, .dds with --format)");
  }
}

// The files' images, read once each, at the size the rule gives the first.
struct Loaded {
  std::vector<std::string> files;
  std::vector<Image> images;
  const Image& of(const std::string& file) const {
    return images[std::size_t(std::find(files.begin(), files.end(), file) - files.begin())];
  }
};

Loaded load_sources(const PackArgs& a, std::vector<std::string>& warnings) {
  Loaded l;
  for (int k = 0; k < a.channels; ++k) {
    const Source& s = a.sources[k];
    if (s.file.empty() || std::find(l.files.begin(), l.files.end(), s.file) != l.files.end()) continue;
    Image img = read_image(s.file, nullptr, cli_read_options());
    read_as_finite(s.file, img, warnings);
    apply_size_options(a.size, img, "linear");
    if (!l.images.empty() && (img.width() != l.images[0].width() || img.height() != l.images[0].height())) {
      throw Error(ErrorCode::bad_arguments,
                  "the sources must be one size (--resize WxH makes them): " + s.file + " is " +
                      std::to_string(img.width()) + "x" + std::to_string(img.height()) + ", " + l.files[0] + " " +
                      std::to_string(l.images[0].width()) + "x" + std::to_string(l.images[0].height()));
    }
    l.files.push_back(s.file);
    l.images.push_back(std::move(img));
  }
  return l;
}

void run_pack(const PackArgs& a, const std::string& output, FileReport& r) {
  PhaseTimer phases(r);
  const Loaded l = load_sources(a, r.warnings);
  phases.read_done();
  int width = 0, height = 0;
  PixelType type = PixelType::u8;
  for (const Image& img : l.images) {
    width = img.width();
    height = img.height();
    if (img.type() == PixelType::f32 || (img.type() == PixelType::u16 && type == PixelType::u8)) type = img.type();
  }
  Image packed(width, height, a.channels, type);
  for (int k = 0; k < a.channels; ++k) {
    const Source& s = a.sources[k];
    if (s.file.empty()) {
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) packed.set(x, y, k, s.constant);
      continue;
    }
    ChannelMap pick;
    pick.channels = 1;
    pick.from[0] = std::int8_t(s.channel);
    const Image one = map_channels(l.of(s.file).view(), pick);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) packed.set(x, y, k, one.get(x, y, 0));
  }
  phases.compute_done();
  if (a.format.empty() && !is_container_path(output)) {
    WriteOptions w = cli_write_options();
    w.color_space = a.srgb ? "srgb" : "linear";
    w.red_green = a.channels == 2;
    write_image(output, packed.view(), w);
  } else {
    if (a.format.empty()) throw Error(ErrorCode::bad_arguments, output + ": a texture output needs --format");
    const TexelFormat format = block_format_for(a.format, a.srgb);
    std::vector<Image> surfaces;
    surfaces.push_back(std::move(packed));
    Texture t;
    if (a.mips) {
      MipOptions m;
      m.color_space = format_info(format).srgb ? "srgb" : "linear";
      m.premultiplied_alpha = false;  // packed channels are data, the fourth is not coverage
      t = compress_texture_mips(surfaces, m, {}, format, parse_quality(a.quality));
    } else {
      std::vector<std::vector<Image>> chains(1);
      chains[0].push_back(std::move(surfaces[0]));
      t = compress_texture(chains, {}, format, parse_quality(a.quality));
    }
    write_texture(output, t, DdsHeader::automatic, zstd_level_for(a.zstd, output));
  }
  phases.write_done();
  std::ostringstream line;
  line << output << ": " << width << "x" << height << " from";
  for (int k = 0; k < a.channels; ++k) line << " " << kSlots[k] << "=" << a.specs[k];
  if (!a.format.empty()) line << ", " << a.format;
  r.line = line.str();
  r.details["width"] = width;
  r.details["height"] = height;
  r.details["channels"] = a.channels;
}

}  // namespace

void add_pack_command(CLI::App& app) {
  auto args = std::make_shared<PackArgs>();
  CLI::App* cmd = app.add_subcommand(
      "pack",
      "Pack channels of several images into one (ORM: occlusion, roughness, metalness), as an image or "
      "block-compressed.");
  cmd->footer(
      "Each of -r -g -b -a is FILE (the same channel of FILE; a grey image's grey), FILE:CH (CH one of r g b a)\n"
      "or a constant 0 or 1. The output has channels up to the last one given. Values are data: they move as\n"
      "stored (8/16-bit codes, floats); the sources must be one size (--resize WxH makes them). See docs/cli.md.");
  for (int k = 0; k < 4; ++k) {
    const std::string flag = std::string("-") + kSlots[k];
    cmd->add_option(flag, args->specs[k],
                    std::string("The output's ") + "RGBA"[k] + " channel: FILE, FILE:CH (r, g, b, a) or 0 or 1");
  }
  cmd->add_option("-o,--output", args->io.output,
                  "Output image (.png, .tga, .tif, .exr...) or, with --format, texture (.ktx2, .dds, .ktx)")
      ->required();
  cmd->add_option("--format", args->format,
                  "Block-compress to this format (as compress names them: bc7, bc1, bc5, "
                  "etc2, astc-6x6...)");
  cmd->add_option("--quality", args->quality, "With --format: fast, normal, high, max")->capture_default_str();
  cmd->add_flag("--srgb", args->srgb, "The packed channels are sRGB colour (default: linear data)");
  cmd->add_flag("--mips", args->mips, "With --format: a mip chain (channels filtered as data)");
  cmd->add_option("--zstd", args->zstd, "KTX2 output: Zstandard-supercompress each level (1-22)")
      ->check(in_range(1, 22));
  add_size_options(*cmd, args->size);
  add_common_options(*cmd);
  set_runner(*cmd, [args] {
    BatchCommand c;
    c.name = "pack";
    c.default_extension = ".png";
    c.input_extensions = image_extensions();
    c.validate = [args] {
      validate(*args);
      // The batch's one input: the first file named; the others are inputs of the output too.
      args->io.inputs.clear();
      for (int k = 0; k < args->channels && args->io.inputs.empty(); ++k)
        if (!args->sources[k].file.empty()) args->io.inputs.push_back(args->sources[k].file);
      if (args->io.inputs.empty()) throw Error(ErrorCode::bad_arguments, "pack: name at least one source file");
    };
    c.plan = [](const InputFile&, const std::string& out) { return std::vector<std::string>{out}; };
    c.run = [args](const std::string&, const std::string& out, FileReport& r) { run_pack(*args, out, r); };
    return run_batch(c, args->io);
  });
}

}  // namespace texproc::cli
