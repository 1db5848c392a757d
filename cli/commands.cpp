#include "commands.h"

#include <algorithm>
#include <cctype>
#include <iostream>
#include <utility>
#include <vector>

#include "batch.h"
#include "common.h"
#include "exit_codes.h"
#include "report.h"
#include "texproc/error.h"
#include "texproc/tools.h"

namespace texproc::cli {

namespace {

// Options whose values are names from a fixed list: read in any case
// (`--quality High`, `--format BC7_UNORM_SRGB`). Colour-space names are not
// among them: OpenColorIO's names are case-sensitive.
void lower_case_enumerations(CLI::App& app) {
  static const char* const kEnumerated[] = {
      "--format",    "--quality", "--wrap",   "--filter",         "--dds-header", "--transparent-color",
      "--precision", "--mode",    "--kernel", "--height-channel", "--channels",   "--y",
      "--type",      "--to",      "--ibl",    "--layout",         "--flip",       "--compression"};
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
  add_pack_command(app);
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

namespace {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

// The first "--name" of the command line that neither the command nor the
// top level knows ("" if none), and the closest name they know.
std::pair<std::string, std::string> unknown_option(CLI::App& app, int argc, const char* const* argv) {
  std::vector<std::string> known;
  // The top level and every selected command down the chain (sat, sat blur).
  for (CLI::App* a = &app; a;) {
    for (const CLI::Option* o : a->get_options()) {
      for (const std::string& n : o->get_lnames()) known.push_back("--" + n);
    }
    const auto subs = a->get_subcommands();
    a = subs.empty() ? nullptr : subs.front();
  }
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    if (arg.size() < 3 || arg.rfind("--", 0) != 0) continue;
    const std::string name = arg.substr(0, arg.find('='));
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string best;
    std::size_t best_d = 4;  // suggest only a near miss
    for (const std::string& k : known) {
      const std::size_t d = edit_distance(name, k);
      if (d < best_d) {
        best_d = d;
        best = k;
      }
    }
    return {name, best};
  }
  return {"", ""};
}

bool asks_for_json(int argc, const char* const* argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--") break;
    if (std::string(argv[i]) == "--json") return true;
  }
  return false;
}

}  // namespace

int report_usage_error(CLI::App& app, const CLI::ParseError& e, int argc, const char* const* argv) {
  const std::string cmd = command_name(app);
  const std::string prefix = cmd.empty() ? "texproc" : "texproc " + cmd;
  std::string message = e.what();
  // An unknown option explains the other errors it causes ("--format is
  // required" after "--fromat bc1"): it is named first.
  if (!app.get_subcommands().empty()) {
    const auto [name, closest] = unknown_option(app, argc, argv);
    if (!name.empty()) message = "unknown option " + name + (closest.empty() ? "" : " (did you mean " + closest + "?)");
  }
  print_error(cmd, message);
  print_note("See '" + prefix + " --help'.");
  if (asks_for_json(argc, argv)) print_json_summary(cmd, int(ExitCode::bad_arguments), message);
  return int(ExitCode::bad_arguments);
}

int run_selected(CLI::App& app) {
  const std::string cmd = command_name(app);
  for (CLI::App* sub : app.get_subcommands()) {
    CommandRunner* run = runner_of(*sub);
    if (!run) break;
    try {
      const int rc = (*run)();
      if (rc == 0) write_depfile_if_requested();
      print_failure_summary(cmd);
      if (run_options().json) print_json_summary(cmd, rc);
      return rc;
    } catch (const texproc::Error& e) {
      const std::string message = in_cli_terms(e.what());
      print_error(cmd, message);
      if (e.code() == ErrorCode::bad_arguments) print_note("See 'texproc " + cmd + " --help'.");
      if (run_options().json) print_json_summary(cmd, int(e.code()), message);
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
