// texproc: the command-line front end. Each command lives in cmd_<name>.cpp.
#include <CLI/CLI.hpp>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <iostream>
#include <thread>

#include "batch.h"
#include "commands.h"
#include "common.h"
#include "exit_codes.h"
#include "texproc/error.h"
#include "texproc/tools.h"
#include "tool_info.h"
#include "texproc/version.h"

namespace {

// SIGINT, SIGTERM and SIGHUP are taken by one thread (blocked in every other
// thread, which inherit the mask): it removes the named temporaries of
// outputs being written and exits at once with 128 + the signal, as a shell
// reports it. Outputs already in place stay; unnamed temporaries vanish with
// the process.
void remove_temporaries_on_signals() {
  sigset_t set;
  sigemptyset(&set);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&set, sig);
  if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return;
  std::thread([set] {
    int sig = 0;
    while (sigwait(&set, &sig) != 0) {
    }
    texproc::remove_pending_temporaries();
    ::_exit(128 + sig);
  }).detach();
}

}  // namespace

int main(int argc, char** argv) {
  remove_temporaries_on_signals();
  CLI::App app{"texproc: texture asset processing for asset pipelines.\n" + std::string(texproc::cli::kExitCodeHelp)};
  // --version, --version --json (version, tool digest, runtime files,
  // libraries: what a build cache keys on) and --runtime-files (what a
  // remote action ships beside the binary) stand alone, without a command.
  bool version = false, version_json = false, runtime_files = false;
  app.add_flag("--version", version,
               "Print the version and exit (with --json: version, digest of the tool and its "
               "modules, runtime files and library versions, as JSON)");
  app.add_flag("--runtime-files", runtime_files,
               "Print the files texproc runs with (the binary, its runtime modules), one a line, and exit");
  CLI::Option* json_flag = app.add_flag("--json", version_json, "With --version: print JSON");
  app.require_subcommand(0, 1);
  // The runtime modules (OpenEXR, OpenImageIO, OpenColorIO) are loaded on
  // first use; this is read then, so setting it while parsing is in time.
  app.add_option_function<std::string>(
         "--module-dir", [](const std::string& dir) { ::setenv("TEXPROC_MODULE_DIR", dir.c_str(), 1); },
         "Folder of texproc's runtime modules (default: beside the binary, then the installed lib/.../texproc; "
         "also TEXPROC_MODULE_DIR)")
      ->check(CLI::ExistingDirectory);
  app.fallthrough();  // top-level options (--module-dir) may follow the command too
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
    return texproc::cli::report_usage_error(app, e, argc, argv);
  }
  const bool command = !app.get_subcommands().empty();
  if (version || runtime_files) {
    if (command) {
      std::cerr << "texproc: error: --version and --runtime-files take no command\n";
      return int(texproc::cli::ExitCode::bad_arguments);
    }
    try {
      if (version && version_json)
        std::cout << texproc::cli::to_json(texproc::cli::version_json());
      else if (version)
        std::cout << "texproc " << texproc::version_string() << "\n";
      if (runtime_files) {
        for (const std::string& f : texproc::runtime_files()) std::cout << f << "\n";
      }
    } catch (const texproc::Error& e) {
      std::cerr << "texproc: error: " << e.what() << "\n";
      return int(e.code());
    }
    return 0;
  }
  if (json_flag->count() > 0 && !command) {
    std::cerr << "texproc: error: --json needs --version or a command\n";
    return int(texproc::cli::ExitCode::bad_arguments);
  }
  if (!command) {
    std::cerr << "texproc: error: a command is required\n" << app.help();
    return int(texproc::cli::ExitCode::bad_arguments);
  }
  return texproc::cli::run_selected(app);
}
