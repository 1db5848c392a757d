// Options and helpers every command shares.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace texproc::cli {

// --threads, --force, --quiet, --verbose: one struct, one registration.
struct CommonOptions {
  int threads = 0;
  bool force = false;
  bool quiet = false;
  bool verbose = false;
};
void add_common_options(CLI::App& cmd, CommonOptions& o);

// A command registers itself with add_<name>_command and stores here what
// main() runs after parsing.
using CommandRunner = std::function<int()>;
void set_runner(CLI::App& cmd, CommandRunner runner);
CommandRunner* runner_of(CLI::App& cmd);

// Checks that writing `output` is allowed: it must not be one of `inputs`
// (compared as files, not strings) and must not exist unless --force.
// Creates the parent folder. Throws Error{bad_arguments}.
void check_output(const std::string& output, const std::vector<std::string>& inputs, bool force);

// "Strings like a, b, c" for messages.
std::string join(const std::vector<std::string>& items, const char* sep = ", ");

}  // namespace texproc::cli
