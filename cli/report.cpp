// The CLI's one reporter (report.h).
#include "report.h"

#include <iostream>
#include <utility>

namespace texproc::cli {
namespace {

// The library's names for what the command line calls flags, longest
// first where one name starts another.
const std::pair<const char*, const char*> kTerms[] = {
    {"MipOptions::filter.sigma", "--sigma"},
    {"MipOptions::normal_map", "--normal-map"},
    {"MipOptions::alpha_coverage_ref", "--alpha-coverage"},
    {"MipOptions::min_size", "--min-size"},
    {"NormalMapOptions::multiscale_weights", "--multiscale-weights"},
    {"NormalMapOptions::height_channel", "--height-channel"},
    {"NormalMapOptions::height_scale", "--height-scale"},
    {"NormalMapOptions::strength", "--strength"},
    {"NormalChannels", "--channels"},
    {"ConeMapOptions::bilinear_safe", "--bilinear-safe"},
    {"ConeMapOptions::fast_reach", "--fast-reach"},
    {"ConeMapOptions::max_ratio", "--max-ratio"},
    {"ConeMapOptions::depth", "--depth"},
    {"ConeMapOptions::wrap", "--wrap for conemap"},
    {"ConeMode::relaxed", "--mode relaxed"},
    {"BoxBlurOptions::radius_map", "--radius-map"},
    {"BoxBlurOptions::radius", "--radius"},
    {"WriteOptions::compression", "--compression"},
    {"SatPrecision", "--precision"},
    {"quality name", "--quality"},
};

}  // namespace

std::string in_cli_terms(const std::string& message) {
  std::string s = message;
  for (const auto& [api, flag] : kTerms) {
    const std::string from = api;
    for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + 1)) {
      s.replace(at, from.size(), flag);
    }
  }
  return s;
}

std::string about(const std::string& file, const std::string& message) {
  if (file.empty() || message.rfind(file, 0) == 0) return message;
  return file + ": " + message;
}

void print_error(const std::string& command, const std::string& message) {
  std::cerr << "texproc" << (command.empty() ? "" : " " + command) << ": error: " << message << "\n";
}

void print_warning(const std::string& command, const std::string& message) {
  std::cerr << "texproc" << (command.empty() ? "" : " " + command) << ": warning: " << message << "\n";
}

void print_note(const std::string& line) { std::cerr << line << "\n"; }

}  // namespace texproc::cli
