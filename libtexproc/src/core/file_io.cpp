#include "texproc/file_io.h"

#include <fcntl.h>
#include <stdio.h>
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

namespace {

// ".~NAME.tmpPID-N.EXT", with NAME cut so that the whole fits the folder's
// name limit (a 250-byte output name still gets a temporary).
std::string temp_name(const fs::path& p, unsigned n) {
  const std::string ext = p.extension().string();
  const std::string tail = ".tmp" + std::to_string(::getpid()) + "-" + std::to_string(n) + ext;
  std::string name = p.filename().string();
  const long max_name = ::pathconf(p.parent_path().empty() ? "." : p.parent_path().c_str(), _PC_NAME_MAX);
  const std::size_t limit = max_name > 0 ? std::size_t(max_name) : 255;
  const std::size_t room = limit > tail.size() + 2 ? limit - tail.size() - 2 : 0;
  if (name.size() > room) name.resize(room);
  return ".~" + name + tail;
}

}  // namespace

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path_);
  const std::string dir = p.parent_path().empty() ? "." : p.parent_path().string();
#ifdef O_TMPFILE
  fd_ = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd_ >= 0) {
    temp_ = "/proc/self/fd/" + std::to_string(fd_);
    return;
  }
#endif
  temp_ = (p.parent_path() / temp_name(p, counter++)).string();
}

AtomicFile::AtomicFile(std::string path, CommitPolicy policy) : AtomicFile(std::move(path)) { policy_ = int(policy); }

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);  // an unnamed temporary vanishes with its last descriptor
  if (fd_ < 0 && !committed_) {
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
  const CommitPolicy policy = policy_ >= 0 ? CommitPolicy(policy_) : g_policy.load();
  auto fail = [&](int err) -> bool {
    throw Error(ErrorCode::io, path_ + ": cannot write: " + std::strerror(err));
  };
  auto exists_now = [&]() -> bool {
    throw Error(ErrorCode::io, path_ + ": cannot write: the file appeared while this run was writing it (another "
                                       "process?) and is kept; --force replaces it");
  };
  if (policy == CommitPolicy::keep_identical && same_bytes(temp_, path_)) {
    if (fd_ < 0) {
      std::error_code ec;
      fs::remove(temp_, ec);
    }
    committed_ = true;
    return false;
  }
  if (fd_ >= 0) {
    // Name the unnamed file: straight at path() when nothing is there (which
    // is also how no_replace refuses, atomically, a file that appeared since
    // the check); otherwise under a temporary name, renamed over path().
    if (::linkat(AT_FDCWD, temp_.c_str(), AT_FDCWD, path_.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      committed_ = true;
      return true;
    }
    const int err = errno;
    if (err != EEXIST) fail(err);
    if (policy == CommitPolicy::no_replace) exists_now();
    static std::atomic<unsigned> counter{0};
    const fs::path p(path_);
    const std::string named = (p.parent_path() / temp_name(p, 1000000 + counter++)).string();
    if (::linkat(AT_FDCWD, temp_.c_str(), AT_FDCWD, named.c_str(), AT_SYMLINK_FOLLOW) != 0) fail(errno);
    if (std::rename(named.c_str(), path_.c_str()) != 0) {
      const int e = errno;
      ::unlink(named.c_str());
      fail(e);
    }
    committed_ = true;
    return true;
  }
  if (policy == CommitPolicy::no_replace) {
    // renameat2's RENAME_NOREPLACE where the file system has it, else a hard
    // link (which fails on an existing name) and the temporary's removal.
    if (::renameat2(AT_FDCWD, temp_.c_str(), AT_FDCWD, path_.c_str(), RENAME_NOREPLACE) != 0) {
      const int err = errno;
      if (err == EEXIST) exists_now();
      if (err != EINVAL && err != ENOSYS) fail(err);
      if (::link(temp_.c_str(), path_.c_str()) != 0) errno == EEXIST ? exists_now() : fail(errno);
      ::unlink(temp_.c_str());
    }
    committed_ = true;
    return true;
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) fail(errno);
  committed_ = true;
  return true;
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
  write_file_atomic(path, bytes, g_policy.load());
}

void write_file_atomic(const std::string& path, const std::string& bytes, CommitPolicy policy) {
  AtomicFile file(path, policy);
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
