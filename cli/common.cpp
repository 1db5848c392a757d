#include "common.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>

#include <unistd.h>

#include "batch.h"
#include "texproc/block_decode.h"
#include "texproc/error.h"
#include "texproc/metrics.h"
#include "texproc/tools.h"

namespace fs = std::filesystem;

namespace texproc::cli {

namespace {
// The files check_output() saw and commands recorded, for --depfile.
struct BuildState {
  std::vector<std::string> outputs, inputs;
  std::mutex mutex;  // commands record inputs from worker threads
};
BuildState& build_state() {
  static BuildState d;
  return d;
}

// Throws Error{bad_arguments} when `output` is the same file as one of
// `inputs` (compared as files, not strings); `what` names the output.
void refuse_overwriting_input(const std::string& output, const std::vector<std::string>& inputs, const char* what) {
  std::error_code ec;
  if (!fs::exists(output, ec)) return;
  for (const auto& in : inputs) {
    if (fs::equivalent(output, in, ec)) {
      throw Error(ErrorCode::bad_arguments, output + ": " + what + " would overwrite the input; choose another name");
    }
  }
}
}  // namespace

RunOptions& run_options() {
  static RunOptions o;
  return o;
}

void add_common_options(CLI::App& cmd) {
  RunOptions& s = run_options();
  cmd.add_option("--threads", s.threads, "Worker threads (default 0: all cores). Output is identical for any value.")
      ->check(in_range(0, 4096))
      ->group("Common");
  cmd.add_option("-j,--jobs", s.jobs,
                 "Files processed at once (default 0: as many as threads); they share the threads, output is "
                 "identical for any value")
      ->check(in_range(0, 4096))
      ->group("Common");
  cmd.add_flag("--fail-fast", s.fail_fast, "Stop starting files after the first failure (default: do the rest)")
      ->group("Common");
  cmd.add_flag("--skip-existing", s.skip_existing, "Skip inputs whose outputs all exist already")->group("Common");
  cmd.add_flag("--json", s.json, "Print one JSON summary on stdout (schema in docs/cli.md) instead of lines")
      ->group("Common");
  cmd.add_flag("--timings", s.timings,
               "With --json: report each file's seconds and phases (left out by default, so "
               "that the summary is the same bytes on every run)")
      ->group("Common");
  cmd.add_option_function<std::string>(
         "--shard",
         [&s](const std::string& v) {
           int i = -1, n = 0;
           char extra = 0;
           if (std::sscanf(v.c_str(), "%d/%d%c", &i, &n, &extra) != 2 || n < 1 || i < 0 || i >= n) {
             throw CLI::ValidationError("--shard", "'" + v + "': expected I/N with 0 <= I < N (e.g. 3/8)");
           }
           s.shard_index = i;
           s.shard_count = n;
         },
         "Run only share I of N (I/N, 0 <= I < N): the files whose number in the run is I modulo N, for job arrays "
         "and CI matrices; the N shares together are the whole run")
      ->group("Common");
  cmd.add_option_function<std::string>(
         "--ocio-config",
         [&s](const std::string& v) {
           std::error_code ec;
           if (!std::filesystem::is_regular_file(v, ec)) {
             throw CLI::ValidationError("--ocio-config", v + ": no such file");
           }
           // The runtime module reads $OCIO when it loads, after parsing.
           s.ocio_config = v;
           ::setenv("OCIO", v.c_str(), 1);
         },
         "OpenColorIO config for --colorspace names, instead of $OCIO; an input of every output (depfiles, "
         "manifests, actions), so that builds that clear the environment see it")
      ->group("Common");
  cmd.add_flag("--progress", s.progress, "Draw progress on stderr even when it is not a terminal")->group("Common");
  cmd.add_flag("-f,--force", s.force, "Overwrite outputs that already exist")->group("Common");
  cmd.add_flag("-q,--quiet", s.quiet, "Print nothing but errors")->group("Common");
  cmd.add_flag("-v,--verbose", s.verbose, "Print details of the work")->group("Common");
  cmd.add_option("--depfile", s.depfile,
                 "After success, write a Make-style dependency file (outputs: inputs) for Make and Ninja")
      ->group("Common");
  cmd.add_flag("-n,--dry-run", s.dry_run,
               "Check the arguments and inputs, print the outputs that would be written, one a line; write nothing")
      ->group("Common");
  cmd.add_flag("--write-if-changed", s.write_if_changed,
               "Overwrite outputs, but leave an output untouched (time stamp too) when its bytes would not change")
      ->group("Common");
}

std::vector<std::string> recorded_inputs() {
  std::lock_guard lock(build_state().mutex);
  return build_state().inputs;
}

void record_input(const std::string& path) {
  std::lock_guard lock(build_state().mutex);
  auto& v = build_state().inputs;
  if (std::find(v.begin(), v.end(), path) == v.end()) v.push_back(path);
}

namespace {
std::string escape_make(const std::string& path) {
  std::string out;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const char c = path[i];
    if (c == '$') {
      out += "$$";
    } else if (c == ' ' || c == '#') {
      // gcc's rule: backslashes right before a space or '#' are doubled too.
      for (std::size_t j = i; j > 0 && path[j - 1] == '\\'; --j) out += '\\';
      out += '\\';
      out += c;
    } else {
      out += c;
    }
  }
  return out;
}

// The rule "outputs: inputs" with spaces and '#' escaped by backslashes (and
// backslashes right before them doubled) and '$' doubled, as gcc -MD writes.
// Make reads a depfile line by line: no escape can carry a line break.
void check_depfile_name(const std::string& path) {
  if (path.find_first_of("\n\r") != std::string::npos) {
    std::string shown = path;
    for (char& c : shown) c = (c == '\n' || c == '\r') ? '?' : c;
    throw Error(ErrorCode::bad_arguments, shown +
                                              ": a file name with a line break cannot be written to --depfile (Make "
                                              "cannot read it): rename the file or drop --depfile");
  }
}

std::string make_rule(const std::vector<std::string>& outputs, const std::vector<std::string>& inputs) {
  for (const auto& o : outputs) check_depfile_name(o);
  for (const auto& in : inputs) check_depfile_name(in);
  std::string rule;
  for (std::size_t i = 0; i < outputs.size(); ++i) rule += (i ? " " : "") + escape_make(outputs[i]);
  rule += ":";
  for (const auto& in : inputs) rule += " \\\n  " + escape_make(in);
  rule += "\n";
  return rule;
}
}  // namespace

// The depfile's folder is made (as an output's is) and must be writable
// before any work: a depfile that fails after the outputs were written
// would leave Make with outputs and no record of their inputs.
namespace {
void check_depfile_folder(const std::string& path) {
  static std::string checked;
  if (checked == path) return;
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec || ::access(parent.c_str(), W_OK) != 0) {
    const std::string why = ec ? ec.message() : std::strerror(errno);
    throw Error(ErrorCode::io, path + ": --depfile cannot be written in " + parent.string() + ": " + why);
  }
  checked = path;
}
}  // namespace

void write_depfile_if_requested() {
  const BuildState& d = build_state();
  const std::string& depfile = run_options().depfile;
  if (depfile.empty() || run_options().dry_run) return;
  if (d.outputs.empty()) throw Error(ErrorCode::bad_arguments, depfile + ": --depfile: this command writes no files");
  refuse_overwriting_input(depfile, d.inputs, "--depfile");  // again: commands record inputs late (a config)
  std::error_code ec;
  const fs::path parent = fs::path(depfile).parent_path();
  if (!parent.empty()) fs::create_directories(parent, ec);  // a failure is reported by the write
  write_file_atomic(depfile, make_rule(d.outputs, d.inputs),
                    CommitPolicy::replace);  // the rule of this run replaces the last
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
  BuildState& d = build_state();
  const RunOptions& o = run_options();
  if (std::find(d.outputs.begin(), d.outputs.end(), output) == d.outputs.end()) d.outputs.push_back(output);
  for (const auto& in : inputs) record_input(in);
  refuse_overwriting_input(output, inputs, "output");
  if (!o.depfile.empty()) {  // --depfile, checked before any work
    check_depfile_folder(o.depfile);
    check_depfile_name(output);
    for (const auto& in : inputs) check_depfile_name(in);
    refuse_overwriting_input(o.depfile, inputs, "--depfile");
    if (fs::path(output).lexically_normal() == fs::path(o.depfile).lexically_normal()) {
      throw Error(ErrorCode::bad_arguments, o.depfile + ": --depfile names an output of the command");
    }
  }
  std::error_code ec;
  if (fs::exists(output, ec)) {
    if (fs::is_directory(output, ec)) throw Error(ErrorCode::bad_arguments, output + ": output is a directory");
    if (!force && !o.write_if_changed) {
      throw Error(ErrorCode::bad_arguments,
                  output + ": output exists (use --force or --write-if-changed to replace it)");
    }
  }
  const fs::path parent = fs::path(output).parent_path();
  if (!o.dry_run && !parent.empty() && !fs::exists(parent, ec)) {
    fs::create_directories(parent, ec);
    if (ec) throw Error(ErrorCode::io, parent.string() + ": cannot create folder: " + ec.message());
  }
}

CLI::Validator in_range(double lo, double hi, bool lo_open) {
  auto text = [](double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.10g", v);
    return std::string(b);
  };
  const std::string range = (lo_open ? "(" : "[") + text(lo) + ", " + text(hi) + "]";
  return CLI::Validator(
      [lo, hi, lo_open, range](std::string& value) -> std::string {
        const char* begin = value.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(begin, &end);
        if (end == begin || *end != '\0') return "'" + value + "' is not a number (valid: " + range + ")";
        if (!std::isfinite(v) || v < lo || v > hi || (lo_open && v == lo)) {
          return value + " is outside the valid range " + range;
        }
        return "";
      },
      range);
}

void add_channel_options(CLI::App& cmd, ChannelArgs& a) {
  cmd.add_option("--swizzle", a.swizzle,
                 "Rearrange channels as read: one to four of r, g, b, a, 0, 1, one per output channel (bgra, rrr1, "
                 "gggr; grey reads as l, l, l, 1)")
      ->group("Channels");
  cmd.add_flag("--flip-green", a.flip_green,
               "Invert green (G = max - G): OpenGL <-> DirectX normal maps (after --swizzle)")
      ->group("Channels");
  cmd.add_option("--invert", a.invert, "Invert these channels (some of r, g, b, a; after --swizzle)")
      ->group("Channels");
}

void validate_channel_options(ChannelArgs& a) {
  a.map = a.swizzle.empty() ? ChannelMap{} : parse_swizzle(a.swizzle);
  if (!a.invert.empty()) add_inverted_channels(a.map, a.invert);
  if (a.flip_green) add_inverted_channels(a.map, "g");
}

void apply_channel_options(const ChannelArgs& a, Image& image) {
  if (!a.map.identity()) image = map_channels(image.view(), a.map);
}

void add_size_options(CLI::App& cmd, SizeArgs& a) {
  cmd.add_option("--resize", a.resize, "Resize to WxH first (0 for a side keeps the aspect ratio: 1024x0)")
      ->group("Size");
  cmd.add_option("--max-size", a.max_size, "At most N texels on the longer side (aspect ratio kept)")
      ->check(in_range(1, 16384))
      ->group("Size");
  cmd.add_option("--pow2", a.pow2, "Each side to a power of two: up, down, nearest")->group("Size");
  cmd.add_option("--multiple-of", a.multiple_of, "Each side rounded up to a multiple of N (4: whole blocks)")
      ->check(in_range(1, 4096))
      ->group("Size");
  cmd.add_option("--resize-filter", a.filter,
                 "Filter for --resize and the others: mitchell, lanczos3, gaussian, triangle, box, kaiser")
      ->capture_default_str()
      ->group("Size");
}

void validate_size_options(SizeArgs& a) {
  a.rule = SizeRule{};
  if (!a.resize.empty()) {
    int w = -1, h = -1;
    char x = 0, extra = 0;
    if (std::sscanf(a.resize.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 0 ||
        h < 0 || (w == 0 && h == 0) || w > 16384 || h > 16384) {
      throw Error(ErrorCode::bad_arguments,
                  "--resize " + a.resize + ": WxH with sides of 0 to 16384, not both 0 (0 keeps the aspect ratio)");
    }
    a.rule.resize_width = w;
    a.rule.resize_height = h;
  }
  if (!a.pow2.empty() && a.pow2 != "up" && a.pow2 != "down" && a.pow2 != "nearest")
    throw Error(ErrorCode::bad_arguments, "--pow2 " + a.pow2 + ": valid: up, down, nearest");
  a.rule.max_size = a.max_size;
  a.rule.pow2 = a.pow2;
  a.rule.multiple_of = a.multiple_of;
  a.resize_filter = Filter{parse_filter_kind(a.filter)};
}

void apply_size_options(const SizeArgs& a, Image& image, const std::string& color_space, bool normal_map) {
  if (a.rule.empty()) return;
  int w = image.width(), h = image.height();
  apply_size_rule(a.rule, w, h);
  if (w == image.width() && h == image.height()) return;
  ResizeOptions o;
  o.filter = a.resize_filter;
  o.color_space = color_space;
  o.normal_map = normal_map;
  image = resize_image(image.view(), w, h, o);
}

void add_chain_options(CLI::App& cmd, ChainArgs& a, const char* group) {
  cmd.add_option("--filter", a.filter, "Mip filter: gaussian, box, triangle, kaiser, lanczos3, mitchell")
      ->capture_default_str()
      ->group(group);
  cmd.add_option("--sigma", a.sigma, "Gaussian standard deviation in destination texels (0 < sigma <= 4)")
      ->capture_default_str()
      ->check(in_range(0, 4, true))
      ->group(group);
  cmd.add_option("--levels", a.levels, "Number of levels, level 0 included (default 0: down to 1x1)")
      ->check(in_range(0, 32))
      ->group(group);
  cmd.add_option("--min-size", a.min_size, "Stop before a level whose larger side is below this")
      ->check(in_range(1, 1 << 20))
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
    names.push_back(
        (p.parent_path() / (p.stem().string() + "_mip" + std::to_string(l) + p.extension().string())).string());
  }
  return names;
}

const ReadOptions& cli_read_options() {
  static const ReadOptions options = ReadOptions::from_environment();
  return options;
}

WriteOptions cli_write_options() {
  WriteOptions w;
  w.io_path = cli_read_options().io_path;
  return w;
}

void write_levels(const std::string& output, const std::vector<Image>& levels, const WriteOptions& options) {
  if (holds_mip_levels(output)) {
    write_mip_file(output, levels, options);
    return;
  }
  const auto names = level_outputs(output, int(levels.size()));
  for (std::size_t l = 0; l < levels.size(); ++l) write_image(names[l], levels[l].view(), options);
}

namespace {
std::string lower_extension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  for (auto& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}
}  // namespace

void read_as_finite(const std::string& input, Image& image, std::vector<std::string>& warnings) {
  if (const std::size_t n = replace_non_finite(image)) {
    warnings.push_back(input + ": " + std::to_string(n) + " non-finite value(s) (NaN or infinity) read as 0");
  }
}

void check_dds_header_fits(const std::string& dds_header, const std::string& output) {
  const std::string e = lower_extension(output);
  if (dds_header != "auto" && e != ".dds") {
    throw Error(ErrorCode::bad_arguments, output + ": --dds-header " + dds_header + " applies to .dds outputs only");
  }
}

int zstd_level_for(int zstd, const std::string& output) {
  const std::string e = lower_extension(output);
  if (zstd != 0 && e != ".ktx2") {
    throw Error(ErrorCode::bad_arguments,
                output + ": --zstd " + std::to_string(zstd) + " applies to .ktx2 outputs only");
  }
  if (zstd < 0 || zstd > 22)
    throw Error(ErrorCode::bad_arguments, "--zstd " + std::to_string(zstd) + " (valid: 1 to 22)");
  return zstd;
}

void check_surfaces_fit(const std::string& input, const ImageArray& in, const std::string& output) {
  if (in.images.size() <= 1 || is_container_path(output)) return;
  const std::string what = in.faces == 6
                               ? (in.layers > 1 ? std::to_string(in.layers) + " cubemaps" : std::string("a cubemap"))
                               : std::to_string(in.layers) + " array layers";
  throw Error(ErrorCode::unsupported, input + ": holds " + what +
                                          "; write it to .dds, .ktx2 or .ktx, which keep them (" + output +
                                          " holds one image)");
}

const std::vector<std::string>& image_extensions() {
  static const std::vector<std::string> e = {".png", ".jpg", ".jpeg", ".tga",  ".tif", ".tiff", ".exr",
                                             ".hdr", ".bmp", ".psd",  ".webp", ".gif", ".ppm",  ".pgm",
                                             ".pnm", ".dds", ".ktx2", ".ktx",  ".pkm", ".astc"};
  return e;
}
const std::vector<std::string>& texture_extensions() {
  static const std::vector<std::string> e = {".dds", ".ktx2", ".ktx", ".pkm", ".astc"};
  return e;
}

bool is_container_path(const std::string& path) {
  const std::string e = lower_extension(path);
  return e == ".dds" || e == ".ktx2" || e == ".ktx" || e == ".pkm" || e == ".astc";
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

std::vector<double> level_errors(const std::vector<std::vector<Image>>& encoded, const Texture& t) {
  std::vector<double> out;
  const int surfaces = int(encoded.size());
  for (std::uint32_t l = 0; l < t.levels; ++l) {
    const int n = encoded[0][l].height();
    const int width = encoded[0][l].width();
    const PixelType type = encoded[0][l].type();
    ImageRows a{{nullptr, width, surfaces * n, encoded[0][l].channels(), type, 0},
                [&](int y0, int y1, void* dst, std::size_t stride) {
                  for (int y = y0; y < y1; ++y) {
                    const Image& surface = encoded[y / n][l];
                    std::memcpy(static_cast<std::uint8_t*>(dst) + std::size_t(y - y0) * stride,
                                surface.row<std::uint8_t>(y % n), surface.row_stride());
                  }
                }};
    ImageRows b{{nullptr, width, surfaces * n, format_info(t.format).channels, type, 0},
                [&](int y0, int y1, void* dst, std::size_t stride) {
                  for (int y = y0; y < y1;) {
                    const int s = y / n, end = std::min(y1, (s + 1) * n);
                    decode_texture_rows(t, l, std::uint32_t(s) / t.faces, std::uint32_t(s) % t.faces, type, y - s * n,
                                        end - s * n, static_cast<std::uint8_t*>(dst) + std::size_t(y - y0) * stride,
                                        stride);
                    y = end;
                  }
                }};
    const ImageDifference d = compare_image_rows(a, b, std::min(3, format_info(t.format).channels));
    out.push_back(format_info(t.format).is_float ? d.log_rmse_rgb() : d.psnr_rgb());
  }
  return out;
}

}  // namespace texproc::cli
