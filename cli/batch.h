// Many inputs in one call: every command that turns an input file into
// output files runs through run_batch(), which expands the inputs (files,
// folders with -r, --file-list), names the outputs (-o FILE, -o DIR, or a
// template such as 'out/{stem}.dds'), checks every output before any work,
// processes the files in parallel on the one oneTBB pool the block-level
// kernels use, prints one line per file in input order, shows progress on a
// terminal, and keeps going past a failed file unless --fail-fast.
//
// What a run produced is collected as FileReports; the top level prints
// them as JSON (--json) and turns failures into the exit code.
#pragma once

#include <CLI/CLI.hpp>
#include <json/value.h>

#include <chrono>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "common.h"
#include "json.h"
#include "texproc/error.h"

namespace texproc::cli {

// The inputs and output naming of one command invocation.
struct BatchInputs {
  std::vector<std::string> inputs;
  std::string output;  // a file, a folder, or a template with {placeholders}
  bool recursive = false;
  std::string file_list;
};
// Registers `inputs` (positional, 1 or more), -o, -r and --file-list.
// `what` names the inputs in the help ("Input images").
void add_batch_inputs(CLI::App& cmd, BatchInputs& b, const char* what, const char* output_help,
                      bool output_required = true);

// One input file found by expansion.
struct InputFile {
  std::string path;    // as given or as found under a folder argument
  std::string reldir;  // its folder relative to the folder argument ("" if named directly)
};

// The input files `b` stands for: files as given, folders expanded (sorted;
// -r: recursively) to the files with `extensions`, --file-list read.
// Throws Error for an unreadable list or a folder with no such files.
std::vector<InputFile> expand_inputs(const BatchInputs& b, const std::vector<std::string>& extensions);

// Expands {stem}, {name}, {ext}, {dir}, {reldir} in `pattern` for `in`
// ({{ and }} are literal braces). Throws Error{bad_arguments} for an
// unknown placeholder.
std::string expand_template(const std::string& pattern, const InputFile& in);
bool is_template(const std::string& output);

// How far a file got: ok, failed, skipped (--skip-existing or up to
// date), not_run (a failure before it, with --fail-fast).
enum class FileStatus { ok, failed, skipped, not_run };
// "ok", "failed", "skipped", "not_run": the summary's spelling.
const char* to_string(FileStatus s);

// What a run produced for one input.
struct FileReport {
  std::string input;
  std::vector<std::string> inputs;   // every file the outputs depend on: input, OCIO config, radius map...
  std::vector<std::string> outputs;  // the files written (or, with --dry-run, to be written)
  FileStatus status = FileStatus::ok;
  std::string error;  // the message, when failed
  ErrorCode code = ErrorCode::success;
  std::string line;                        // the human summary ("a.png -> a.dds: ..."), printed unless --quiet
  std::vector<std::string> warnings;       // "FILE: what", printed on stderr unless --quiet, in --json too
  Json::Value details{Json::objectValue};  // format, sizes, levels, quality figures (--report)
  double seconds = 0;
  // Wall time of the file's phases in milliseconds, set by the command
  // (PhaseTimer); --verbose prints them and --json reports them. -1: none.
  struct Phases {
    double read = -1, compute = -1, write = -1;
  } phases;
  // Set by run_batch before `run`: how far the work on this file has got,
  // in [0, 1], for the progress line (callable from any thread, one call
  // at a time).
  std::function<void(double)> progress;
};

// Times a command's phases into FileReport::phases: construct it before
// reading; read_done(), compute_done() and write_done() each add the time
// since the last call to their phase (a command that decodes and writes
// level by level calls them in turn).
class PhaseTimer {
 public:
  explicit PhaseTimer(FileReport& r) : r_(r), last_(std::chrono::steady_clock::now()) { r_.phases = {0, 0, 0}; }
  void read_done() { r_.phases.read += lap(); }
  void compute_done() { r_.phases.compute += lap(); }
  void write_done() { r_.phases.write += lap(); }

 private:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }
  FileReport& r_;
  std::chrono::steady_clock::time_point last_;
};

// A command that maps each input file to output files.
struct BatchCommand {
  std::string name;                           // "mip"
  std::string default_extension;              // for -o DIR: ".dds"
  std::vector<std::string> input_extensions;  // files picked from folders (lower case, with the dot)
  // Once, before any file: checks the options; throws Error (the whole run fails).
  std::function<void()> validate;
  // Per file, before any work: every file `output` stands for (one name, or
  // one per mip level). Throws Error for this file only (a missing input).
  std::function<std::vector<std::string>(const InputFile& input, const std::string& output)> plan;
  // Per file: the work. Fills the report's line and details.
  std::function<void(const std::string& input, const std::string& output, FileReport& report)> run;
};

// The output for each input: -o names one file (one input only), a folder
// (-o DIR/, an existing folder, or several inputs and no extension), or a
// template.
std::vector<std::string> name_outputs(const BatchCommand& c, const BatchInputs& b, const std::vector<InputFile>& files);

// Runs `c` over the inputs; returns 0, or the exit code of the first failed
// file in input order. Throws Error for problems of the whole run (options,
// an -o that cannot name several files, two inputs naming one output).
int run_batch(const BatchCommand& c, const BatchInputs& in);

// What the batches of one process share beyond the options: set by
// `build`, which runs several, and read by run_batch.
struct BatchSession {
  // Set by `build` for a first pass over its jobs: run_batch checks the
  // options, inputs and output names, and returns before planning files.
  bool check_only = false;
  // Set by `build` unless --force: a file whose outputs all exist and are no
  // older than each of its inputs (the recipe among them) is skipped as up
  // to date; any other is rebuilt, its old outputs replaced.
  bool incremental = false;
  std::vector<std::string> run_inputs;  // what every file depends on besides its own inputs: the recipe
  // Set by `build`: the outputs its recipe wrote in earlier runs (keys from
  // output_key). An incremental run replaces an existing output only if it
  // is one of them; any other existing file needs --force.
  std::set<std::string> owned_outputs;
  // Set by `build` for its first pass: run_batch appends each file's inputs
  // and outputs here, so that every output can be checked against every
  // input of every job before the first job runs.
  struct PlannedFile {
    std::string input, output;  // the file and its -o (for one action a file)
    std::vector<std::string> inputs, outputs;
    bool outputs_known = false;  // false: `outputs` is the -o name; the real ones depend on the input
  };
  std::vector<PlannedFile>* plans = nullptr;
  // Set by `build`: which of a job's files this run takes (its excludes,
  // the files of one override); null: all.
  std::function<bool(const std::string& input)> select;
  // Files selected so far, over the whole process (RunOptions::shard_count).
  std::size_t shard_counter = 0;
  // Set by `build` unless --force: per-file change tracking. Returns "" when
  // the file's outputs are up to date, else why it is to be rebuilt; used
  // instead of time stamps when set.
  std::function<std::string(const FileReport&)> why_rebuild;
  // Set by `build --dry-run`: the files earlier jobs would write (absolute,
  // normalized) and the job writing each. A file reading one of them is
  // listed as rebuilt, even while that input does not exist yet.
  std::map<std::string, std::string> pending;
};
// The key a file is known by in owned_outputs: its absolute, normalized
// path with symlinks in its folders resolved.
std::string output_key(const std::string& path);
BatchSession& batch_session();
// `path` made absolute (from the working folder) and normalized (no "." or
// ".."; symlinks kept): how a recipe compares the paths its jobs name.
std::string absolute_path(const std::string& path);

// Every FileReport of this process, in order (a `build` recipe adds several
// batches).
std::vector<FileReport>& session_reports();
// Prints the --json summary of session_reports() for `command` to stdout;
// `error`: a failure of the whole run (bad options), if any.
void print_json_summary(const std::string& command, int exit_code, const std::string& error = "");
// After several files, a closing line on stderr listing the failures.
void print_failure_summary(const std::string& command);

}  // namespace texproc::cli
