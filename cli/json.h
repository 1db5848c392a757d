// The one JSON writer of the CLI: --json summaries, info --json, sat query
// --json, --emit-actions, --version --json, the spherical-harmonics file and
// the build state all print through to_json().
#pragma once

#include <json/value.h>

#include <string>

namespace texproc::cli {

// Numbers to this many significant digits read back as the same double.
constexpr int kExactDigits = 17;

// `v` as JSON: objects one member a line, indented by two spaces, keys in
// sorted order; arrays of numbers and strings on one line, arrays holding
// objects or arrays one element a line; UTF-8 kept as it is; numbers to
// `digits` significant digits. Reports use the default (figures such as
// PSNR read the same from run to run); data a script computes with (info,
// sat query, spherical harmonics) uses kExactDigits. No final newline.
std::string to_json(const Json::Value& v, int digits = 6);

}  // namespace texproc::cli
