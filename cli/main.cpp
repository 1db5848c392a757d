// texproc: the command-line front end. Each command lives in cmd_<name>.cpp.
#include <CLI/CLI.hpp>

#include <iostream>

#include "commands.h"
#include "common.h"
#include "exit_codes.h"
#include "texproc/version.h"

int main(int argc, char** argv) {
  CLI::App app{"texproc: texture asset processing for asset pipelines.\n" +
               std::string(texproc::cli::kExitCodeHelp)};
  app.set_version_flag("--version", std::string("texproc ") + texproc::version_string());
  app.require_subcommand(1, 1);
  texproc::cli::add_all_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return texproc::cli::report_usage_error(app, e);
  }
  return texproc::cli::run_selected(app);
}
