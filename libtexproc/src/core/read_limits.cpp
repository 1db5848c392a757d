// ReadLimits from the environment (the texproc tool's limits).
#include "texproc/read_limits.h"

#include <cstdlib>

namespace texproc {
namespace {

// A positive decimal number from `name`, if it holds one and nothing else.
bool positive_from(const char* name, unsigned long long& out) {
  const char* e = std::getenv(name);
  if (!e || !*e) return false;
  char* end = nullptr;
  const unsigned long long v = std::strtoull(e, &end, 10);
  if (end == e || *end != '\0' || v == 0 || *e == '-') return false;
  out = v;
  return true;
}

}  // namespace

ReadLimits ReadLimits::from_environment() {
  ReadLimits l;
  unsigned long long v = 0;
  if (positive_from("TEXPROC_MAX_IMAGE_PIXELS", v) && v < (1ULL << 62)) l.max_image_pixels = static_cast<long long>(v);
  if (positive_from("TEXPROC_MAX_JPEG_SCANS", v) && v < (1ULL << 30)) l.max_jpeg_scans = static_cast<int>(v);
  if (positive_from("TEXPROC_MAX_TEXTURE_BYTES", v)) l.max_inflated_bytes = v;
  return l;
}

}  // namespace texproc
