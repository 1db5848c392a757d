// texproc info: what a file holds, for people and (with --json) for scripts.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "batch.h"
#include "common.h"
#include "report.h"
#include "texproc/container.h"
#include "texproc/error.h"
#include "texproc/image_io.h"
#include "texproc/sat.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

struct InfoArgs {
  BatchInputs io;
  bool json = false;
};

std::string num(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// One file as a JSON object (the stable form, documented in docs/cli.md) and
// as text.
void describe(const std::string& path, Json::Value& json, std::ostringstream& text) {
  if (fs::path(path).extension() == ".sat") {
    const SummedAreaTable t = read_sat_file(path);
    json["file"] = path;
    json["container"] = "sat";
    json["width"] = t.width;
    json["height"] = t.height;
    json["channels"] = t.channels;
    json["precision"] = to_string(t.precision);
    json["source_type"] = to_string(t.source);
    json["block"] = t.block;
    json["max_exact_box"] = Json::UInt64(t.max_exact_box());
    json["error_bound"] = t.error_bound();
    json["data_bytes"] = Json::UInt64(t.data.size());
    text << path << ": summed-area table, " << t.width << "x" << t.height << ", " << t.channels << " channel(s), "
         << to_string(t.precision) << " sums of " << to_string(t.source) << " values";
    if (t.max_exact_box()) text << ", exact for boxes up to " << t.max_exact_box() << " texels";
    if (t.error_bound() > 0) text << ", box sums within +-" << num(t.error_bound());
    text << "\n";
    return;
  }
  if (is_texture_container(path)) {
    ReadLimits headers = cli_read_options().limits;
    headers.headers_only = true;  // the facts, without inflating or copying a level
    const Texture t = read_texture(path, headers);
    const FormatInfo& f = format_info(t.format);
    ContainerKind kind = ContainerKind::dds;
    {
      std::ifstream in(path, std::ios::binary);
      char h[12] = {};
      in.read(h, 12);
      container_from_signature(reinterpret_cast<const std::uint8_t*>(h), std::size_t(in.gcount()), kind);
    }
    const std::string container = to_string(kind);
    json["file"] = path;
    json["container"] = container;
    json["format"] = f.name;
    json["vk_format"] = f.vk_format;
    json["dxgi_format"] = f.dxgi_format;
    json["color_space"] = f.srgb ? "srgb" : "linear";
    json["width"] = t.width;
    json["height"] = t.height;
    json["faces"] = t.faces;
    json["layers"] = t.layers;
    json["is_array"] = t.is_array;
    Json::Value levels(Json::arrayValue);
    std::uint64_t total = 0;
    for (std::uint32_t l = 0; l < t.levels; ++l) {
      const std::uint64_t bytes = image_bytes(t.format, t.level_width(l), t.level_height(l)) * t.layers * t.faces;
      total += bytes;
      Json::Value level(Json::objectValue);
      level["width"] = t.level_width(l);
      level["height"] = t.level_height(l);
      level["bytes"] = Json::UInt64(bytes);
      levels.append(level);
    }
    json["levels"] = levels;
    json["data_bytes"] = Json::UInt64(total);
    Ktx2Storage storage;
    if (kind == ContainerKind::ktx2) {
      storage = ktx2_storage(path);
      std::uint64_t stored = 0;
      for (std::uint64_t b : storage.stored_bytes) stored += b;
      Json::Value stored_levels(Json::arrayValue);
      for (std::uint64_t b : storage.stored_bytes) stored_levels.append(Json::UInt64(b));
      json["supercompression"] = ktx2_scheme_name(storage.scheme);
      json["stored_level_bytes"] = stored_levels;
      json["stored_bytes"] = Json::UInt64(stored);
    }
    const bool packed = storage.scheme != 0 && storage.stored_bytes.size() == t.levels;
    text << path << ": " << container << ", " << f.name << " (" << (f.srgb ? "sRGB" : "linear") << "), " << t.width
         << "x" << t.height << ", " << t.levels << " level(s)";
    if (t.faces == 6) text << ", cubemap";
    if (t.is_array) text << ", " << t.layers << " layers";
    text << ", " << total << " bytes of texel data";
    if (packed) {
      std::uint64_t stored = 0;
      for (std::uint64_t b : storage.stored_bytes) stored += b;
      char share[32];
      std::snprintf(share, sizeof share, "%.1f%%", 100.0 * double(stored) / double(std::max<std::uint64_t>(1, total)));
      text << ", " << ktx2_scheme_name(storage.scheme) << "-supercompressed to " << stored << " bytes (" << share
           << ")";
    }
    text << "\n";
    for (std::uint32_t l = 0; l < t.levels; ++l) {
      const std::uint64_t bytes = image_bytes(t.format, t.level_width(l), t.level_height(l)) * t.layers * t.faces;
      text << "  level " << l << ": " << t.level_width(l) << "x" << t.level_height(l) << ", " << bytes << " bytes";
      if (packed) text << ", stored in " << storage.stored_bytes[l];
      text << "\n";
    }
    return;
  }
  const ImageFileInfo i = probe_image(path, cli_read_options());
  json["file"] = path;
  json["container"] = i.format;
  json["width"] = i.width;
  json["height"] = i.height;
  json["channels"] = i.channels;
  json["type"] = i.file_type;
  json["color_space_tag"] = i.color_space_tag;
  json["color_space_tagged"] = i.color_space_tagged;
  json["subimages"] = i.subimages;
  Json::Value levels(Json::arrayValue);
  for (const auto& [width, height] : i.level_sizes) {
    Json::Value level(Json::objectValue);
    level["width"] = width;
    level["height"] = height;
    levels.append(level);
  }
  json["levels"] = levels;
  text << path << ": " << i.format << ", " << i.width << "x" << i.height << ", " << i.channels << " channel(s) of "
       << i.file_type;
  if (!i.color_space_tag.empty()) {
    text << (i.color_space_tagged ? ", tagged " : ", no colour tag (read as ") << i.color_space_tag
         << (i.color_space_tagged ? "" : ")");
  }
  if (i.mip_levels > 1) text << ", " << i.mip_levels << " MIP levels";
  if (i.subimages > 1) text << ", " << i.subimages << " subimages";
  text << "\n";
}

int run_info(const InfoArgs& args) {
  std::vector<std::string> files;
  std::vector<std::string> extensions = image_extensions();
  for (const auto& e : texture_extensions())
    if (std::find(extensions.begin(), extensions.end(), e) == extensions.end()) extensions.push_back(e);
  extensions.push_back(".sat");
  for (const InputFile& f : expand_inputs(args.io, extensions)) files.push_back(f.path);
  std::ostringstream text;
  Json::Value json(Json::arrayValue);
  int failures = 0;
  ErrorCode last = ErrorCode::success;
  for (std::size_t k = 0; k < files.size(); ++k) {
    try {
      Json::Value j(Json::objectValue);
      describe(files[k], j, text);
      json.append(j);
    } catch (const Error& e) {
      print_error("info", about(files[k], e.what()));
      Json::Value j(Json::objectValue);
      j["file"] = files[k];
      j["error"] = about(files[k], e.what());
      j["exit_code"] = int(e.code());
      json.append(j);
      ++failures;
      last = e.code();
    }
  }
  if (args.json) {
    std::cout << to_json(json, kExactDigits) << "\n";
  } else {
    std::cout << text.str();
  }
  return failures ? int(last) : 0;
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto args = std::make_shared<InfoArgs>();
  CLI::App* cmd =
      app.add_subcommand("info", "Describe images, MIP chains, DDS/KTX2/KTX1/PKM/.astc textures and .sat tables.");
  cmd->add_option("files", args->io.inputs, "Files to describe, or folders (their images, textures and tables)")
      ->required();
  cmd->add_flag("-r,--recursive", args->io.recursive, "Folders: their subfolders too");
  cmd->add_option("--file-list", args->io.file_list, "Read more files from FILE, one a line");
  cmd->add_flag("--json", args->json, "Print a JSON array, one object per file (schema in docs/cli.md)");
  set_runner(*cmd, [args] { return run_info(*args); });
}

}  // namespace texproc::cli
