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

std::string join(const std::vector<std::string>& items, const char* sep) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : sep) + i;
  return s;
}

}  // namespace texproc::cli
