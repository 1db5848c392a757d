#include "commands.h"

#include <iostream>

#include "batch.h"
#include "common.h"
#include "exit_codes.h"
#include "texproc/error.h"
#include "texproc/file_io.h"

namespace texproc::cli {

void add_all_commands(CLI::App& app) {
  add_mip_command(app);
  add_normalmap_command(app);
  add_sat_command(app);
  add_conemap_command(app);
  add_cubemap_command(app);
  add_compress_command(app);
  add_decompress_command(app);
  add_info_command(app);
  add_compare_command(app);
  add_build_command(app);
}

namespace {
std::string command_name(CLI::App& app) {
  for (CLI::App* sub : app.get_subcommands()) return sub->get_name();
  return "";
}
}  // namespace

int report_usage_error(CLI::App& app, const CLI::ParseError& e) {
  const std::string cmd = command_name(app);
  const std::string prefix = cmd.empty() ? "texproc" : "texproc " + cmd;
  std::cerr << prefix << ": error: " << e.what() << "\nSee '" << prefix << " --help'.\n";
  return int(ExitCode::bad_arguments);
}

int run_selected(CLI::App& app) {
  const std::string cmd = command_name(app);
  for (CLI::App* sub : app.get_subcommands()) {
    CommandRunner* run = runner_of(*sub);
    if (!run) break;
    try {
      if (write_if_changed()) set_commit_policy(CommitPolicy::keep_identical);
      const int rc = (*run)();
      if (rc == 0) write_depfile_if_requested();
      print_failure_summary(cmd);
      if (session_options().json) print_json_summary(cmd, rc);
      return rc;
    } catch (const texproc::Error& e) {
      std::cerr << "texproc " << cmd << ": error: " << e.what() << "\n";
      if (e.code() == ErrorCode::bad_arguments) std::cerr << "See 'texproc " << cmd << " --help'.\n";
      if (session_options().json) print_json_summary(cmd, int(e.code()), e.what());
      return int(e.code());
    } catch (const std::bad_alloc&) {
      std::cerr << "texproc " << cmd << ": error: out of memory\n";
      return int(ExitCode::runtime);
    } catch (const std::exception& e) {
      std::cerr << "texproc " << cmd << ": error: " << e.what() << "\n";
      return int(ExitCode::runtime);
    }
  }
  std::cerr << "texproc: error: no command given\nSee 'texproc --help'.\n";
  return int(ExitCode::bad_arguments);
}

}  // namespace texproc::cli
