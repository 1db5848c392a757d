// The CLI's exit codes: texproc::ErrorCode, the table of KTX-Software's `ktx`.
// Documented in `texproc --help` and docs/cli.md.
#pragma once
#include "texproc/error.h"

namespace texproc::cli {
using ExitCode = texproc::ErrorCode;
inline constexpr const char* kExitCodeHelp =
    "Exit codes: 0 success, 1 bad arguments, 2 I/O failure, 3 invalid input file,\n"
    "            4 runtime error, 5 unsupported, 7 difference found (compare).";
}  // namespace texproc::cli
