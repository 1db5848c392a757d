#include "commands.h"

#include <cctype>
#include <iostream>

#include "batch.h"
#include "common.h"
#include "exit_codes.h"
#include "report.h"
#include "texproc/error.h"
#include "texproc/file_io.h"

namespace texproc::cli {

namespace {

// Options whose values are names from a fixed list: read in any case
// (`--quality High`, `--format BC7_UNORM_SRGB`). Colour-space names are not
// among them: OpenColorIO's names are case-sensitive.
void lower_case_enumerations(CLI::App& app) {
  static const char* const kEnumerated[] = {"--format", "--quality", "--wrap", "--filter", "--dds-header",
                                            "--transparent-color", "--precision", "--mode", "--kernel",
                                            "--height-channel", "--channels", "--y", "--type", "--to", "--ibl",
                                            "--layout", "--flip", "--compression"};
  const CLI::Validator lower(
      [](std::string& value) {
        for (char& c : value) c = char(std::tolower(static_cast<unsigned char>(c)));
        return std::string();
      },
      "", "lower case");
  for (CLI::Option* opt : app.get_options()) {
    for (const char* name : kEnumerated) {
      if (opt->check_lname(name + 2)) opt->transform(lower);
    }
  }
  for (CLI::App* sub : app.get_subcommands({})) lower_case_enumerations(*sub);
}

}  // namespace

void add_all_commands(CLI::App& app) {
  add_mip_command(app);
  add_normalmap_command(app);
  add_sat_command(app);
  add_conemap_command(app);
  add_cubemap_command(app);
  add_compress_command(app);
  add_decompress_command(app);
  add_convert_command(app);
  add_info_command(app);
  add_compare_command(app);
  add_build_command(app);
  lower_case_enumerations(app);
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
  print_error(cmd, e.what());
  print_note("See '" + prefix + " --help'.");
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
      const std::string message = in_cli_terms(e.what());
      print_error(cmd, message);
      if (e.code() == ErrorCode::bad_arguments) print_note("See 'texproc " + cmd + " --help'.");
      if (session_options().json) print_json_summary(cmd, int(e.code()), message);
      return int(e.code());
    } catch (const std::bad_alloc&) {
      print_error(cmd, "out of memory");
      return int(ExitCode::runtime);
    } catch (const std::exception& e) {
      print_error(cmd, e.what());
      return int(ExitCode::runtime);
    }
  }
  print_error("", "no command given");
  print_note("See 'texproc --help'.");
  return int(ExitCode::bad_arguments);
}

}  // namespace texproc::cli
