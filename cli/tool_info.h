// What a build system needs to know about the texproc tool itself: content
// hashes (XXH3, 128 bits), the files the tool runs with, and a digest of
// them for cache keys (`texproc --version --json`, `--runtime-files`,
// `texproc build`'s change tracking and --emit-actions).
#pragma once

#include <json/value.h>

#include <string>
#include <string_view>

namespace texproc::cli {

// XXH3-128 of bytes / of a file's bytes, as 32 lower-case hex digits.
// hash_file throws Error{io} naming the file.
std::string hash_bytes(std::string_view bytes);
std::string hash_file(const std::string& path);

// The digest of the tool: XXH3-128 over the name and bytes of each of
// texproc::runtime_files() (the executable, then the runtime modules).
// Computed once a process.
const std::string& tool_digest();

// `texproc --version --json`: version, tool digest, runtime files, libraries.
Json::Value version_json();

}  // namespace texproc::cli
