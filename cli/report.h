// The one way the CLI speaks: every error and warning goes through here, so
// they all read `texproc <command>: error: FILE: problem`, and library
// messages, which name the API (MipOptions::filter.sigma), reach the user
// in the command line's terms (--sigma).
#pragma once

#include <string>

namespace texproc::cli {

// A library message with the API names of options replaced by their flags.
std::string in_cli_terms(const std::string& library_message);
// `message` about `file`: the file's name in front, unless the message
// starts with it already.
std::string about(const std::string& file, const std::string& message);

// "texproc <command>: error: <message>" (and warning) on standard error.
void print_error(const std::string& command, const std::string& message);
void print_warning(const std::string& command, const std::string& message);
// Any other line for standard error ("texproc mip: 2 of 5 files failed").
void print_note(const std::string& line);

}  // namespace texproc::cli
