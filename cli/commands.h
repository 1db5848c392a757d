// Registration of every command, and the one place that turns errors into
// messages and exit codes: `texproc <command>: error: <message>`.
#pragma once

#include <CLI/CLI.hpp>

namespace texproc::cli {

void add_mip_command(CLI::App& app);
void add_normalmap_command(CLI::App& app);
void add_sat_command(CLI::App& app);
void add_conemap_command(CLI::App& app);
void add_decompress_command(CLI::App& app);
void add_convert_command(CLI::App& app);
void add_pack_command(CLI::App& app);
void add_compress_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_build_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_cubemap_command(CLI::App& app);

void add_all_commands(CLI::App& app);
// A command line CLI11 refused: the error (an unknown option first, with the
// closest valid one), a hint, and with --json the JSON error document.
int report_usage_error(CLI::App& app, const CLI::ParseError& e, int argc, const char* const* argv);
int run_selected(CLI::App& app);

}  // namespace texproc::cli
