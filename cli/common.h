// Options and helpers every command shares.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "texproc/channels.h"
#include "texproc/image.h"
#include "texproc/container.h"
#include "texproc/image_io.h"
#include "texproc/mip.h"

namespace texproc::cli {

// The options of the run, in one object. A process runs one command, so
// there is one: add_common_options registers its fields on a command, and
// everything reads them through run_options().
struct RunOptions {
  int threads = 0;  // --threads: worker threads (0: all cores)
  bool force = false;
  bool quiet = false;
  bool verbose = false;
  int jobs = 0;  // --jobs: files in flight (0: as many as threads)
  bool fail_fast = false;
  bool skip_existing = false;
  bool json = false;
  bool timings = false;   // --timings: --json reports seconds and phases (without: the summary is reproducible)
  bool progress = false;  // --progress: draw progress even when stderr is not a terminal
  bool dry_run = false;
  // --write-if-changed: existing outputs may be replaced, and are kept
  // (bytes and time stamp) when the new bytes are the same.
  bool write_if_changed = false;
  std::string depfile;
  // --shard I/N: of the files selected (counted over the whole process, in
  // order), only those whose number is I modulo N are run. count 0: all.
  int shard_index = 0;
  int shard_count = 0;
  // --ocio-config FILE: the OpenColorIO config (set as $OCIO for this process).
  std::string ocio_config;
};
RunOptions& run_options();
// Registers every option of RunOptions on `cmd`, in the "Common" group.
void add_common_options(CLI::App& cmd);

// Build-system dependencies of this run. check_output() records each output
// and its inputs; commands record other files they read (an OpenColorIO
// config) here. After a successful run, `--depfile FILE` (every command)
// writes them as a Make rule, "outputs: inputs", as gcc -MD does; Make and
// Ninja (depfile = ..., deps = gcc) read it.
void record_input(const std::string& path);
// Every input recorded so far, in order.
std::vector<std::string> recorded_inputs();
// Writes the depfile if --depfile was given (atomically). Throws Error.
void write_depfile_if_requested();

// A command registers itself with add_<name>_command and stores here what
// main() runs after parsing.
using CommandRunner = std::function<int()>;
void set_runner(CLI::App& cmd, CommandRunner runner);
CommandRunner* runner_of(CLI::App& cmd);

// Checks that writing `output` is allowed: it must not be one of `inputs`
// (compared as files, not strings) and must not exist unless --force.
// Creates the parent folder (not under --dry-run). Throws Error{bad_arguments}.
void check_output(const std::string& output, const std::vector<std::string>& inputs, bool force);

// How the tool reads files: ReadOptions::from_environment() (TEXPROC_IMAGE_IO,
// TEXPROC_MAX_IMAGE_PIXELS, TEXPROC_MAX_JPEG_SCANS, TEXPROC_MAX_TEXTURE_BYTES),
// read once.
const texproc::ReadOptions& cli_read_options();
// Default write options, with the image I/O path of cli_read_options().
texproc::WriteOptions cli_write_options();

// Options that shape a mip chain, shared by every command that writes one.
struct ChainArgs {
  std::string filter = "gaussian";
  float sigma = 0.5f;
  int levels = 0;
  int min_size = 1;
};
void add_chain_options(CLI::App& cmd, ChainArgs& a, const char* group = "Mip chain");

// --swizzle, --flip-green, --invert: the channel map applied to the pixels
// as read (before any colour conversion or filtering).
struct ChannelArgs {
  std::string swizzle, invert;
  bool flip_green = false;
  texproc::ChannelMap map;  // validate_channel_options sets it
};
void add_channel_options(CLI::App& cmd, ChannelArgs& a);

// --resize WxH, --max-size N, --pow2 up|down|nearest, --multiple-of N,
// --resize-filter: level 0's size, resampled (never point-sampled) from
// the image read.
struct SizeArgs {
  std::string resize, pow2, filter = "mitchell";
  int max_size = 0, multiple_of = 0;
  texproc::SizeRule rule;  // validate_size_options sets it
  texproc::Filter resize_filter{texproc::FilterKind::mitchell};
};
void add_size_options(CLI::App& cmd, SizeArgs& a);
void validate_size_options(SizeArgs& a);
// `image` resized by the rule (nothing when it keeps the size), in
// `color_space` ("" as ResizeOptions), as a normal map where said.
void apply_size_options(const SizeArgs& a, texproc::Image& image, const std::string& color_space,
                        bool normal_map = false);
void validate_channel_options(ChannelArgs& a);
// `image` through a.map (nothing when it is the identity).
void apply_channel_options(const ChannelArgs& a, texproc::Image& image);

// --type u8|u16|f16|f32: the element type, and whether f32 is stored as half.
// Empty: std::nullopt. Throws Error{bad_arguments}.
std::optional<texproc::PixelType> parse_output_type(const std::string& type, texproc::WriteOptions& w);

// Output names for a chain of `levels` levels: one name when `output` holds
// MIP levels (.tif, .tiff, .exr), else {stem}_mip{L}{ext} per level.
std::vector<std::string> level_outputs(const std::string& output, int levels);

// Writes a chain to the names level_outputs gives.
void write_levels(const std::string& output, const std::vector<texproc::Image>& levels,
                  const texproc::WriteOptions& options);

// File extensions (lower case, with the dot) that folder inputs pick: the
// image formats texproc reads, and the texture containers.
const std::vector<std::string>& image_extensions();
// A cubemap or array input (more than one surface) can only go to a GPU
// container: Error{unsupported} naming `input` otherwise.
void check_surfaces_fit(const std::string& input, const ImageArray& in, const std::string& output);
// --dds-header other than auto for an output that is not .dds: Error{bad_arguments}.
void check_dds_header_fits(const std::string& dds_header, const std::string& output);
// --zstd N for an output that is not .ktx2: Error{bad_arguments}; the level to pass on otherwise.
int zstd_level_for(int zstd, const std::string& output);
// Float inputs: NaN and infinity read as 0, with a warning in `warnings`
// naming the file and the count (a filter would spread them).
void read_as_finite(const std::string& input, Image& image, std::vector<std::string>& warnings);
const std::vector<std::string>& texture_extensions();

// True for .dds, .ktx2, .ktx, .pkm outputs.
bool is_container_path(const std::string& path);
// --dds-header auto|dx9|dx10. Throws Error{bad_arguments}.
texproc::DdsHeader parse_dds_header(const std::string& s);

// A CLI11 check for a numeric option: the value must be a finite number in
// [lo, hi] ((lo, hi] with lo_open), else exit 1 naming the option and the
// range. NaN and infinities are refused.
CLI::Validator in_range(double lo, double hi, bool lo_open = false);

// "Strings like a, b, c" for messages.
std::string join(const std::vector<std::string>& items, const char* sep = ", ");

// The error of each level of a block-compressed texture against the images
// it encoded (encoded[layer * faces + face][level]), every surface pooled,
// a block of rows at a time: log2 RMSE over RGB for HDR formats, PSNR over
// RGB (the channels the format has, up to three) for the others.
std::vector<double> level_errors(const std::vector<std::vector<Image>>& encoded, const Texture& t);

}  // namespace texproc::cli
