// What the file-reading harnesses share: the input as a file in /dev/shm,
// and the image limits they run under.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

#include "texproc/image_io.h"

namespace texproc::fuzz {

// Writes the input to /dev/shm/texproc_fuzz_<tag>_<pid><ext>; "" if it cannot.
inline std::string put_file(const char* tag, const std::string& ext, const std::uint8_t* data, std::size_t size) {
  const std::string path = "/dev/shm/texproc_fuzz_" + std::string(tag) + "_" + std::to_string(::getpid()) + ext;
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return "";
  const bool ok = std::fwrite(data, 1, size, f) == size;
  return std::fclose(f) == 0 && ok ? path : "";
}

// Images of at most 4096 a side and 4 Mpixels, textures inflating to at
// most 16 MiB: the harnesses look for faults, not for large allocations the
// limits allow.
inline ReadOptions limited_reads() {
  ReadOptions o;
  o.limits.max_image_dimension = 4096;
  o.limits.max_image_pixels = 1 << 22;
  o.limits.max_inflated_bytes = std::uint64_t(16) << 20;
  return o;
}

}  // namespace texproc::fuzz
