#include "tool_info.h"

#include <fcntl.h>
#include <unistd.h>

#define XXH_INLINE_ALL
#include <xxhash.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <vector>

#include "texproc/error.h"
#include "texproc/tools.h"
#include "texproc/version.h"

namespace fs = std::filesystem;

namespace texproc::cli {
namespace {

std::string hex(const XXH128_hash_t& h) {
  XXH128_canonical_t c;
  XXH128_canonicalFromHash(&c, h);
  static const char digits[] = "0123456789abcdef";
  std::string s;
  for (unsigned char b : c.digest) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

// Feeds a file's bytes to `state`; throws Error{io}.
void hash_into(XXH3_state_t* state, const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorCode::io, path + ": cannot open: " + std::strerror(errno));
  std::vector<char> buf(1 << 20);
  for (;;) {
    const ssize_t n = ::read(fd, buf.data(), buf.size());
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      throw Error(ErrorCode::io, path + ": cannot read: " + std::strerror(e));
    }
    XXH3_128bits_update(state, buf.data(), std::size_t(n));
  }
  ::close(fd);
}

struct State {
  XXH3_state_t* s = XXH3_createState();
  State() { XXH3_128bits_reset(s); }
  ~State() { XXH3_freeState(s); }
  State(const State&) = delete;
  State& operator=(const State&) = delete;
};

}  // namespace

std::string hash_bytes(std::string_view bytes) { return hex(XXH3_128bits(bytes.data(), bytes.size())); }

std::string hash_file(const std::string& path) {
  State st;
  hash_into(st.s, path);
  return hex(XXH3_128bits_digest(st.s));
}

const std::string& tool_digest() {
  static std::once_flag once;
  static std::string digest;
  std::call_once(once, [] {
    State st;
    for (const std::string& f : runtime_files()) {
      // The name without its folder: the same tool installed elsewhere has
      // the same digest.
      const std::string name = fs::path(f).filename().string();
      XXH3_128bits_update(st.s, name.data(), name.size() + 1);
      hash_into(st.s, f);
    }
    digest = hex(XXH3_128bits_digest(st.s));
  });
  return digest;
}

Json::Value version_json() {
  Json::Value v(Json::objectValue);
  v["name"] = "texproc";
  v["version"] = version_string();
  v["version_major"] = TEXPROC_VERSION_MAJOR;
  v["version_minor"] = TEXPROC_VERSION_MINOR;
  v["version_patch"] = TEXPROC_VERSION_PATCH;
  v["digest"] = tool_digest();
  v["digest_algorithm"] = "xxh3-128";
  Json::Value files(Json::arrayValue);
  for (const std::string& f : runtime_files()) {
    Json::Value e(Json::objectValue);
    e["path"] = f;
    e["digest"] = hash_file(f);
    files.append(e);
  }
  v["runtime_files"] = files;
  Json::Value libs(Json::objectValue);
  for (const auto& [name, version] : linked_libraries()) libs[name] = version;
  v["libraries"] = libs;
  return v;
}

}  // namespace texproc::cli
