#include "texproc/tools.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <set>
#include <vector>

#include "core/fd_writer.h"
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

namespace {

// Named temporaries this process has made and not yet renamed or removed,
// for remove_pending_temporaries(). commit() holds the lock from naming a
// temporary to renaming it, so a signal-handling thread that takes the lock
// finds every name that exists.
std::mutex g_pending_mutex;
std::set<std::string>& pending() {
  static auto* p = new std::set<std::string>;  // never destroyed: used until _exit
  return *p;
}

// Folders already swept for stale temporaries by this process.
std::mutex g_swept_mutex;
std::set<std::string>& swept() {
  static auto* s = new std::set<std::string>;
  return *s;
}

thread_local CommitGroup* t_group = nullptr;

// The PID in a temporary's name ".~NAME.tmpPID-N.EXT", or 0.
long temp_pid(const std::string& name) {
  if (name.rfind(".~", 0) != 0) return 0;
  const std::size_t at = name.rfind(".tmp");
  if (at == std::string::npos) return 0;
  std::size_t i = at + 4;
  long pid = 0;
  const std::size_t digits = i;
  while (i < name.size() && name[i] >= '0' && name[i] <= '9' && pid < (1L << 30)) pid = pid * 10 + (name[i++] - '0');
  if (i == digits || i >= name.size() || name[i] != '-') return 0;
  const std::size_t n0 = ++i;
  while (i < name.size() && name[i] >= '0' && name[i] <= '9') ++i;
  if (i == n0 || (i < name.size() && name[i] != '.')) return 0;
  return pid;
}

void sweep_once(const std::string& dir) {
  {
    std::lock_guard<std::mutex> lock(g_swept_mutex);
    if (!swept().insert(dir).second) return;
  }
  remove_stale_temporaries(dir);
}

}  // namespace

int remove_stale_temporaries(const std::string& folder) {
  int removed = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const long pid = temp_pid(name);
    if (pid <= 0 || pid == long(::getpid())) continue;
    if (::kill(pid_t(pid), 0) == 0 || errno != ESRCH) continue;  // running (or not ours to ask about): kept
    std::error_code rc;
    if (fs::remove(it->path(), rc)) ++removed;
  }
  return removed;
}

void remove_pending_temporaries() {
  std::lock_guard<std::mutex> lock(g_pending_mutex);
  for (const std::string& t : pending()) ::unlink(t.c_str());
  pending().clear();
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  static std::atomic<unsigned> counter{0};
  const fs::path p(path_);
  const std::string dir = p.parent_path().empty() ? "." : p.parent_path().string();
  sweep_once(dir);
#ifdef O_TMPFILE
  fd_ = ::open(dir.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd_ >= 0) {
    temp_ = "/proc/self/fd/" + std::to_string(fd_);
    return;
  }
#endif
  temp_ = (p.parent_path() / temp_name(p, counter++)).string();
  std::lock_guard<std::mutex> lock(g_pending_mutex);
  pending().insert(temp_);
}

AtomicFile::AtomicFile(std::string path, CommitPolicy policy) : AtomicFile(std::move(path)) { policy_ = int(policy); }

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);  // an unnamed temporary vanishes with its last descriptor
  if (fd_ < 0 && !committed_ && !temp_.empty()) {
    std::lock_guard<std::mutex> lock(g_pending_mutex);
    std::error_code ec;
    fs::remove(temp_, ec);
    pending().erase(temp_);
  }
}

namespace {

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

bool AtomicFile::commit() {
  if (CommitGroup* g = t_group) {
    auto kept = std::unique_ptr<AtomicFile>(new AtomicFile);
    kept->path_ = path_;
    kept->temp_ = temp_;
    kept->fd_ = fd_;
    kept->policy_ = policy_ >= 0 ? policy_ : int(g->policy_);
    fd_ = -1;
    committed_ = true;  // the group owns the temporary now
    g->files_.push_back(std::move(kept));
    return true;
  }
  return commit_now();
}

void AtomicFile::check_free() const {
  const CommitPolicy policy = policy_ >= 0 ? CommitPolicy(policy_) : CommitPolicy::replace;
  std::error_code ec;
  if (policy == CommitPolicy::no_replace && fs::exists(fs::symlink_status(path_, ec))) {
    throw Error(ErrorCode::io, path_ +
                                   ": cannot write: the file appeared while this run was writing it (another "
                                   "process?) and is kept; --force replaces it");
  }
}

bool AtomicFile::commit_now() {
  std::lock_guard<std::mutex> lock(g_pending_mutex);
  const CommitPolicy policy = policy_ >= 0 ? CommitPolicy(policy_) : CommitPolicy::replace;
  auto fail = [&](int err) -> bool { throw Error(ErrorCode::io, path_ + ": cannot write: " + std::strerror(err)); };
  auto exists_now = [&]() -> bool {
    throw Error(ErrorCode::io, path_ +
                                   ": cannot write: the file appeared while this run was writing it (another "
                                   "process?) and is kept; --force replaces it");
  };
  if (policy == CommitPolicy::keep_identical && same_bytes(temp_, path_)) {
    if (fd_ < 0) {
      std::error_code ec;
      fs::remove(temp_, ec);
      pending().erase(temp_);
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
    // The lock is held from here to the rename: a signal-handling thread
    // removing pending temporaries sees this name or its rename, never a
    // name left behind.
    pending().insert(named);
    if (::linkat(AT_FDCWD, temp_.c_str(), AT_FDCWD, named.c_str(), AT_SYMLINK_FOLLOW) != 0) {
      pending().erase(named);
      fail(errno);
    }
    if (std::rename(named.c_str(), path_.c_str()) != 0) {
      const int e = errno;
      ::unlink(named.c_str());
      pending().erase(named);
      fail(e);
    }
    pending().erase(named);
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
    pending().erase(temp_);
    committed_ = true;
    return true;
  }
  if (std::rename(temp_.c_str(), path_.c_str()) != 0) fail(errno);
  pending().erase(temp_);
  committed_ = true;
  return true;
}

// A group opened while another is open on the thread (a worker that takes
// up another file's work while it waits inside this one's parallel loop)
// holds its own files until it closes, then the outer one is open again.
CommitGroup::CommitGroup(CommitPolicy policy) : outer_(t_group), policy_(policy) { t_group = this; }

CommitGroup::~CommitGroup() {
  t_group = outer_;
  // files_ goes with the group: each uncommitted temporary is removed.
}

void CommitGroup::commit() {
  t_group = outer_;
  for (const auto& f : files_) f->check_free();
  std::vector<std::string> made;  // files new under their names, removed again if a later one fails
  try {
    for (const auto& f : files_) {
      std::error_code ec;
      const bool existed = fs::exists(fs::symlink_status(f->path_, ec));
      if (f->commit_now() && !existed) made.push_back(f->path_);
    }
  } catch (...) {
    for (const std::string& m : made) ::unlink(m.c_str());
    throw;
  }
  files_.clear();
}

void write_file_atomic(const std::string& path, const std::string& bytes) {
  AtomicFile file(path);
  FdWriter out(file.temp_path(), path);  // every failure names path and the OS error
  out.write(bytes.data(), bytes.size());
  out.close();
  file.commit();
}

void write_file_atomic(const std::string& path, const std::string& bytes, CommitPolicy policy) {
  AtomicFile file(path, policy);
  FdWriter out(file.temp_path(), path);  // every failure names path and the OS error
  out.write(bytes.data(), bytes.size());
  out.close();
  file.commit();
}

}  // namespace texproc
