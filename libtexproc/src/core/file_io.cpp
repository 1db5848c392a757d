#include "texproc/file_io.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "texproc/error.h"

namespace fs = std::filesystem;

namespace texproc {

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path_);
  const std::string name = ".~" + p.filename().string() + ".tmp" + std::to_string(::getpid()) + "-" +
                           std::to_string(counter++) + p.extension().string();
  temp_ = (p.parent_path() / name).string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_, ec);
  }
}

namespace {
std::atomic<CommitPolicy> g_policy{CommitPolicy::replace};

bool same_bytes(const std::string& a, const std::string& b) {
  std::error_code ec;
  const auto size_a = fs::file_size(a, ec);
  if (ec) return false;
  const auto size_b = fs::file_size(b, ec);
  if (ec || size_a != size_b) return false;
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  if (!fa || !fb) return false;
  std::vector<char> ba(1 << 16), bb(1 << 16);
  while (fa && fb) {
    fa.read(ba.data(), std::streamsize(ba.size()));
    fb.read(bb.data(), std::streamsize(bb.size()));
    if (fa.gcount() != fb.gcount()) return false;
    if (std::memcmp(ba.data(), bb.data(), std::size_t(fa.gcount())) != 0) return false;
  }
  return fa.eof() && fb.eof();
}
}  // namespace

void set_commit_policy(CommitPolicy policy) { g_policy = policy; }
CommitPolicy commit_policy() { return g_policy; }

bool AtomicFile::commit() {
  if (g_policy == CommitPolicy::keep_identical && same_bytes(temp_, path_)) {
    std::error_code ec;
    fs::remove(temp_, ec);
    committed_ = true;
    return false;
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
    const int err = errno;
    throw Error(ErrorCode::io, path_ + ": cannot write: " + std::strerror(err));
  }
  committed_ = true;
  return true;
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
  AtomicFile file(path);
  {
    std::ofstream out(file.temp_path(), std::ios::binary);
    if (!out) throw Error(ErrorCode::io, path + ": cannot create: " + std::strerror(errno));
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    if (!out) throw Error(ErrorCode::io, path + ": write failed");
  }
  file.commit();
}

}  // namespace texproc
