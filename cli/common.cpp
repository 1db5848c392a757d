#include "common.h"

#include <filesystem>
#include <map>

#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc::cli {

void add_common_options(CLI::App& cmd, CommonOptions& o) {
  cmd.add_option("-j,--threads", o.threads, "Worker threads (default 0: all cores). Output is identical for any value.")
      ->check(CLI::NonNegativeNumber)
      ->group("Common");
  cmd.add_flag("-f,--force", o.force, "Overwrite outputs that already exist")->group("Common");
  cmd.add_flag("-q,--quiet", o.quiet, "Print nothing but errors")->group("Common");
  cmd.add_flag("-v,--verbose", o.verbose, "Print details of the work")->group("Common");
}

namespace {
std::map<const CLI::App*, CommandRunner>& runners() {
  static std::map<const CLI::App*, CommandRunner> r;
  return r;
}
}  // namespace

void set_runner(CLI::App& cmd, CommandRunner runner) { runners()[&cmd] = std::move(runner); }
CommandRunner* runner_of(CLI::App& cmd) {
  auto it = runners().find(&cmd);
  return it == runners().end() ? nullptr : &it->second;
}

void check_output(const std::string& output, const std::vector<std::string>& inputs, bool force) {
  std::error_code ec;
  for (const auto& in : inputs) {
    if (fs::exists(output, ec) && fs::equivalent(output, in, ec)) {
      throw Error(ErrorCode::bad_arguments, output + ": output would overwrite the input; choose another name");
    }
  }
  if (fs::exists(output, ec)) {
    if (fs::is_directory(output, ec)) throw Error(ErrorCode::bad_arguments, output + ": output is a directory");
    if (!force) throw Error(ErrorCode::bad_arguments, output + ": output exists (use --force to overwrite it)");
  }
  const fs::path parent = fs::path(output).parent_path();
  if (!parent.empty() && !fs::exists(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) throw Error(ErrorCode::io, parent.string() + ": cannot create folder: " + ec.message());
  }
}

void add_chain_options(CLI::App& cmd, ChainArgs& a, const char* group) {
  cmd.add_option("--filter", a.filter, "Mip filter: gaussian, box, triangle, kaiser, lanczos3, mitchell")
      ->capture_default_str()
      ->group(group);
  cmd.add_option("--sigma", a.sigma, "Gaussian standard deviation in destination texels (0 < sigma <= 4)")
      ->capture_default_str()
      ->group(group);
  cmd.add_option("--levels", a.levels, "Number of levels, level 0 included (default 0: down to 1x1)")
      ->check(CLI::NonNegativeNumber)
      ->group(group);
  cmd.add_option("--min-size", a.min_size, "Stop before a level whose larger side is below this")
      ->check(CLI::PositiveNumber)
      ->group(group);
}

std::optional<PixelType> parse_output_type(const std::string& type, WriteOptions& w) {
  if (type.empty()) return std::nullopt;
  if (type == "u8") return PixelType::u8;
  if (type == "u16") return PixelType::u16;
  if (type == "f32") return PixelType::f32;
  if (type == "f16") {
    w.half = true;
    return PixelType::f32;
  }
  throw Error(ErrorCode::bad_arguments, "unknown --type '" + type + "' (valid: u8, u16, f16, f32)");
}

std::vector<std::string> level_outputs(const std::string& output, int levels) {
  if (holds_mip_levels(output)) return {output};
  const fs::path p(output);
  std::vector<std::string> names;
  for (int l = 0; l < levels; ++l) {
    names.push_back((p.parent_path() / (p.stem().string() + "_mip" + std::to_string(l) + p.extension().string())).string());
  }
  return names;
}

void write_levels(const std::string& output, const std::vector<Image>& levels, const WriteOptions& options) {
  if (holds_mip_levels(output)) {
    write_mip_file(output, levels, options);
    return;
  }
  const auto names = level_outputs(output, int(levels.size()));
  for (std::size_t l = 0; l < levels.size(); ++l) write_image(names[l], levels[l].view(), options);
}

bool is_container_path(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e == ".dds" || e == ".ktx2" || e == ".ktx" || e == ".pkm";
}

DdsHeader parse_dds_header(const std::string& s) {
  if (s == "auto") return DdsHeader::automatic;
  if (s == "dx9") return DdsHeader::dx9;
  if (s == "dx10") return DdsHeader::dx10;
  throw Error(ErrorCode::bad_arguments, "unknown --dds-header '" + s + "' (valid: auto, dx9, dx10)");
}

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : sep) + i;
  return s;
}

}  // namespace texproc::cli
